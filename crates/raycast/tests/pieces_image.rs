//! A partitioned file renders as the same volume in one file: the blood
//! vessel `.pvtu` (4 pieces, `data/real/blood_vessels`) joined by the
//! reader, against its pieces read one by one, joined by this test
//! (points welded by their file coordinates) and written as one `.vtu`.
//! Any seam the reader left at a piece interface, or any cell it lost or
//! doubled, shows in the image.
//!
//! The two are not the same tetrahedra: a hexahedron is split by the
//! smallest point number on each face, and a piece read alone numbers its
//! points its own way (the reader welds first, then splits, so its split
//! conforms across the interfaces; the pieces split alone may cut an
//! interface face two ways, which the walk crosses through the BVH). A
//! field linear in position is interpolated exactly by any split, so the
//! exact integrator sees the same function along every ray.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::{DVec3, Vec3};
use tetray_boundary_bvh::BuildPreset;
use tetray_core::{Camera, Image};
use tetray_integrate::{IntegratorOptions, Method, ScalarIntegrator, TransferFunction};
use tetray_io::vtk::{VtuEncoding, read_vtu_file, write_vtu};
use tetray_io::{LoadOptions, load};
use tetray_mesh::{ScalarField, TetMesh};
use tetray_raycast::{RenderOptions, render_scalar};
use tetray_scene::Scene;

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/real/blood_vessels")
}

/// A field linear in position, the same function on both meshes (the
/// files' cell fields are averaged to points per piece when the pieces are
/// read alone, so they would differ at the interfaces for a reason that
/// has nothing to do with joining).
fn with_field(mut mesh: TetMesh) -> TetMesh {
    let values = mesh
        .points
        .iter()
        .map(|p| 0.01 * (p.x + 0.7 * p.y - 0.4 * p.z))
        .collect();
    mesh.fields = vec![ScalarField {
        name: "s".into(),
        values,
    }];
    mesh
}

fn render(mesh: TetMesh, topology: tetray_mesh::Topology, views: &[(f32, f32)]) -> Vec<Image> {
    let scene = Scene::new(with_field(mesh), topology, "s", BuildPreset::default()).unwrap();
    let (lo, hi) = scene.bounds();
    let tf = TransferFunction::default_for_range(0.2, 1.6);
    let unit = (hi - lo).length() / 40.0;
    let integrator = ScalarIntegrator::new(
        Method::Exact,
        &tf,
        &IntegratorOptions {
            unit_distance: unit,
            ..IntegratorOptions::default()
        },
    )
    .unwrap();
    views
        .iter()
        .map(|&(azimuth, elevation)| {
            let mut camera = Camera::reset_to_bounds(lo, hi).unwrap();
            camera.azimuth(azimuth).unwrap();
            camera.elevation(elevation).unwrap();
            camera.orthogonalize_view_up().unwrap();
            let options = RenderOptions {
                width: 64,
                height: 64,
                ..RenderOptions::default()
            };
            render_scalar(&scene, &camera, &integrator, &options)
                .unwrap()
                .image
        })
        .collect()
}

#[test]
fn the_pvtu_renders_as_its_cells_in_one_file() {
    let joined = load(&data().join("T0000000500.pvtu"), &LoadOptions::default()).unwrap();
    assert_eq!(joined.report.origin, DVec3::ZERO, "compared uncentred");

    // The pieces one by one, welded here by their file coordinates.
    let mut points: Vec<Vec3> = Vec::new();
    let mut tets = Vec::new();
    let mut index: HashMap<[u64; 3], u32> = HashMap::new();
    let mut written = 0;
    for piece in 0..4 {
        let read = read_vtu_file(&data().join(format!("T0000000500/00{piece}.vtu"))).unwrap();
        let map: Vec<u32> = read
            .mesh
            .points
            .iter()
            .map(|p| {
                let file = p.as_dvec3() + read.origin;
                let key = file.to_array().map(|c| (c as f32).to_bits() as u64);
                *index.entry(key).or_insert_with(|| {
                    points.push(file.as_vec3());
                    (points.len() - 1) as u32
                })
            })
            .collect();
        written += read.mesh.points.len();
        tets.extend(read.mesh.tets.iter().map(|t| t.map(|p| map[p as usize])));
    }
    // The reader welded as many points as this test did.
    assert_eq!(
        written - points.len(),
        joined.report.pieces.welded_points,
        "welded points"
    );
    let one = TetMesh {
        points,
        tets,
        fields: Vec::new(),
    };
    let dir = std::env::temp_dir().join(format!("tetray-pieces-image-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("one.vtu");
    let mut out = std::fs::File::create(&file).unwrap();
    write_vtu(&with_field(one), &mut out, VtuEncoding::AppendedRaw, false).unwrap();
    drop(out);
    let single = load(&file, &LoadOptions::default()).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    eprintln!(
        "tetrahedra: {} joined by the reader, {} from the pieces split alone",
        joined.mesh.tets.len(),
        single.mesh.tets.len()
    );
    assert_eq!(single.report.validation.components, 1);
    assert_eq!(joined.report.validation.components, 1);
    assert_eq!(joined.report.validation.seam_faces, 0);

    // 1e-6 per channel, twice the measured worst (5.4e-7 over the three
    // views): the same linear function over the same volume, cut into
    // tetrahedra differently, so only the f32 crossing points and their
    // accumulation differ.
    let views = [(30.0, 20.0), (120.0, -35.0), (250.0, 60.0)];
    let a = render(joined.mesh, joined.topology, &views);
    let b = render(single.mesh, single.topology, &views);
    for ((x, y), view) in a.iter().zip(&b).zip(views) {
        let lit = x.rgba.iter().filter(|p| p[3] > 1e-3).count();
        assert!(lit > 64 * 64 / 50, "{view:?}: {lit} pixels lit");
        let worst = x
            .rgba
            .iter()
            .zip(&y.rgba)
            .map(|(p, q)| (0..4).map(|c| (p[c] - q[c]).abs()).fold(0.0, f32::max))
            .fold(0.0, f32::max);
        eprintln!("{view:?}: {lit} pixels lit, worst difference {worst:.2e}");
        assert!(worst <= 1e-6, "{view:?}: worst difference {worst}");
    }
}
