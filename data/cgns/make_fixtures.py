#!/usr/bin/env python3
"""Writes small CGNS files in the HDF5 storage beside this script, each for
one part of the CGNS standard's SIDS and its HDF5 mapping (every node a
group with "name", "label" and "type" attributes and a " data" dataset;
arrays in Fortran order, so the HDF5 shape is reversed):

- structured.cgns: one structured zone of 4 x 3 x 2 vertices (x = i, y = j,
  z = k), a CellCenter solution "cell" with one rind layer on every side:
  interior cells hold their index i + 3 j (0 .. 5), rind cells hold -1; a
  Vertex solution "f" = x + 2y + 3z and "VelocityX", "VelocityY",
  "VelocityZ" = 3, 4, 0.
- unstructured.cgns: one unstructured zone: two unit cubes side by side
  along x as a HEXA_8 section (elements 1-2), a MIXED section with a
  pyramid on top of the first cube (apex (0.5, 0.5, 1.5)) and a tetrahedron
  on the pyramid's face 5-6-13 (fourth vertex (0, 0, 2)) (elements 3-4:
  volumes 1/6 and 1/12), and a
  QUAD_4 boundary face (element 5); Vertex solution "f" = x + 2y + 3z.
- polyhedral.cgns: one unstructured zone of polyhedra: a unit cube and a
  pyramid on its top (apex (0.5, 0.5, 1.5); volumes 1 and 1/6) as an
  NFACE_n section (elements 11-12, face counts in the connectivity, as
  CGNS 3 writes them) over an NGON_n section of their ten faces (elements
  1-10, with ElementStartOffset, as CGNS 4 writes them); the pyramid names
  the shared face with a minus sign (its normal points into the pyramid).
  Vertex solution "f" = x + 2y + 3z, CellCenter solution "cell" = 1, 2.
- temporal.cgns: a structured zone of 3 x 2 x 2 vertices with two time
  steps (BaseIterativeData_t: times 0.5 and 1.5; ZoneIterativeData_t:
  FlowSolutionPointers "Step0", "Step1" and GridCoordinatesPointers
  "GridCoordinates", "Moved"): at step 0 the vertices are (i, j, k) and
  "f" = i; at step 1 they are (i + 10, j, k) and "f" = 2 i.
- quadratic.cgns: one unstructured zone of five quadratic cells apart
  from each other, each in its own section, every node at its exact place
  (mid-edge nodes at edge midpoints, face and body nodes at centres), in
  CGNS's node order: HEXA_27 (the unit cube at x 0..1), PENTA_18 (the
  wedge of the triangle (0, 0), (1, 0), (0, 1) times z 0..1, at x 2..3),
  PYRA_14 (the unit square base, apex 1 above its centre, at x 4..5),
  HEXA_20 (x 6..7) and PENTA_15 (x 8..9): volumes 1, 1/2, 1/3, 1, 1/2.
  Vertex solution "f" = x + 2y + 3z.

Each is also converted to CGNS's older ADF storage (<name>-adf.cgns) by
CGNS's own hdf2adf when it is on PATH (Debian package cgns-convert).

Run with h5py: python3 make_fixtures.py (writes into this folder)."""

import shutil
import subprocess
from pathlib import Path

import h5py
import numpy as np

HERE = Path(__file__).resolve().parent


def attribute(g, key, value, size):
    """A fixed-length, null-terminated string of `size` characters, as the
    CGNS library writes its node attributes."""
    g.attrs.create(key, np.bytes_(value.ljust(size + 1, "\0")), dtype=f"S{size + 1}")


def describe(g, name, label, kind):
    attribute(g, "name", name, 32)
    attribute(g, "label", label, 32)
    attribute(g, "type", kind, 2)


def node(parent, name, label, kind, data=None):
    g = parent.create_group(name)
    describe(g, name, label, kind)
    g.attrs.create("flags", np.array([1], dtype="i4"))
    if data is not None:
        g.create_dataset(" data", data=data)
    return g


def text(s):
    return np.frombuffer(s.encode(), dtype="i1")


def base(f):
    describe(f, "HDF5 MotherNode", "Root Node of HDF5 File", "MT")
    f.create_dataset(" format", data=np.frombuffer(b"IEEE_LITTLE_32\0", dtype="i1"))
    f.create_dataset(" hdf5version", data=np.frombuffer(b"HDF5 Version 1.10.8".ljust(33, b"\0"), dtype="i1"))
    node(f, "CGNSLibraryVersion", "CGNSLibraryVersion_t", "R4", np.array([4.2], dtype="f4"))
    return node(f, "Base", "CGNSBase_t", "I4", np.array([3, 3], dtype="i4"))


def coordinates(zone, x, y, z):
    g = node(zone, "GridCoordinates", "GridCoordinates_t", "MT")
    for name, v in (("CoordinateX", x), ("CoordinateY", y), ("CoordinateZ", z)):
        node(g, name, "DataArray_t", "R8", v)


def structured():
    with h5py.File(HERE / "structured.cgns", "w") as f:
        b = base(f)
        ni, nj, nk = 4, 3, 2
        # Zone sizes (vertex, cell, boundary) x (i, j, k), stored reversed.
        zone = node(b, "Zone", "Zone_t", "I4", np.array([[ni, nj, nk], [ni - 1, nj - 1, nk - 1], [0, 0, 0]], dtype="i4"))
        node(zone, "ZoneType", "ZoneType_t", "C1", text("Structured"))
        k, j, i = np.meshgrid(np.arange(nk), np.arange(nj), np.arange(ni), indexing="ij")
        coordinates(zone, i.astype("f8"), j.astype("f8"), k.astype("f8"))
        cells = node(zone, "CellSolution", "FlowSolution_t", "MT")
        node(cells, "GridLocation", "GridLocation_t", "C1", text("CellCenter"))
        node(cells, "Rind", "Rind_t", "I4", np.array([1, 1, 1, 1, 1, 1], dtype="i4"))
        stored = np.full((nk - 1 + 2, nj - 1 + 2, ni - 1 + 2), -1.0)
        for kk in range(nk - 1):
            for jj in range(nj - 1):
                for ii in range(ni - 1):
                    stored[kk + 1, jj + 1, ii + 1] = ii + 3 * jj
        node(cells, "cell", "DataArray_t", "R8", stored)
        points = node(zone, "PointSolution", "FlowSolution_t", "MT")
        node(points, "f", "DataArray_t", "R4", (i + 2 * j + 3 * k).astype("f4"))
        for name, v in (("VelocityX", 3.0), ("VelocityY", 4.0), ("VelocityZ", 0.0)):
            node(points, name, "DataArray_t", "R8", np.full(i.shape, v))


def unstructured():
    with h5py.File(HERE / "unstructured.cgns", "w") as f:
        b = base(f)
        pts = np.array([
            [0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
            [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1],
            [2, 0, 0], [2, 1, 0], [2, 0, 1], [2, 1, 1],
            [0.5, 0.5, 1.5], [0, 0, 2],
        ], dtype="f8")
        zone = node(b, "Zone", "Zone_t", "I4", np.array([[len(pts)], [4], [0]], dtype="i4"))
        node(zone, "ZoneType", "ZoneType_t", "C1", text("Unstructured"))
        coordinates(zone, pts[:, 0], pts[:, 1], pts[:, 2])
        # 1-based vertex numbers; CGNS HEXA_8 order is VTK's.
        hexa = node(zone, "Hexahedra", "Elements_t", "I4", np.array([17, 0], dtype="i4"))
        node(hexa, "ElementRange", "IndexRange_t", "I4", np.array([1, 2], dtype="i4"))
        node(hexa, "ElementConnectivity", "DataArray_t", "I4",
             np.array([1, 2, 3, 4, 5, 6, 7, 8, 2, 9, 10, 3, 6, 11, 12, 7], dtype="i4"))
        mixed = node(zone, "Mixed", "Elements_t", "I4", np.array([20, 0], dtype="i4"))
        node(mixed, "ElementRange", "IndexRange_t", "I4", np.array([3, 4], dtype="i4"))
        # A pyramid on the first cube's top (apex 13), a tetrahedron on the
        # pyramid's face 5-6-13 with vertex 14.
        node(mixed, "ElementConnectivity", "DataArray_t", "I4",
             np.array([12, 5, 6, 7, 8, 13, 10, 5, 6, 13, 14], dtype="i4"))
        node(mixed, "ElementStartOffset", "DataArray_t", "I4", np.array([0, 6, 11], dtype="i4"))
        face = node(zone, "Bottom", "Elements_t", "I4", np.array([7, 0], dtype="i4"))
        node(face, "ElementRange", "IndexRange_t", "I4", np.array([5, 5], dtype="i4"))
        node(face, "ElementConnectivity", "DataArray_t", "I4", np.array([1, 4, 3, 2], dtype="i4"))
        sol = node(zone, "FlowSolution", "FlowSolution_t", "MT")
        node(sol, "GridLocation", "GridLocation_t", "C1", text("Vertex"))
        node(sol, "f", "DataArray_t", "R8", pts[:, 0] + 2 * pts[:, 1] + 3 * pts[:, 2])


def polyhedral():
    with h5py.File(HERE / "polyhedral.cgns", "w") as f:
        b = base(f)
        pts = np.array([
            [0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
            [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1],
            [0.5, 0.5, 1.5],
        ], dtype="f8")
        zone = node(b, "Zone", "Zone_t", "I4", np.array([[len(pts)], [2], [0]], dtype="i4"))
        node(zone, "ZoneType", "ZoneType_t", "C1", text("Unstructured"))
        coordinates(zone, pts[:, 0], pts[:, 1], pts[:, 2])
        # Faces by 1-based vertices, normals out of the cube, then out of
        # the pyramid.
        faces = [[1, 4, 3, 2], [5, 6, 7, 8], [1, 2, 6, 5], [2, 3, 7, 6], [3, 4, 8, 7],
                 [4, 1, 5, 8], [5, 6, 9], [6, 7, 9], [7, 8, 9], [8, 5, 9]]
        ngon = node(zone, "Faces", "Elements_t", "I4", np.array([22, 0], dtype="i4"))
        node(ngon, "ElementRange", "IndexRange_t", "I4", np.array([1, 10], dtype="i4"))
        node(ngon, "ElementConnectivity", "DataArray_t", "I4",
             np.array([v for face in faces for v in face], dtype="i4"))
        node(ngon, "ElementStartOffset", "DataArray_t", "I4",
             np.cumsum([0] + [len(face) for face in faces]).astype("i4"))
        nface = node(zone, "Cells", "Elements_t", "I4", np.array([23, 0], dtype="i4"))
        node(nface, "ElementRange", "IndexRange_t", "I4", np.array([11, 12], dtype="i4"))
        node(nface, "ElementConnectivity", "DataArray_t", "I4",
             np.array([6, 1, 2, 3, 4, 5, 6, 5, -2, 7, 8, 9, 10], dtype="i4"))
        sol = node(zone, "FlowSolution", "FlowSolution_t", "MT")
        node(sol, "GridLocation", "GridLocation_t", "C1", text("Vertex"))
        node(sol, "f", "DataArray_t", "R8", pts[:, 0] + 2 * pts[:, 1] + 3 * pts[:, 2])
        cells = node(zone, "CellSolution", "FlowSolution_t", "MT")
        node(cells, "GridLocation", "GridLocation_t", "C1", text("CellCenter"))
        node(cells, "cell", "DataArray_t", "R8", np.array([1.0, 2.0]))


def names(*words):
    """A C1 array of 32-character names, as the pointers of iterative data."""
    return np.frombuffer("".join(w.ljust(32) for w in words).encode(), dtype="i1").reshape(len(words), 32)


def temporal():
    with h5py.File(HERE / "temporal.cgns", "w") as f:
        b = base(f)
        ni, nj, nk = 3, 2, 2
        it = node(b, "BaseIterativeData", "BaseIterativeData_t", "I4", np.array([2], dtype="i4"))
        node(it, "TimeValues", "DataArray_t", "R8", np.array([0.5, 1.5]))
        zone = node(b, "Zone", "Zone_t", "I4", np.array([[ni, nj, nk], [ni - 1, nj - 1, nk - 1], [0, 0, 0]], dtype="i4"))
        node(zone, "ZoneType", "ZoneType_t", "C1", text("Structured"))
        zit = node(zone, "ZoneIterativeData", "ZoneIterativeData_t", "MT")
        node(zit, "FlowSolutionPointers", "DataArray_t", "C1", names("Step0", "Step1"))
        node(zit, "GridCoordinatesPointers", "DataArray_t", "C1", names("GridCoordinates", "Moved"))
        k, j, i = np.meshgrid(np.arange(nk), np.arange(nj), np.arange(ni), indexing="ij")
        coordinates(zone, i.astype("f8"), j.astype("f8"), k.astype("f8"))
        moved = node(zone, "Moved", "GridCoordinates_t", "MT")
        for name, v in (("CoordinateX", i + 10), ("CoordinateY", j), ("CoordinateZ", k)):
            node(moved, name, "DataArray_t", "R8", v.astype("f8"))
        for step in range(2):
            sol = node(zone, f"Step{step}", "FlowSolution_t", "MT")
            node(sol, "GridLocation", "GridLocation_t", "C1", text("Vertex"))
            node(sol, "f", "DataArray_t", "R8", ((step + 1) * i).astype("f8"))


def quadratic():
    """CGNS node orders (SIDS): corners, then edge midpoints (bottom, then
    vertical, then top), then face centres, then the body centre."""
    hexa = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
    hexa_edges = [(0, 1), (1, 2), (2, 3), (3, 0), (0, 4), (1, 5), (2, 6), (3, 7), (4, 5), (5, 6), (6, 7), (7, 4)]
    hexa_faces = [(0, 1, 2, 3), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (0, 3, 7, 4), (4, 5, 6, 7)]
    wedge = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1)]
    wedge_edges = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 4), (2, 5), (3, 4), (4, 5), (5, 3)]
    wedge_faces = [(0, 1, 4, 3), (1, 2, 5, 4), (2, 0, 3, 5)]
    pyramid = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 1)]
    pyramid_edges = [(0, 1), (1, 2), (2, 3), (3, 0), (0, 4), (1, 4), (2, 4), (3, 4)]
    pyramid_faces = [(0, 1, 2, 3)]

    def nodes(corners, edges, faces, centre):
        c = np.array(corners, dtype="f8")
        out = list(c) + [(c[a] + c[b]) / 2 for a, b in edges] + [c[list(f)].mean(axis=0) for f in faces]
        if centre:
            out.append(c.mean(axis=0))
        return out

    cells = [  # (CGNS code, nodes, x offset)
        (19, nodes(hexa, hexa_edges, hexa_faces, True), 0),
        (16, nodes(wedge, wedge_edges, wedge_faces, False), 2),
        (13, nodes(pyramid, pyramid_edges, pyramid_faces, False), 4),
        (18, nodes(hexa, hexa_edges, [], False), 6),
        (15, nodes(wedge, wedge_edges, [], False), 8),
    ]
    pts = []
    with h5py.File(HERE / "quadratic.cgns", "w") as f:
        b = base(f)
        sections = []
        for code, cell, dx in cells:
            first = len(pts) + 1
            pts.extend(p + np.array([dx, 0, 0]) for p in cell)
            sections.append((code, list(range(first, len(pts) + 1))))
        pts = np.array(pts)
        zone = node(b, "Zone", "Zone_t", "I4", np.array([[len(pts)], [len(cells)], [0]], dtype="i4"))
        node(zone, "ZoneType", "ZoneType_t", "C1", text("Unstructured"))
        coordinates(zone, pts[:, 0], pts[:, 1], pts[:, 2])
        for e, (code, conn) in enumerate(sections):
            sec = node(zone, f"Cell{e + 1}", "Elements_t", "I4", np.array([code, 0], dtype="i4"))
            node(sec, "ElementRange", "IndexRange_t", "I4", np.array([e + 1, e + 1], dtype="i4"))
            node(sec, "ElementConnectivity", "DataArray_t", "I4", np.array(conn, dtype="i4"))
        sol = node(zone, "FlowSolution", "FlowSolution_t", "MT")
        node(sol, "GridLocation", "GridLocation_t", "C1", text("Vertex"))
        node(sol, "f", "DataArray_t", "R8", pts[:, 0] + 2 * pts[:, 1] + 3 * pts[:, 2])


if __name__ == "__main__":
    structured()
    unstructured()
    polyhedral()
    temporal()
    quadratic()
    if shutil.which("hdf2adf"):
        for name in ("structured", "unstructured", "polyhedral", "temporal", "quadratic"):
            subprocess.run(["hdf2adf", HERE / f"{name}.cgns", HERE / f"{name}-adf.cgns"],
                           check=True, stdout=subprocess.DEVNULL)
