"""What a frame costs from Python against the CLI's `tetray bench`, and
what handing a 1 M-cell PyVista grid to tetray costs. A benchmark, not a
test: it prints a table (and JSON with --json).

    python crates/python/bench/overhead.py --tetray target/release/tetray

Frame: the same mesh, flags and view (`tetray bench --orbit-step 0`: ten
frames of the default view after a warm-up frame; its median render time)
against `Scene.render()` from Python (same warm-up, median wall time of
the call, which includes the camera, releasing the GIL and making the
NumPy array). Conversion: a 100^3-cell PyVista grid (ImageData cast to an
UnstructuredGrid of 1 M voxels, one point field) to the native Grid
(tetray's Python side: arrays to float64/int64, one copy into the raw
grid), then the load (assembly into 6 M tetrahedra, topology, checks),
reported apart, beside the CLI's load of the same grid written as .vtu.
"""

from __future__ import annotations

import argparse
import json
import pathlib
import statistics
import subprocess
import tempfile
import time

import numpy as np

import tetray
from tetray import _mesh

REPO = pathlib.Path(__file__).resolve().parents[3]


def cli_json(binary: str, args) -> dict:
    out = subprocess.run([binary, *map(str, args)], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def frame(binary: str, mesh: pathlib.Path, size, frames: int, renderer: str) -> dict:
    w, h = size
    cli = cli_json(
        binary,
        ["bench", mesh, "--renderer", renderer, "--size", f"{w}x{h}", "--frames", frames, "--orbit-step", "0"],
    )
    scene = tetray.Scene(mesh, size=size, renderer=renderer)
    scene.render()  # warm-up, as the CLI's
    times = []
    for _ in range(frames):
        start = time.perf_counter()
        image = scene.render()
        times.append(time.perf_counter() - start)
    assert image.shape == (h, w, 4)
    py_ms = statistics.median(times) * 1e3
    return {
        "mesh": str(mesh.relative_to(REPO)) if mesh.is_relative_to(REPO) else str(mesh),
        "tets": cli["tets"],
        "size": f"{w}x{h}",
        "renderer": cli["renderer"],
        "adapter": cli["adapter"],
        "cli_ms_median": cli["ms_per_frame_median"],
        "python_ms_median": py_ms,
        "overhead_percent": 100.0 * (py_ms / cli["ms_per_frame_median"] - 1.0),
    }


def conversion(binary: str, cells_per_axis: int) -> dict:
    import pyvista as pv

    n = cells_per_axis
    image = pv.ImageData(dimensions=(n + 1, n + 1, n + 1), spacing=(1.0 / n,) * 3)
    grid = image.cast_to_unstructured_grid()
    x, y, z = np.asarray(grid.points).T
    grid.point_data["f"] = np.sin(6 * x) * np.cos(5 * y) + z
    start = time.perf_counter()
    source, _ = _mesh.to_source(grid)
    convert_s = time.perf_counter() - start
    start = time.perf_counter()
    scene = tetray.Scene(source, size=(64, 64), renderer="cpu")
    scene_s = time.perf_counter() - start
    info = scene.info
    with tempfile.TemporaryDirectory() as tmp:
        path = pathlib.Path(tmp) / "grid.vtu"
        grid.save(path, binary=True)
        cli = cli_json(binary, ["info", path, "--json"])
    return {
        "cells": grid.n_cells,
        "points": grid.n_points,
        "tets": info["tets"],
        "convert_s": convert_s,
        "python_load_s": info["load_seconds"],
        "python_scene_s": scene_s,
        "cli_load_s_from_vtu": cli["load_seconds"],
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tetray", required=True, help="the CLI binary (a release build)")
    parser.add_argument("--mesh", type=pathlib.Path, action="append")
    parser.add_argument("--size", type=int, nargs=2, default=(512, 512))
    parser.add_argument("--frames", type=int, default=10)
    parser.add_argument("--renderer", default="cpu")
    parser.add_argument("--cells-per-axis", type=int, default=100)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    meshes = args.mesh or [REPO / "data" / "plot3d" / "bluntfinxyz.bin", REPO / "data" / "real" / "can.vtu"]
    import warnings

    warnings.simplefilter("ignore")  # the meshes' load notes
    frames = [frame(args.tetray, m.resolve(), tuple(args.size), args.frames, args.renderer) for m in meshes]
    conv = conversion(args.tetray, args.cells_per_axis) if args.cells_per_axis > 0 else None
    if args.json:
        print(json.dumps({"frames": frames, "conversion": conv}, indent=2))
        return
    print("| mesh | tets | size | renderer | CLI bench ms (median) | Python ms (median) | overhead |")
    print("| --- | ---: | --- | --- | ---: | ---: | ---: |")
    for f in frames:
        print(
            f"| {f['mesh']} | {f['tets']} | {f['size']} | {f['renderer']} | {f['cli_ms_median']:.1f} | "
            f"{f['python_ms_median']:.1f} | {f['overhead_percent']:+.1f}% |"
        )
    if conv:
        print()
        print(
            f"{conv['cells']} cells ({conv['points']} points) from PyVista: conversion {conv['convert_s']:.3f} s, "
            f"load {conv['python_load_s']:.2f} s ({conv['tets']} tetrahedra; scene with BVH and tables "
            f"{conv['python_scene_s']:.2f} s); the CLI loads the same grid from .vtu in {conv['cli_load_s_from_vtu']:.2f} s"
        )


if __name__ == "__main__":
    main()
