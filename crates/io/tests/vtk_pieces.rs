//! Parallel `.pvtu` and multi-block `.vtm` files: the blood-vessel and
//! ex-blow samples, and pieces written here (ghost cells, global ids,
//! nested blocks) read back and compared with the same cells as one file.

mod structured_common;
mod vtk_common;

use std::collections::{HashMap, HashSet};
use std::path::Path;
use std::time::Instant;

use structured_common::{
    Enc, Piece, TempDir, array, block_hexes, extent_attr, real_data, section, unstructured_piece,
    warped_points, xml_file,
};
use tetray_io::vtk::{
    VtkError, VtuEncoding, read_multiblock_file, read_parallel_file, read_vtu_bytes, read_vtu_file,
    write_vtu,
};
use tetray_io::{LoadOptions, load};
use tetray_mesh::TetMesh;
use vtk_common::volume6;

type Key = [u32; 3];

fn key(p: glam::Vec3) -> Key {
    p.to_array().map(f32::to_bits)
}

/// Every tetrahedron as its sorted corner positions: equal sets mean the
/// same tetrahedra whatever the point numbering.
fn tet_set(mesh: &TetMesh) -> HashSet<[Key; 4]> {
    mesh.tets
        .iter()
        .map(|t| {
            let mut k = t.map(|i| key(mesh.points[i as usize]));
            k.sort_unstable();
            k
        })
        .collect()
}

/// The points in the file's coordinates: `origin` (where the reader
/// centred them) added back in f64.
fn point_set(mesh: &TetMesh, origin: glam::DVec3) -> HashSet<Key> {
    mesh.points
        .iter()
        .map(|&p| key((p.as_dvec3() + origin).as_vec3()))
        .collect()
}

fn total_volume(mesh: &TetMesh) -> f64 {
    mesh.tets
        .iter()
        .map(|&t| volume6(mesh, t).abs())
        .sum::<f64>()
        / 6.0
}

#[test]
fn blood_vessel_pieces_join_into_one_component() {
    let pvtu = real_data("blood_vessels/T0000000500.pvtu");
    // The expected numbers come from the four piece files read one by one.
    let pieces: Vec<_> = (0..4)
        .map(|k| {
            read_vtu_file(&real_data(&format!("blood_vessels/T0000000500/00{k}.vtu"))).unwrap()
        })
        .collect();
    let volume_cells =
        |c: &tetray_io::vtk::CellCounts| c.tetra + c.hexahedra + c.voxels + c.wedges + c.pyramids;
    let cells: usize = pieces.iter().map(|p| volume_cells(&p.cells)).sum();
    let points: usize = pieces.iter().map(|p| p.mesh.points.len()).sum();
    let distinct: HashSet<Key> = pieces
        .iter()
        .flat_map(|p| point_set(&p.mesh, p.origin))
        .collect();
    let piece_volume: f64 = pieces.iter().map(|p| total_volume(&p.mesh)).sum();

    let start = Instant::now();
    let loaded = load(&pvtu, &LoadOptions::default()).unwrap();
    eprintln!(
        "T0000000500.pvtu (4 pieces, {cells} cells) loaded in {:.1} ms",
        start.elapsed().as_secs_f64() * 1e3
    );
    let report = &loaded.report;
    assert_eq!(report.format, "VTK parallel XML");
    assert_eq!(report.pieces.pieces, 4);
    // The pieces carry no vtkGhostType array: no ghost cell to drop.
    assert_eq!(report.pieces.ghost_cells_dropped, 0);
    assert_eq!(report.pieces.welded_points, points - distinct.len());
    assert_eq!(loaded.mesh.points.len(), distinct.len());
    assert_eq!(point_set(&loaded.mesh, report.origin), distinct);
    assert_eq!(report.validation.components, 1);
    let read = read_parallel_file(&pvtu).unwrap();
    assert_eq!(volume_cells(&read.cells), cells);
    // Splits of the interface cells may differ from the pieces' own, the
    // volume may not (relative f64 summation error only).
    let volume = total_volume(&loaded.mesh);
    assert!(
        (volume - piece_volume).abs() <= 1e-9 * piece_volume,
        "{volume} vs {piece_volume}"
    );
    let names: Vec<&str> = loaded.mesh.fields.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "node_value",
            "simerr_type",
            "density",
            "velocity_magnitude",
            "shearstress"
        ]
    );

    // The same mesh as ONE .vtu (the existing writer) reads back the same.
    let mut bytes = Vec::new();
    write_vtu(&loaded.mesh, &mut bytes, VtuEncoding::AppendedRaw, true).unwrap();
    let one = read_vtu_bytes(&bytes, "one.vtu").unwrap();
    assert_eq!(tet_set(&one.mesh), tet_set(&loaded.mesh));
    // It holds the stored points: relative to the origin of the load.
    assert_eq!(point_set(&one.mesh, report.origin + one.origin), distinct);
}

/// How the pieces give point ids: the id array's name, whether
/// `<PointData GlobalIds>` marks it, and how far piece 1 moves its copy of
/// the shared plane (so that only ids can weld it).
type Ids = (&'static str, bool, f64);
const MARKED: Ids = ("gid", true, 1e-6);
/// VTK's Exodus reader's name: ids even unmarked.
const NAMED: Ids = ("GlobalNodeId", false, 1e-6);
/// A plain field: pieces weld by coordinates.
const PLAIN: Ids = ("node", false, 0.0);

/// A 5 x 3 x 3 point block (16 hexahedra) cut at x = 2 into two pieces,
/// each with one layer of ghost cells (vtkGhostType 1) from the other and
/// the points they need, with point ids as `ids` says.
fn write_two_pieces(dir: &TempDir, ids: Ids) -> (std::path::PathBuf, Vec<f64>) {
    let (id_name, marked, shift) = ids;
    let whole = warped_points([0, 4, 0, 2, 0, 2]);
    let piece = |x0: usize, x1: usize, owned: std::ops::Range<usize>, shift: f64| {
        // Points x0..=x1 of the block, cells between them.
        let nx = x1 - x0 + 1;
        let mut points = Vec::new();
        let mut gids = Vec::new();
        for k in 0..3 {
            for j in 0..3 {
                for i in x0..=x1 {
                    let g = i + 5 * (j + 3 * k);
                    gids.push(g as f64);
                    let moved = if i == 2 && x0 == 1 { shift } else { 0.0 };
                    points.extend_from_slice(&[
                        whole[3 * g] + moved,
                        whole[3 * g + 1],
                        whole[3 * g + 2],
                    ]);
                }
            }
        }
        let cells = block_hexes([nx, 3, 3]);
        let mut ghosts = Vec::new();
        let mut cell_ids = Vec::new();
        for c in 0..cells.len() {
            let i = x0 + c % (nx - 1);
            ghosts.push(if owned.contains(&i) { 0.0 } else { 1.0 });
            cell_ids.push((i + 4 * (c / (nx - 1))) as f64);
        }
        let point_data = vec![
            array(id_name, "Int64", 1, gids.clone()),
            array("f", "Float64", 1, gids.iter().map(|g| 0.25 * g).collect()),
        ];
        let cell_data = vec![
            array("vtkGhostType", "UInt8", 1, ghosts),
            array("cell", "Float64", 1, cell_ids),
        ];
        let attrs = if marked {
            format!("GlobalIds=\"{id_name}\"")
        } else {
            String::new()
        };
        let types = vec![12; cells.len()];
        let p = unstructured_piece(&points, &cells, &types, point_data, cell_data, &attrs);
        xml_file("UnstructuredGrid", "", &[p], Enc::Base64)
    };
    dir.write("parts/p0.vtu", &piece(0, 3, 0..2, 0.0));
    dir.write("parts/p1.vtu", &piece(1, 4, 2..4, shift));
    let pvtu = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\">\n\
                <PUnstructuredGrid GhostLevel=\"1\">\n<PPoints><PDataArray type=\"Float64\" NumberOfComponents=\"3\"/></PPoints>\n\
                <Piece Source=\"parts/p0.vtu\"/>\n<Piece Source=\"parts/p1.vtu\"/>\n\
                </PUnstructuredGrid>\n</VTKFile>\n";
    (dir.write("two.pvtu", pvtu.as_bytes()), whole)
}

#[test]
fn ghost_cells_drop_and_pieces_weld_like_one_file() {
    for ids in [MARKED, NAMED, PLAIN] {
        let dir = TempDir::new(&format!("pvtu-{}", ids.0));
        let (path, whole) = write_two_pieces(&dir, ids);
        let loaded = load(&path, &LoadOptions::default()).unwrap();
        let p = loaded.report.pieces;
        // 4 ghost cells (one layer of 1 x 2 x 2) in each piece.
        assert_eq!(p.ghost_cells_dropped, 8, "ids {ids:?}");
        // The 3 x 3 points of the plane x = 2; the ghost-only planes go.
        assert_eq!(p.welded_points, 9, "ids {ids:?}");
        assert_eq!(loaded.mesh.points.len(), 45, "ids {ids:?}");
        assert_eq!(loaded.report.cells_split, 16, "ids {ids:?}");
        assert_eq!(loaded.report.validation.components, 1, "ids {ids:?}");
        let names: Vec<&str> = loaded.mesh.fields.iter().map(|f| f.name.as_str()).collect();
        let want_names: &[&str] = if ids == PLAIN {
            &["node", "f", "cell"]
        } else {
            &["f", "cell"]
        };
        assert_eq!(names, want_names, "ids {ids:?}");

        // The same 16 hexahedra as one .vtu, numbered as the block: the
        // welded points keep that order, so the splits agree.
        let one = unstructured_piece(
            &whole,
            &block_hexes([5, 3, 3]),
            &[12; 16],
            vec![array(
                "f",
                "Float64",
                1,
                (0..45).map(|g| 0.25 * g as f64).collect(),
            )],
            vec![],
            "",
        );
        let bytes = xml_file("UnstructuredGrid", "", &[one], Enc::AppendedRaw);
        let one = read_vtu_bytes(&bytes, "one.vtu").unwrap();
        let mut oriented = one.mesh.clone();
        oriented.orient();
        assert_eq!(
            point_set(&loaded.mesh, loaded.report.origin),
            point_set(&one.mesh, one.origin),
            "ids {ids:?}"
        );
        assert_eq!(tet_set(&loaded.mesh), tet_set(&oriented), "ids {ids:?}");
        let f = |m: &TetMesh| -> HashMap<Key, u32> {
            let field = &m.fields.iter().find(|f| f.name == "f").unwrap().values;
            m.points
                .iter()
                .zip(field)
                .map(|(&p, v)| (key(p), v.to_bits()))
                .collect()
        };
        assert_eq!(f(&loaded.mesh), f(&one.mesh), "ids {ids:?}");
    }
}

#[test]
fn ex_blow_multiblock_is_one_clear_error() {
    let vtm = real_data("ex-blow_5.vtm");
    // The surface cells of the 16 leaves, read one by one.
    let mut surface = 0;
    for b in 0..2 {
        for k in 0..8 {
            let leaf = real_data(&format!("ex-blow_5/ex-blow_5_{b}_{k}.vtu"));
            let read = read_vtu_file(&leaf).unwrap();
            assert!(read.mesh.tets.is_empty());
            surface += read.cells.skipped_lower_dim;
        }
    }
    let start = Instant::now();
    let e = load(&vtm, &LoadOptions::default()).unwrap_err().to_string();
    eprintln!(
        "ex-blow_5.vtm refused in {:.1} ms: {e}",
        start.elapsed().as_secs_f64() * 1e3
    );
    assert!(
        e.contains("ex-blow_5.vtm holds only surface cells ("),
        "{e}"
    );
    assert!(
        e.ends_with("in 16 block files: nothing to volume-render"),
        "{e}"
    );
    let inside = &e[e.find('(').unwrap() + 1..e.find(')').unwrap()];
    let counted: usize = inside
        .split(", ")
        .map(|part| part.split(' ').next().unwrap().parse::<usize>().unwrap())
        .sum();
    assert_eq!(counted, surface, "{inside}");
    assert_eq!(e.matches("nothing to volume-render").count(), 1);
}

fn vtm_text(blocks: &str) -> String {
    format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\">\n<vtkMultiBlockDataSet>\n{blocks}</vtkMultiBlockDataSet>\n</VTKFile>\n"
    )
}

/// left.vts (x 0..2), a right .pvtu of two pieces (x 2..3, 3..4), a flat
/// wall and a polygonal outline, nested.
fn write_nested(dir: &TempDir) -> std::path::PathBuf {
    let structured = |e: [i64; 6], extra: bool| {
        let n = warped_points(e).len() / 3;
        let mut arrays = vec![array("temp", "Float64", 1, vec![1.5; n])];
        if extra {
            arrays.push(array("only_left", "Float64", 1, vec![0.0; n]));
        }
        let piece = Piece {
            attrs: extent_attr(e),
            sections: vec![
                section("PointData", "", arrays),
                section(
                    "Points",
                    "",
                    vec![array("Points", "Float64", 3, warped_points(e))],
                ),
            ],
        };
        let whole = extent_attr(e).replace("Extent", "WholeExtent");
        xml_file("StructuredGrid", &whole, &[piece], Enc::AppendedBase64)
    };
    dir.write("m/left.vts", &structured([0, 2, 0, 2, 0, 2], true));
    dir.write("m/right/r0.vts", &structured([2, 3, 0, 2, 0, 2], false));
    dir.write("m/right/r1.vts", &structured([3, 4, 0, 2, 0, 2], false));
    dir.write("m/wall.vts", &structured([0, 4, 0, 2, 0, 0], false));
    let pvts = "<VTKFile type=\"PStructuredGrid\"><PStructuredGrid WholeExtent=\"2 4 0 2 0 2\">\
                <Piece Extent=\"2 3 0 2 0 2\" Source=\"right/r0.vts\"/><Piece Extent=\"3 4 0 2 0 2\" Source=\"right/r1.vts\"/>\
                </PStructuredGrid></VTKFile>";
    dir.write("m/right.pvts", pvts.as_bytes());
    let blocks = "<Block index=\"0\" name=\"fluid\">\n\
          <Block index=\"0\" name=\"left\"><Piece index=\"0\"><DataSet index=\"0\" file=\"m/left.vts\"/></Piece></Block>\n\
          <Block index=\"1\" name=\"right\"><DataSet index=\"0\" file=\"m/right.pvts\"/></Block>\n\
        </Block>\n\
        <Block index=\"1\" name=\"walls\"><DataSet index=\"0\" file=\"m/wall.vts\"/></Block>\n\
        <DataSet index=\"2\" name=\"outline\" file=\"m/outline.vtp\"/>\n\
        <DataSet index=\"3\" name=\"empty\"/>\n";
    dir.write("nested.vtm", vtm_text(blocks).as_bytes())
}

#[test]
fn nested_blocks_merge_and_one_can_be_chosen() {
    let dir = TempDir::new("vtm");
    let path = write_nested(&dir);
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    let p = loaded.report.pieces;
    assert_eq!(loaded.report.format, "VTK multi-block");
    assert_eq!((p.blocks, p.blocks_skipped), (2, 2));
    // 27 + 18 + 18 points; the planes x = 2 and x = 3 (9 points each) weld.
    assert_eq!(p.welded_points, 18);
    assert_eq!(loaded.mesh.points.len(), 45);
    assert_eq!(loaded.report.cells_split, 8 + 4 + 4);
    assert_eq!(loaded.report.validation.components, 1);
    let names: Vec<&str> = loaded.mesh.fields.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["temp"]);
    let notes = loaded.report.warnings.join("\n");
    assert!(
        notes.contains(
            "skipped block \"walls\" (m/wall.vts): only surface cells (8 quadrilaterals)"
        ),
        "{notes}"
    );
    assert!(
        notes.contains("skipped block \"outline\" (m/outline.vtp): polygonal data"),
        "{notes}"
    );
    assert!(
        notes.contains("\"only_left\"") && notes.contains("not in every Piece, dropped"),
        "{notes}"
    );

    let only = |block: &str| {
        let options = LoadOptions {
            block: Some(block.into()),
            ..LoadOptions::default()
        };
        load(&path, &options)
    };
    let left = only("fluid/left").unwrap();
    assert_eq!((left.mesh.points.len(), left.report.cells_split), (27, 8));
    let right = only("right").unwrap();
    assert_eq!((right.mesh.points.len(), right.report.cells_split), (27, 8));
    assert_eq!(right.report.pieces.welded_points, 9);
    let e = only("walls").unwrap_err().to_string();
    assert!(
        e.ends_with(
            "holds only surface cells (8 quadrilaterals) in 1 block file: nothing to volume-render"
        ),
        "{e}"
    );
    let e = only("nope").unwrap_err().to_string();
    assert!(
        e.ends_with(
            "no block named \"nope\"; the blocks are: fluid/left, fluid/right, walls, outline"
        ),
        "{e}"
    );
}

#[test]
fn missing_pieces_and_blocks_name_the_file_and_the_piece() {
    let dir = TempDir::new("missing");
    let (path, _) = write_two_pieces(&dir, MARKED);
    std::fs::remove_file(dir.path().join("parts/p1.vtu")).unwrap();
    let e = read_parallel_file(&path).unwrap_err();
    assert!(matches!(e, VtkError::MissingFile { .. }), "{e}");
    let text = e.to_string();
    assert!(
        text.starts_with(&format!(
            "{}: piece \"parts/p1.vtu\" is missing: no file ",
            path.display()
        )),
        "{text}"
    );

    let vtm = dir.write(
        "gone.vtm",
        vtm_text(
            "<Block index=\"0\" name=\"b\"><DataSet index=\"0\" file=\"nowhere/x.vtu\"/></Block>\n",
        )
        .as_bytes(),
    );
    let e = read_multiblock_file(&vtm, None).unwrap_err().to_string();
    assert!(
        e.starts_with(&format!(
            "{}: block \"b\": file \"nowhere/x.vtu\" is missing",
            vtm.display()
        )),
        "{e}"
    );

    // A broken piece: its own error, naming the piece file.
    let (path, _) = write_two_pieces(&dir, PLAIN);
    std::fs::write(
        dir.path().join("parts/p0.vtu"),
        b"<VTKFile type=\"UnstructuredGrid\"><Unstr",
    )
    .unwrap();
    let e = read_parallel_file(&path).unwrap_err().to_string();
    let piece = Path::new(dir.path()).join("parts/p0.vtu");
    assert!(e.starts_with(&piece.display().to_string()), "{e}");
}
