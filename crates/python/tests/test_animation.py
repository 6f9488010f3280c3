"""Animations from Python: ``Scene.frames`` over a three-step series written
here (one grid; the field f = (k + 1) x at step k, x in [0, 1]) makes the
frames ``tetray animate`` makes: each is the render of its step in the
range the field spans over all the steps (0 to 3), bit for bit; an orbit of
one step turns the view."""

from __future__ import annotations

import base64
import json

import numpy as np
import pytest

import tetray
from conftest import DATA, REPO, run_cli

SIZE = (40, 32)


def write_series(folder):
    nx, ny, nz = 5, 4, 3
    for k in range(3):
        values = " ".join(f"{(k + 1) * i / (nx - 1)!r}" for _ in range(nz * ny) for i in range(nx))
        (folder / f"s{k}.vtk").write_text(
            "# vtk DataFile Version 3.0\nstep\nASCII\nDATASET STRUCTURED_POINTS\n"
            f"DIMENSIONS {nx} {ny} {nz}\nORIGIN 0 0 0\nSPACING 0.25 0.3333333 0.5\n"
            f"POINT_DATA {nx * ny * nz}\nSCALARS f double\nLOOKUP_TABLE default\n{values}\n"
        )
    files = [{"name": f"s{k}.vtk", "time": 0.5 * k} for k in range(3)]
    (folder / "s.series").write_text(json.dumps({"file-series-version": "1.0", "files": files}))
    return folder / "s.series"


def test_frames_are_the_renders_of_their_steps_in_one_range(tmp_path, tetray_bin):
    series = write_series(tmp_path)
    common = dict(size=SIZE, renderer="cpu", elevation=20.0)
    scene = tetray.Scene(series, **common)
    assert scene.info["times"] == [0.0, 0.5, 1.0]
    frames = list(scene.frames())
    assert len(frames) == 3
    for k, frame in enumerate(frames):
        alone = tetray.Scene(series, time_step=k, clim=(0.0, 3.0), **common).render()
        assert np.array_equal(frame, alone), f"step {k}"
    assert not np.array_equal(frames[0], frames[2])
    # The CLI's frames, from the same flags: the same pixels.
    run_cli(tetray_bin, ["animate", series, "-o", f"{tmp_path}/cli/", "--renderer", "cpu",
                         "--size", f"{SIZE[0]}x{SIZE[1]}", "--elevation", "20"])
    from PIL import Image

    for k, frame in enumerate(frames):
        cli = np.asarray(Image.open(tmp_path / "cli" / f"frame_{k:04d}.png").convert("RGB"))
        assert np.array_equal(tetray.to_rgb8(frame), cli), f"step {k}"
    # Two steps, given as a pair.
    assert len(list(scene.frames(times=(1, 2)))) == 2


def test_an_orbit_of_one_step_turns_the_view(tmp_path):
    series = write_series(tmp_path)
    scene = tetray.Scene(tmp_path / "s0.vtk", size=SIZE, renderer="cpu")
    frames = list(scene.frames(orbit=180.0, n_frames=4))
    assert len(frames) == 4
    assert np.abs(frames[0] - scene.render()).max() < 1e-6
    assert not np.array_equal(frames[0], frames[2])
    with pytest.raises(ValueError, match="orbit="):
        next(scene.frames())
    with pytest.raises(ValueError, match="out of range"):
        next(tetray.Scene(series, size=SIZE, renderer="cpu").frames(times=[0, 5]))


def test_animate_writes_what_the_cli_writes(tmp_path, tetray_bin):
    """``Scene.animate`` to a folder of PNG frames and to a GIF: the folder
    holds the CLI's frames, byte for byte decoded; the GIF one frame per
    step. ``_repr_png_`` is the first view's PNG."""
    from PIL import Image

    series = write_series(tmp_path)
    scene = tetray.Scene(series, size=SIZE, renderer="cpu", elevation=20.0)
    assert scene.animate(f"{tmp_path}/py/", background=(0.1, 0.2, 0.3)) == 3
    run_cli(tetray_bin, ["animate", series, "-o", f"{tmp_path}/cli/", "--renderer", "cpu",
                         "--size", f"{SIZE[0]}x{SIZE[1]}", "--elevation", "20", "--background", "0.1,0.2,0.3"])
    for k in range(3):
        py = np.asarray(Image.open(tmp_path / "py" / f"frame_{k:04d}.png"))
        cli = np.asarray(Image.open(tmp_path / "cli" / f"frame_{k:04d}.png"))
        assert np.array_equal(py, cli), f"frame {k}"
    assert scene.animate(tmp_path / "s.gif", times=(0, 1), fps=5) == 2
    with Image.open(tmp_path / "s.gif") as gif:
        assert gif.n_frames == 2 and gif.size == SIZE
    with pytest.raises(ValueError, match="write a .gif, a .mp4"):
        scene.animate(tmp_path / "s.txt")
    png = scene._repr_png_()
    import io

    shown = np.asarray(Image.open(io.BytesIO(png)))
    assert np.array_equal(shown, tetray.to_rgb8(scene.render()))


def test_animation_shows_inline_as_the_file_animate_writes(tmp_path):
    series = write_series(tmp_path)
    scene = tetray.Scene(series, size=SIZE, renderer="cpu", elevation=20.0)
    shown = scene.animation(fps=5)
    assert (shown.format, shown.frames, shown.size) == ("gif", 3, SIZE)
    scene.animate(tmp_path / "file.gif", fps=5)
    assert shown.data == (tmp_path / "file.gif").read_bytes()
    html = shown._repr_html_()
    assert html.startswith('<img src="data:image/gif;base64,')
    encoded = html.split("base64,", 1)[1].split('"', 1)[0]
    assert base64.b64decode(encoded) == shown.data
    assert shown.save(tmp_path / "saved.gif").read_bytes() == shown.data
    with pytest.raises(ValueError, match="format"):
        scene.animation(format="avi")


@pytest.mark.parametrize(
    "path, scalars",
    [(DATA / "series" / "can" / "can.hdf.series", "EQPS"), (REPO / "data" / "exodus" / "tet_wedge_netcdf4.exo", None)],
    ids=["crushed can (points move)", "exodus (mesh shared)"],
)
def test_real_series_animate_as_the_cli_does(tmp_path, tetray_bin, path, scalars):
    """The crushed can (its points move between steps) and an Exodus file
    with three steps: ``frames`` gives the frames ``tetray animate`` writes,
    and ``animate`` writes an MP4 of one frame per step."""
    from PIL import Image

    scene = tetray.Scene(path, size=SIZE, renderer="cpu", scalars=scalars)
    frames = list(scene.frames())
    assert len(frames) == 3
    flags = ["--scalar", scalars] if scalars else []
    run_cli(tetray_bin, ["animate", path, "-o", f"{tmp_path}/cli/", "--renderer", "cpu",
                         "--size", f"{SIZE[0]}x{SIZE[1]}", *flags])
    for k, frame in enumerate(frames):
        cli = np.asarray(Image.open(tmp_path / "cli" / f"frame_{k:04d}.png").convert("RGB"))
        assert np.array_equal(tetray.to_rgb8(frame), cli), f"step {k}"
    assert scene.animate(tmp_path / "run.mp4", fps=5) == 3
    import subprocess

    probe = subprocess.run(
        ["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
         "stream=nb_read_frames,width,height", "-of", "csv=p=0", str(tmp_path / "run.mp4")],
        capture_output=True, text=True, check=True,
    )
    assert probe.stdout.strip() == f"{SIZE[0]},{SIZE[1]},3"
