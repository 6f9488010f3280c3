"""Writes the fuzz targets' seed corpora (fuzz/corpus/<target>/) from the
repository's data/ and from small files VTK's own writers make, so the
fuzzer starts from every reader's real paths: appended, compressed and
inline XML, parallel pieces, classic and netCDF-4 Exodus, both CGNS
storages, VTKHDF, PLOT3D, an OpenFOAM and an EnSight case.

    python fuzz/make_seeds.py       # needs the vtk package (pip install vtk)

The classic-netCDF Exodus seeds come from the Exodus tests' own writer:
`UPDATE_FUZZ_SEEDS=1 cargo test -p tetray-io --test fuzz_seeds`.
"""

from __future__ import annotations

import pathlib
import shutil
import struct
import tempfile

import vtk

FUZZ = pathlib.Path(__file__).resolve().parent
DATA = FUZZ.parent / "data"
CORPUS = FUZZ / "corpus"
SEP = b"@@@ "


def archive(files):
    out = b""
    for name, data in files:
        out += SEP + name.encode() + b"\n" + data + b"\n"
    return out


def put(target, name, data):
    folder = CORPUS / target
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_bytes(data)


def small_grid():
    """Two tetrahedra, a hexahedron and a wedge, with point and cell data."""
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(str(DATA / "real" / "tetra.vtu"))
    reader.Update()
    return reader.GetOutput()


def write_xml(writer, data, path, mode, compressor):
    writer.SetInputData(data)
    writer.SetFileName(str(path))
    {"ascii": writer.SetDataModeToAscii, "binary": writer.SetDataModeToBinary,
     "appended": writer.SetDataModeToAppended}[mode]()
    if compressor is None:
        writer.SetCompressorTypeToNone()
    else:
        writer.SetCompressorTypeToZLib()
    writer.Write()
    return path.read_bytes()


def image():
    source = vtk.vtkRTAnalyticSource()
    source.SetWholeExtent(0, 3, 0, 2, 0, 2)
    source.Update()
    return source.GetOutput()


def main():
    tmp = pathlib.Path(tempfile.mkdtemp())
    grid = small_grid()

    put("vtk_legacy", "uGridEx.vtk", (DATA / "real" / "uGridEx.vtk").read_bytes())
    for kind in ("ascii", "binary"):
        writer = vtk.vtkUnstructuredGridWriter()
        writer.SetInputData(grid)
        writer.SetFileName(str(tmp / f"g-{kind}.vtk"))
        writer.SetFileTypeToASCII() if kind == "ascii" else writer.SetFileTypeToBinary()
        writer.Write()
        put("vtk_legacy", f"tetra-{kind}.vtk", (tmp / f"g-{kind}.vtk").read_bytes())
        put("render", f"tetra-{kind}.vtk", (tmp / f"g-{kind}.vtk").read_bytes())
    points = vtk.vtkStructuredPointsWriter()
    points.SetInputData(image())
    points.SetFileName(str(tmp / "image.vtk"))
    points.Write()
    put("vtk_legacy", "image.vtk", (tmp / "image.vtk").read_bytes())
    put("render", "image.vtk", (tmp / "image.vtk").read_bytes())

    for mode in ("ascii", "binary", "appended"):
        for compressor in (None, "zlib"):
            if mode == "ascii" and compressor:
                continue
            tag = f"{mode}-{compressor or 'raw'}"
            data = write_xml(vtk.vtkXMLUnstructuredGridWriter(), grid, tmp / f"{tag}.vtu", mode, compressor)
            put("vtk_xml", f"{tag}.vtu", b"\x00" + data)
    put("vtk_xml", "polyhedron2pieces.vtu", b"\x00" + (DATA / "real" / "polyhedron2pieces.vtu").read_bytes())
    put("vtk_xml", "QuadraticWedge.vtu", b"\x00" + (DATA / "real" / "QuadraticWedge.vtu").read_bytes())
    put("vtk_xml", "StructuredGrid.vts", b"\x01" + (DATA / "real" / "StructuredGrid.vts").read_bytes())
    put("vtk_xml", "image.vti", b"\x03" + write_xml(vtk.vtkXMLImageDataWriter(), image(), tmp / "i.vti", "appended", "zlib"))
    rect = vtk.vtkRectilinearGrid()
    rect.SetDimensions(3, 2, 2)
    for axis, n in ((rect.SetXCoordinates, 3), (rect.SetYCoordinates, 2), (rect.SetZCoordinates, 2)):
        coords = vtk.vtkDoubleArray()
        for i in range(n):
            coords.InsertNextValue(i * 0.5)
        axis(coords)
    scalars = vtk.vtkDoubleArray()
    scalars.SetName("f")
    for i in range(12):
        scalars.InsertNextValue(i)
    rect.GetPointData().SetScalars(scalars)
    put("vtk_xml", "rect.vtr", b"\x02" + write_xml(vtk.vtkXMLRectilinearGridWriter(), rect, tmp / "r.vtr", "binary", None))

    # A parallel file of two pieces, and a multi-block file of one block.
    pwriter = vtk.vtkXMLPUnstructuredGridWriter()
    pwriter.SetInputData(grid)
    pwriter.SetFileName(str(tmp / "p.pvtu"))
    pwriter.SetNumberOfPieces(2)
    pwriter.SetStartPiece(0)
    pwriter.SetEndPiece(1)
    pwriter.SetDataModeToAscii()
    pwriter.Write()
    files = [("p.pvtu", (tmp / "p.pvtu").read_bytes())]
    files += [(f.name, f.read_bytes()) for f in sorted(tmp.glob("p_*.vtu"))]
    put("collections", "two-pieces.pvtu", archive(files))
    mb = vtk.vtkMultiBlockDataSet()
    mb.SetBlock(0, grid)
    mwriter = vtk.vtkXMLMultiBlockDataWriter()
    mwriter.SetInputData(mb)
    mwriter.SetFileName(str(tmp / "m.vtm"))
    mwriter.SetDataModeToAscii()
    mwriter.Write()
    files = [("m.vtm", (tmp / "m.vtm").read_bytes())]
    files += [(str(f.relative_to(tmp)), f.read_bytes()) for f in sorted((tmp / "m").rglob("*.vtu"))]
    put("collections", "one-block.vtm", archive(files))
    series = b'{"file-series-version": "1.0", "files": [{"name": "a.vtk", "time": 0}, {"name": "b.vtk", "time": 1}]}'
    legacy = (tmp / "g-ascii.vtk").read_bytes()
    put("collections", "two-steps.series", archive([("s.series", series), ("a.vtk", legacy), ("b.vtk", legacy)]))

    put("exodus", "netcdf4.exo", (DATA / "exodus" / "tet_wedge_netcdf4.exo").read_bytes())

    n = (3, 3, 2)
    count = n[0] * n[1] * n[2]
    xyz = struct.pack("<3i", *n)
    for axis in range(3):
        xyz += b"".join(struct.pack("<f", [i % 3, (i // 3) % 3, i // 9][axis] * 0.5) for i in range(count))
    q = struct.pack("<3i", *n) + struct.pack("<4f", 0.5, 0.0, 1e6, 0.0)
    q += b"".join(struct.pack("<f", 1.0 + 0.1 * i) for i in range(5 * count))
    put("plot3d", "small.bin", archive([("xyz", xyz), ("q", q)]))

    for name in ("polyhedron.vtkhdf", "image.vtkhdf", "cube_temporal.vtkhdf"):
        put("hdf5_formats", name, b"\x00" + (DATA / "vtkhdf" / name).read_bytes())
    for name in ("unstructured.cgns", "polyhedral.cgns"):
        put("hdf5_formats", name, b"\x01" + (DATA / "cgns" / name).read_bytes())
    for name in ("unstructured-adf.cgns", "polyhedral-adf.cgns", "structured-adf.cgns"):
        put("cgns_adf", name, (DATA / "cgns" / name).read_bytes())

    cavity = DATA / "real" / "openfoam" / "cavity"
    files = [("system/controlDict", (cavity / "system" / "controlDict").read_bytes())]
    for sub in ("constant/polyMesh", "0"):
        files += [(str(f.relative_to(cavity)), f.read_bytes()) for f in sorted((cavity / sub).rglob("*")) if f.is_file()]
    put("case_folders", "cavity.foam", archive(files))
    ensight = DATA / "real" / "ensight"
    files = [("LShape.case", (ensight / "LShape.case").read_bytes())]
    files += [(f.name, f.read_bytes()) for f in sorted(ensight.glob("LShape_*"))]
    put("case_folders", "lshape.case", archive(files))

    # Cells: a point count, coordinates, then (type pick, count, ids)...
    put("cells", "tets.bin", bytes([8] + list(range(24)) + [0, 4, 0, 1, 2, 3, 0, 4, 4, 5, 6, 7]))
    put("cells", "hex.bin", bytes([8] + [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1] + [1, 8, 0, 1, 2, 3, 4, 5, 6, 7]))
    put("cells", "polyhedron.bin", bytes([4] + [0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1] + [12, 17, 4, 3, 0, 2, 1, 3, 0, 1, 3, 3, 0, 3, 2, 3, 1, 2, 3]))
    shutil.rmtree(tmp)
    total = sum(f.stat().st_size for f in CORPUS.rglob("*") if f.is_file())
    print(f"wrote {sum(1 for f in CORPUS.rglob('*') if f.is_file())} seeds, {total} bytes")


if __name__ == "__main__":
    main()
