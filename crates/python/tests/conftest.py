"""Shared fixtures: the CLI binary to compare with, and small meshes built
with PyVista (VTK's own code, independent of tetray)."""

from __future__ import annotations

import os
import pathlib
import subprocess
from typing import List, Sequence

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[3]
DATA = REPO / "data" / "real"


def _tetray_bin() -> pathlib.Path:
    given = os.environ.get("TETRAY_BIN")
    if given:
        path = pathlib.Path(given)
    else:
        target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
        path = target / "debug" / "tetray"
    if not path.is_file():
        pytest.fail(f"the tetray CLI is not at {path}: build it (cargo build --bin tetray) and set TETRAY_BIN")
    return path


@pytest.fixture(scope="module")
def tetray_bin() -> pathlib.Path:
    return _tetray_bin()


def run_cli(bin_path: pathlib.Path, args: Sequence[str]) -> subprocess.CompletedProcess:
    result = subprocess.run([str(bin_path), *map(str, args)], capture_output=True, text=True)
    if result.returncode != 0:
        pytest.fail(f"tetray {' '.join(map(str, args))} failed:\n{result.stderr}")
    return result


@pytest.fixture
def cli_render(tetray_bin, tmp_path):
    """tetray render MESH --renderer cpu --size WxH -o out.npy FLAGS, read
    back with numpy.load."""

    def render(mesh, size, flags: List[str] = ()) -> np.ndarray:
        out = tmp_path / f"cli_{len(list(tmp_path.iterdir()))}.npy"
        run_cli(
            tetray_bin,
            ["render", mesh, "--renderer", "cpu", "--size", f"{size[0]}x{size[1]}", "-o", out, *flags],
        )
        image = np.load(out)
        assert image.dtype == np.float32 and image.shape == (size[1], size[0], 4)
        return image

    return render


def block_grid():
    """A 6x5x4-point block of hexahedra, its points moved off the regular
    lattice, with a smooth point field "p" and a cell field "c"."""
    import pyvista as pv

    image = pv.ImageData(dimensions=(6, 5, 4), spacing=(0.5, 0.6, 0.7), origin=(1.0, -2.0, 0.5))
    grid = image.cast_to_unstructured_grid()
    pts = np.array(grid.points, dtype=np.float64)
    pts += 0.05 * np.sin(3.0 * pts[:, [1, 2, 0]])
    grid.points = pts
    x, y, z = pts.T
    grid.point_data["p"] = np.sin(2.0 * x) * np.cos(y) + 0.3 * z
    grid.point_data["flat"] = np.full(len(pts), 2.5)
    grid.cell_data["c"] = np.arange(grid.n_cells, dtype=np.float64)
    return grid


def tet_grid():
    """``block_grid`` cut into tetrahedra by VTK (triangulate)."""
    return block_grid().triangulate()


def max_diff(a: np.ndarray, b: np.ndarray) -> float:
    assert a.shape == b.shape, (a.shape, b.shape)
    diff = float(np.max(np.abs(a.astype(np.float64) - b.astype(np.float64))))
    print(f"max |difference| {diff:.3g}")
    return diff
