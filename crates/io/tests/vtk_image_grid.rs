//! Image data read as a grid: legacy STRUCTURED_POINTS and XML ImageData
//! (with an offset extent); other datasets are errors.

mod structured_common;

use structured_common::TempDir;
use tetray_io::vtk::read_image_grid;

#[test]
fn legacy_structured_points() {
    let dir = TempDir::new("image-grid-legacy");
    let path = dir.write(
        "a.vtk",
        b"# vtk DataFile Version 3.0\nimage\nASCII\nDATASET STRUCTURED_POINTS\n\
         DIMENSIONS 3 2 2\nORIGIN 1 2 3\nSPACING 0.5 1 2\nPOINT_DATA 12\n\
         SCALARS s float 1\nLOOKUP_TABLE default\n0 1 2 3 4 5 6 7 8 9 10 11\n",
    );
    let g = read_image_grid(&path).unwrap();
    assert_eq!(g.dims, [3, 2, 2]);
    assert_eq!(g.origin, [1.0, 2.0, 3.0]);
    assert_eq!(g.spacing, [0.5, 1.0, 2.0]);
    assert_eq!(g.fields[0].name, "s");
    assert_eq!(g.fields[0].values[11], 11.0);
}

#[test]
fn xml_image_data_with_an_offset_extent() {
    let dir = TempDir::new("image-grid-xml");
    let path = dir.write(
        "b.vti",
        br#"<?xml version="1.0"?>
<VTKFile type="ImageData" version="0.1">
  <ImageData WholeExtent="1 2 0 1 0 1" Origin="0 0 0" Spacing="2 1 1">
    <Piece Extent="1 2 0 1 0 1">
      <PointData Scalars="d">
        <DataArray type="Float32" Name="d" format="ascii">0 1 2 3 4 5 6 7</DataArray>
      </PointData>
    </Piece>
  </ImageData>
</VTKFile>
"#,
    );
    let g = read_image_grid(&path).unwrap();
    assert_eq!(g.dims, [2, 2, 2]);
    assert_eq!(g.origin, [2.0, 0.0, 0.0]);
    assert_eq!(g.fields[0].values.len(), 8);
}

#[test]
fn other_datasets_are_errors() {
    let dir = TempDir::new("image-grid-other");
    let path = dir.write(
        "c.vtk",
        b"# vtk DataFile Version 3.0\ngrid\nASCII\nDATASET RECTILINEAR_GRID\n\
         DIMENSIONS 2 2 2\nX_COORDINATES 2 float\n0 1\nY_COORDINATES 2 float\n0 1\n\
         Z_COORDINATES 2 float\n0 3\n",
    );
    let err = read_image_grid(&path).unwrap_err().to_string();
    assert!(err.contains("single-piece ImageData"), "{err}");
}
