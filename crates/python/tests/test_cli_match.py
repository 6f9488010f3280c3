"""A mesh from PyVista renders the image ``tetray render`` makes of the same
mesh written to a file by VTK, with the same flags.

Tolerance 1e-6 per channel: both go through the same assembly of the same
arrays and the same f32 ray caster, so they should agree to the bit; 1e-6
leaves room only for an f64 -> text -> f64 difference in the file's points
(VTK writes them binary, so none is expected)."""

from __future__ import annotations

import json

import numpy as np
import pyvista as pv
import pytest

import tetray
from conftest import DATA, block_grid, max_diff, run_cli, tet_grid

TOL = 1e-6
SIZE = (48, 40)


@pytest.fixture
def block_vtu(tmp_path):
    grid = block_grid()
    path = tmp_path / "block.vtu"
    grid.save(path)
    return grid, path


def test_pyvista_grid_matches_cli_defaults(block_vtu, cli_render):
    grid, path = block_vtu
    ours = tetray.render(grid, size=SIZE, renderer="cpu")
    theirs = cli_render(path, SIZE)
    assert ours.dtype == np.float32 and ours.shape == (SIZE[1], SIZE[0], 4)
    assert ours[..., 3].max() > 0.05, "the default view shows the volume"
    assert max_diff(ours, theirs) <= TOL


def test_tetrahedra_with_flags_match_cli(tmp_path, cli_render):
    grid = tet_grid()
    path = tmp_path / "tets.vtu"
    grid.save(path)
    preset = [
        {
            "Name": "test",
            "ColorSpace": "RGB",
            "RGBPoints": [0.0, 0.1, 0.2, 0.9, 0.5, 0.9, 0.9, 0.2, 1.0, 0.8, 0.1, 0.1],
            "Points": [0.0, 0.0, 0.5, 0.0, 1.0, 0.8, 0.5, 0.0],
        }
    ]
    tf_path = tmp_path / "preset.json"
    tf_path.write_text(json.dumps(preset))
    ours = tetray.render(
        grid,
        "p",
        size=SIZE,
        renderer="cpu",
        integrator="exact",
        tf=preset,
        unit_distance=0.4,
        opacity_mode="vtk",
        early_termination=0.98,
    )
    theirs = cli_render(
        path,
        SIZE,
        [
            "--scalar", "p", "--integrator", "exact", "--tf", tf_path, "--unit-distance", "0.4",
            "--opacity-mode", "vtk", "--early-termination", "0.98",
        ],
    )
    assert ours[..., 3].max() > 0.05
    assert max_diff(ours, theirs) <= TOL


def test_constant_field_renders_solid_like_cli(block_vtu, cli_render):
    grid, path = block_vtu
    with pytest.warns(RuntimeWarning, match="constant"):
        ours = tetray.render(grid, "flat", size=SIZE, renderer="cpu")
    theirs = cli_render(path, SIZE, ["--scalar", "flat"])
    assert ours[..., 3].max() > 0.05
    assert max_diff(ours, theirs) <= TOL


def test_pyvista_camera_position_matches_vtk_flags(block_vtu, cli_render):
    grid, path = block_vtu
    cpos = [(6.0, -7.0, 5.0), (2.2, -0.8, 1.6), (0.0, 0.0, 1.0)]
    ours = tetray.render(grid, size=SIZE, renderer="cpu", camera=cpos, view_angle=25.0)
    flags = ["--camera-position", "6,-7,5", "--focal-point", "2.2,-0.8,1.6", "--view-up", "0,0,1", "--view-angle", "25"]
    theirs = cli_render(path, SIZE, flags)
    assert ours[..., 3].max() > 0.05
    assert max_diff(ours, theirs) <= TOL
    # The same view as a pyvista.Camera object, orthographic.
    camera = pv.Camera()
    camera.position, camera.focal_point, camera.up = cpos
    camera.parallel_projection = True
    camera.parallel_scale = 2.5
    ours = tetray.render(grid, size=SIZE, renderer="cpu", camera=camera)
    theirs = cli_render(path, SIZE, flags[:6] + ["--parallel-scale", "2.5"])
    assert ours[..., 3].max() > 0.05
    assert max_diff(ours, theirs) <= TOL


def test_azimuth_elevation_default_and_zero(block_vtu, cli_render):
    grid, path = block_vtu
    scene = tetray.Scene(grid, size=SIZE, renderer="cpu")
    zero = scene.render(azimuth=0, elevation=0)
    assert max_diff(zero, cli_render(path, SIZE, ["--azimuth", "0", "--elevation", "0"])) <= TOL
    turned = scene.render(azimuth=-40, elevation=15)
    assert max_diff(turned, cli_render(path, SIZE, ["--azimuth", "-40", "--elevation", "15"])) <= TOL
    # No camera value: the CLI's oblique default, which is not the plain fit.
    default = scene.render()
    assert max_diff(default, cli_render(path, SIZE)) <= TOL
    assert max_diff(default, zero) > 0.01
    assert tetray.DEFAULT_VIEW == (30.0, 20.0)


def test_path_and_rgb8_match_cli_png(tetray_bin, tmp_path, cli_render):
    from PIL import Image

    mesh = DATA / "tetra.vtu"
    ours = tetray.render(mesh, size=SIZE, renderer="cpu")
    assert max_diff(ours, cli_render(mesh, SIZE)) <= TOL
    png = tmp_path / "out.png"
    run_cli(
        tetray_bin,
        ["render", mesh, "--renderer", "cpu", "--size", f"{SIZE[0]}x{SIZE[1]}", "--background", "0.2,0.3,0.4", "-o", png],
    )
    pixels = np.asarray(Image.open(png).convert("RGB"))
    # Exact: the same f32 compositing and rounding as the CLI's writer.
    assert np.array_equal(tetray.to_rgb8(ours, (0.2, 0.3, 0.4)), pixels)


def test_info_matches_cli_info(block_vtu, tetray_bin):
    grid, path = block_vtu
    info = tetray.Scene(grid, size=(8, 8), renderer="cpu").info
    cli = json.loads(run_cli(tetray_bin, ["info", path, "--json"]).stdout)
    for key in ("points", "tets", "boundary_faces", "interior_faces", "components", "input_cells"):
        assert info[key] == cli[key], key
    assert [f["name"] for f in info["fields"]] == [f["name"] for f in cli["fields"]]
    assert info["field"] == "p" and info["renderer"] == "cpu" and info["integrator"] == "ppi"
