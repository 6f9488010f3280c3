//! `.vtu` files built by hand (not by our writer): VTK's own output, big-
//! endian appended raw zlib data with UInt64 headers, several Pieces,
//! separately padded base64 headers.

mod vtk_common;

use std::io::Write;

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use flate2::Compression;
use flate2::write::ZlibEncoder;
use tetray_io::vtk::read_vtu_bytes;

/// The payloads of a file written by VTK 9's vtkXMLUnstructuredGridWriter
/// (4 points of the unit square, 2 triangles; UInt32 headers, zlib, inline
/// base64 with header and blocks encoded separately), kept with VTK's
/// `<InformationKey>` element nested inside the Points DataArray.
#[test]
fn reads_vtk_written_inline_zlib_arrays() {
    let xml = r#"<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian" header_type="UInt32" compressor="vtkZLibDataCompressor">
<UnstructuredGrid>
<Piece NumberOfPoints="4" NumberOfCells="2">
<PointData>
</PointData>
<CellData>
</CellData>
<Points>
<DataArray type="Float32" Name="Points" NumberOfComponents="3" format="binary" RangeMin="0" RangeMax="1.4142135623730951">
AQAAAACAAAAwAAAAFQAAAA==eAFjYEAGDfYIHoiNzmdgAAA65AL9
<InformationKey name="L2_NORM_RANGE" location="vtkDataArray" length="2">
<Value index="0">
0
</Value>
<Value index="1">
1.4142135624
</Value>
</InformationKey>
</DataArray>
</Points>
<Cells>
<DataArray type="Int64" Name="connectivity" format="binary" RangeMin="0" RangeMax="3">
AQAAAACAAAAwAAAAFQAAAA==eAFjYIAARijNhEYzQ/kwCgAA+AAJ
</DataArray>
<DataArray type="Int64" Name="offsets" format="binary" RangeMin="3" RangeMax="6">
AQAAAACAAAAQAAAADgAAAA==eAFjZoAANigNAABwAAo=
</DataArray>
<DataArray type="UInt8" Name="types" format="binary" RangeMin="5" RangeMax="5">
AQAAAACAAAACAAAACgAAAA==eAFjZQUAABEACw==
</DataArray>
</Cells>
</Piece>
</UnstructuredGrid>
</VTKFile>"#;
    let read = read_vtu_bytes(xml.as_bytes(), "vtk9.vtu").unwrap();
    let xyz: Vec<f32> = read.mesh.points.iter().flat_map(|p| p.to_array()).collect();
    assert_eq!(xyz, [0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.]);
    assert!(read.mesh.tets.is_empty());
    assert_eq!(read.cells.skipped_lower_dim, 2);
    assert!(
        read.warnings[0].contains("2 triangle"),
        "{:?}",
        read.warnings
    );
}

/// zlib blocks of `block` bytes with a big-endian UInt64 header.
fn zlib_be64(raw: &[u8], block: usize) -> Vec<u8> {
    let mut header = vec![
        raw.chunks(block).len() as u64,
        block as u64,
        (raw.len() % block) as u64,
    ];
    let mut data = Vec::new();
    for chunk in raw.chunks(block) {
        let mut e = ZlibEncoder::new(Vec::new(), Compression::best());
        e.write_all(chunk).unwrap();
        let c = e.finish().unwrap();
        header.push(c.len() as u64);
        data.extend(c);
    }
    let mut out: Vec<u8> = header.iter().flat_map(|h| h.to_be_bytes()).collect();
    out.extend(data);
    out
}

#[test]
fn reads_big_endian_appended_raw_zlib_with_uint64_headers() {
    let points: [f32; 15] = [0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1., 1., 1., 1.];
    let s: [f64; 5] = [0.5, -1.25, 1e-30, 3.0, 1e30];
    let cells: [i32; 11] = [0, 1, 2, 3, 1, 2, 3, 4, 0, 1, 2];
    let offsets: [i64; 3] = [4, 8, 11];
    let types: [u8; 3] = [10, 10, 5];
    let c: [i32; 3] = [10, 20, 70000];
    let arrays: Vec<Vec<u8>> = vec![
        s.iter().flat_map(|x| x.to_be_bytes()).collect(),
        c.iter().flat_map(|x| x.to_be_bytes()).collect(),
        points.iter().flat_map(|x| x.to_be_bytes()).collect(),
        cells.iter().flat_map(|x| x.to_be_bytes()).collect(),
        offsets.iter().flat_map(|x| x.to_be_bytes()).collect(),
        types.to_vec(),
    ];
    let mut blob = Vec::new();
    let mut at = Vec::new();
    for raw in &arrays {
        at.push(blob.len());
        blob.extend(zlib_be64(raw, 16));
    }
    let xml = format!(
        r#"<?xml version="1.0"?>
<!-- written by hand -->
<VTKFile type="UnstructuredGrid" version="1.0" byte_order="BigEndian" header_type="UInt64" compressor="vtkZLibDataCompressor">
  <UnstructuredGrid>
    <FieldData><DataArray type="Float64" Name="TIME" NumberOfTuples="1" format="ascii">0</DataArray></FieldData>
    <Piece NumberOfPoints="5" NumberOfCells="3">
      <PointData Scalars="s"><DataArray type="Float64" Name="s" format="appended" offset="{}"/></PointData>
      <CellData><DataArray type="Int32" Name="c" format="appended" offset="{}"/></CellData>
      <Points><DataArray type="Float32" NumberOfComponents="3" format="appended" offset="{}"/></Points>
      <Cells>
        <DataArray type="Int32" Name="connectivity" format="appended" offset="{}"/>
        <DataArray type="Int64" Name="offsets" format="appended" offset="{}"/>
        <DataArray type="UInt8" Name="types" format="appended" offset="{}"/>
      </Cells>
    </Piece>
  </UnstructuredGrid>
  <AppendedData encoding="raw">
   _"#,
        at[0], at[1], at[2], at[3], at[4], at[5]
    );
    let mut bytes = xml.into_bytes();
    bytes.extend(&blob);
    bytes.extend(b"\n  </AppendedData>\n</VTKFile>\n");

    let read = read_vtu_bytes(&bytes, "be.vtu").unwrap();
    let xyz: Vec<f32> = read.mesh.points.iter().flat_map(|p| p.to_array()).collect();
    assert_eq!(xyz, points);
    assert_eq!(read.mesh.tets, vec![[0, 1, 2, 3], [1, 2, 3, 4]]);
    assert_eq!(read.cells.skipped_lower_dim, 1);
    assert_eq!(read.mesh.fields[0].name, "s");
    assert_eq!(read.mesh.fields[0].values, s.map(|x| x as f32));
    // Cell "c" averaged over the tetrahedra only (the triangle's 70000
    // does not count): point 0 -> 10, points 1-3 -> 15, point 4 -> 20.
    assert_eq!(read.mesh.fields[1].name, "c");
    assert_eq!(read.mesh.fields[1].values, [10.0, 15.0, 15.0, 15.0, 20.0]);
}

/// Base64 of a UInt32 little-endian byte-count header and the data,
/// encoded separately (two padded runs), as meshio and VTK's compressed
/// arrays do.
fn split_b64(raw: &[u8]) -> String {
    STANDARD.encode((raw.len() as u32).to_le_bytes()) + &STANDARD.encode(raw)
}

#[test]
fn concatenates_pieces_and_reads_separately_padded_base64() {
    let piece = |shift: f32, extra: &str| {
        let pts: Vec<u8> = [0., 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.]
            .iter()
            .flat_map(|&x: &f32| (x + shift).to_le_bytes())
            .collect();
        format!(
            r#"<Piece NumberOfPoints="4" NumberOfCells="1">
  <PointData>
    <DataArray type="Float32" Name="t" format="ascii">{} 1 2 3</DataArray>{extra}
  </PointData>
  <Points><DataArray type="Float32" NumberOfComponents="3" format="binary">{}</DataArray></Points>
  <Cells>
    <DataArray type="Int64" Name="connectivity" format="ascii">0 1 2 3</DataArray>
    <DataArray type="Int32" Name="offsets" format="binary">{}</DataArray>
    <DataArray type="UInt8" Name="types" format="ascii">10</DataArray>
  </Cells>
</Piece>"#,
            shift,
            split_b64(&pts),
            split_b64(&4i32.to_le_bytes()),
        )
    };
    let extra = r#"<DataArray type="Float32" Name="only_first" format="ascii">9 9 9 9</DataArray>"#;
    let xml = format!(
        "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n{}\n{}\n</UnstructuredGrid>\n</VTKFile>\n",
        piece(0.0, extra),
        piece(5.0, "")
    );
    let read = read_vtu_bytes(xml.as_bytes(), "pieces.vtu").unwrap();
    assert_eq!(read.mesh.points.len(), 8);
    assert_eq!(read.mesh.points[4].x, 5.0);
    assert_eq!(read.mesh.tets, vec![[0, 1, 2, 3], [4, 5, 6, 7]]);
    assert_eq!(read.mesh.fields.len(), 1);
    assert_eq!(read.mesh.fields[0].values, [0., 1., 2., 3., 5., 1., 2., 3.]);
    assert!(
        read.warnings.iter().any(|w| w.contains("only_first")),
        "{:?}",
        read.warnings
    );
}

#[test]
fn reads_appended_base64_with_both_header_layouts() {
    let pts: Vec<u8> = [0f32, 0., 0., 1., 0., 0., 0., 1., 0., 0., 0., 1.]
        .iter()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    let conn: Vec<u8> = [0i32, 1, 2, 3]
        .iter()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    // Joined: one base64 run for header + data.
    let joined = |raw: &[u8]| {
        let mut v = (raw.len() as u32).to_le_bytes().to_vec();
        v.extend_from_slice(raw);
        STANDARD.encode(v)
    };
    let runs = [
        split_b64(&pts),
        joined(&conn),
        split_b64(&4i32.to_le_bytes()),
        joined(&[10u8]),
    ];
    let mut offsets = Vec::new();
    let mut text = String::new();
    for r in &runs {
        offsets.push(text.len());
        text.push_str(r);
    }
    let xml = format!(
        r#"<VTKFile type="UnstructuredGrid" byte_order="LittleEndian" header_type="UInt32">
<UnstructuredGrid><Piece NumberOfPoints="4" NumberOfCells="1">
<Points><DataArray type="Float32" NumberOfComponents="3" format="appended" offset="{}"/></Points>
<Cells><DataArray type="Int32" Name="connectivity" format="appended" offset="{}"/>
<DataArray type="Int32" Name="offsets" format="appended" offset="{}"/>
<DataArray type="UInt8" Name="types" format="appended" offset="{}"/></Cells>
</Piece></UnstructuredGrid>
<AppendedData encoding="base64">_{text}</AppendedData></VTKFile>"#,
        offsets[0], offsets[1], offsets[2], offsets[3]
    );
    let read = read_vtu_bytes(xml.as_bytes(), "b64.vtu").unwrap();
    assert_eq!(read.mesh.tets, vec![[0, 1, 2, 3]]);
    assert_eq!(read.mesh.points[3].z, 1.0);
}

#[test]
fn empty_pieces_keep_the_fields_of_the_others() {
    let full = r#"<Piece NumberOfPoints="4" NumberOfCells="1">
<PointData><DataArray type="Float32" Name="t" format="ascii">0 1 2 3</DataArray></PointData>
<Points><DataArray type="Float32" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 0 1 0 0 0 1</DataArray></Points>
<Cells><DataArray type="Int32" Name="connectivity" format="ascii">0 1 2 3</DataArray>
<DataArray type="Int32" Name="offsets" format="ascii">4</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">10</DataArray></Cells></Piece>"#;
    let empty =
        r#"<Piece NumberOfPoints="0" NumberOfCells="0"><PointData/><Points/><Cells/></Piece>"#;
    let xml = format!(
        "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid>{empty}{full}{empty}{full}</UnstructuredGrid></VTKFile>"
    );
    let read = read_vtu_bytes(xml.as_bytes(), "parallel.vtu").unwrap();
    assert_eq!(read.mesh.tets, vec![[0, 1, 2, 3], [4, 5, 6, 7]]);
    assert_eq!(read.mesh.fields[0].values, [0., 1., 2., 3., 0., 1., 2., 3.]);
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
    let none = "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid></UnstructuredGrid></VTKFile>";
    let e = read_vtu_bytes(none.as_bytes(), "none.vtu").unwrap_err();
    assert!(e.to_string().contains("no <Piece>"), "{e}");
}
