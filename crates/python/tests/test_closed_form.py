"""Images from Python against closed forms, on every renderer, for meshes
built with PyVista: a box of constant material seen along an axis is
Beer-Lambert's image, whatever the renderer, the split of its cells into
tetrahedra or the blocks it comes in.

A constant luminance L and attenuation tau over a chord of length d give
premultiplied colour L (1 - T) and alpha 1 - T with T = exp(-tau d); with
an opacity a per unit distance u (the exact opacity mode),
T = (1 - a)^(d / u)."""

from __future__ import annotations

import os

import numpy as np
import pytest

import tetray

SIZE = (64, 48)
RGB = (1.0, 0.5, 0.25)
ALPHA = 0.4
# Orthographic, looking obliquely at the box [0, 2] x [0, 1] x [0, 1]
# (faces seen edge-on are a degenerate case for the projection), the chord
# of every pixel's ray known exactly from the box.
FOCAL = np.array([1.0, 0.5, 0.5])
TOWARDS_EYE = np.array([0.35, 0.25, 1.0]) / np.linalg.norm([0.35, 0.25, 1.0])
CAMERA = {
    "position": tuple(FOCAL + 10.0 * TOWARDS_EYE),
    "focal_point": tuple(FOCAL),
    "view_up": (0.0, 1.0, 0.0),
    "parallel_scale": 1.0,
}
# The Psi table's bilinear error (about 1e-6) and f32 rounding over the few
# segments of a ray: measured worst 1.2e-6 on the CPU, 1.8e-6 on lavapipe,
# and 3.1e-7 for the exact method on the linear field.
TOLERANCE = 5e-6


# Straight down -z: every ray through the box's top crosses a chord of 1,
# entering at z = 1.
CAMERA_AXIS = {
    "position": (1.0, 0.5, 10.0),
    "focal_point": (1.0, 0.5, 0.5),
    "view_up": (0.0, 1.0, 0.0),
    "parallel_scale": 1.0,
}


def chords(offset=(0.0, 0.0), camera=CAMERA) -> np.ndarray:
    """The length inside the box of every pixel's ray (the ray through the
    pixel centre moved by `offset` pixels), as VTK's camera with
    OrthogonalizeViewUp casts them."""
    width, height = SIZE
    direction = np.asarray(camera["focal_point"]) - np.asarray(camera["position"])
    direction /= np.linalg.norm(direction)
    right = np.cross(direction, camera["view_up"])
    right /= np.linalg.norm(right)
    up = np.cross(right, direction)
    pixel = 2.0 * camera["parallel_scale"] / height
    x = (np.arange(width) + 0.5 + offset[0] - width / 2) * pixel
    y = (height / 2 - np.arange(height) - 0.5 + offset[1]) * pixel
    gx, gy = np.meshgrid(x, y)
    origin = np.asarray(camera["position"]) + gx[..., None] * right + gy[..., None] * up
    lo, hi = np.array([0.0, 0.0, 0.0]), np.array([2.0, 1.0, 1.0])
    with np.errstate(divide="ignore", invalid="ignore"):
        t0 = (lo - origin) / direction
        t1 = (hi - origin) / direction
    near = np.minimum(t0, t1).max(axis=-1)
    far = np.maximum(t0, t1).min(axis=-1)
    return np.clip(far - near, 0.0, None)


def expected(camera=CAMERA) -> tuple[np.ndarray, np.ndarray]:
    """The closed-form image, and the mask of pixels whose whole footprint
    is inside or outside the box's silhouette (edge pixels are left out)."""
    chord = chords(camera=camera)
    shifted = [chords((dx, dy), camera) for dx in (-0.5, 0.5) for dy in (-0.5, 0.5)]
    inside = np.all([c > 0 for c in shifted], axis=0)
    outside = np.all([c == 0 for c in shifted], axis=0)
    alpha = 1.0 - (1.0 - ALPHA) ** chord
    image = np.zeros((*chord.shape, 4))
    for c in range(3):
        image[..., c] = RGB[c] * alpha
    image[..., 3] = alpha
    return image, inside | outside


def box(lo_x: float, hi_x: float):
    import pyvista as pv

    cells = round((hi_x - lo_x) / 0.25)
    grid = pv.ImageData(dimensions=(cells + 1, 5, 5), spacing=(0.25, 0.25, 0.25), origin=(lo_x, 0, 0))
    grid.point_data["c"] = np.full(grid.n_points, 0.5)
    return grid


def render(mesh, renderer: str) -> np.ndarray:
    return tetray.render(
        mesh,
        "c",
        size=SIZE,
        renderer=renderer,
        camera=CAMERA,
        cmap=[RGB],
        opacity=ALPHA,
        clim=(0.0, 1.0),
        unit_distance=1.0,
        opacity_mode="exact",
    )


def gpu_or_skip():
    """A GPU renderer needs an adapter: lavapipe in CI, which sets
    TETRAY_REQUIRE_GPU=1 so that a missing one fails."""
    try:
        tetray.render(box(0.0, 2.0), "c", size=(4, 4), renderer="gpu")
    except (ValueError, OSError) as e:
        if os.environ.get("TETRAY_REQUIRE_GPU") == "1":
            raise
        pytest.skip(f"no GPU adapter: {e}")


@pytest.mark.parametrize("renderer", ["cpu", "gpu"])
def test_a_constant_box_is_beer_lamberts_image(renderer):
    if renderer != "cpu":
        gpu_or_skip()
    image = render(box(0.0, 2.0), renderer)
    want, checked = expected()
    assert image.shape == want.shape
    error = np.abs(image - want)[checked].max()
    assert error < TOLERANCE, f"{renderer}: worst pixel off by {error}"
    lit = want[..., 3] > 0
    assert np.count_nonzero(lit & checked) > 1000
    assert np.all(image[..., 3][checked & ~lit] == 0)


def test_the_projection_of_a_constant_box_is_beer_lamberts_image():
    """The cell projection draws the same segments with the same WGSL, in a
    visibility order exact on a convex box. Its rasterizer and the exit
    plane found per fragment disagree with the exact chord on a few pixels
    where a tetrahedron's face is seen nearly edge-on (measured on lavapipe:
    9 of the 2 900 pixels checked on this view, worst 0.11): every other
    pixel within the tolerance, at most 1% of them beyond."""
    gpu_or_skip()
    image = render(box(0.0, 2.0), "project")
    want, checked = expected()
    error = np.abs(image - want).max(axis=-1)[checked]
    beyond = np.count_nonzero(error > TOLERANCE)
    assert beyond <= checked.sum() // 100, f"{beyond} pixels beyond {TOLERANCE}, worst {error.max()}"


def test_a_multiblock_box_is_the_same_closed_form():
    import pyvista as pv

    blocks = pv.MultiBlock([box(0.0, 1.0), box(1.0, 2.0)])
    image = render(blocks, "cpu")
    want, checked = expected()
    error = np.abs(image - want)[checked].max()
    assert error < TOLERANCE, f"worst pixel off by {error}"
    # The blocks' shared face is welded: one component with the one box's
    # boundary, no seam to re-enter through.
    welded = tetray.Scene(blocks, "c", size=(8, 8), renderer="cpu").info
    whole = tetray.Scene(box(0.0, 2.0), "c", size=(8, 8), renderer="cpu").info
    assert welded["components"] == 1
    assert welded["boundary_faces"] == whole["boundary_faces"]
    assert welded["tets"] == whole["tets"]


def test_a_linear_field_has_the_integral_of_an_f64_quadrature():
    """A field rising linearly along the rays with a transfer function
    linear in it: luminance L(t) = l t and attenuation tau(t) = k t along
    each chord (t from the entry, d = 1), whose light is
    I = integral of L tau exp(-integral of tau) = integral of l k t^2
    exp(-k t^2 / 2) dt, here by Simpson's rule in f64 (error below 1e-12),
    and whose alpha is 1 - exp(-k d^2 / 2)."""
    import pyvista as pv

    grid = pv.ImageData(dimensions=(9, 5, 5), spacing=(0.25, 0.25, 0.25), origin=(0, 0, 0))
    # s = 1 - z: 0 where the rays enter (z = 1, the face towards the
    # camera), 1 where they leave (z = 0).
    grid.point_data["s"] = 1.0 - grid.points[:, 2]
    k, lum = 2.0, 0.8
    # The "vtk" opacity mode makes tau = alpha / u, linear in the opacity:
    # an opacity from 0 to k / 2 over a unit distance of 0.5 is tau = k s.
    image = tetray.render(
        grid,
        "s",
        size=SIZE,
        renderer="cpu",
        integrator="exact",
        camera=CAMERA_AXIS,
        cmap=[(0.0, 0.0, 0.0), (lum, lum, lum)],
        opacity=[0.0, k / 2.0],
        clim=(0.0, 1.0),
        unit_distance=0.5,
        opacity_mode="vtk",
    )
    t = np.linspace(0.0, 1.0, 20001)
    f = lum * k * t * t * np.exp(-k * t * t / 2.0)
    h = t[1] - t[0]
    light = h / 3.0 * (f[0] + f[-1] + 4.0 * f[1:-1:2].sum() + 2.0 * f[2:-1:2].sum())
    alpha = 1.0 - np.exp(-k / 2.0)
    want, checked = expected(CAMERA_AXIS)
    inside = (want[..., 3] > 0) & checked
    assert np.count_nonzero(inside) > 1000
    assert np.abs(image[..., 3][inside] - alpha).max() < TOLERANCE
    for c in range(3):
        assert np.abs(image[..., c][inside] - light).max() < TOLERANCE
    assert np.abs(image[checked & ~inside]).max() == 0.0


def write_vtkhdf_box(path, steps=(0.0, 0.5)):
    """The box [0, 2] x [0, 1] x [0, 1] as a VTKHDF 2.2 UnstructuredGrid
    written with h5py: two partitions (x below and above 1), each its own
    points, over two time steps of the same cells, "c" = 0 at the first
    (clear) and 0.5 at the second."""
    import h5py

    parts = [box(0.0, 1.0).cast_to_unstructured_grid(), box(1.0, 2.0).cast_to_unstructured_grid()]
    with h5py.File(path, "w") as f:
        root = f.create_group("VTKHDF")
        root.attrs.create("Version", np.array([2, 2], dtype="i8"))
        root.attrs.create("Type", np.bytes_("UnstructuredGrid"))
        root["NumberOfPoints"] = np.array([p.n_points for p in parts], dtype="i8")
        root["NumberOfCells"] = np.array([p.n_cells for p in parts], dtype="i8")
        root["NumberOfConnectivityIds"] = np.array([len(p.cell_connectivity) for p in parts], dtype="i8")
        root["Points"] = np.vstack([p.points for p in parts]).astype("f8")
        root["Types"] = np.concatenate([p.celltypes for p in parts]).astype("u1")
        root["Offsets"] = np.concatenate([p.cell_offsets for p in parts]).astype("i8")
        root["Connectivity"] = np.concatenate([p.cell_connectivity for p in parts]).astype("i8")
        n = sum(p.n_points for p in parts)
        values = np.concatenate([np.full(n, 0.5 * (i > 0)) for i in range(len(steps))])
        root.create_group("PointData")["c"] = values
        group = root.create_group("Steps")
        group.attrs.create("NSteps", np.int64(len(steps)))
        group["Values"] = np.array(steps)
        for name in ("PartOffsets", "PointOffsets", "CellOffsets", "ConnectivityIdOffsets"):
            group[name] = np.zeros(len(steps), dtype="i8")
        group["NumberOfParts"] = np.full(len(steps), len(parts), dtype="i8")
        group.create_group("PointDataOffsets")["c"] = np.arange(len(steps), dtype="i8") * n


@pytest.mark.parametrize("renderer", ["cpu", "gpu"])
def test_a_vtkhdf_box_is_the_same_closed_form(tmp_path, renderer):
    """The box read from a temporal, partitioned VTKHDF file: its second
    step (chosen by time) is Beer-Lambert's image; its first is clear. The
    opacity rises from 0 at c = 0 to 2 ALPHA at c = 1: ALPHA at c = 0.5."""
    if renderer != "cpu":
        gpu_or_skip()
    path = tmp_path / "box.vtkhdf"
    write_vtkhdf_box(path)
    common = dict(size=SIZE, renderer=renderer, camera=CAMERA, cmap=[RGB], opacity=[0.0, 2 * ALPHA],
                  clim=(0.0, 1.0), unit_distance=1.0, opacity_mode="exact")
    image = tetray.render(str(path), "c", time=0.4, **common)
    want, checked = expected()
    error = np.abs(image - want)[checked].max()
    assert error < TOLERANCE, f"{renderer}: worst pixel off by {error}"
    clear = tetray.render(str(path), "c", time_step=0, **common)
    assert np.abs(clear).max() == 0.0
    info = tetray.Scene(str(path), "c", size=(8, 8), renderer="cpu").info
    assert info["components"] == 1, info


def write_openfoam_box(case):
    """The box [0, 2] x [0, 1] x [0, 1] as an ASCII OpenFOAM case of 8 x 4 x 4
    hexahedra (internal faces first, each turned from its owner, the lower
    cell, to its neighbour; boundary faces outward): "c" uniform 0 in time
    folder 0 and 0.5 per cell (nonuniform) in time folder 1."""
    n, h = (8, 4, 4), 0.25

    def point(i, j, k):
        return i + (n[0] + 1) * (j + (n[1] + 1) * k)

    def cell(i, j, k):
        return i + n[0] * (j + n[1] * k)

    def quad(axis, i, j, k):
        # Corners of the face at index (i, j, k) across `axis`, normal +axis.
        if axis == 0:
            return [point(i, j, k), point(i, j + 1, k), point(i, j + 1, k + 1), point(i, j, k + 1)]
        if axis == 1:
            return [point(i, j, k), point(i, j, k + 1), point(i + 1, j, k + 1), point(i + 1, j, k)]
        return [point(i, j, k), point(i + 1, j, k), point(i + 1, j + 1, k), point(i, j + 1, k)]

    internal, boundary = [], []
    for axis in range(3):
        for k in range(n[2] + (axis == 2)):
            for j in range(n[1] + (axis == 1)):
                for i in range(n[0] + (axis == 0)):
                    idx = [i, j, k]
                    below, above = list(idx), list(idx)
                    below[axis] -= 1
                    face = quad(axis, i, j, k)
                    if idx[axis] == 0:
                        boundary.append((face[::-1], cell(*above), None))
                    elif idx[axis] == n[axis]:
                        boundary.append((face, cell(*below), None))
                    else:
                        internal.append((face, cell(*below), cell(*above)))
    faces = internal + boundary
    points = [(i * h, j * h, k * h) for k in range(n[2] + 1) for j in range(n[1] + 1) for i in range(n[0] + 1)]
    ncells = n[0] * n[1] * n[2]

    def write(path, cls, body):
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(f"FoamFile\n{{\n    format ascii;\n    class {cls};\n}}\n{body}\n")

    mesh = case / "constant" / "polyMesh"
    write(mesh / "points", "vectorField", f"{len(points)}\n(\n" + "\n".join(f"({x} {y} {z})" for x, y, z in points) + "\n)")
    write(mesh / "faces", "faceList", f"{len(faces)}\n(\n" + "\n".join("4(" + " ".join(map(str, f)) + ")" for f, _, _ in faces) + "\n)")
    write(mesh / "owner", "labelList", f"{len(faces)}\n(\n" + "\n".join(str(o) for _, o, _ in faces) + "\n)")
    write(mesh / "neighbour", "labelList", f"{len(internal)}\n(\n" + "\n".join(str(nb) for _, _, nb in internal) + "\n)")
    write(case / "system" / "controlDict", "dictionary", "application icoFoam;")
    write(case / "0" / "c", "volScalarField", "internalField uniform 0;\nboundaryField { }")
    values = "\n".join(["0.5"] * ncells)
    write(case / "1" / "c", "volScalarField", f"internalField nonuniform List<scalar> {ncells}\n(\n{values}\n);\nboundaryField {{ }}")


@pytest.mark.parametrize("renderer", ["cpu", "gpu"])
def test_an_openfoam_box_is_the_same_closed_form(tmp_path, renderer):
    """The box read from an OpenFOAM case (its folder): time 1 (0.5 in
    every cell, averaged to 0.5 at every point) is Beer-Lambert's image;
    time 0 is clear."""
    if renderer != "cpu":
        gpu_or_skip()
    case = tmp_path / "box"
    write_openfoam_box(case)
    common = dict(size=SIZE, renderer=renderer, camera=CAMERA, cmap=[RGB], opacity=[0.0, 2 * ALPHA],
                  clim=(0.0, 1.0), unit_distance=1.0, opacity_mode="exact")
    image = tetray.render(str(case), "c", time=1.0, **common)
    want, checked = expected()
    error = np.abs(image - want)[checked].max()
    assert error < TOLERANCE, f"{renderer}: worst pixel off by {error}"
    assert np.abs(tetray.render(str(case), "c", time_step=0, **common)).max() == 0.0
    info = tetray.Scene(str(case), "c", size=(8, 8), renderer="cpu").info
    assert info["components"] == 1 and info["tets"] == 128 * 6, info


def write_ensight_box(folder):
    """The box [0, 2] x [0, 1] x [0, 1] as an ASCII EnSight Gold case: one
    uniform block of 9 x 5 x 5 points, "c" per node 0 at time 0 and 0.5 at
    time 1 (files c.0000 and c.0001 of a time set)."""
    folder.mkdir(parents=True, exist_ok=True)
    n = 9 * 5 * 5
    geo = ["written by a test", "a box", "node id off", "element id off", "part", "1", "box",
           "block uniform", "9 5 5", "0.0", "0.0", "0.0", "0.25", "0.25", "0.25"]
    (folder / "box.geo").write_text("\n".join(geo) + "\n")
    for step, value in ((0, 0.0), (1, 0.5)):
        lines = ["c", "part", "1", "block"] + [f"{value:12.5e}"] * n
        (folder / f"c.{step:04d}").write_text("\n".join(lines) + "\n")
    (folder / "box.case").write_text(
        "FORMAT\ntype: ensight gold\nGEOMETRY\nmodel: box.geo\nVARIABLE\nscalar per node: 1 c c.****\n"
        "TIME\ntime set: 1\nnumber of steps: 2\nfilename start number: 0\nfilename increment: 1\n"
        "time values: 0 1\n"
    )


@pytest.mark.parametrize("renderer", ["cpu", "gpu"])
def test_an_ensight_box_is_the_same_closed_form(tmp_path, renderer):
    """The box read from an EnSight Gold case: time 1 is Beer-Lambert's
    image, time 0 is clear."""
    if renderer != "cpu":
        gpu_or_skip()
    write_ensight_box(tmp_path)
    case = str(tmp_path / "box.case")
    common = dict(size=SIZE, renderer=renderer, camera=CAMERA, cmap=[RGB], opacity=[0.0, 2 * ALPHA],
                  clim=(0.0, 1.0), unit_distance=1.0, opacity_mode="exact")
    image = tetray.render(case, "c", time=1.0, **common)
    want, checked = expected()
    error = np.abs(image - want)[checked].max()
    assert error < TOLERANCE, f"{renderer}: worst pixel off by {error}"
    assert np.abs(tetray.render(case, "c", time_step=0, **common)).max() == 0.0


def write_cgns_box(path):
    """The box [0, 2] x [0, 1] x [0, 1] as CGNS (HDF5 storage, written with
    h5py): one structured zone of 9 x 5 x 5 vertices, "c" = 0.5 at the
    vertices."""
    import h5py

    def node(parent, name, label, kind, data=None):
        g = parent.create_group(name)
        g.attrs.create("name", np.bytes_(name))
        g.attrs.create("label", np.bytes_(label))
        g.attrs.create("type", np.bytes_(kind))
        if data is not None:
            g.create_dataset(" data", data=data)
        return g

    with h5py.File(path, "w") as f:
        base = node(f, "Base", "CGNSBase_t", "I4", np.array([3, 3], dtype="i4"))
        zone = node(base, "Box", "Zone_t", "I4", np.array([[9, 5, 5], [8, 4, 4], [0, 0, 0]], dtype="i4"))
        node(zone, "ZoneType", "ZoneType_t", "C1", np.frombuffer(b"Structured", dtype="i1"))
        # Arrays in Fortran order: HDF5 shape (k, j, i).
        k, j, i = np.meshgrid(np.arange(5), np.arange(5), np.arange(9), indexing="ij")
        coords = node(zone, "GridCoordinates", "GridCoordinates_t", "MT")
        for name, v in (("CoordinateX", i), ("CoordinateY", j), ("CoordinateZ", k)):
            node(coords, name, "DataArray_t", "R8", 0.25 * v.astype("f8"))
        solution = node(zone, "FlowSolution", "FlowSolution_t", "MT")
        node(solution, "GridLocation", "GridLocation_t", "C1", np.frombuffer(b"Vertex", dtype="i1"))
        node(solution, "c", "DataArray_t", "R8", np.full((5, 5, 9), 0.5))


@pytest.mark.parametrize("renderer", ["cpu", "gpu"])
def test_a_cgns_box_is_the_same_closed_form(tmp_path, renderer):
    """The box read from a CGNS file is Beer-Lambert's image."""
    if renderer != "cpu":
        gpu_or_skip()
    path = tmp_path / "box.cgns"
    write_cgns_box(path)
    image = render(str(path), renderer)
    want, checked = expected()
    error = np.abs(image - want)[checked].max()
    assert error < TOLERANCE, f"{renderer}: worst pixel off by {error}"
