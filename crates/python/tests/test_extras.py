"""segment, psi, compare, Scene views and orbits."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import tetray
from conftest import block_grid, max_diff, run_cli


def test_segment_constant_matches_closed_form():
    # Constant luminance L and attenuation tau over D: emitted L (1 - e^{-tau D}),
    # transmittance e^{-tau D} (eq. 2.1 with constant terms). f32 methods:
    # 1e-5 absolute.
    L, tau, D = 0.7, 1.3, 0.8
    for method in ("exact", "ppi", "reference"):
        out = tetray.segment(method, lb=L, lf=L, tau_b=tau, tau_f=tau, length=D)
        t = math.exp(-tau * D)
        assert out["transmittance"] == pytest.approx([t] * 3, abs=1e-5), method
        assert out["emitted"] == pytest.approx([L * (1 - t)] * 3, abs=1e-5), method


def test_segment_all_matches_cli(tetray_bin):
    args = dict(lb=(0.2, 0.5, 0.9), lf=0.4, tau_b=2.0, tau_f=0.5, length=1.5, incoming=0.1)
    ours = tetray.segment("all", **args)
    cli = json.loads(
        run_cli(
            tetray_bin,
            ["segment", "--lb", "0.2,0.5,0.9", "--lf", "0.4", "--tau-b", "2", "--tau-f", "0.5", "--length", "1.5", "--incoming", "0.1"],
        ).stdout
    )["methods"]
    assert [m["method"] for m in ours] == [m["method"] for m in cli]
    for a, b in zip(ours, cli):
        # Same f32 code; the JSON text round trip is exact for f32.
        assert a["colour"] == pytest.approx(b["colour"], abs=1e-7)
        assert a["abs_error"] == pytest.approx(b["abs_error"], abs=1e-7)
    with pytest.raises(ValueError, match="length"):
        tetray.segment("exact", lb=0, lf=0, tau_b=1, tau_f=1, length=-1)


def test_psi_against_f64_and_cli(tetray_bin):
    out = tetray.psi(0.3, 0.6, size=256)
    assert out["error_bilinear"] < 1e-3
    cli = json.loads(run_cli(tetray_bin, ["psi", "--gamma-b", "0.3", "--gamma-f", "0.6", "--size", "256"]).stdout)
    assert out["f64"] == pytest.approx(cli["f64"], rel=1e-12)
    assert out["table_bilinear"] == pytest.approx(cli["table_bilinear"], abs=1e-7)
    with pytest.raises(ValueError, match="outside"):
        tetray.psi(1.5, 0.2)


def test_compare_table_and_images():
    table, images = tetray.compare(block_grid(), ["cpu:exact", "cpu:average"], size=(24, 20))
    assert [row["label"] for row in table] == ["cpu exact", "cpu average"]
    assert images["reference"].shape == (20, 24, 4)
    exact, average = table
    # exact is the reference's model in f32; average is a coarser method.
    assert exact["abs_error"]["max"] < 1e-3
    assert average["abs_error"]["max"] >= exact["abs_error"]["max"]
    assert max_diff(images["cpu exact"], images["reference"]) == pytest.approx(exact["abs_error"]["max"], abs=1e-7)


def test_scene_views_and_orbit():
    scene = tetray.Scene(block_grid(), size=(24, 20), renderer="cpu")
    first = scene.render()
    again = scene.render(camera={k: scene.camera[k] for k in ("position", "focal_point", "view_up")})
    # The first view's camera, handed back in file coordinates (f64), gives
    # the same image up to the f32 rounding of the camera: 1e-4.
    assert max_diff(first, again) < 1e-4
    frames = scene.orbit(4)
    assert len(frames) == 4 and max_diff(frames[0], first) == 0.0
    assert max_diff(frames[1], first) > 0.01
    big = scene.render(size=(48, 40))
    assert big.shape == (40, 48, 4)
    over = scene.render(background=(1.0, 1.0, 1.0))
    assert over.shape == (20, 24, 3) and np.all(over >= first[..., :3] - 1e-7)
