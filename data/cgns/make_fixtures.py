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

Run with h5py: python3 make_fixtures.py (writes into this folder)."""

from pathlib import Path

import h5py
import numpy as np

HERE = Path(__file__).resolve().parent


def node(parent, name, label, kind, data=None):
    g = parent.create_group(name)
    g.attrs.create("name", np.bytes_(name.ljust(32, "\0")[:33]))
    g.attrs.create("label", np.bytes_(label))
    g.attrs.create("type", np.bytes_(kind))
    g.attrs.create("flags", np.array([1], dtype="i4"))
    if data is not None:
        g.create_dataset(" data", data=data)
    return g


def text(s):
    return np.frombuffer(s.encode(), dtype="i1")


def base(f):
    f.create_dataset(" format", data=np.frombuffer(b"IEEE_LITTLE_32\0", dtype="i1"))
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


if __name__ == "__main__":
    structured()
    unstructured()
