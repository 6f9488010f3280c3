"""Transfer functions the PyVista way: ``cmap`` (a matplotlib colormap
name or object, or a list of colours) and ``opacity`` ("linear",
"linear_r", "geom", "geom_r", "sigmoid", "sigmoid_r", a number, or a list
of values spread evenly over the range), sampled into control points
over [0, 1] that the native side maps onto ``clim`` or the field's range.
Or a ParaView preset: a path to its JSON, or the preset as a dict/list.

Opacity is ParaView's: the opacity of one unit distance of material (see
``unit_distance``), as for the CLI's presets.
"""

from __future__ import annotations

import json
import os
from typing import Any, List, Optional, Tuple

import numpy as np

SAMPLES = 256


def preset(tf: Any) -> str:
    """A ParaView preset as JSON text."""
    if isinstance(tf, (str, os.PathLike)):
        try:
            with open(tf, encoding="utf-8") as f:
                return f.read()
        except OSError as e:
            raise OSError(f"tf {os.fspath(tf)}: cannot read: {e.strerror}") from e
    if isinstance(tf, (dict, list)):
        return json.dumps(tf)
    raise ValueError(f"tf: expected a path to a ParaView preset or the preset as a dict, got {type(tf).__name__}")


def _colormap(cmap: Any):
    if isinstance(cmap, (list, tuple)) and cmap and not isinstance(cmap[0], str) or isinstance(cmap, np.ndarray):
        colours = np.asarray(cmap, dtype=np.float64)
        if colours.ndim != 2 or colours.shape[1] not in (3, 4) or len(colours) < 1:
            raise ValueError("cmap: a list of colours must have shape (n, 3) or (n, 4)")
        if colours.max(initial=0.0) > 1.0:
            colours = colours / 255.0
        return lambda s: np.stack([np.interp(s, np.linspace(0, 1, len(colours)), colours[:, c]) for c in range(3)], axis=1)
    try:
        import matplotlib
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ValueError("cmap: a colormap name or object needs matplotlib (pip install matplotlib)") from e
    if isinstance(cmap, str):
        try:
            cmap = matplotlib.colormaps[cmap]
        except KeyError:
            raise ValueError(f"cmap: unknown matplotlib colormap {cmap!r}") from None
    if not callable(cmap):
        raise ValueError(f"cmap: expected a colormap name, object or list of colours, got {type(cmap).__name__}")
    return lambda s: np.asarray(cmap(s), dtype=np.float64)[:, :3]


def _opacity(opacity: Any, s: np.ndarray) -> np.ndarray:
    if isinstance(opacity, str):
        name = opacity.lower()
        reverse = name.endswith("_r")
        base = name[:-2] if reverse else name
        x = 1.0 - s if reverse else s
        if base == "linear":
            values = x
        elif base == "geom":
            # PyVista's "geom": a geometric ramp from 0 to 1.
            values = (np.power(10.0, x * 2.0) - 1.0) / 99.0
        elif base == "sigmoid":
            values = 1.0 / (1.0 + np.exp(-10.0 * (x - 0.5)))
        else:
            raise ValueError(
                f"opacity: unknown {opacity!r}: expected linear, geom, sigmoid (or _r), a number or a list"
            )
        return values
    values = np.asarray(opacity, dtype=np.float64)
    if values.ndim == 0:
        return np.full_like(s, float(values))
    if values.ndim != 1 or len(values) < 1:
        raise ValueError("opacity: a list of values must be one-dimensional and not empty")
    if len(values) == 1:
        return np.full_like(s, values[0])
    return np.interp(s, np.linspace(0.0, 1.0, len(values)), values)


def points(cmap: Any, opacity: Any) -> Tuple[List[Tuple[float, float, float, float]], List[Tuple[float, float]]]:
    """Colour points (s, r, g, b) and opacity points (s, alpha) over [0, 1]
    (PyVista's defaults where one is missing: viridis, linear)."""
    s = np.linspace(0.0, 1.0, SAMPLES)
    rgb = _colormap("viridis" if cmap is None else cmap)(s)
    alpha = _opacity("linear" if opacity is None else opacity, s)
    if not (np.all(np.isfinite(rgb)) and np.all(np.isfinite(alpha))):
        raise ValueError("cmap/opacity: values must be finite")
    if alpha.min() < 0.0 or alpha.max() > 1.0:
        raise ValueError(f"opacity: values must lie in [0, 1], got [{alpha.min()}, {alpha.max()}]")
    colour = [(float(t), float(r), float(g), float(b)) for t, (r, g, b) in zip(s, np.clip(rgb, 0.0, None))]
    return colour, [(float(t), float(a)) for t, a in zip(s, alpha)]


def clim_range(clim: Optional[Any]) -> Optional[Tuple[float, float]]:
    if clim is None:
        return None
    lo, hi = (float(v) for v in clim)
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
        raise ValueError(f"clim: expected (low, high) with low < high, got {clim!r}")
    return lo, hi
