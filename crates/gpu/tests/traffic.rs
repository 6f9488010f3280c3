//! The kernel's mesh traffic, counted by its CPU twin (whose loads are the
//! kernel's one for one): a step carries the three vertices of the face it
//! crosses over from the previous cell, finds the new one from the XOR in
//! the cell's compact record and reads that one point and the neighbour
//! across the exit face: 24 bytes per tetrahedron stepped, where a record
//! of vertex ids and neighbours and all four points reloaded would be 96.
//! The entry queries' reads of the BVH are counted beside it.

use tetray_core::Camera;
use tetray_gpu::twin::{render, render_traffic};
use tetray_gpu::{GpuRenderOptions, IntegratorData, SceneData};
use tetray_integrate::{IntegratorOptions, Method, ScalarIntegrator, TransferFunction};
use tetray_scene::Scene;

const RECORD: u64 = 16;

#[test]
fn a_step_reads_one_new_point() {
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/plot3d");
    let loaded =
        tetray_io::load(&data.join("bluntfinxyz.bin"), &Default::default()).expect("dataset");
    let scene = Scene::from_loaded(loaded, "density", Default::default()).expect("scene");
    let (lo, hi) = scene.bounds();
    let (s_lo, s_hi) = scene
        .scalar
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let options = IntegratorOptions {
        unit_distance: (hi - lo).length() / (scene.tet_count() as f32).cbrt(),
        ..IntegratorOptions::default()
    };
    let tf = TransferFunction::default_for_range(s_lo, s_hi);
    let integrator = ScalarIntegrator::new(Method::Ppi, &tf, &options).expect("integrator");
    let mut camera = Camera::reset_to_bounds(lo, hi).expect("camera");
    camera.azimuth(30.0).expect("azimuth");
    camera.elevation(20.0).expect("elevation");
    camera.orthogonalize_view_up().expect("view up");
    let opts = GpuRenderOptions {
        width: 48,
        height: 48,
        ..GpuRenderOptions::default()
    };
    let scene_data = SceneData::new(&scene).expect("scene data");
    let integrator_data = IntegratorData::new(&integrator).expect("integrator data");
    let (image, stats, traffic) =
        render_traffic(&scene_data, &integrator_data, &camera, &opts).expect("twin");
    let (plain, plain_stats) = render(&scene_data, &integrator_data, &camera, &opts).expect("twin");
    assert_eq!(image.rgba, plain.rgba, "counting must not change the image");
    assert_eq!(stats, plain_stats);

    let rays = u64::from(opts.width * opts.height);
    let steps = stats[tetray_gpu::layout::STAT_STEPS_LO];
    let entries = stats[tetray_gpu::layout::STAT_ENTRIES];
    assert!(
        steps > 10 * rays / 2,
        "the view walks the mesh: {steps} steps"
    );
    // Every entry loads the three points of its face; every step loads the
    // one new point.
    assert_eq!(traffic.point_bytes, RECORD * (steps + 3 * entries));
    // Every step reads its record's XOR and, unless the ray stops in the
    // cell (at most once per entry and once per ray: early termination, a
    // failure), the one neighbour across its exit face.
    let (most, least) = (8 * steps, 8 * steps - 4 * (entries + rays));
    assert!(
        (least..=most).contains(&traffic.tet_bytes),
        "tetrahedron bytes {} outside [{least}, {most}]",
        traffic.tet_bytes
    );
    let per_step = traffic.walk_bytes() as f64 / steps as f64;
    eprintln!(
        "Blunt Fin 48x48: {steps} steps, {entries} entries, {per_step:.1} mesh bytes per step \
         (points {:.1}, tetrahedra {:.1})",
        traffic.point_bytes as f64 / steps as f64,
        traffic.tet_bytes as f64 / steps as f64
    );
    // Measured 24.6 (the entries' faces on top of 24).
    assert!(per_step < 28.0, "{per_step} mesh bytes per step");

    // Every ray asks at least once; every query but a ray's last finds an
    // entry. Each query reads at least the root's two records, and each
    // face tested reads three points.
    let queries = traffic.bvh_queries;
    assert!(
        (entries.max(rays)..=entries + rays).contains(&queries),
        "{queries} queries for {entries} entries of {rays} rays"
    );
    assert!(traffic.bvh_bytes >= 2 * RECORD * queries);
    assert_eq!(traffic.bvh_point_bytes % (3 * RECORD), 0);
    assert!(traffic.bvh_point_bytes > 0, "entries test faces");
    let segments = stats[tetray_gpu::layout::STAT_SEGMENTS_LO];
    eprintln!(
        "{queries} entry queries, {:.0} bytes each (BVH {:.0}, points {:.0}); \
         {:.1} bytes per segment in all",
        traffic.entry_bytes() as f64 / queries as f64,
        traffic.bvh_bytes as f64 / queries as f64,
        traffic.bvh_point_bytes as f64 / queries as f64,
        (traffic.entry_bytes() + traffic.walk_bytes()) as f64 / segments as f64
    );
}
