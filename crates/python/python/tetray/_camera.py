"""Cameras the PyVista way or VTK's, as the native side's dict.

The dict's keys are VTK's (and the CLI's flags): position, focal_point,
view_up, view_angle, parallel_scale, azimuth, elevation. What is missing
comes from the CLI's ResetCamera fit; with nothing given at all the fit is
turned to the CLI's oblique default view (``tetray.DEFAULT_VIEW``).
"""

from __future__ import annotations

from typing import Any, Dict, Optional

import numpy as np

KEYS = ("position", "focal_point", "view_up", "view_angle", "parallel_scale", "azimuth", "elevation")


def _triple(value: Any, what: str):
    v = np.asarray(value, dtype=np.float64).reshape(-1)
    if v.shape != (3,):
        raise ValueError(f"camera {what}: expected three numbers (x, y, z), got {value!r}")
    return tuple(float(x) for x in v)


def options(
    camera: Any = None,
    azimuth: Optional[float] = None,
    elevation: Optional[float] = None,
    view_angle: Optional[float] = None,
    parallel_scale: Optional[float] = None,
) -> Dict[str, Any]:
    """``camera`` is None, PyVista's camera position ``[(position),
    (focal_point), (view_up)]`` (a ``CameraPosition`` or a list of three
    triples), a ``pyvista.Camera`` (or anything with position, focal_point
    and up), or a dict of VTK's terms."""
    out: Dict[str, Any] = {}
    if camera is None:
        pass
    elif isinstance(camera, dict):
        unknown = set(camera) - set(KEYS) - {"up"}
        if unknown:
            raise ValueError(f"camera: unknown keys {sorted(unknown)}; expected some of {list(KEYS)}")
        out.update({k: v for k, v in camera.items() if v is not None})
        if "up" in out:
            out["view_up"] = out.pop("up")
    elif hasattr(camera, "focal_point") and hasattr(camera, "position") and hasattr(camera, "up"):
        out["position"] = camera.position
        out["focal_point"] = camera.focal_point
        out["view_up"] = camera.up
        if getattr(camera, "view_angle", None) is not None:
            out["view_angle"] = float(camera.view_angle)
        if getattr(camera, "parallel_projection", False):
            out["parallel_scale"] = float(camera.parallel_scale)
    else:
        try:
            position, focal, up = list(camera)
        except (TypeError, ValueError):
            raise ValueError(
                "camera: expected PyVista's [(position), (focal_point), (view_up)], a pyvista.Camera "
                f"or a dict of VTK's terms, got {camera!r}"
            ) from None
        out.update(position=position, focal_point=focal, view_up=up)
    for key in ("position", "focal_point", "view_up"):
        if key in out:
            out[key] = _triple(out[key], key)
    for key, value in (
        ("azimuth", azimuth),
        ("elevation", elevation),
        ("view_angle", view_angle),
        ("parallel_scale", parallel_scale),
    ):
        if value is not None:
            out[key] = float(value)
    return out
