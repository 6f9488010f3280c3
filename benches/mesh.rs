//! Mesh stages: loading files (reading, splitting cells, orienting,
//! validating, topology; tets/s), face topology (tets/s), the scene (walk records, Morton
//! order, BVH; tets/s), the boundary BVH's build (faces/s) and its entry
//! queries (rays/s), on the Blunt Fin and a generated box.

use std::hint::black_box;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::Vec3;
use tetray_boundary_bvh::{BoundaryBvh, BuildPreset};
use tetray_core::watertight::RayFrame;
use tetray_mesh::Topology;
use tetray_mesh::synthetic::{CellSplit, box_grid};
use tetray_scene::{CellOrder, Scene};

mod support;

fn topology_build(c: &mut Criterion) {
    let fin = support::blunt_fin_mesh().mesh;
    let cube = box_grid(Vec3::ZERO, Vec3::ONE, [40; 3], CellSplit::Five).expect("box");
    let mut group = c.benchmark_group("topology_build");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(3));
    for (name, mesh) in [("blunt_fin", &fin), ("box_40^3x5", &cube)] {
        group.throughput(Throughput::Elements(mesh.tets.len() as u64));
        group.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| Topology::build(black_box(mesh)).expect("topology"))
        });
    }
    group.finish();
}

fn bvh(c: &mut Criterion) {
    let loaded = support::blunt_fin_mesh();
    let (mesh, topology) = (&loaded.mesh, &loaded.topology);
    let faces = topology.boundary_faces.len() as u64;
    let mut group = c.benchmark_group("bvh_build");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(3));
    group.throughput(Throughput::Elements(faces));
    // Every preset: build time against query speed is the trade-off they
    // make (the queries below use the default).
    for preset in BuildPreset::ALL {
        group.bench_function(BenchmarkId::from_parameter(preset.name()), |b| {
            b.iter(|| BoundaryBvh::build(mesh, topology, preset).expect("bvh"))
        });
    }
    group.finish();

    // Entry queries: the primary rays of a 128 x 128 view of the mesh.
    let bvh = BoundaryBvh::build(mesh, topology, BuildPreset::default()).expect("bvh");
    let scene = support::blunt_fin();
    let camera = support::camera(&scene);
    let rays = camera.pixel_rays(128, 128).expect("rays");
    let frames: Vec<RayFrame> = (0..128 * 128).map(|i| rays.ray(i % 128, i / 128)).collect();
    let mut group = c.benchmark_group("bvh_queries");
    group.throughput(Throughput::Elements(frames.len() as u64));
    group.measurement_time(Duration::from_secs(3));
    group.bench_function("first_entry_128x128", |b| {
        b.iter(|| {
            frames
                .iter()
                .filter(|ray| bvh.first_entry(ray, 0.0, f32::INFINITY, &[]).is_some())
                .count()
        })
    });
    group.finish();
}

/// `Scene::new_with_order` in the file's order and in Morton order (the
/// difference is the renumbering's cost), fastest BVH preset.
fn scene_build(c: &mut Criterion) {
    let loaded = support::blunt_fin_mesh();
    let mut group = c.benchmark_group("scene_build");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(3));
    group.throughput(Throughput::Elements(loaded.mesh.tets.len() as u64));
    for (name, order) in [("file", CellOrder::File), ("morton", CellOrder::Morton)] {
        group.bench_function(BenchmarkId::new("blunt_fin", name), |b| {
            b.iter(|| {
                Scene::new_with_order(
                    loaded.mesh.clone(),
                    loaded.topology.clone(),
                    "density",
                    BuildPreset::Fastest,
                    order,
                )
                .expect("scene")
            })
        });
    }
    group.finish();
}

/// `tetray_io::load` of three of the real files: XML with quadratic cells,
/// a parallel XML file of four pieces, and Exodus II.
fn load(c: &mut Criterion) {
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/real");
    let mut group = c.benchmark_group("load");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(3));
    for name in [
        "notch_disp.vtu",
        "blood_vessels/T0000000500.pvtu",
        "disk_out_ref.ex2",
    ] {
        let path = data.join(name);
        let options = tetray_io::LoadOptions::default();
        let tets = tetray_io::load(&path, &options)
            .expect("load")
            .mesh
            .tets
            .len();
        group.throughput(Throughput::Elements(tets as u64));
        group.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| tetray_io::load(black_box(&path), &options).expect("load"))
        });
    }
    group.finish();
}

criterion_group!(benches, load, topology_build, scene_build, bvh);
criterion_main!(benches);
