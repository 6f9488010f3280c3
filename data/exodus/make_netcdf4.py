"""Writes tet_wedge_netcdf4.exo: a tiny Exodus II file in netCDF-4 (HDF5),
with the Python netCDF4 package (an independent writer), for the tetray
reader tests. Run: python make_netcdf4.py (netCDF4 1.7, numpy 2).

Layout after the SEACAS Exodus II API: one TETRA block (id 1, two tets),
one WEDGE block (id 2, one wedge on top of the unit triangle) and one
BEAM block (id 3, skipped by the reader); three time steps; nodal
variables "pressure" = x + y + z + step and "vel_x", "vel_y", "vel_z";
element variable "heat" on the wedge block only (truth table).
"""

import numpy as np
from netCDF4 import Dataset, stringtochar

LEN_NAME = 33

coords = np.array(
    [
        [0.0, 0.0, 0.0],  # 1: wedge bottom
        [1.0, 0.0, 0.0],  # 2
        [0.0, 1.0, 0.0],  # 3
        [0.0, 0.0, 1.0],  # 4: wedge top
        [1.0, 0.0, 1.0],  # 5
        [0.0, 1.0, 1.0],  # 6
        [0.0, 0.0, -1.0],  # 7: tets below the wedge's bottom face
        [1.0, 1.0, -1.0],  # 8
    ]
)
times = [0.0, 1.0, 2.5]


def names(rows):
    return stringtochar(np.array(rows, dtype=f"S{LEN_NAME}"))


with Dataset("tet_wedge_netcdf4.exo", "w", format="NETCDF4") as d:
    d.api_version = np.float32(8.0)
    d.version = np.float32(8.0)
    d.floating_point_word_size = np.int32(8)
    d.file_size = np.int32(1)
    d.title = "tetray netCDF-4 Exodus test"
    d.createDimension("len_name", LEN_NAME)
    d.createDimension("time_step", None)
    d.createDimension("num_dim", 3)
    d.createDimension("num_nodes", len(coords))
    d.createDimension("num_elem", 4)
    d.createDimension("num_el_blk", 3)
    d.createDimension("num_el_in_blk1", 2)
    d.createDimension("num_nod_per_el1", 4)
    d.createDimension("num_el_in_blk2", 1)
    d.createDimension("num_nod_per_el2", 6)
    d.createDimension("num_el_in_blk3", 1)
    d.createDimension("num_nod_per_el3", 2)
    d.createDimension("num_nod_var", 4)
    d.createDimension("num_elem_var", 1)

    d.createVariable("time_whole", "f8", ("time_step",))[:] = times
    d.createVariable("eb_status", "i4", ("num_el_blk",))[:] = [1, 1, 1]
    prop = d.createVariable("eb_prop1", "i4", ("num_el_blk",))
    prop.setncattr("name", "ID")
    prop[:] = [1, 2, 3]
    d.createVariable("eb_names", "S1", ("num_el_blk", "len_name"))[:] = names(
        ["tets", "wedges", "rod"]
    )
    for axis, name in enumerate(["coordx", "coordy", "coordz"]):
        d.createVariable(name, "f8", ("num_nodes",))[:] = coords[:, axis]

    # Both tets share the face 1-2-3 of the wedge's bottom; 1-based ids.
    c1 = d.createVariable("connect1", "i4", ("num_el_in_blk1", "num_nod_per_el1"))
    c1.setncattr("elem_type", "TETRA")
    c1[:] = [[1, 2, 3, 7], [2, 3, 7, 8]]
    c2 = d.createVariable("connect2", "i4", ("num_el_in_blk2", "num_nod_per_el2"))
    c2.setncattr("elem_type", "WEDGE")
    c2[:] = [[1, 2, 3, 4, 5, 6]]
    c3 = d.createVariable("connect3", "i4", ("num_el_in_blk3", "num_nod_per_el3"))
    c3.setncattr("elem_type", "BEAM")
    c3[:] = [[4, 5]]

    d.createVariable("name_nod_var", "S1", ("num_nod_var", "len_name"))[:] = names(
        ["pressure", "vel_x", "vel_y", "vel_z"]
    )
    s = np.arange(len(times))[:, None]
    fields = [
        coords.sum(axis=1)[None, :] + s,
        np.ones((len(times), len(coords))) * 3.0,
        np.ones((len(times), len(coords))) * 4.0,
        np.zeros((len(times), len(coords))) + s,
    ]
    for i, values in enumerate(fields):
        d.createVariable(f"vals_nod_var{i + 1}", "f8", ("time_step", "num_nodes"))[:] = values

    d.createVariable("name_elem_var", "S1", ("num_elem_var", "len_name"))[:] = names(["heat"])
    d.createVariable("elem_var_tab", "i4", ("num_el_blk", "num_elem_var"))[:] = [[0], [1], [0]]
    heat = d.createVariable("vals_elem_var1eb2", "f8", ("time_step", "num_el_in_blk2"))
    heat[:] = [[7.0], [8.0], [9.0]]
