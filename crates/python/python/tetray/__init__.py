"""tetray: exact volume rendering of unstructured meshes, from Python.

``tetray.render(mesh)`` returns a (height, width, 4) float32 image with
premultiplied colour and alpha (what ``tetray render -o image.exr`` writes);
``tetray.to_rgb8(image, background)`` gives the PNG's pixels. ``mesh`` is a
path (every format the CLI reads), a PyVista dataset with volume cells, a
meshio.Mesh, or plain arrays. ``tetray.Scene`` keeps a loaded mesh for
many views. Defaults are the CLI's: the same call gives the same image as
``tetray render`` with the same flags.
"""

from __future__ import annotations

import base64
import json
import os
import pathlib
import tempfile
import warnings
from html import escape as html_escape
from typing import Any, Dict, Iterator, List, Optional, Sequence, Tuple

import numpy as np

from . import _camera, _mesh, _native, _tf

__all__ = ["render", "to_rgb8", "Scene", "Page", "Animation", "compare", "segment", "psi", "mesh", "methods", "DEFAULT_VIEW"]

#: Azimuth and elevation (degrees) the CLI turns its ResetCamera fit by
#: when no camera value at all is given.
DEFAULT_VIEW: Tuple[float, float] = tuple(_native.DEFAULT_VIEW)

mesh = _mesh.unstructured
methods = _native.methods


def _size(size: Any) -> Tuple[int, int]:
    try:
        w, h = (int(v) for v in size)
    except (TypeError, ValueError):
        raise ValueError(f"size: expected (width, height), got {size!r}") from None
    return w, h


class Scene:
    """A mesh loaded once (topology, BVH, integrator tables, GPU uploads)
    and rendered from many cameras.

    Takes ``tetray.render``'s arguments but the per-view ones; ``camera``,
    ``azimuth``, ``elevation`` here set the first view (``scene.camera``),
    which ``render()`` without arguments draws.
    """

    def __init__(
        self,
        mesh: Any,
        scalars: Any = None,
        *,
        size: Sequence[int] = (512, 512),
        integrator: str = "ppi",
        renderer: str = "auto",
        camera: Any = None,
        azimuth: Optional[float] = None,
        elevation: Optional[float] = None,
        view_angle: Optional[float] = None,
        parallel_scale: Optional[float] = None,
        tf: Any = None,
        tf_name: Optional[str] = None,
        rescale: bool = True,
        cmap: Any = None,
        opacity: Any = None,
        clim: Any = None,
        unit_distance: Optional[float] = None,
        opacity_mode: str = "exact",
        early_termination: float = 1.0,
        max_steps: Optional[int] = None,
        linearize: str = "subdivide",
        q: Any = None,
        time_step: Optional[int] = None,
        time: Optional[float] = None,
        block: Optional[str] = None,
        name: Optional[str] = None,
    ) -> None:
        # What the scene was made from, to make the other time steps'.
        self._args = {k: v for k, v in locals().items() if k != "self"}
        source, field = _mesh.to_source(mesh, scalars, name)
        tf_json = None if tf is None else _tf.preset(tf)
        if tf_json is not None and (cmap is not None or opacity is not None):
            raise ValueError("give tf (a ParaView preset) or cmap/opacity, not both")
        tf_points = None if cmap is None and opacity is None else _tf.points(cmap, opacity)
        self._size = _size(size)
        self._native = _native.Scene(
            source,
            scalars=field,
            size=self._size,
            integrator=integrator,
            renderer=renderer,
            camera=_camera.options(camera, azimuth, elevation, view_angle, parallel_scale),
            tf_json=tf_json,
            tf_name=tf_name,
            tf_rescale=rescale,
            tf_points=tf_points,
            clim=_tf.clim_range(clim),
            unit_distance=unit_distance,
            opacity_mode=opacity_mode,
            early_termination=early_termination,
            max_steps=max_steps,
            linearize=linearize,
            q=None if q is None else str(q),
            time_step=time_step,
            time=time,
            block=block,
        )
        self._warn()

    def _warn(self) -> None:
        _, warned = self._native.take_log()
        for line in warned:
            warnings.warn(line, RuntimeWarning, stacklevel=3)

    def render(
        self,
        camera: Any = None,
        *,
        azimuth: Optional[float] = None,
        elevation: Optional[float] = None,
        view_angle: Optional[float] = None,
        parallel_scale: Optional[float] = None,
        size: Optional[Sequence[int]] = None,
        background: Any = None,
    ) -> np.ndarray:
        """One view: the scene's first view when no camera value is given,
        else the camera as ``tetray.render`` reads it (fit to the mesh,
        then ``azimuth``/``elevation``)."""
        given = _camera.options(camera, azimuth, elevation, view_angle, parallel_scale)
        image = self._native.render(given or None, None if size is None else _size(size))
        self._warn()
        return image if background is None else composite(image, background)

    def frames(self, times: Any = None, orbit: Optional[float] = None, n_frames: Optional[int] = None) -> Iterator[np.ndarray]:
        """The frames of an animation, as ``tetray animate`` makes them: one
        per time step (``times``: ``"all"``, a ``(first, last)`` pair, both
        included, or a list of steps; default every step of a file that
        has several), the first view turning ``orbit`` degrees about its
        view-up over the animation (``n_frames`` frames, default 36, when
        there are no steps). The transfer function spans the field over
        every step rendered unless the scene was given ``clim``, so frame k
        of a mesh that does not move is ``Scene(mesh, ..., time_step=k,
        clim=(lo, hi)).render()`` (a moving mesh keeps the first step's
        view). Each
        step is read when its frame is made; steps that share their points
        and cells share one scene, and only their fields are taken (the
        range takes one more pass over the steps, reading only)."""
        stored = list(self.info["times"])
        if times is None:
            steps = list(range(len(stored))) if len(stored) > 1 else []
        elif isinstance(times, str):
            if times != "all":
                raise ValueError(f"times: expected 'all', a (first, last) pair or a list, got {times!r}")
            steps = list(range(len(stored)))
        elif isinstance(times, tuple) and len(times) == 2:
            steps = list(range(int(times[0]), int(times[1]) + 1))
        else:
            steps = [int(t) for t in times]
        for step in steps:
            if not 0 <= step < len(stored):
                raise ValueError(f"times: step {step} is out of range: the data stores {len(stored)} time steps")
        if not steps and orbit is None:
            raise ValueError("nothing to animate: the data has no time steps to go through; give orbit=")
        count = len(steps) if steps else int(36 if n_frames is None else n_frames)
        if count < 1:
            raise ValueError(f"n_frames: expected 1 or more, got {n_frames}")
        args = dict(self._args, time=None)
        if steps and args.get("clim") is None:
            rng = self._native.range_over(steps)
            if rng is not None:
                args["clim"] = rng
        # One scene for every step: a step whose points and cells are the
        # ones held brings only its fields (see ``tetray animate``).
        scene = Scene(**dict(args, time_step=steps[0])) if steps else self
        current = steps[0] if steps else None
        for i in range(count):
            if steps and steps[i] != current:
                current = steps[i]
                scene._native.go_to_step(current)
            yield scene._native.render_turned(None if orbit is None else float(orbit) * i / count)

    def animate(
        self,
        path: Any,
        times: Any = None,
        orbit: Optional[float] = None,
        n_frames: Optional[int] = None,
        fps: int = 10,
        background: Any = (0.0, 0.0, 0.0),
    ) -> int:
        """Writes the frames of ``frames(times, orbit, n_frames)`` as
        ``tetray animate -o path`` does: a folder of PNG frames (a path
        ending in ``/`` or an existing folder), an animated GIF (``.gif``)
        or an MP4 through ffmpeg (``.mp4``), at ``fps`` frames per second
        over ``background``. Returns the number of frames written."""
        bg = tuple(float(v) for v in _background(background).reshape(3))
        writer = _native.MovieWriter(os.fspath(path), self._size, int(fps), bg)
        try:
            for image in self.frames(times, orbit, n_frames):
                writer.add(image)
        finally:
            writer.close()
        return writer.frames

    def animation(
        self,
        times: Any = None,
        orbit: Optional[float] = None,
        n_frames: Optional[int] = None,
        fps: int = 10,
        background: Any = (0.0, 0.0, 0.0),
        format: str = "gif",
    ) -> "Animation":
        """The frames of ``animate`` held in memory as an animated GIF
        (``format="gif"``) or an MP4 (``"mp4"``, through ffmpeg), which a
        notebook shows inline; ``save(path)`` writes the file."""
        if format not in ("gif", "mp4"):
            raise ValueError(f"format: expected 'gif' or 'mp4', got {format!r}")
        with tempfile.TemporaryDirectory() as folder:
            path = pathlib.Path(folder) / f"animation.{format}"
            count = self.animate(path, times, orbit, n_frames, fps, background)
            data = path.read_bytes()
        return Animation(data, format, count, self._size)

    def _repr_png_(self) -> bytes:
        """The first view as the CLI's PNG, for notebooks to show."""
        return _native.png_bytes(self.render())

    def to_html(
        self,
        path: Any = None,
        *,
        folder: bool = False,
        background: Any = (1.0, 1.0, 1.0),
        bench: Optional[Tuple[int, int]] = None,
    ) -> Any:
        """``tetray export-html``: a web page that renders the scene on the
        visitor's GPU through WebGPU (the ray caster's own WGSL and
        buffers), starting from the first view at the scene's size.

        Without ``path``, returns the page as one HTML string. With one,
        writes it there (``folder=True``: a folder holding ``index.html``
        and ``scene.js``) and returns the HTML file's path. ``bench``:
        ``(frames, views)`` the page benchmarks on opening."""
        bg = [float(v) for v in _background(background).reshape(3)]
        bench_pair = None if bench is None else (int(bench[0]), int(bench[1]))
        html, scene_js = self._native.to_html(bg, bench_pair, bool(folder and path is not None))
        self._warn()
        if path is None:
            return html
        path = pathlib.Path(os.fspath(path))
        if folder:
            path.mkdir(parents=True, exist_ok=True)
            (path / "index.html").write_text(html, encoding="utf-8")
            (path / "scene.js").write_text(scene_js or "", encoding="utf-8")
            return path / "index.html"
        path.write_text(html, encoding="utf-8")
        return path

    def show(self, height: Optional[int] = None) -> "Page":
        """The interactive page of ``to_html()`` for a notebook: Jupyter
        shows the returned object as the page in a frame (the scene's own
        ``_repr_png_`` stays the still image)."""
        return Page(self.to_html(), height or self._size[1] + 160)

    def orbit(self, frames: int = 36, step: Optional[float] = None) -> List[np.ndarray]:
        """``frames`` views turning about the view-up from the first view
        by ``step`` degrees (default 360 / frames), as ``tetray bench``."""
        return self._native.orbit(int(frames), step)

    def compare(self, methods: Sequence[Any] = ("gpu", "project:centroid", "project:mpvo", "project:mpvonc"), frames: int = 1):
        """See ``tetray.compare``."""
        specs = [_spec(m) for m in methods]
        rows, reference, images = self._native.compare(specs, int(frames))
        table = json.loads(rows)
        return table, {"reference": reference, **{row["label"]: im for row, im in zip(table, images)}}

    @property
    def info(self) -> Dict[str, Any]:
        """``tetray info``'s summary of the mesh, and the scene's field,
        range, unit distance, integrator and renderer."""
        return self._native.info

    @property
    def camera(self) -> Dict[str, Any]:
        """The first view's camera in the mesh's coordinates (VTK's terms)."""
        return self._native.camera

    @property
    def size(self) -> Tuple[int, int]:
        return self._size


class Animation:
    """Frames of ``Scene.animation()`` as one GIF or MP4 file's bytes;
    Jupyter shows it inline."""

    def __init__(self, data: bytes, format: str, frames: int, size: Tuple[int, int]) -> None:
        self.data = data
        self.format = format
        self.frames = frames
        self.size = size

    def _repr_html_(self) -> str:
        encoded = base64.b64encode(self.data).decode("ascii")
        width, height = self.size
        if self.format == "gif":
            return f'<img src="data:image/gif;base64,{encoded}" width="{width}" height="{height}">'
        return (
            f'<video src="data:video/mp4;base64,{encoded}" width="{width}" height="{height}" '
            "controls autoplay loop muted></video>"
        )

    def save(self, path: Any) -> pathlib.Path:
        path = pathlib.Path(os.fspath(path))
        path.write_bytes(self.data)
        return path


class Page:
    """A page of ``Scene.to_html()``, shown by Jupyter in a frame."""

    def __init__(self, html: str, height: int) -> None:
        self.html = html
        self.height = int(height)

    def _repr_html_(self) -> str:
        return (
            f'<iframe srcdoc="{html_escape(self.html, quote=True)}" '
            f'style="width: 100%; height: {self.height}px; border: 0"></iframe>'
        )

    def save(self, path: Any) -> pathlib.Path:
        path = pathlib.Path(os.fspath(path))
        path.write_text(self.html, encoding="utf-8")
        return path


def render(
    mesh: Any,
    scalars: Any = None,
    *,
    size: Sequence[int] = (512, 512),
    integrator: str = "ppi",
    renderer: str = "auto",
    camera: Any = None,
    azimuth: Optional[float] = None,
    elevation: Optional[float] = None,
    tf: Any = None,
    cmap: Any = None,
    opacity: Any = None,
    unit_distance: Optional[float] = None,
    opacity_mode: str = "exact",
    early_termination: float = 1.0,
    background: Any = None,
    **options: Any,
) -> np.ndarray:
    """Renders ``mesh`` to a (height, width, 4) float32 array, colour
    premultiplied by alpha (the CLI's EXR), row 0 at the top.

    ``scalars``: a point field name or an array of point values (default:
    the first field that varies). ``camera``: PyVista's camera position
    ``[(position), (focal_point), (view_up)]``, a ``pyvista.Camera`` or a
    dict of VTK's terms (position, focal_point, view_up, view_angle,
    parallel_scale); unspecified parts come from VTK's ResetCamera fit.
    ``azimuth``/``elevation`` (degrees) turn the camera after the fit; with
    no camera value at all the CLI's default oblique view
    ``DEFAULT_VIEW`` = (30, 20) applies, so ``azimuth=0, elevation=0`` gives
    the plain fit. ``tf``: a ParaView preset (path or dict); or ``cmap``,
    ``opacity`` and ``clim`` as PyVista takes them. ``background``: None
    returns the RGBA image, a colour returns it composited as (h, w, 3).
    Further keywords: ``view_angle``, ``parallel_scale``, ``clim``,
    ``tf_name``, ``rescale``, ``max_steps``, ``linearize``, ``q``,
    ``time_step``, ``time``, ``block``, ``name`` (see ``Scene``).
    """
    scene = Scene(
        mesh,
        scalars,
        size=size,
        integrator=integrator,
        renderer=renderer,
        camera=camera,
        azimuth=azimuth,
        elevation=elevation,
        tf=tf,
        cmap=cmap,
        opacity=opacity,
        unit_distance=unit_distance,
        opacity_mode=opacity_mode,
        early_termination=early_termination,
        **options,
    )
    return scene.render(background=background)


def _background(background: Any) -> np.ndarray:
    bg = np.asarray(0.0 if background is None else background, dtype=np.float32).reshape(-1)
    if bg.size == 1:
        bg = np.repeat(bg, 3)
    if bg.shape != (3,) or not np.all(np.isfinite(bg)) or bg.min() < 0:
        raise ValueError(f"background: expected r, g, b (or one grey value) >= 0, got {background!r}")
    return bg


def _image(image: Any) -> np.ndarray:
    a = np.asarray(image, dtype=np.float32)
    if a.ndim != 3 or a.shape[2] != 4:
        raise ValueError(f"image: expected shape (height, width, 4), got {a.shape}")
    return a


def composite(image: Any, background: Any = (0.0, 0.0, 0.0)) -> np.ndarray:
    """Premultiplied RGBA over an opaque background: (h, w, 3) float32,
    unclamped (as the CLI composites, in f32)."""
    a = _image(image)
    bg = _background(background)
    return a[..., :3] + (np.float32(1.0) - a[..., 3:4]) * bg


def to_rgb8(image: Any, background: Any = (0.0, 0.0, 0.0)) -> np.ndarray:
    """The PNG the CLI writes for ``image`` over ``background``: (h, w, 3)
    uint8, no sRGB transform, each value clamped to [0, 1] and rounded."""
    rgb = np.clip(composite(image, background), 0.0, 1.0)
    rgb = np.nan_to_num(rgb, nan=0.0)
    # Rust's f32::round (half away from zero) on values >= 0.
    return np.floor(rgb * np.float32(255.0) + np.float32(0.5)).astype(np.uint8)


def _spec(method: Any) -> Tuple[str, Optional[str], Optional[str]]:
    """"gpu", "cpu:exact", "project:ppi:mpvo" or a (renderer, integrator,
    sort) tuple."""
    if isinstance(method, (tuple, list)):
        items = list(method) + [None] * (3 - len(method))
        return str(items[0]), items[1], items[2]
    parts = str(method).strip().split(":")
    renderer, integrator, sort = parts[0].lower(), None, None
    for part in parts[1:]:
        if part.lower() in ("centroid", "mpvo", "mpvonc"):
            sort = part.lower()
        elif integrator is None:
            integrator = part
        else:
            raise ValueError(f"{method!r}: one integrator")
    return renderer, integrator, sort


def compare(
    mesh: Any,
    methods: Sequence[Any] = ("gpu", "project:centroid", "project:mpvo", "project:mpvonc"),
    *,
    frames: int = 1,
    size: Sequence[int] = (256, 256),
    **options: Any,
):
    """``tetray compare``: the CPU f64 reference and each method
    ("cpu:exact", "project:ppi:mpvo", ...) from one camera. Returns the
    table (a list of dicts: label, renderer, integrator, sort, abs_error
    {max, mean, p99, over_one_level, pixels}, flip_mean, flip_p99, speed)
    and the images by label (plus "reference")."""
    scene = Scene(mesh, size=size, renderer="cpu", **options)
    return scene.compare(methods, frames)


def segment(integrator: str = "all", **kwargs: Any):
    """``tetray segment``: one ray segment (lb, lf, tau_b, tau_f, length;
    colours as one value or r, g, b) by one method, or with "all" a list of
    every method with its error against its model's f64 reference."""
    def rgb(v: Any) -> Tuple[float, float, float]:
        a = np.asarray(v, dtype=np.float64).reshape(-1)
        if a.size == 1:
            a = np.repeat(a, 3)
        if a.shape != (3,):
            raise ValueError(f"expected one value or r, g, b, got {v!r}")
        return tuple(float(x) for x in a)

    for key in ("lb", "lf", "tau_b", "tau_f", "incoming"):
        if key in kwargs:
            kwargs[key] = rgb(kwargs[key])
    if integrator != "all":
        return _native.segment(integrator, **kwargs)
    out = []
    for name in _native.methods():
        result = _native.segment(name, **kwargs)
        reference_name = _REFERENCE[result["model"]]
        reference = _native.segment(reference_name, **kwargs)
        error = max(abs(a - b) for a, b in zip(result["colour"], reference["colour"]))
        result["reference"] = reference_name
        result["abs_error"] = max(error, abs(result["alpha"] - reference["alpha"]))
        out.append(result)
    return out


_REFERENCE = {"linear attenuation": "reference", "linear opacity": "reference-opacity"}


def psi(gamma_b: float, gamma_f: float, size: int = 1024) -> Dict[str, Any]:
    """``tetray psi``: the Psi table at (gamma_b, gamma_f) against f64."""
    return _native.psi(float(gamma_b), float(gamma_f), int(size))
