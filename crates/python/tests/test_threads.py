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


def test_concurrent_renders_equal_serial_ones():
    """Four threads render at once, on one shared scene and on a scene of
    their own, each from its own azimuth: every image equals the same
    render made alone, bit for bit (the native work keeps no state between
    calls that another thread could change)."""
    from concurrent.futures import ThreadPoolExecutor

    import numpy as np

    azimuths = (0.0, 40.0, 80.0, 120.0)

    def scene():
        return tetray.Scene(DATA / "can.vtu", size=(48, 40), renderer="cpu")

    shared = scene()
    alone = [shared.render(azimuth=a) for a in azimuths]
    assert all(image[..., 3].max() > 0.05 for image in alone)
    with ThreadPoolExecutor(max_workers=4) as pool:
        on_shared = list(pool.map(lambda a: shared.render(azimuth=a), azimuths * 2))
        own = list(pool.map(lambda a: scene().render(azimuth=a), azimuths))
    for k, image in enumerate(on_shared):
        assert np.array_equal(image, alone[k % 4]), f"shared scene, azimuth {azimuths[k % 4]}"
    for k, image in enumerate(own):
        assert np.array_equal(image, alone[k]), f"own scene, azimuth {azimuths[k]}"


def test_ctrl_c_stops_a_long_render_and_leaves_the_scene_usable():
    """A SIGINT (Ctrl-C) during a long CPU render raises KeyboardInterrupt
    long before the render would have ended (the ray caster stops between
    bands of rows; Python's handler runs within 50 ms), and the scene then
    renders the same image as before."""
    import os
    import signal
    import time

    import numpy as np
    import pytest

    scene = tetray.Scene(DATA / "can.vtu", size=(48, 40), renderer="cpu")
    before = scene.render()
    # A render long enough to interrupt: at least a second here.
    side = 256
    while True:
        start = time.perf_counter()
        scene.render(size=(side, side))
        full = time.perf_counter() - start
        if full >= 1.0 or side >= 4096:
            break
        side *= 2
    timer = threading.Timer(0.2 * full, os.kill, (os.getpid(), signal.SIGINT))
    start = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        scene.render(size=(side, side))
    stopped = time.perf_counter() - start
    timer.join()
    assert stopped < 0.6 * full, f"stopped after {stopped:.2f} s of a {full:.2f} s render"
    assert np.array_equal(scene.render(), before)
