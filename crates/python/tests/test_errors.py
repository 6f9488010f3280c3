"""Bad input raises ValueError (or OSError for files) naming the problem,
and never takes the interpreter down."""

from __future__ import annotations

import numpy as np
import pytest

import tetray

TET = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
CELLS = np.array([[0, 1, 2, 3]])


def test_good_tetrahedron_renders():
    image = tetray.render((TET, CELLS), np.array([0.0, 1, 2, 3]), size=(8, 8), renderer="cpu")
    assert image.shape == (8, 8, 4) and np.all(np.isfinite(image))


@pytest.mark.parametrize(
    "points, cells, match",
    [
        (TET[:, :2], CELLS, r"points must have shape \(n, 3\)"),
        (TET, np.array([[0, 1, 2, 7]]), r"index 7"),
        (TET, np.array([[0, 1, 2, -1]]), r"index -1"),
        (np.array([[0.0, 0, 0], [1, 0, 0], [0, np.nan, 0], [0, 0, 1]]), CELLS, r"point 2 coordinate y"),
        (np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, np.inf]]), CELLS, r"not finite|inf"),
        (TET, np.array([[0.5, 1, 2, 3]]), r"cells must be integers"),
        (TET, np.array([[0, 1, 2]]), r"give celltypes"),
    ],
)
def test_bad_arrays(points, cells, match):
    with pytest.raises(ValueError, match=match):
        tetray.render((points, cells), size=(8, 8), renderer="cpu")


def test_unsupported_cell_type_is_named():
    # 78, a Bezier tetrahedron, has four corners like a tetrahedron but is
    # not split (71, the order-2 Lagrange tetrahedron, is).
    with pytest.raises(ValueError, match=r"cell 0: VTK cell type 78 \(Bezier tetrahedron\) is not supported"):
        tetray.render((TET, CELLS, [78]), size=(8, 8), renderer="cpu")
    with pytest.raises(ValueError, match=r"cell 0: VTK cell type 200 \(.*\) is not supported"):
        tetray.render((TET, CELLS, [200]), size=(8, 8), renderer="cpu")


def test_bad_offsets_and_arrays():
    with pytest.raises(ValueError, match="offsets"):
        tetray.mesh(TET, np.array([0, 1, 2, 3]), celltypes=[10], offsets=[0, 5])
    with pytest.raises(ValueError, match="offsets"):
        tetray.mesh(TET, np.array([0, 1, 2, 3]), celltypes=[10, 10], offsets=[0, 4, 2])
    with pytest.raises(ValueError, match=r"point_data\[\"v\"\]"):
        tetray.mesh(TET, CELLS, point_data={"v": np.zeros(3)})
    with pytest.raises(ValueError, match="count-prefixed|past the end"):
        tetray.mesh(TET, np.array([9, 0, 1, 2, 3]), celltypes=[10])


def test_options_and_files():
    mesh = (TET, CELLS, None, {"v": np.array([0.0, 1, 2, 3])})
    with pytest.raises(ValueError, match="field \"w\""):
        tetray.render(mesh, "w", size=(8, 8))
    with pytest.raises(ValueError, match="unknown|expected one of"):
        tetray.render(mesh, integrator="simpson", size=(8, 8))
    with pytest.raises(ValueError, match="renderer"):
        tetray.render(mesh, renderer="raytrace", size=(8, 8))
    with pytest.raises(ValueError, match="size"):
        tetray.render(mesh, size=(0, 8))
    with pytest.raises(ValueError, match="early_termination"):
        tetray.render(mesh, size=(8, 8), early_termination=0.0)
    with pytest.raises(ValueError, match="view_angle"):
        tetray.render(mesh, size=(8, 8), camera={"view_angle": 200})
    with pytest.raises(ValueError, match="position"):
        tetray.render(mesh, size=(8, 8), camera=[(1, 2), (0, 0, 0), (0, 0, 1)])
    with pytest.raises(ValueError, match="opacity"):
        tetray.render(mesh, size=(8, 8), cmap="viridis", opacity=[0.0, 2.0])
    with pytest.raises(ValueError, match="colormap"):
        tetray.render(mesh, size=(8, 8), cmap="no-such-map")
    with pytest.raises(OSError, match="no such file"):
        tetray.render("/no/such/mesh.vtu", size=(8, 8))
    with pytest.raises(OSError):
        tetray.render(mesh, size=(8, 8), tf="/no/such/preset.json")
    with pytest.raises(ValueError, match="unknown mesh format"):
        tetray.render(__file__, size=(8, 8))
    with pytest.raises(ValueError, match="mesh"):
        tetray.render(42, size=(8, 8))
    with pytest.raises(ValueError, match="shape"):
        tetray.to_rgb8(np.zeros((4, 4, 3)))


def test_surface_only_mesh_is_refused():
    import pyvista as pv

    with pytest.raises(ValueError, match="surface|volume"):
        tetray.render(pv.Sphere(), size=(8, 8))
