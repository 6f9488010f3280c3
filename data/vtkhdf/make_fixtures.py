#!/usr/bin/env python3
"""Writes the small VTKHDF files beside this script, each exercising one
part of VTK's "VTKHDF format specification" (versions 2.x):

- cube_temporal.vtkhdf: an UnstructuredGrid of two unit hexahedra side by
  side along x, one per partition (their shared face's points stored twice),
  with two time steps (0 and 0.5) over the same geometry. Point array `s`
  is x at step 0 and 2x at step 1 (per-array step offsets); cell array `id`
  is the partition number, stored once and replayed.
- image.vtkhdf: ImageData of 4 x 3 x 2 points, origin (1, 2, 3), spacing
  (0.5, 0.25, 1); point array `f` = x + 2y + 3z, cell array `g` = the cell's
  flat index.
- image_temporal.vtkhdf: the same image over three steps (times 0, 1, 2)
  whose array `f` has two stored rows, gzip-compressed in chunks: rows f and
  10 f, replayed as steps 0 -> row 0, 1 -> row 1, 2 -> row 0.
- polyhedron.vtkhdf: the unit cube as one polyhedron (VTK type 42, six
  quadrilateral faces), point array `s` = x + y + z.
- polydata.vtkhdf: a PolyData triangle (surfaces: refused).

Run with h5py: python3 make_fixtures.py (writes into this folder)."""

from pathlib import Path

import h5py
import numpy as np

HERE = Path(__file__).resolve().parent
HEX = 12
POLYHEDRON = 42


def root(f: h5py.File, kind: str, version=(2, 2)) -> h5py.Group:
    g = f.create_group("VTKHDF")
    g.attrs.create("Version", np.array(version, dtype="i8"))
    g.attrs.create("Type", np.bytes_(kind))
    return g


def cube_points(x0: float) -> np.ndarray:
    # VTK's hexahedron order: the bottom quad counter-clockwise, then the top.
    return np.array(
        [
            [x0, 0, 0], [x0 + 1, 0, 0], [x0 + 1, 1, 0], [x0, 1, 0],
            [x0, 0, 1], [x0 + 1, 0, 1], [x0 + 1, 1, 1], [x0, 1, 1],
        ],
        dtype="f8",
    )


def cube_temporal():
    with h5py.File(HERE / "cube_temporal.vtkhdf", "w") as f:
        g = root(f, "UnstructuredGrid")
        points = np.vstack([cube_points(0.0), cube_points(1.0)])
        g["NumberOfPoints"] = np.array([8, 8], dtype="i8")
        g["NumberOfCells"] = np.array([1, 1], dtype="i8")
        g["NumberOfConnectivityIds"] = np.array([8, 8], dtype="i8")
        g["Points"] = points
        g["Types"] = np.array([HEX, HEX], dtype="u1")
        g["Offsets"] = np.array([0, 8, 0, 8], dtype="i8")
        g["Connectivity"] = np.tile(np.arange(8, dtype="i8"), 2)
        x = points[:, 0]
        g.create_group("PointData")["s"] = np.concatenate([x, 2.0 * x]).astype("f4")
        g.create_group("CellData")["id"] = np.array([0, 1], dtype="i4")
        steps = g.create_group("Steps")
        steps.attrs.create("NSteps", np.int64(2))
        steps["Values"] = np.array([0.0, 0.5])
        for name in ["PartOffsets", "PointOffsets", "CellOffsets", "ConnectivityIdOffsets"]:
            steps[name] = np.array([0, 0], dtype="i8")
        steps["NumberOfParts"] = np.array([2, 2], dtype="i8")
        steps.create_group("PointDataOffsets")["s"] = np.array([0, 16], dtype="i8")
        steps.create_group("CellDataOffsets")["id"] = np.array([0, 0], dtype="i8")


def image_values():
    # Arrays are shaped (z, y, x): x varies fastest, as VTK stores points.
    x = 1.0 + 0.5 * np.arange(4)
    y = 2.0 + 0.25 * np.arange(3)
    z = 3.0 + 1.0 * np.arange(2)
    zz, yy, xx = np.meshgrid(z, y, x, indexing="ij")
    return xx + 2.0 * yy + 3.0 * zz


def image_root(f: h5py.File) -> h5py.Group:
    g = root(f, "ImageData")
    g.attrs.create("WholeExtent", np.array([0, 3, 0, 2, 0, 1], dtype="i8"))
    g.attrs.create("Origin", np.array([1.0, 2.0, 3.0]))
    g.attrs.create("Spacing", np.array([0.5, 0.25, 1.0]))
    g.attrs.create("Direction", np.eye(3).flatten())
    return g


def image():
    with h5py.File(HERE / "image.vtkhdf", "w") as f:
        g = image_root(f)
        g.create_group("PointData")["f"] = image_values()
        g.create_group("CellData")["g"] = np.arange(6, dtype="f4").reshape(1, 2, 3)


def image_temporal():
    with h5py.File(HERE / "image_temporal.vtkhdf", "w") as f:
        g = image_root(f)
        f_rows = np.stack([image_values(), 10.0 * image_values()])
        g.create_group("PointData").create_dataset(
            "f", data=f_rows, chunks=(1, 2, 3, 4), compression="gzip"
        )
        steps = g.create_group("Steps")
        steps.attrs.create("NSteps", np.int64(3))
        steps["Values"] = np.array([0.0, 1.0, 2.0])
        steps.create_group("PointDataOffsets")["f"] = np.array([0, 1, 0], dtype="i8")


def polyhedron():
    with h5py.File(HERE / "polyhedron.vtkhdf", "w") as f:
        g = root(f, "UnstructuredGrid", (2, 5))
        points = cube_points(0.0)
        g["NumberOfPoints"] = np.array([8], dtype="i8")
        g["NumberOfCells"] = np.array([1], dtype="i8")
        g["NumberOfConnectivityIds"] = np.array([8], dtype="i8")
        g["Points"] = points
        g["Types"] = np.array([POLYHEDRON], dtype="u1")
        g["Offsets"] = np.array([0, 8], dtype="i8")
        g["Connectivity"] = np.arange(8, dtype="i8")
        # Six faces, each counter-clockwise seen from outside.
        faces = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [1, 2, 6, 5], [0, 4, 7, 3]]
        g["NumberOfFaces"] = np.array([6], dtype="i8")
        g["NumberOfFaceConnectivityIds"] = np.array([24], dtype="i8")
        g["NumberOfPolyhedronToFaceIds"] = np.array([6], dtype="i8")
        g["FaceConnectivity"] = np.array(faces, dtype="i8").flatten()
        g["FaceOffsets"] = np.arange(0, 25, 4, dtype="i8")
        g["PolyhedronToFaces"] = np.arange(6, dtype="i8")
        g["PolyhedronOffsets"] = np.array([0, 6], dtype="i8")
        g.create_group("PointData")["s"] = points.sum(axis=1)


def polydata():
    with h5py.File(HERE / "polydata.vtkhdf", "w") as f:
        g = root(f, "PolyData")
        g["NumberOfPoints"] = np.array([3], dtype="i8")
        g["Points"] = np.eye(3)
        for kind in ["Vertices", "Lines", "Strips", "Polygons"]:
            c = g.create_group(kind)
            n = 1 if kind == "Polygons" else 0
            c["NumberOfCells"] = np.array([n], dtype="i8")
            c["NumberOfConnectivityIds"] = np.array([3 * n], dtype="i8")
            c["Offsets"] = np.array([0, 3] if n else [0], dtype="i8")
            c["Connectivity"] = np.arange(3 * n, dtype="i8")


if __name__ == "__main__":
    cube_temporal()
    image()
    image_temporal()
    polyhedron()
    polydata()
