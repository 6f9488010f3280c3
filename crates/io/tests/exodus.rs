//! The Exodus II reader: the ParaView tutorial file, round trips through
//! netCDF classic files written here (CDF-1, CDF-2, CDF-5), a netCDF-4 file
//! made by an independent writer, and malformed input.

mod exodus_common;

use std::path::{Path, PathBuf};
use std::time::Instant;

use exodus_common::{Block, ElemVar, Model, Version};
use tetray_io::{
    ElementBlock, ExodusError, ExodusOptions, IoError, LoadOptions, load, read_exodus_bytes,
};
use tetray_mesh::{MeshSummary, TetMesh};

fn data(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(path)
}

fn field<'a>(mesh: &'a TetMesh, name: &str) -> &'a [f32] {
    let names: Vec<&str> = mesh.fields.iter().map(|f| f.name.as_str()).collect();
    &mesh
        .fields
        .iter()
        .find(|f| f.name == name)
        .unwrap_or_else(|| panic!("no field {name} among {names:?}"))
        .values
}

fn range(values: &[f32]) -> (f32, f32) {
    values
        .iter()
        .fold((f32::MAX, f32::MIN), |(lo, hi), &v| (lo.min(v), hi.max(v)))
}

fn close(a: f32, b: f64) -> bool {
    (f64::from(a) - b).abs() <= 1e-6 * b.abs().max(1e-3)
}

/// Expected numbers from Python netCDF4 1.7 on the same file (offline):
/// `d = netCDF4.Dataset("disk_out_ref.ex2")`; dimensions num_nodes 8499,
/// num_el_in_blk1 7472, connect1 elem_type "HEX8", eb_prop1 [1],
/// time_whole [0.]; `v = d["vals_nod_var"][0]` (old 3-D layout) in the
/// order of name_nod_var `Temp VX VY VZ Pres AsH3 GaMe3 CH4 H2`; min/max
/// per row, node 4242, and `sqrt(VX^2+VY^2+VZ^2)` for V.
#[test]
fn disk_out_ref_is_read_with_its_fields() {
    let path = data("real/disk_out_ref.ex2");
    let start = Instant::now();
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    eprintln!(
        "disk_out_ref.ex2: loaded in {:.3} s ({} tets)",
        start.elapsed().as_secs_f64(),
        loaded.mesh.tets.len()
    );
    let report = &loaded.report;
    assert_eq!(report.format, "Exodus II");
    assert_eq!(loaded.mesh.points.len(), 8499);
    assert_eq!(report.cells_split, 7472, "every HEX8 is split");
    assert_eq!(report.tets_from_split, loaded.mesh.tets.len());
    assert!(loaded.mesh.tets.len() >= 5 * 7472);
    assert_eq!(report.times, vec![0.0]);
    assert_eq!(report.time_step, Some(0));
    assert_eq!(
        report.blocks,
        vec![ElementBlock {
            id: 1,
            name: String::new(),
            elem_type: "HEX8".into(),
            nodes_per_element: 8,
            cells: 7472,
            kept: true,
        }]
    );
    let mesh = &loaded.mesh;
    for (name, lo, hi, at_4242) in [
        (
            "Temp",
            293.1499938964844,
            913.1500244140625,
            310.7834777832031,
        ),
        (
            "Pres",
            0.006785521749407053,
            0.028818512335419655,
            0.017534418031573296,
        ),
        ("VZ", -21.1259765625, 6.7119011878967285, -6.063072681427002),
        (
            "AsH3",
            0.08047682046890259,
            0.18483947217464447,
            0.14588281512260437,
        ),
        (
            "GaMe3",
            0.00022284436272457242,
            0.007213925942778587,
            0.0063100713305175304,
        ),
        ("CH4", 0.0, 0.0011702391784638166, 2.8323938749963418e-05),
        (
            "H2",
            0.8076131343841553,
            0.9176878929138184,
            0.8477787971496582,
        ),
        ("V_magnitude", 0.0, 22.418820167105352, 6.249357854987234),
    ] {
        let values = field(mesh, name);
        assert_eq!(values.len(), 8499, "{name}");
        let (min, max) = range(values);
        assert!(
            close(min, lo) && close(max, hi),
            "{name}: {min}..{max}, expected {lo}..{hi}"
        );
        assert!(
            close(values[4242], at_4242),
            "{name}[4242] = {}",
            values[4242]
        );
    }
    // Coordinates: node 4242 at (-3.00701642, 1.09446442, 8.33023739).
    let p = mesh.points[4242];
    assert!(close(p.x, -3.00701642) && close(p.y, 1.09446442) && close(p.z, 8.33023739));
}

/// A hex cube (block 10), two tets sharing a face away from it (block
/// 20) and a shell on the cube's bottom (block 30, skipped); two time
/// steps. Nodal: Temp = x + 10 step, VX = 1 + step, VY = 2, VZ = y.
/// Element: "stress" on the hex only (truth table), "rho" everywhere.
fn model() -> Model {
    let coords = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 1.0],
        [0.0, 1.0, 1.0],
        [3.0, 0.0, 0.0],
        [4.0, 0.0, 0.0],
        [3.0, 1.0, 0.0],
        [3.0, 0.0, 1.0],
        [4.0, 1.0, 1.0],
    ];
    let times = vec![0.0, 0.5];
    let per_node = |f: &dyn Fn(&[f64; 3], f64) -> f64| -> Vec<Vec<f64>> {
        (0..2)
            .map(|s| coords.iter().map(|p| f(p, s as f64)).collect())
            .collect()
    };
    let nodal = vec![
        ("Temp".to_string(), per_node(&|p, s| p[0] + 10.0 * s)),
        ("VX".to_string(), per_node(&|_, s| 1.0 + s)),
        ("VY".to_string(), per_node(&|_, _| 2.0)),
        ("VZ".to_string(), per_node(&|p, _| p[1])),
    ];
    let elem = vec![
        ElemVar {
            name: "stress".into(),
            per_step: (0..2)
                .map(|s| vec![Some(vec![100.0 + s as f64]), None, None])
                .collect(),
        },
        ElemVar {
            name: "rho".into(),
            per_step: (0..2)
                .map(|s| {
                    let s = s as f64;
                    vec![
                        Some(vec![1.0 + s]),
                        Some(vec![2.0 + s, 4.0 + s]),
                        Some(vec![9.0]),
                    ]
                })
                .collect(),
        },
    ];
    Model {
        coords,
        blocks: vec![
            Block::new(10, "solid", "HEX8", 8, &[1, 2, 3, 4, 5, 6, 7, 8]),
            Block::new(20, "tets", "tetra", 4, &[9, 10, 11, 12, 10, 11, 12, 13]),
            Block::new(30, "skin", "SHELL4", 4, &[1, 2, 3, 4]),
        ],
        times,
        nodal,
        elem,
        old_layout: false,
        int64: false,
    }
}

fn step(time_step: Option<usize>, time: Option<f64>) -> ExodusOptions {
    ExodusOptions {
        time_step,
        time,
        ..ExodusOptions::default()
    }
}

/// Checks a read of [`model`] at time step 1 against the values it was
/// written with.
fn check_step_1(bytes: &[u8], name: &str) {
    let read = read_exodus_bytes(bytes, name, &step(Some(1), None)).unwrap();
    assert_eq!(read.times, vec![0.0, 0.5], "{name}");
    assert_eq!(read.time_step, Some(1));
    assert_eq!(read.cells.hexahedra, 1);
    assert_eq!(read.cells.tetra, 2);
    let kept: Vec<(i64, &str, usize, bool)> = read
        .blocks
        .iter()
        .map(|b| (b.id, b.name.as_str(), b.cells, b.kept))
        .collect();
    assert_eq!(
        kept,
        vec![
            (10, "solid", 1, true),
            (20, "tets", 2, true),
            (30, "skin", 1, false)
        ]
    );
    let skipped = read
        .warnings
        .iter()
        .find(|w| w.contains("non-volume"))
        .unwrap();
    assert!(
        skipped.contains("\"skin\" (id 30, SHELL4, 1 elements)"),
        "{skipped}"
    );
    let mesh = &read.mesh;
    assert_eq!(mesh.points.len(), 13);
    assert_eq!(mesh.points[12], glam::Vec3::new(4.0, 1.0, 1.0));
    let temp = field(mesh, "Temp");
    for (p, t) in mesh.points.iter().zip(temp) {
        assert_eq!(*t, p.x + 10.0);
    }
    // V = (2, 2, y): |V| = sqrt(8 + y^2); the components stay.
    let v = field(mesh, "V_magnitude");
    for (p, m) in mesh.points.iter().zip(v) {
        assert!((m - (8.0 + p.y * p.y).sqrt()).abs() < 1e-6);
    }
    assert_eq!(field(mesh, "VX")[0], 2.0);
    // stress: 101 on the hex's nodes, nothing (0) at the tets'.
    let stress = field(mesh, "stress");
    assert_eq!(&stress[..8], &[101.0; 8]);
    assert_eq!(&stress[8..], &[0.0; 5]);
    // rho: hex 2; tets 3 and 5; the shell's 9 plays no part.
    let rho = field(mesh, "rho");
    assert_eq!(&rho[..8], &[2.0; 8]);
    assert_eq!(&rho[8..], &[3.0, 4.0, 4.0, 4.0, 5.0]);
}

#[test]
fn round_trips_through_every_classic_version() {
    for version in [Version::Cdf1, Version::Cdf2, Version::Cdf5] {
        for old_layout in [false, true] {
            let mut m = model();
            m.old_layout = old_layout;
            m.int64 = version == Version::Cdf5;
            let name = format!("model-{version:?}-old{old_layout}.exo");
            check_step_1(&m.write(version), &name);
        }
    }
}

#[test]
fn time_is_chosen_by_step_or_nearest_time() {
    let bytes = model().write(Version::Cdf1);
    let at = |opts| read_exodus_bytes(&bytes, "t.exo", &opts);
    let temp0 = |opts| field(&at(opts).unwrap().mesh, "Temp")[1];
    assert_eq!(temp0(step(None, None)), 1.0, "step 0 by default");
    assert_eq!(temp0(step(None, Some(0.4))), 11.0, "0.4 is nearest 0.5");
    assert_eq!(temp0(step(None, Some(-7.0))), 1.0);
    assert_eq!(at(step(None, Some(0.4))).unwrap().time_step, Some(1));
    let e = at(step(Some(2), None)).unwrap_err();
    assert!(matches!(
        e,
        ExodusError::TimeStepOutOfRange {
            requested: 2,
            count: 2,
            ..
        }
    ));
    let message = e.to_string();
    assert!(
        message.contains("t.exo") && message.contains("2 time step(s)"),
        "{message}"
    );
    let e = at(step(Some(0), Some(0.0))).unwrap_err();
    assert!(matches!(e, ExodusError::Time { .. }), "{e}");
    let e = at(step(None, Some(f64::NAN))).unwrap_err();
    assert!(matches!(e, ExodusError::Time { .. }), "{e}");
}

#[test]
fn load_reads_a_file_by_its_name_and_reports_steps_and_blocks() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("exodus_load");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("model.E");
    std::fs::write(&path, model().write(Version::Cdf2)).unwrap();
    let opts = LoadOptions {
        time: Some(0.5),
        ..LoadOptions::default()
    };
    let loaded = load(&path, &opts).unwrap();
    assert_eq!(loaded.report.format, "Exodus II");
    assert_eq!(loaded.report.time_step, Some(1));
    assert_eq!(loaded.report.times, vec![0.0, 0.5]);
    assert_eq!(loaded.report.blocks.len(), 3);
    assert_eq!(loaded.report.cells_split, 1);
    assert!(loaded.report.validation.components == 2);
    // What `tetray info` prints of them.
    let text = MeshSummary::new(&loaded).to_string();
    for line in [
        "time steps:      2 (read step 1, time 0.5)",
        "  id 10 \"solid\": 1 x HEX8 (8 nodes), kept",
        "  id 20 \"tets\": 2 x tetra (4 nodes), kept",
        "  id 30 \"skin\": 1 x SHELL4 (4 nodes), skipped",
    ] {
        assert!(
            text.lines().any(|l| l == line),
            "no line {line:?} in\n{text}"
        );
    }
    let opts = LoadOptions {
        time_step: Some(5),
        ..LoadOptions::default()
    };
    let e = load(&path, &opts).unwrap_err();
    assert!(matches!(
        e,
        IoError::Exodus(ExodusError::TimeStepOutOfRange { .. })
    ));
    assert!(e.to_string().contains("model.E"), "{e}");
}

/// `data/exodus/tet_wedge_netcdf4.exo`, written by Python netCDF4 with
/// `data/exodus/make_netcdf4.py`; every expected number below is the
/// value that script writes.
#[test]
fn netcdf4_file_from_an_independent_writer() {
    let path = data("exodus/tet_wedge_netcdf4.exo");
    let bytes = std::fs::read(&path).unwrap();
    let read = read_exodus_bytes(&bytes, "tet_wedge_netcdf4.exo", &step(None, Some(3.0))).unwrap();
    assert_eq!(read.times, vec![0.0, 1.0, 2.5]);
    assert_eq!(read.time_step, Some(2), "3.0 is nearest 2.5");
    assert_eq!(read.cells.tetra, 2);
    assert_eq!(read.cells.wedges, 1);
    let blocks: Vec<(i64, &str, &str, bool)> = read
        .blocks
        .iter()
        .map(|b| (b.id, b.name.as_str(), b.elem_type.as_str(), b.kept))
        .collect();
    assert_eq!(
        blocks,
        vec![
            (1, "tets", "TETRA", true),
            (2, "wedges", "WEDGE", true),
            (3, "rod", "BEAM", false)
        ]
    );
    let mesh = &read.mesh;
    assert_eq!(mesh.points.len(), 8);
    for (p, v) in mesh.points.iter().zip(field(mesh, "pressure")) {
        assert_eq!(*v, p.x + p.y + p.z + 2.0);
    }
    // vel = (3, 4, 2): |vel| = sqrt(29).
    for v in field(mesh, "vel_magnitude") {
        assert!((v - 29f32.sqrt()).abs() < 1e-6);
    }
    // heat: 9 at step 2 on the wedge's nodes 1-6; nodes 7, 8 (tets only) 0.
    assert_eq!(
        field(mesh, "heat"),
        &[9.0, 9.0, 9.0, 9.0, 9.0, 9.0, 0.0, 0.0]
    );
    // The whole file through load: it validates as one piece.
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    assert_eq!(loaded.report.time_step, Some(0));
    assert_eq!(loaded.report.validation.components, 1);
    assert_eq!(loaded.mesh.tets.len(), 2 + 3);
}

/// One tetrahedron written by hand: `coordz` over a dimension of
/// `coordz_len` values, the nodal variable over one of `values_len`, the
/// given connectivity and element type.
fn one_tet(coordz_len: usize, values_len: usize, connect: &[i32], elem_type: &str) -> Vec<u8> {
    use exodus_common::{Cdf, Values};
    let mut nc = Cdf::new(Version::Cdf1);
    let time = nc.record_dim("time_step", 1);
    nc.dim("num_dim", 3);
    let nodes = nc.dim("num_nodes", 4);
    let z_dim = if coordz_len == 4 {
        nodes
    } else {
        nc.dim("other", coordz_len)
    };
    let v_dim = if values_len == 4 {
        nodes
    } else {
        nc.dim("another", values_len)
    };
    nc.dim("num_el_blk", 1);
    let elems = nc.dim("num_el_in_blk1", 1);
    let per = nc.dim("num_nod_per_el1", connect.len());
    let vars = nc.dim("num_nod_var", 1);
    let len = nc.dim("len_name", 8);
    nc.var("time_whole", &[time], Values::Doubles(vec![0.0]));
    nc.var(
        "coordx",
        &[nodes],
        Values::Doubles(vec![0.0, 1.0, 0.0, 0.0]),
    );
    nc.var(
        "coordy",
        &[nodes],
        Values::Doubles(vec![0.0, 0.0, 1.0, 0.0]),
    );
    let z = (0..coordz_len)
        .map(|i| f64::from(u8::from(i == 3)))
        .collect();
    nc.var("coordz", &[z_dim], Values::Doubles(z));
    nc.var("connect1", &[elems, per], Values::Ints(connect.to_vec()))
        .attr("elem_type", Values::Chars(elem_type.as_bytes().to_vec()));
    nc.var(
        "name_nod_var",
        &[vars, len],
        Values::Chars(b"T\0\0\0\0\0\0\0".to_vec()),
    );
    nc.var(
        "vals_nod_var1",
        &[time, v_dim],
        Values::Doubles(vec![1.5; values_len]),
    );
    nc.to_bytes()
}

fn error_of(bytes: &[u8], name: &str) -> ExodusError {
    let Err(e) = read_exodus_bytes(bytes, name, &ExodusOptions::default()) else {
        panic!("{name}: read as a mesh");
    };
    assert!(
        e.to_string().contains(name),
        "the message names the file: {e}"
    );
    e
}

#[test]
fn the_hand_written_tetrahedron_reads() {
    // The base case of the malformed files below is itself valid.
    let read = read_exodus_bytes(
        &one_tet(4, 4, &[1, 2, 3, 4], "TET4"),
        "ok.exo",
        &ExodusOptions::default(),
    )
    .unwrap();
    assert_eq!(read.mesh.tets.len(), 1);
    assert_eq!(field(&read.mesh, "T"), &[1.5; 4]);
}

#[test]
fn out_of_range_node_ids_are_errors_naming_block_and_element() {
    for (bad, connect) in [(0, [1, 2, 0, 4]), (5, [1, 2, 3, 5]), (-3, [-3, 2, 3, 4])] {
        let e = error_of(&one_tet(4, 4, &connect, "TETRA"), "ids.exo");
        assert!(
            matches!(e, ExodusError::BadNodeId { node_id, element: 1, num_nodes: 4, .. } if node_id == bad),
            "{e}"
        );
        assert!(e.to_string().contains("node ids run from 1 to 4"), "{e}");
    }
}

#[test]
fn variables_of_the_wrong_length_are_errors() {
    let e = error_of(&one_tet(3, 4, &[1, 2, 3, 4], "TETRA"), "z.exo");
    assert!(
        matches!(&e, ExodusError::WrongLength { variable, expected: 4, found: 3, .. } if variable == "coordz"),
        "{e}"
    );
    let e = error_of(&one_tet(4, 5, &[1, 2, 3, 4], "TETRA"), "vals.exo");
    assert!(
        matches!(&e, ExodusError::WrongLength { variable, expected: 4, found: 5, .. } if variable == "vals_nod_var1"),
        "{e}"
    );
}

#[test]
fn unsupported_volume_elements_are_errors() {
    let e = error_of(
        &one_tet(4, 4, &[1, 2, 3, 4, 1, 2, 3, 4, 1], "HEX9"),
        "hex9.exo",
    );
    assert!(
        matches!(&e, ExodusError::UnsupportedElement { nodes: 9, .. }),
        "{e}"
    );
    let e = error_of(&one_tet(4, 4, &[1, 2, 3, 4], "blob"), "blob.exo");
    assert!(e.to_string().contains("\"blob\""), "{e}");
}

#[test]
fn a_file_without_volume_blocks_is_one_error_listing_them() {
    let mut m = model();
    m.blocks.truncate(0);
    m.blocks
        .push(Block::new(30, "skin", "SHELL4", 4, &[1, 2, 3, 4]));
    m.blocks
        .push(Block::new(31, "rods", "BAR2", 2, &[1, 2, 2, 3]));
    m.elem.clear();
    let e = error_of(&m.write(Version::Cdf1), "flat.exo");
    assert!(matches!(e, ExodusError::NoVolumeBlock { .. }), "{e}");
    let message = e.to_string();
    assert!(
        message.contains("\"skin\" (id 30, SHELL4, 1 elements)")
            && message.contains("\"rods\" (id 31, BAR2, 2 elements)"),
        "{message}"
    );
}

#[test]
fn missing_coordinates_are_an_error() {
    let mut bytes = one_tet(4, 4, &[1, 2, 3, 4], "TETRA");
    // Rename coordx/coordy/coordz (same length, so the file stays valid).
    for name in [&b"coordx"[..], b"coordy", b"coordz"] {
        let at = bytes.windows(6).position(|w| w == name).unwrap();
        bytes[at..at + 5].copy_from_slice(b"COORD");
    }
    let e = error_of(&bytes, "nocoords.exo");
    assert!(
        matches!(&e, ExodusError::Missing { what, .. } if what.contains("coordinates")),
        "{e}"
    );
}

#[test]
fn truncated_files_are_errors_never_panics() {
    let bytes = model().write(Version::Cdf2);
    for cut in 0..bytes.len() {
        let name = format!("cut-at-{cut}.exo");
        error_of(&bytes[..cut], &name);
    }
    let disk = std::fs::read(data("real/disk_out_ref.ex2")).unwrap();
    // (The file's last 4 bytes lie past its data: cut inside the last
    // variable, H2, which fills the 33,996 bytes before them.)
    for cut in [4, 100, 1000, disk.len() / 2, disk.len() - 1000] {
        let e = error_of(&disk[..cut], "disk_out_ref.ex2");
        assert!(matches!(e, ExodusError::NetCdf { .. }), "{e}");
    }
}

#[test]
fn garbage_is_an_error_never_a_panic() {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let header = model().write(Version::Cdf1);
    for trial in 0..200 {
        let len = (next() % 4096) as usize;
        let mut bytes: Vec<u8> = (0..len).map(|_| next() as u8).collect();
        if trial % 2 == 0 {
            error_of(&bytes, "noise.exo");
            continue;
        }
        // A real start of a file, then noise: an error, or a mesh when the
        // noise lies past what the header describes; never a panic.
        let keep = (next() as usize % header.len()).min(len);
        bytes[..keep].copy_from_slice(&header[..keep]);
        if let Err(e) = read_exodus_bytes(&bytes, "noise.exo", &ExodusOptions::default()) {
            assert!(e.to_string().contains("noise.exo"), "{e}");
        }
    }
    // Flipped bytes inside a valid file: an error or a mesh, never a panic.
    for i in 0..header.len() {
        let mut bytes = header.clone();
        bytes[i] ^= 0x5a;
        if let Err(e) = read_exodus_bytes(&bytes, "flipped.exo", &ExodusOptions::default()) {
            assert!(e.to_string().contains("flipped.exo"), "{e}");
        }
    }
}
