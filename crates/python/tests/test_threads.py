"""A render runs while another Python thread runs: the GIL is released
around the native work. The main thread records its loop times while a
render runs on a worker; with the GIL held for the whole render the main
thread would stall for about the render's duration."""

from __future__ import annotations

import threading
import time

import tetray
from conftest import DATA


def test_render_releases_the_gil():
    scene = tetray.Scene(DATA / "can.vtu", size=(160, 160), renderer="cpu")
    start = time.perf_counter()
    scene.render()
    single = time.perf_counter() - start
    frames = max(1, int(0.6 / max(single, 1e-3)) + 1)
    result = {}

    def work():
        t0 = time.perf_counter()
        for _ in range(frames):
            result["image"] = scene.render()
        result["seconds"] = time.perf_counter() - t0

    worker = threading.Thread(target=work)
    stamps = [time.perf_counter()]
    worker.start()
    while worker.is_alive():
        sum(range(200))  # Python work that needs the GIL
        stamps.append(time.perf_counter())
    worker.join()
    gaps = [b - a for a, b in zip(stamps, stamps[1:])]
    assert result["image"].shape == (160, 160, 4)
    assert result["seconds"] >= 0.3, "the render must take long enough to tell"
    # Python switches threads every 5 ms; a held GIL would stall the loop
    # for a whole frame (>= 0.3 s / frames). Allow 0.1 s for a busy machine.
    assert max(gaps) < max(0.1, 0.5 * result["seconds"] / frames), max(gaps)
    assert len(stamps) > 50
