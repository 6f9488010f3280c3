"""meshio meshes, plain arrays, PyVista ImageData and StructuredGrid, and
paths render; each is compared with ``tetray render`` on the same mesh
written by an independent writer (meshio or VTK). Tolerance 1e-6 as in
test_cli_match.py (the same assembly and ray caster on both sides)."""

from __future__ import annotations

import meshio
import numpy as np
import pyvista as pv
import pytest

import tetray
from conftest import DATA, max_diff, tet_grid

TOL = 1e-6
SIZE = (40, 32)


def _tets():
    grid = tet_grid()
    points = np.array(grid.points, dtype=np.float64)
    tets = np.array(grid.cell_connectivity, dtype=np.int64).reshape(-1, 4)
    return points, tets, np.array(grid.point_data["p"])


def test_meshio_mesh_matches_cli(tmp_path, cli_render):
    points, tets, p = _tets()
    mesh = meshio.Mesh(points, [("tetra", tets)], point_data={"p": p})
    path = tmp_path / "m.vtu"
    meshio.write(path, mesh)
    ours = tetray.render(mesh, size=SIZE, renderer="cpu")
    assert ours[..., 3].max() > 0.05
    assert max_diff(ours, cli_render(path, SIZE)) <= TOL


def test_plain_arrays_match_cli(tmp_path, cli_render):
    points, tets, p = _tets()
    path = tmp_path / "a.vtu"
    meshio.write(path, meshio.Mesh(points, [("tetra", tets)], point_data={"values": p}))
    expected = cli_render(path, SIZE, ["--integrator", "average"])
    # (points, (m, 4) tetrahedra) with the values as scalars=...
    ours = tetray.render((points, tets), p, size=SIZE, renderer="cpu", integrator="average")
    assert max_diff(ours, expected) <= TOL
    # VTK connectivity + offsets + cell types, in a dict.
    arrays = {
        "points": points,
        "cells": tets.reshape(-1),
        "offsets": np.arange(0, 4 * len(tets) + 1, 4),
        "celltypes": np.full(len(tets), 10),
        "point_data": {"values": p},
    }
    ours = tetray.render(arrays, size=SIZE, renderer="cpu", integrator="average")
    assert max_diff(ours, expected) <= TOL
    # VTK's legacy count-prefixed layout (PyVista's grid.cells).
    legacy = np.hstack([np.full((len(tets), 1), 4), tets]).reshape(-1)
    grid = tetray.mesh(points, legacy, celltypes=np.full(len(tets), 10), point_data={"values": p})
    assert max_diff(tetray.render(grid, size=SIZE, renderer="cpu", integrator="average"), expected) <= TOL


@pytest.mark.parametrize("kind", ["ImageData", "StructuredGrid", "RectilinearGrid"])
def test_structured_pyvista_matches_cli(tmp_path, cli_render, kind):
    image = pv.ImageData(dimensions=(7, 6, 5), spacing=(0.25, 0.3, 0.4), origin=(-1.0, 0.0, 2.0))
    if kind == "StructuredGrid":
        grid = image.cast_to_structured_grid()
        grid.points = grid.points + 0.03 * np.sin(4.0 * grid.points[:, [2, 0, 1]])
        ext = "vts"
    elif kind == "RectilinearGrid":
        grid = pv.RectilinearGrid(np.array([0.0, 0.2, 0.5, 0.9, 1.0]), np.linspace(0, 1, 4), np.array([0.0, 0.1, 0.7]))
        ext = "vtr"
    else:
        grid = image
        ext = "vti"
    x, y, z = np.asarray(grid.points).T
    grid.point_data["d"] = np.exp(-((x + 0.2) ** 2 + (y - 0.7) ** 2)) + 0.1 * z
    path = tmp_path / f"g.{ext}"
    grid.save(path)
    ours = tetray.render(grid, size=SIZE, renderer="cpu")
    assert ours[..., 3].max() > 0.02
    assert max_diff(ours, cli_render(path, SIZE)) <= TOL


def test_path_formats_render(cli_render):
    for name in ("StructuredGrid.vts", "uGridEx.vtk", "can.vtu", "multi.cgns"):
        path = DATA / name
        ours = tetray.render(str(path), size=(24, 20), renderer="cpu")
        assert ours.shape == (20, 24, 4)
        assert max_diff(ours, cli_render(path, (24, 20))) <= TOL


def test_both_cgns_storages_render_the_same_image():
    """VTK's multi.cgns in its ADF storage and its HDF5 twin (adf2hdf):
    the same mesh and arrays, so the same image, bit for bit."""
    adf = tetray.render(str(DATA / "multi.cgns"), size=(32, 24), renderer="cpu", scalars="Density")
    hdf5 = tetray.render(str(DATA / "multi-hdf5.cgns"), size=(32, 24), renderer="cpu", scalars="Density")
    assert adf[..., 3].max() > 0.0
    assert np.array_equal(adf, hdf5)


def test_cmap_and_opacity_pyvista_habits():
    points, tets, p = _tets()
    grid = (points, tets, None, {"p": p})
    a = tetray.render(grid, size=SIZE, renderer="cpu", cmap="viridis", opacity="linear")
    b = tetray.render(grid, size=SIZE, renderer="cpu", cmap="viridis", opacity=[0.0, 1.0])
    # "linear" is the list [0, 1] spread over the range: the same curve.
    assert max_diff(a, b) <= TOL
    c = tetray.render(grid, size=SIZE, renderer="cpu", cmap="viridis", opacity="sigmoid", clim=(p.min(), p.max() * 2))
    assert a[..., 3].max() > 0.05 and max_diff(a, c) > 0.01
    import matplotlib

    d = tetray.render(grid, size=SIZE, renderer="cpu", cmap=matplotlib.colormaps["viridis"], opacity="linear")
    assert max_diff(a, d) <= TOL
    # Greens has no red at the top of the map, viridis does.
    g = tetray.render(grid, size=SIZE, renderer="cpu", cmap="Greens", opacity=0.5)
    assert g[..., 1].sum() > g[..., 0].sum()
