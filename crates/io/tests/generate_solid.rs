//! The procedural torus shell (`generate::solid`): a valid, conforming,
//! positively oriented mesh; nonconvex (two genus-1 boundary surfaces, rays
//! that leave and re-enter it); analytic scalars; the resolution chosen for
//! a requested count; the streamed `.vtu` it writes.

use std::collections::HashMap;

use glam::{DVec3, Vec3};
use tetray_io::LoadedMesh;
use tetray_io::generate::GenerateError;
use tetray_io::generate::solid::{FIELDS, TorusShell, linear, wave};
use tetray_io::vtk::{
    TetChunks, VtuEncoding, VtuIndex, VtuOptions, VtuStreamOptions, read_vtu_bytes, read_vtu_file,
    write_vtu_streamed, write_vtu_with,
};
use tetray_mesh::{TetMesh, Topology, prepare};

fn shell_mesh(cells: [usize; 3]) -> (TorusShell, LoadedMesh) {
    let shell = TorusShell::new(cells).unwrap();
    let loaded = prepare(shell.mesh()).unwrap();
    (shell, loaded)
}

#[test]
fn the_shell_is_valid_and_positively_oriented() {
    // The smallest shell and a usual one.
    for cells in [[4, 4, 1], [24, 12, 3]] {
        let (shell, loaded) = shell_mesh(cells);
        let report = &loaded.report;
        assert_eq!(loaded.mesh.tets.len(), shell.tet_count());
        assert_eq!(loaded.mesh.points.len(), shell.point_count());
        assert_eq!(
            report.inverted_fixed, 0,
            "{cells:?}: written orientation is kept"
        );
        assert_eq!(report.validation.components, 1);
        assert_eq!(report.validation.duplicate_points, 0);
        assert_eq!(report.validation.unused_points, 0);
        assert!(report.warnings.is_empty(), "{:?}", report.warnings);
        // Conforming and closed: every face is shared by two tetrahedra but
        // those of the two walls (2 triangles per wall quad).
        let [nu, nv, _] = cells;
        assert_eq!(loaded.topology.boundary_faces.len(), 2 * 2 * nu * nv);
    }
}

/// Boundary surfaces: `(triangles, Euler characteristic)` of each
/// component, connected through shared edges.
fn boundary_surfaces(topology: &Topology) -> Vec<(usize, i64)> {
    let faces = &topology.boundary_faces;
    let mut parent: Vec<usize> = (0..faces.len()).collect();
    fn root(parent: &mut [usize], mut x: usize) -> usize {
        while parent[x] != x {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        x
    }
    let mut edge_face: HashMap<(u32, u32), usize> = HashMap::new();
    for (f, face) in faces.iter().enumerate() {
        for e in 0..3 {
            let (a, b) = (face.vertices[e], face.vertices[(e + 1) % 3]);
            if let Some(&g) = edge_face.get(&(a.min(b), a.max(b))) {
                let (x, y) = (root(&mut parent, f), root(&mut parent, g));
                parent[x] = y;
            } else {
                edge_face.insert((a.min(b), a.max(b)), f);
            }
        }
    }
    let mut components: HashMap<usize, (usize, Vec<u32>, usize)> = HashMap::new();
    for (f, face) in faces.iter().enumerate() {
        let r = root(&mut parent, f);
        let entry = components.entry(r).or_default();
        entry.0 += 1;
        entry.1.extend(face.vertices);
    }
    for (&(a, _), &f) in &edge_face {
        let _ = a;
        components.get_mut(&root(&mut parent, f)).unwrap().2 += 1;
    }
    let mut out: Vec<(usize, i64)> = components
        .into_values()
        .map(|(triangles, mut points, edges)| {
            points.sort_unstable();
            points.dedup();
            let chi = points.len() as i64 - edges as i64 + triangles as i64;
            (triangles, chi)
        })
        .collect();
    out.sort_unstable();
    out
}

#[test]
fn the_boundary_is_two_tori() {
    let (_, loaded) = shell_mesh([24, 12, 3]);
    let surfaces = boundary_surfaces(&loaded.topology);
    // Inner and outer walls: 2 x 24 x 12 triangles each, Euler
    // characteristic V - E + F = 0, genus 1.
    assert_eq!(surfaces, [(576, 0), (576, 0)]);
}

/// Ray parameters where the ray `origin + t dir` crosses a boundary
/// triangle (Moller-Trumbore in f64).
fn boundary_crossings(mesh: &TetMesh, topology: &Topology, origin: DVec3, dir: DVec3) -> Vec<f64> {
    let mut hits: Vec<f64> = topology
        .boundary_faces
        .iter()
        .filter_map(|face| {
            let [a, b, c] = face.vertices.map(|v| mesh.points[v as usize].as_dvec3());
            let (e1, e2) = (b - a, c - a);
            let p = dir.cross(e2);
            let det = e1.dot(p);
            if det.abs() < 1e-14 {
                return None;
            }
            let s = origin - a;
            let u = s.dot(p) / det;
            let q = s.cross(e1);
            let v = dir.dot(q) / det;
            let t = e2.dot(q) / det;
            (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0).then_some(t)
        })
        .collect();
    hits.sort_by(f64::total_cmp);
    hits
}

#[test]
fn rays_leave_and_re_enter_the_shell() {
    let (_, loaded) = shell_mesh([48, 24, 4]);
    // Along x through the ring's hole and both tube hollows (off the grid's
    // planes of symmetry so no edge is hit): in, out of the wall into the
    // hollow, in, out into the hole, and again on the other side.
    let origin = DVec3::new(-3.0, 0.0123, 0.0071);
    let hits = boundary_crossings(&loaded.mesh, &loaded.topology, origin, DVec3::X);
    assert_eq!(hits.len(), 8, "{hits:?}");
    // Crossing x near -1.5, -1.25, -0.75, -0.5, then mirrored (faceted
    // walls: within a cell size).
    let expected = [-1.5, -1.25, -0.75, -0.5, 0.5, 0.75, 1.25, 1.5];
    for (t, x) in hits.iter().zip(expected) {
        assert!((origin.x + t - x).abs() < 0.02, "{hits:?}");
    }
    // Along z through the tube wall only: in, into the hollow, out of it,
    // out: 4 crossings.
    let down = DVec3::new(1.0123, 0.0071, 2.0);
    assert_eq!(
        boundary_crossings(&loaded.mesh, &loaded.topology, down, -DVec3::Z).len(),
        4
    );
}

#[test]
fn the_scalars_are_the_analytic_functions_at_the_points() {
    let (_, loaded) = shell_mesh([16, 8, 2]);
    let names: Vec<&str> = loaded.mesh.fields.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, FIELDS);
    for (p, &point) in loaded.mesh.points.iter().enumerate() {
        assert_eq!(loaded.mesh.fields[0].values[p], wave(point));
        assert_eq!(loaded.mesh.fields[1].values[p], linear(point));
    }
    let p = Vec3::new(0.1, 0.2, 0.3);
    let expected = (0.3f64).sin() * (0.6f64).cos() + 0.5 * (1.8f64).sin();
    assert!((f64::from(wave(p)) - expected).abs() < 1e-6);
    assert!((linear(p) - 1.4).abs() < 1e-6);
    // Points sit on the parametrisation: tube radius within [0.25, 0.5].
    for point in &loaded.mesh.points {
        let ring = (point.x.hypot(point.y) - 1.0).hypot(point.z);
        assert!((0.25 - 1e-6..=0.5 + 1e-6).contains(&ring), "{point}");
    }
}

#[test]
fn the_requested_count_picks_the_resolution() {
    for requested in [1, 80, 81, 1000, 20_000, 1_000_000, 10_000_000, 40_000_000] {
        let shell = TorusShell::with_tets(requested).unwrap();
        let [nu, nv, nw] = shell.cells;
        assert!(nu % 2 == 0 && nv % 2 == 0 && nu >= 4 && nv >= 4 && nw >= 1);
        let tets = shell.tet_count();
        assert!(tets >= requested, "{requested}: {tets}");
        // Within one step of nv (2 cells) above the request, or the
        // smallest shell.
        assert!(
            tets < requested + 10 * nu * nw || tets == 80,
            "{requested}: {:?}",
            shell.cells
        );
        if requested >= 1_000_000 {
            assert!(
                (tets - requested) as f64 <= 0.002 * requested as f64,
                "{requested}: {tets}"
            );
            // Nearly cubic cells: edge lengths within a factor 1.5.
            let edges = [
                std::f64::consts::TAU / nu as f64,
                std::f64::consts::TAU * 0.375 / nv as f64,
                0.25 / nw as f64,
            ];
            let (lo, hi) = (
                edges.iter().copied().fold(f64::MAX, f64::min),
                edges.iter().copied().fold(0.0, f64::max),
            );
            assert!(hi / lo < 1.3, "{requested}: {edges:?}");
        }
    }
    assert_eq!(TorusShell::with_tets(1).unwrap().cells, [4, 4, 1]);
    assert_eq!(TorusShell::with_tets(20_000).unwrap().tet_count(), 20_160);
    assert_eq!(
        TorusShell::with_tets(10_000_000).unwrap().cells,
        [500, 200, 20]
    );
    assert!(matches!(
        TorusShell::with_tets(0),
        Err(GenerateError::TetCount { .. })
    ));
    assert!(matches!(
        TorusShell::with_tets(usize::MAX),
        Err(GenerateError::TetCount { .. })
    ));
    assert!(matches!(
        TorusShell::new([5, 4, 1]),
        Err(GenerateError::BadShell { .. })
    ));
    assert!(matches!(
        TorusShell::new([4, 2, 1]),
        Err(GenerateError::BadShell { .. })
    ));
    assert!(matches!(
        TorusShell::new([4, 4, 0]),
        Err(GenerateError::BadShell { .. })
    ));
}

#[test]
fn the_streamed_vtu_reads_back_bit_exact() {
    let shell = TorusShell::new([16, 8, 2]).unwrap();
    let mesh = shell.mesh();
    let dir = std::env::temp_dir().join(format!("tetray-solid-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("shell.vtu");
    let bytes = shell.write_vtu(&path).unwrap();
    assert_eq!(bytes, std::fs::metadata(&path).unwrap().len());
    let read = read_vtu_file(&path).unwrap();
    assert_eq!(read.mesh, mesh);
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
    let text = std::fs::read(&path).unwrap();
    assert!(
        String::from_utf8_lossy(&text[..2000]).contains("type=\"Int32\" Name=\"connectivity\"")
    );
    std::fs::remove_dir_all(&dir).unwrap();

    // The streaming writer with Int64 indices writes what the in-memory
    // writer does (which now uses it for appended raw data).
    for (header_u64, big_endian) in [(true, false), (false, true)] {
        let mut streamed = Vec::new();
        let options = VtuStreamOptions {
            index: VtuIndex::Int64,
            header_u64,
            big_endian,
        };
        write_vtu_streamed(&mesh.points, &mesh.fields, &shell, &mut streamed, &options).unwrap();
        let mut whole = Vec::new();
        let mut vtu = VtuOptions::new(VtuEncoding::AppendedRaw, false);
        vtu.header_u64 = header_u64;
        vtu.big_endian = big_endian;
        write_vtu_with(&mesh, &mut whole, &vtu).unwrap();
        assert!(streamed == whole);
        assert_eq!(read_vtu_bytes(&streamed, "s.vtu").unwrap().mesh, mesh);
    }
}

/// A source that promises more tetrahedra than it gives.
struct Short(Vec<[u32; 4]>);

impl TetChunks for Short {
    fn tet_count(&self) -> usize {
        self.0.len() + 1
    }

    fn for_each_chunk(
        &self,
        sink: &mut dyn FnMut(&[[u32; 4]]) -> std::io::Result<()>,
    ) -> std::io::Result<()> {
        sink(&self.0)
    }
}

#[test]
fn the_streaming_writer_rejects_inconsistent_input() {
    let mesh = TorusShell::new([4, 4, 1]).unwrap().mesh();
    let options = VtuStreamOptions {
        index: VtuIndex::Int32,
        header_u64: true,
        big_endian: false,
    };
    let write = |tets: &dyn Fn(&mut Vec<u8>) -> std::io::Result<u64>| {
        let mut out = Vec::new();
        tets(&mut out).unwrap_err().to_string()
    };
    let short = Short(mesh.tets.clone());
    let e = write(&|out| write_vtu_streamed(&mesh.points, &mesh.fields, &short, out, &options));
    assert!(e.contains("80 of the 81"), "{e}");
    let mut bad = mesh.tets.clone();
    bad[7][2] = 9999;
    let e =
        write(&|out| write_vtu_streamed(&mesh.points, &mesh.fields, bad.as_slice(), out, &options));
    assert!(e.contains("tetrahedron 7 uses point 9999"), "{e}");
    let e = write(&|out| {
        write_vtu_streamed(
            &mesh.points[1..],
            &mesh.fields,
            mesh.tets.as_slice(),
            out,
            &options,
        )
    });
    assert!(e.contains("field \"wave\""), "{e}");
}
