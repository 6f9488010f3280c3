//! `mpirun -n P tetray render` (P = 1 to 4, `--oversubscribe`) against
//! `tetray render` of the same file in one process: the composited image
//! must equal the single-process render to 1e-5 per pixel channel (the
//! same segments, composited in groups and in another order: f32
//! rounding, measured at a few 1e-7).
//!
//! Meshes: a convex box in one `.vtu` (split spatially by rank), a hollow
//! box in four striped pieces that interleave along the rays, the same in
//! pieces carrying a layer of ghost cells each (dropped, so not
//! integrated twice), and the blood-vessel `.pvtu` of `data/real`
//! (hexahedra, split by point numbers). Without `mpirun` the tests skip
//! loudly, unless `TETRAY_REQUIRE_MPI=1`, where that is a failure.
#![cfg(feature = "mpi")]

mod support;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use glam::Vec3;
use support::{BIN, run, scratch, text};
use tetray_mesh::TetMesh;
use tetray_mesh::synthetic::{CellSplit, box_grid, hollow_box};

/// The bound on the difference per pixel channel against one process:
/// about 3 times the worst measured (4.8e-7, the blood vessels at every
/// rank count; 3.6e-7 for the striped and ghost-cell boxes), as the
/// fragments of the ranks composite the same segments in groups, so only
/// f32 rounding differs.
const TOLERANCE: f32 = 1.4e-6;

fn mpirun() -> Option<PathBuf> {
    let found = std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|dir| dir.join("mpirun"))
            .find(|p| p.is_file())
    });
    if found.is_none() {
        assert!(
            std::env::var("TETRAY_REQUIRE_MPI").as_deref() != Ok("1"),
            "TETRAY_REQUIRE_MPI=1 but there is no mpirun on PATH"
        );
        eprintln!(
            "SKIPPED: no mpirun on PATH (install openmpi-bin; TETRAY_REQUIRE_MPI=1 makes this \
             a failure)"
        );
    }
    found
}

/// Float RGBA of an EXR the CLI wrote.
fn read_exr(path: &Path) -> Vec<[f32; 4]> {
    let image = image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .into_rgba32f();
    image.pixels().map(|p| p.0).collect()
}

/// Renders `mesh` in one process, then under `mpirun -n P` for P = 1..4,
/// and checks each composited image against the single one.
/// Returns the single-process image (`None` when the test skips).
fn check(dir: &Path, mesh: &Path, extra: &[&str]) -> Option<Vec<[f32; 4]>> {
    let mpirun = mpirun()?;
    let mesh = mesh.to_str().unwrap();
    // One thread per rank: the tests run on two cores, up to four ranks.
    let mut args = vec!["render", mesh, "--size", "64x64", "--renderer", "cpu"];
    args.extend_from_slice(&["--threads", "1"]);
    args.extend_from_slice(extra);
    let single = run(dir, &[&args[..], &["-o", "single.exr"]].concat());
    assert!(single.status.success(), "{}", text(&single.stderr));
    let expected = read_exr(&dir.join("single.exr"));
    let lit = expected.iter().filter(|p| p[3] > 1e-3).count();
    assert!(lit > 200, "only {lit} pixels lit: a test of nothing");
    for ranks in 1..=4 {
        let out_name = format!("ranks{ranks}.exr");
        let out = Command::new(&mpirun)
            .args([
                "-n",
                &ranks.to_string(),
                "--oversubscribe",
                "--bind-to",
                "none",
            ])
            .arg(BIN)
            .args(&args)
            .args(["--distributed", "-o", &out_name])
            .current_dir(dir)
            .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
            .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
            .env("OMPI_MCA_btl_vader_single_copy_mechanism", "none")
            .output()
            .expect("run mpirun");
        assert!(
            out.status.success(),
            "{ranks} ranks:\n{}\n{}",
            text(&out.stdout),
            text(&out.stderr)
        );
        let stdout = text(&out.stdout);
        assert!(
            stdout.contains(&format!("distributed over {ranks} ranks")),
            "{stdout}"
        );
        let got = read_exr(&dir.join(&out_name));
        let worst = got
            .iter()
            .zip(&expected)
            .flat_map(|(a, b)| (0..4).map(move |c| (a[c] - b[c]).abs()))
            .fold(0.0f32, f32::max);
        println!("{mesh}: {ranks} ranks, max error {worst:e} ({lit} pixels lit)");
        assert!(worst <= TOLERANCE, "{ranks} ranks: max error {worst}");
    }
    Some(expected)
}

/// A nonlinear point field, so that a wrong split or order shows.
fn field(p: Vec3) -> f32 {
    (p.x * 1.3).sin() * 0.6 + 0.4 * p.y * p.z
}

/// Writes tetrahedra `tets` of `mesh` as an ASCII `.vtu` with the field
/// `s`, and a `vtkGhostType` cell array (1: a duplicate cell) when `ghost`
/// is given.
fn write_vtu(path: &Path, mesh: &TetMesh, tets: &[usize], ghost: Option<&[bool]>) {
    let mut ids = vec![u32::MAX; mesh.points.len()];
    let mut points = Vec::new();
    for &t in tets {
        for &v in &mesh.tets[t] {
            if ids[v as usize] == u32::MAX {
                ids[v as usize] = points.len() as u32;
                points.push(mesh.points[v as usize]);
            }
        }
    }
    let join = |items: Vec<String>| items.join(" ");
    let mut xml = String::new();
    let _ = write!(
        xml,
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" \
         byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"{}\" \
         NumberOfCells=\"{}\">\n<PointData Scalars=\"s\">\n<DataArray type=\"Float32\" \
         Name=\"s\" format=\"ascii\">{}</DataArray>\n</PointData>\n",
        points.len(),
        tets.len(),
        join(points.iter().map(|&p| field(p).to_string()).collect())
    );
    if let Some(ghost) = ghost {
        let flags = tets
            .iter()
            .map(|&t| u8::from(ghost[t]).to_string())
            .collect();
        let _ = write!(
            xml,
            "<CellData>\n<DataArray type=\"UInt8\" Name=\"vtkGhostType\" \
             format=\"ascii\">{}</DataArray>\n</CellData>\n",
            join(flags)
        );
    }
    let coords = points
        .iter()
        .map(|p| format!("{} {} {}", p.x, p.y, p.z))
        .collect();
    let connectivity = tets
        .iter()
        .flat_map(|&t| mesh.tets[t].map(|v| ids[v as usize].to_string()))
        .collect();
    let offsets = (1..=tets.len()).map(|i| (4 * i).to_string()).collect();
    let _ = write!(
        xml,
        "<Points>\n<DataArray type=\"Float32\" NumberOfComponents=\"3\" \
         format=\"ascii\">{}</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int32\" \
         Name=\"connectivity\" format=\"ascii\">{}</DataArray>\n<DataArray type=\"Int32\" \
         Name=\"offsets\" format=\"ascii\">{}</DataArray>\n<DataArray type=\"UInt8\" \
         Name=\"types\" format=\"ascii\">{}</DataArray>\n</Cells>\n</Piece>\n\
         </UnstructuredGrid>\n</VTKFile>\n",
        join(coords),
        join(connectivity),
        join(offsets),
        join(vec!["10".to_string(); tets.len()])
    );
    std::fs::write(path, xml).unwrap();
}

fn write_pvtu(path: &Path, sources: &[String], ghosts: bool) {
    let mut xml = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" \
         byte_order=\"LittleEndian\">\n",
    );
    let _ = writeln!(
        xml,
        "<PUnstructuredGrid GhostLevel=\"{}\">\n<PPointData Scalars=\"s\">\n<PDataArray \
         type=\"Float32\" Name=\"s\"/>\n</PPointData>",
        u8::from(ghosts)
    );
    if ghosts {
        xml.push_str(
            "<PCellData>\n<PDataArray type=\"UInt8\" Name=\"vtkGhostType\"/>\n</PCellData>\n",
        );
    }
    xml.push_str(
        "<PPoints>\n<PDataArray type=\"Float32\" NumberOfComponents=\"3\"/>\n</PPoints>\n",
    );
    for s in sources {
        let _ = writeln!(xml, "<Piece Source=\"{s}\"/>");
    }
    xml.push_str("</PUnstructuredGrid>\n</VTKFile>\n");
    std::fs::write(path, xml).unwrap();
}

/// A hollow box whose tetrahedra go to 4 pieces by slab along x (slab
/// index mod 4): every piece is a set of separate slabs, so a ray along x
/// crosses the pieces in turn, several times, and the hole.
fn striped_hollow_box() -> (TetMesh, Vec<Vec<usize>>) {
    let mesh = hollow_box(
        Vec3::new(-2.0, -1.0, -1.0),
        Vec3::new(2.0, 1.0, 1.0),
        [16, 4, 4],
        [4, 1, 1],
        [12, 3, 3],
        CellSplit::Five,
    )
    .unwrap();
    let mut pieces = vec![Vec::new(); 4];
    for (t, tet) in mesh.tets.iter().enumerate() {
        let x: f32 = tet.iter().map(|&v| mesh.points[v as usize].x).sum::<f32>() / 4.0;
        let slab = ((x + 2.0) / 0.25) as usize;
        pieces[slab % 4].push(t);
    }
    (mesh, pieces)
}

/// Looking along x (azimuth 90 from the default -z view), slightly
/// oblique, so rays cross the stripes.
const ALONG_X: [&str; 8] = [
    "--azimuth",
    "80",
    "--elevation",
    "12",
    "--integrator",
    "exact",
    "--scalar",
    "s",
];

#[test]
fn convex_box_in_one_file_split_by_rank() {
    let dir = scratch("distributed", "convex");
    let mesh = box_grid(
        Vec3::new(-1.0, -1.0, -1.0),
        Vec3::new(1.5, 1.0, 1.0),
        [6, 5, 5],
        CellSplit::Six,
    )
    .unwrap();
    let all: Vec<usize> = (0..mesh.tets.len()).collect();
    write_vtu(&dir.join("box.vtu"), &mesh, &all, None);
    // The default integrator (ppi) and view.
    check(&dir, &dir.join("box.vtu"), &[]);
}

#[test]
fn hollow_box_pieces_interleave_along_the_rays() {
    let dir = scratch("distributed", "striped");
    let (mesh, pieces) = striped_hollow_box();
    let mut sources = Vec::new();
    for (i, tets) in pieces.iter().enumerate() {
        let name = format!("piece{i}.vtu");
        write_vtu(&dir.join(&name), &mesh, tets, None);
        sources.push(name);
    }
    write_pvtu(&dir.join("striped.pvtu"), &sources, false);
    check(&dir, &dir.join("striped.pvtu"), &ALONG_X);
}

#[test]
fn ghost_cells_are_not_integrated_twice() {
    // Each piece also carries, flagged as duplicates, every tetrahedron of
    // the other pieces sharing a point with its own: integrated twice,
    // they would darken the image far beyond the tolerance.
    let dir = scratch("distributed", "ghosts");
    let (mesh, pieces) = striped_hollow_box();
    let mut sources = Vec::new();
    for (i, own) in pieces.iter().enumerate() {
        let mut mine = vec![false; mesh.tets.len()];
        let mut touches = vec![false; mesh.points.len()];
        for &t in own {
            mine[t] = true;
            for &v in &mesh.tets[t] {
                touches[v as usize] = true;
            }
        }
        let ghost: Vec<bool> = (0..mesh.tets.len())
            .map(|t| !mine[t] && mesh.tets[t].iter().any(|&v| touches[v as usize]))
            .collect();
        let tets: Vec<usize> = (0..mesh.tets.len())
            .filter(|&t| mine[t] || ghost[t])
            .collect();
        assert!(ghost.iter().any(|&g| g));
        let name = format!("ghost{i}.vtu");
        write_vtu(&dir.join(&name), &mesh, &tets, Some(&ghost));
        sources.push(name);
    }
    write_pvtu(&dir.join("ghosts.pvtu"), &sources, true);
    let Some(with_ghosts) = check(&dir, &dir.join("ghosts.pvtu"), &ALONG_X) else {
        return;
    };
    // The reference itself drops the ghosts: the same pieces without them
    // render the same image (the same tetrahedra: f32 rounding, 1e-6).
    let plain = scratch("distributed", "ghosts-plain");
    let mut sources = Vec::new();
    for (i, tets) in pieces.iter().enumerate() {
        let name = format!("piece{i}.vtu");
        write_vtu(&plain.join(&name), &mesh, tets, None);
        sources.push(name);
    }
    write_pvtu(&plain.join("plain.pvtu"), &sources, false);
    let mut args = vec![
        "render",
        "plain.pvtu",
        "--size",
        "64x64",
        "--renderer",
        "cpu",
    ];
    args.extend_from_slice(&ALONG_X);
    args.extend_from_slice(&["-o", "plain.exr"]);
    let out = run(&plain, &args);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let without = read_exr(&plain.join("plain.exr"));
    let worst = with_ghosts
        .iter()
        .zip(&without)
        .flat_map(|(a, b)| (0..4).map(move |c| (a[c] - b[c]).abs()))
        .fold(0.0f32, f32::max);
    assert!(worst <= 1e-6, "ghost cells changed the image by {worst}");
}

#[test]
fn blood_vessel_pvtu_of_data_real() {
    let dir = scratch("distributed", "blood");
    let pvtu =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("data/real/blood_vessels/T0000000500.pvtu");
    check(&dir, &pvtu, &["--integrator", "exact"]);
}

/// One rank's piece file is cut short: every rank exits, within seconds,
/// and the error names that rank and that file (the ranks agree on the
/// outcome of loading before any of them waits for the others to render).
/// Tried with the piece of rank 1 and of rank 0 (the one that writes the
/// image).
#[test]
fn a_corrupt_piece_stops_every_rank_with_its_error() {
    let Some(mpirun) = mpirun() else {
        return;
    };
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/real/blood_vessels");
    for bad in ["000.vtu", "001.vtu"] {
        let dir = scratch("distributed", &format!("corrupt-{bad}"));
        std::fs::create_dir_all(dir.join("T0000000500")).unwrap();
        std::fs::copy(
            source.join("T0000000500.pvtu"),
            dir.join("T0000000500.pvtu"),
        )
        .unwrap();
        for piece in ["000.vtu", "001.vtu", "002.vtu", "003.vtu"] {
            let bytes = std::fs::read(source.join("T0000000500").join(piece)).unwrap();
            let keep = if piece == bad { 3000 } else { bytes.len() };
            std::fs::write(dir.join("T0000000500").join(piece), &bytes[..keep]).unwrap();
        }
        let start = std::time::Instant::now();
        let mut child = Command::new(&mpirun)
            .args(["-n", "3", "--oversubscribe", "--bind-to", "none"])
            .arg(BIN)
            .args([
                "render",
                "T0000000500.pvtu",
                "--size",
                "32x32",
                "--renderer",
                "cpu",
                "--threads",
                "1",
                "--distributed",
                "-o",
                "out.png",
            ])
            .current_dir(&dir)
            .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
            .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
            .env("OMPI_MCA_btl_vader_single_copy_mechanism", "none")
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("run mpirun");
        // A hang is the failure looked for: give up after a minute.
        while child.try_wait().unwrap().is_none() {
            if start.elapsed().as_secs() > 60 {
                child.kill().ok();
                panic!("{bad}: the ranks still run after 60 s");
            }
            std::thread::sleep(std::time::Duration::from_millis(50));
        }
        let out = child.wait_with_output().unwrap();
        let stderr = text(&out.stderr);
        println!("{bad}: exited in {:.2} s", start.elapsed().as_secs_f64());
        assert!(!out.status.success(), "{bad}: {stderr}");
        let rank = if bad == "000.vtu" { "rank 0" } else { "rank 1" };
        assert!(
            stderr.contains(rank) && stderr.contains(bad) && stderr.contains("ends inside"),
            "{bad}: {stderr}"
        );
        assert!(!dir.join("out.png").exists(), "{bad}: an image was written");
    }
}
