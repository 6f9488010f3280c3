"""A render runs while another Python thread runs: the GIL is released
around the native work. Shown by what the other thread gets done while the
render is in progress, not by a clock.

The switch interval is raised so that a thread holding the GIL keeps it
until it blocks or releases it: once the worker has entered `render`, the
main thread can run only if `render` released the GIL. With the GIL held,
the main thread would first run after the render returned, and count
nothing."""

from __future__ import annotations

import sys
import threading

import tetray
from conftest import DATA


def test_render_releases_the_gil():
    scene = tetray.Scene(DATA / "can.vtu", size=(64, 64), renderer="cpu")
    entering = threading.Event()
    finished = threading.Event()
    result = {}

    def work():
        entering.set()
        result["image"] = scene.render()
        finished.set()

    interval = sys.getswitchinterval()
    sys.setswitchinterval(2.0)
    try:
        worker = threading.Thread(target=work)
        worker.start()
        entering.wait()
        during = 0
        while not finished.is_set():
            during += 1  # Python work that needs the GIL
        worker.join()
    finally:
        sys.setswitchinterval(interval)
    assert result["image"].shape == (64, 64, 4)
    assert during > 0, "the main thread never ran while the render was in progress"
