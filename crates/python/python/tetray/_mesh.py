"""From whatever the user holds to what the native module loads.

A path stays a path (the native readers, every format the CLI reads). A
PyVista dataset, a meshio.Mesh or plain arrays become a
``tetray._native.Grid``: points, VTK cells (connectivity + offsets +
types) and point/cell arrays, which the native side assembles exactly as
it assembles the same dataset read from a ``.vtu`` (or, for structured
grids, a ``.vts``/``.vti``). Nothing here imports PyVista or meshio: the
objects are recognised by what they have.
"""

from __future__ import annotations

import os
from typing import Any, Dict, Mapping, Optional, Tuple

import numpy as np

from . import _native

# meshio's cell type names -> VTK cell type ids (vtkCellType.h). meshio
# stores these cells' nodes in VTK's order.
MESHIO_TYPES = {
    "vertex": 1,
    "line": 3,
    "triangle": 5,
    "polygon": 7,
    "quad": 9,
    "tetra": 10,
    "hexahedron": 12,
    "wedge": 13,
    "pyramid": 14,
    "line3": 21,
    "triangle6": 22,
    "quad8": 23,
    "tetra10": 24,
    "hexahedron20": 25,
    "wedge15": 26,
    "pyramid13": 27,
    "quad9": 28,
    "hexahedron27": 29,
}

# Cells per row of a plain (m, k) cell array -> VTK type.
ROW_TYPES = {4: 10, 8: 12, 6: 13, 5: 14}

STRUCTURED = {
    "ImageData": "ImageData",
    "UniformGrid": "ImageData",
    "RectilinearGrid": "RectilinearGrid",
    "StructuredGrid": "StructuredGrid",
}


def _float_points(points: Any) -> np.ndarray:
    """(n, 3) float64, C-contiguous; no copy when it already is."""
    p = np.asarray(points)
    if p.ndim != 2 or p.shape[1] != 3:
        raise ValueError(f"points must have shape (n, 3), got {p.shape}")
    if not np.issubdtype(p.dtype, np.number):
        raise ValueError(f"points must be numbers, got dtype {p.dtype}")
    return np.ascontiguousarray(p, dtype=np.float64)


def _ints(values: Any, what: str) -> np.ndarray:
    a = np.asarray(values)
    if a.size and not np.issubdtype(a.dtype, np.integer):
        if np.issubdtype(a.dtype, np.floating) and np.all(np.isfinite(a)) and np.all(a == np.round(a)):
            pass  # whole numbers stored as floats
        else:
            raise ValueError(f"{what} must be integers, got dtype {a.dtype}")
    return np.ascontiguousarray(a.reshape(-1), dtype=np.int64)


def _arrays(data: Optional[Mapping[str, Any]], where: str) -> Dict[str, np.ndarray]:
    """Numeric arrays as float64 (n,) or (n, k); others skipped, as the
    readers skip string arrays."""
    out: Dict[str, np.ndarray] = {}
    if not data:
        return out
    for name in list(data.keys()):
        a = np.asarray(data[name])
        if not (np.issubdtype(a.dtype, np.number) or a.dtype == np.bool_):
            continue
        if a.ndim > 2:
            a = a.reshape(a.shape[0], -1)
        if a.ndim == 0:
            raise ValueError(f"{where}[{name!r}] is a scalar, not an array of values")
        out[str(name)] = np.ascontiguousarray(a, dtype=np.float64)
    return out


def unstructured(
    points: Any,
    cells: Any,
    celltypes: Any = None,
    offsets: Any = None,
    point_data: Optional[Mapping[str, Any]] = None,
    cell_data: Optional[Mapping[str, Any]] = None,
    name: str = "arrays",
) -> "_native.Grid":
    """A Grid from plain arrays.

    ``cells`` is one of: an (m, k) integer array, one cell per row (the
    type from ``celltypes`` or, without it, from k: 4 tetra, 5 pyramid,
    6 wedge, 8 hexahedron); VTK's connectivity with ``offsets`` (one per
    cell plus one, from 0, or one per cell: the starts); or VTK's legacy
    count-prefixed cell array (PyVista's ``grid.cells``) with
    ``celltypes``.
    """
    p = _float_points(points)
    c = np.asarray(cells)
    if c.ndim == 2:
        m, k = c.shape
        if celltypes is None:
            if k not in ROW_TYPES:
                raise ValueError(
                    f"cells of {k} points per row: give celltypes (VTK ids); rows of 4, 5, 6 "
                    "or 8 points are read as tetra, pyramids, wedges or hexahedra"
                )
            types = np.full(m, ROW_TYPES[k], dtype=np.int64)
        else:
            types = _ints(celltypes, "celltypes")
            if len(types) != m:
                raise ValueError(f"{len(types)} celltypes for {m} cells")
        conn = _ints(c, "cells")
        offs = np.arange(0, (m + 1) * k, k, dtype=np.int64)
    elif c.ndim == 1:
        if celltypes is None:
            raise ValueError("a flat cells array needs celltypes (and offsets, unless VTK's count-prefixed layout)")
        types = _ints(celltypes, "celltypes")
        flat = _ints(c, "cells")
        if offsets is not None:
            offs = _ints(offsets, "offsets")
            if len(offs) == len(types) and len(types) > 0:
                offs = np.append(offs, len(flat))  # starts only
            conn = flat
        else:
            conn, offs = _from_counts(flat, len(types))
    else:
        raise ValueError(f"cells must be a 1-D or 2-D integer array, got shape {c.shape}")
    return _native.Grid.unstructured(
        p, conn, offs, types, _arrays(point_data, "point_data"), _arrays(cell_data, "cell_data"), name
    )


def _from_counts(cells: np.ndarray, ncells: int) -> Tuple[np.ndarray, np.ndarray]:
    """VTK's legacy layout [n0, ids..., n1, ids...] -> connectivity, offsets."""
    offsets = np.zeros(ncells + 1, dtype=np.int64)
    starts = np.zeros(ncells, dtype=np.int64)
    at = 0
    for c in range(ncells):
        if at >= len(cells):
            raise ValueError(f"cells: the count-prefixed array ends before cell {c} of {ncells}")
        n = int(cells[at])
        if n < 0 or at + 1 + n > len(cells):
            raise ValueError(f"cells: cell {c} claims {n} points past the end of the array")
        starts[c] = at + 1
        offsets[c + 1] = offsets[c] + n
        at += 1 + n
    if at != len(cells):
        raise ValueError(f"cells: {len(cells) - at} entries left after {ncells} cells")
    counts = np.diff(offsets)
    index = np.repeat(starts - offsets[:-1], counts) + np.arange(offsets[-1])
    return np.ascontiguousarray(cells[index]), offsets


def _pyvista_grid(mesh: Any, name: str) -> "_native.Grid":
    kind = type(mesh).__name__
    if kind == "MultiBlock":
        # One grid, points shared between blocks welded (as the .vtm
        # reader welds bit-equal points of its blocks).
        mesh = mesh.combine(merge_points=True)
        kind = type(mesh).__name__
    point_data = {k: mesh.point_data[k] for k in mesh.point_data.keys()}
    cell_data = {k: mesh.cell_data[k] for k in mesh.cell_data.keys()}
    if kind in STRUCTURED:
        dims = tuple(int(d) for d in mesh.dimensions)
        return _native.Grid.structured(
            dims,
            _float_points(mesh.points),
            _arrays(point_data, "point_data"),
            _arrays(cell_data, "cell_data"),
            STRUCTURED[kind],
            name,
        )
    if kind == "PolyData":
        raise ValueError(f"{name}: a PolyData has surface cells only; tetray renders volume cells")
    if not hasattr(mesh, "celltypes"):
        mesh = mesh.cast_to_unstructured_grid()
    offsets = "cell_offsets" if hasattr(type(mesh), "cell_offsets") else "offset"
    if hasattr(mesh, "cell_connectivity") and hasattr(type(mesh), offsets):
        conn, offs = mesh.cell_connectivity, getattr(mesh, offsets)
    else:
        conn, offs = _from_counts(_ints(mesh.cells, "cells"), mesh.n_cells)
    return _native.Grid.unstructured(
        _float_points(mesh.points),
        _ints(conn, "connectivity"),
        _ints(offs, "offsets"),
        _ints(mesh.celltypes, "celltypes"),
        _arrays(point_data, "point_data"),
        _arrays(cell_data, "cell_data"),
        name,
    )


def _meshio_grid(mesh: Any, name: str) -> "_native.Grid":
    conns, offs, types = [], [np.zeros(1, dtype=np.int64)], []
    total = 0
    for block in mesh.cells:
        kind = block.type
        if kind not in MESHIO_TYPES:
            raise ValueError(f"{name}: meshio cell type {kind!r} is not supported")
        data = np.asarray(block.data, dtype=np.int64)
        if data.ndim != 2:
            raise ValueError(f"{name}: meshio {kind!r} cells must be a 2-D array")
        m, k = data.shape
        conns.append(data.reshape(-1))
        offs.append(total + np.arange(k, (m + 1) * k, k, dtype=np.int64))
        types.append(np.full(m, MESHIO_TYPES[kind], dtype=np.int64))
        total += m * k
    cell_data = {}
    for key, blocks in (mesh.cell_data or {}).items():
        try:
            cell_data[key] = np.concatenate([np.asarray(b) for b in blocks])
        except ValueError:
            continue
    return _native.Grid.unstructured(
        _float_points(mesh.points),
        np.concatenate(conns) if conns else np.zeros(0, dtype=np.int64),
        np.concatenate(offs),
        np.concatenate(types) if types else np.zeros(0, dtype=np.int64),
        _arrays(mesh.point_data, "point_data"),
        _arrays(cell_data, "cell_data"),
        name,
    )


def to_source(mesh: Any, scalars: Any = None, name: Optional[str] = None) -> Tuple[Any, Optional[str]]:
    """(a path or a Grid, the field name to render)."""
    field = scalars if isinstance(scalars, str) or scalars is None else "scalars"
    extra = None if field != "scalars" or isinstance(scalars, str) else scalars
    if isinstance(mesh, (str, os.PathLike)):
        if extra is not None:
            raise ValueError("scalars: an array of values needs a mesh given as arrays or an object, not a path")
        return os.fspath(mesh), field
    if isinstance(mesh, _native.Grid):
        if extra is not None:
            raise ValueError("scalars: give the values in the Grid's point_data")
        return mesh, field
    label = name or type(mesh).__name__
    module = type(mesh).__module__ or ""
    if extra is not None:
        mesh = _with_point_array(mesh, np.asarray(extra))
    if module.startswith("pyvista") or hasattr(mesh, "point_data") and hasattr(mesh, "n_cells"):
        return _pyvista_grid(mesh, label), field
    if module.startswith("meshio") or (hasattr(mesh, "cells") and hasattr(mesh, "points") and hasattr(mesh, "cells_dict")):
        return _meshio_grid(mesh, label), field
    if isinstance(mesh, Mapping):
        args = dict(mesh)
        args.setdefault("name", name or "arrays")
        return unstructured(**args), field
    if isinstance(mesh, (tuple, list)) and 2 <= len(mesh) <= 4:
        items = list(mesh) + [None] * (4 - len(mesh))
        grid = unstructured(
            points=items[0], cells=items[1], celltypes=items[2], point_data=items[3], name=name or "arrays"
        )
        return grid, field
    raise ValueError(
        f"mesh: expected a path, a PyVista dataset, a meshio.Mesh, a dict of arrays or "
        f"(points, cells[, celltypes[, point_data]]), got {type(mesh).__name__}"
    )


def _with_point_array(mesh: Any, values: np.ndarray) -> Any:
    """The mesh with ``values`` as the point array "scalars"."""
    if isinstance(mesh, Mapping):
        copy = dict(mesh)
        copy["point_data"] = {**dict(copy.get("point_data") or {}), "scalars": values}
        return copy
    if isinstance(mesh, (tuple, list)):
        items = list(mesh) + [None] * (4 - len(mesh))
        if items[2] is None and np.asarray(items[1]).ndim == 1:
            raise ValueError("a flat cells array needs celltypes")
        items[3] = {**dict(items[3] or {}), "scalars": values}
        return tuple(items)
    if hasattr(mesh, "point_data") and hasattr(mesh, "copy"):
        copy = mesh.copy(deep=False)
        copy.point_data["scalars"] = values
        return copy
    copy = type(mesh)(mesh.points, mesh.cells, point_data={**dict(mesh.point_data or {}), "scalars": values})
    return copy
