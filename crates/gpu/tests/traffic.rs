//! The kernel's mesh traffic, counted by its CPU twin (whose loads are the
//! kernel's one for one): a step carries the three vertices of the face it
//! crosses over from the previous cell and reads one new point, so the walk
//! reads at most 48 bytes per tetrahedron stepped (vertex ids, neighbours,
//! one point) instead of 96 with all four points reloaded. The entry
//! queries' reads of the BVH are counted beside it.

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
    // Every entry loads a whole cell (4 points); every step that moves on
    // loads one point. At most one step per entry, and one per ray (early
    // termination, a failure), does not move on.
    let most = RECORD * (steps + 3 * entries);
    let least = RECORD * (steps + 3 * entries).saturating_sub(entries + rays);
    assert!(
        (least..=most).contains(&traffic.point_bytes),
        "point bytes {} outside [{least}, {most}]",
        traffic.point_bytes
    );
    // Vertex ids once per cell, neighbours once per step.
    assert!(traffic.tet_bytes <= RECORD * (entries + 2 * steps));
    let per_step = traffic.walk_bytes() as f64 / steps as f64;
    eprintln!(
        "Blunt Fin 48x48: {steps} steps, {entries} entries, {per_step:.1} mesh bytes per step \
         (points {:.1}, tetrahedra {:.1})",
        traffic.point_bytes as f64 / steps as f64,
        traffic.tet_bytes as f64 / steps as f64
    );
    // Measured 48.6 (the entries' whole cells on top of 48); reloading all
    // four points would be about 96.
    assert!(per_step < 56.0, "{per_step} mesh bytes per step");

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
