"""The web page from Python: ``Scene.to_html`` writes the page
``tetray export-html`` writes for the same mesh and flags, byte for byte
(so the browser tests of the CLI's pages cover it), as one file or a
folder; ``Scene.show`` gives notebooks the page in a frame."""

from __future__ import annotations

import html
import json
import re

import numpy as np

import tetray
from conftest import run_cli

SIZE = (40, 32)


def write_grid(path):
    nx, ny, nz = 5, 4, 3
    values = " ".join(f"{i * 0.25 + j * 0.1 + k * 0.05!r}" for k in range(nz) for j in range(ny) for i in range(nx))
    path.write_text(
        "# vtk DataFile Version 3.0\ngrid\nASCII\nDATASET STRUCTURED_POINTS\n"
        f"DIMENSIONS {nx} {ny} {nz}\nORIGIN 0 0 0\nSPACING 0.25 0.3333333 0.5\n"
        f"POINT_DATA {nx * ny * nz}\nSCALARS f double\nLOOKUP_TABLE default\n{values}\n"
    )
    return path


def manifest_of(page: str) -> dict:
    found = re.search(r'<script type="application/json" id="tetray-manifest">(.*?)</script>', page, re.S)
    assert found, "the page has no manifest"
    return json.loads(found.group(1))


def test_page_is_the_cli_page(tmp_path, tetray_bin):
    mesh = write_grid(tmp_path / "grid.vtk")
    scene = tetray.Scene(mesh, size=SIZE, renderer="cpu", elevation=20.0, integrator="exact")
    page = scene.to_html()
    run_cli(tetray_bin, ["export-html", mesh, "--size", "40x32", "--elevation", "20",
                         "--integrator", "exact", "-o", tmp_path / "cli.html"])
    assert page == (tmp_path / "cli.html").read_text(encoding="utf-8")
    manifest = manifest_of(page)
    assert manifest["method"] == "exact"
    assert manifest["size"] == list(SIZE)
    assert len(manifest["methods"]) == 8
    camera = scene.camera
    for key in ("position", "focal_point", "view_up"):
        # The page's camera is the scene's, in single precision.
        assert np.array_equal(np.float32(manifest["camera"][key]), np.float32(camera[key]))


def test_folder_and_notebook_page(tmp_path):
    mesh = write_grid(tmp_path / "grid.vtk")
    scene = tetray.Scene(mesh, size=SIZE, renderer="cpu")
    index = scene.to_html(tmp_path / "site", folder=True, bench=(2, 4))
    assert index == tmp_path / "site" / "index.html"
    text = index.read_text(encoding="utf-8")
    assert '<script src="scene.js"></script>' in text
    assert manifest_of(text)["bench"] == {"frames": 2, "views": 4}
    buffers = (tmp_path / "site" / "scene.js").read_text(encoding="utf-8")
    assert buffers.startswith("window.tetrayBuffers = {")
    for name in manifest_of(text)["buffers"]:
        assert f'"{name}":' in buffers
    single = scene.to_html(tmp_path / "one.html")
    assert single.read_text(encoding="utf-8") == scene.to_html()

    shown = scene.show()
    frame = shown._repr_html_()
    assert frame.startswith("<iframe srcdoc=")
    inner = re.search(r'srcdoc="(.*?)"', frame, re.S).group(1)
    assert html.unescape(inner) == shown.html == scene.to_html()
