//! `tetray animate` on a three-step series written here (the same grid,
//! the field f = (k + 1) x at step k, x in [0, 1]): each frame is the
//! image `tetray render` makes of that step, bit for bit, with the colour
//! range the field spans over all the steps (0 to 3); the GIF holds one
//! frame per step; an orbit turns the view; bad requests are one line.

mod support;

use std::path::Path;

use support::{run, scratch, text};

const SIZE: &str = "40x32";

/// Legacy VTK image data over the unit cube, 5 x 4 x 3 points, with
/// f = scale * x.
fn write_step(path: &Path, scale: f64) {
    let (nx, ny, nz) = (5, 4, 3);
    let mut s = format!(
        "# vtk DataFile Version 3.0\nstep\nASCII\nDATASET STRUCTURED_POINTS\n\
         DIMENSIONS {nx} {ny} {nz}\nORIGIN 0 0 0\nSPACING 0.25 0.3333333 0.5\n\
         POINT_DATA {}\nSCALARS f double\nLOOKUP_TABLE default\n",
        nx * ny * nz
    );
    for _k in 0..nz {
        for _j in 0..ny {
            for i in 0..nx {
                s.push_str(&format!("{} ", scale * f64::from(i) / f64::from(nx - 1)));
            }
            s.push('\n');
        }
    }
    std::fs::write(path, s).unwrap();
}

fn write_series(dir: &Path) {
    for k in 0..3 {
        write_step(&dir.join(format!("s{k}.vtk")), f64::from(k + 1));
    }
    std::fs::write(
        dir.join("s.series"),
        r#"{"file-series-version": "1.0", "files": [
            {"name": "s0.vtk", "time": 0.0},
            {"name": "s1.vtk", "time": 0.5},
            {"name": "s2.vtk", "time": 1.0}]}"#,
    )
    .unwrap();
}

fn rgb(path: &Path) -> image::RgbImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .into_rgb8()
}

fn ok(dir: &Path, args: &[&str]) -> String {
    let out = run(dir, args);
    assert!(out.status.success(), "{args:?}: {}", text(&out.stderr));
    text(&out.stdout)
}

#[test]
fn frames_are_the_renders_of_their_steps_in_one_colour_range() {
    let dir = scratch("animate", "steps");
    write_series(&dir);
    let common = ["--renderer", "cpu", "--size", SIZE, "--elevation", "20"];
    let stdout = ok(
        &dir,
        &[&["animate", "s.series", "-o", "frames/"][..], &common].concat(),
    );
    assert!(stdout.contains("colour range [0, 3]"), "{stdout}");
    assert!(stdout.contains("wrote 3 frames"), "{stdout}");
    let mut frames = Vec::new();
    for k in 0..3 {
        let step = k.to_string();
        let png = format!("render{k}.png");
        let args = [
            "render",
            "s.series",
            "--time-step",
            &step,
            "--clim",
            "0,3",
            "-o",
            &png,
        ];
        ok(&dir, &[&args[..], &common].concat());
        let frame = rgb(&dir.join(format!("frames/frame_{k:04}.png")));
        assert_eq!(frame, rgb(&dir.join(&png)), "step {k}");
        frames.push(frame);
    }
    // The field grows with the step: in one colour range the frames differ.
    assert_ne!(frames[0], frames[2]);

    // The GIF: one frame per step at the size asked; only `--times 1:2`.
    ok(
        &dir,
        &[
            &["animate", "s.series", "-o", "s.gif", "--times", "1:2"][..],
            &common,
        ]
        .concat(),
    );
    use image::AnimationDecoder as _;
    let file = std::io::BufReader::new(std::fs::File::open(dir.join("s.gif")).unwrap());
    let gif = image::codecs::gif::GifDecoder::new(file).unwrap();
    let decoded = gif.into_frames().collect_frames().unwrap();
    assert_eq!(decoded.len(), 2);
    assert_eq!(decoded[0].buffer().dimensions(), (40, 32));
}

#[test]
fn an_orbit_turns_the_view() {
    let dir = scratch("animate", "orbit");
    write_step(&dir.join("one.vtk"), 1.0);
    let common = ["--renderer", "cpu", "--size", SIZE];
    let args = [
        "animate", "one.vtk", "-o", "orbit/", "--orbit", "180", "--frames", "4",
    ];
    let stdout = ok(&dir, &[&args[..], &common].concat());
    assert!(
        stdout.contains("wrote 4 frames of an orbit of 180 degrees"),
        "{stdout}"
    );
    ok(
        &dir,
        &[&["render", "one.vtk", "-o", "still.png"][..], &common].concat(),
    );
    let still = rgb(&dir.join("still.png"));
    let first = rgb(&dir.join("orbit/frame_0000.png"));
    let worst = first
        .pixels()
        .zip(still.pixels())
        .flat_map(|(a, b)| (0..3).map(move |c| a.0[c].abs_diff(b.0[c])))
        .max()
        .unwrap();
    // The first frame is the still view (turned by 0 degrees: at most a
    // rounding of the view-up, one step of 8 bits).
    assert!(worst <= 1, "first frame off the still by {worst}");
    let half = rgb(&dir.join("orbit/frame_0002.png"));
    assert_ne!(first, half, "a quarter of a turn later the view differs");
}

#[test]
fn bad_requests_are_one_line() {
    let dir = scratch("animate", "errors");
    write_series(&dir);
    write_step(&dir.join("one.vtk"), 1.0);
    for (args, expected) in [
        (vec!["animate", "one.vtk", "-o", "x.gif"], "give --orbit"),
        (
            vec!["animate", "s.series", "-o", "x.gif", "--times", "0:7"],
            "out of range",
        ),
        (
            vec!["animate", "s.series", "-o", "x.txt"],
            "write a .gif, a .mp4",
        ),
        (
            vec!["animate", "s.series", "-o", "x.gif", "--time-step", "1"],
            "from --times",
        ),
        (
            vec!["render", "one.vtk", "--clim", "3,1"],
            "below the second",
        ),
    ] {
        let out = run(&dir, &args);
        let stderr = text(&out.stderr);
        assert!(!out.status.success(), "{args:?}");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
        assert_eq!(stderr.trim().lines().count(), 1, "{args:?}: {stderr}");
    }
    // Refused before any output was opened.
    assert!(!dir.join("x.gif").exists());
}

/// An MP4 through ffmpeg (which `tools/system-deps` installs): ffprobe
/// reads back one frame per step at the size asked.
#[test]
fn an_mp4_holds_one_frame_per_step() {
    let dir = scratch("animate", "mp4");
    write_series(&dir);
    ok(
        &dir,
        &[
            "animate",
            "s.series",
            "-o",
            "s.mp4",
            "--renderer",
            "cpu",
            "--size",
            SIZE,
        ],
    );
    assert_eq!(probe(&dir.join("s.mp4")), "40,32,3");
}

/// What ffprobe reads of a video's first stream, decoding every frame:
/// "width,height,frames".
fn probe(video: &Path) -> String {
    let out = std::process::Command::new("ffprobe")
        .args(["-v", "error", "-count_frames", "-select_streams", "v:0"])
        .args([
            "-show_entries",
            "stream=nb_read_frames,width,height",
            "-of",
            "csv=p=0",
        ])
        .arg(video)
        .output()
        .expect("ffprobe (apt-get install ffmpeg; tools/system-deps installs it)");
    assert!(out.status.success(), "{}", text(&out.stderr));
    text(&out.stdout).trim().to_string()
}

/// A series whose steps share points and cells (`generate solid --steps`,
/// unstructured): the later steps keep the first step's scene (topology,
/// BVH, walk records; on the GPU the uploaded tetrahedra, the points'
/// scalars written over) and take only their fields, and their frames are
/// still the renders of their steps, bit for bit, on the CPU and on the
/// GPU.
#[test]
fn steps_that_share_cells_keep_the_scene() {
    let dir = scratch("animate", "kept");
    ok(
        &dir,
        &[
            "generate",
            "solid",
            "--tets",
            "3000",
            "--steps",
            "3",
            "-o",
            "run.series",
        ],
    );
    let renderers: &[&str] = if support::have_gpu() {
        &["cpu", "gpu"]
    } else {
        &["cpu"]
    };
    for renderer in renderers {
        let common = ["--renderer", renderer, "--size", SIZE, "--scalar", "linear"];
        let frames = format!("{renderer}/");
        let stdout = ok(
            &dir,
            &[&["animate", "run.series", "-o", &frames][..], &common].concat(),
        );
        for k in 1..3 {
            assert!(stdout.contains(&format!("step {k}: load")), "{stdout}");
        }
        assert_eq!(stdout.matches("scene kept").count(), 2, "{stdout}");
        let range = stdout
            .lines()
            .find_map(|l| l.strip_prefix("colour range ["))
            .and_then(|l| l.split(']').next())
            .expect("the range line")
            .replace(' ', "");
        for k in 0..3 {
            let step = k.to_string();
            let png = format!("{renderer}-render{k}.png");
            let clim = format!("--clim={range}");
            let args = [
                "render",
                "run.series",
                "--time-step",
                &step,
                &clim,
                "-o",
                &png,
            ];
            ok(&dir, &[&args[..], &common].concat());
            assert_eq!(
                rgb(&dir.join(format!("{renderer}/frame_{k:04}.png"))),
                rgb(&dir.join(&png)),
                "{renderer}, step {k}"
            );
        }
    }
}

/// A series whose points move (the second step's grid stretched along
/// x): that step is made anew, not kept (the engine's tests check that it
/// keeps the first step's camera), and its frame differs from the first.
#[test]
fn a_moving_mesh_is_made_anew() {
    let dir = scratch("animate", "moving");
    write_step(&dir.join("a.vtk"), 1.0);
    let stretched = std::fs::read_to_string(dir.join("a.vtk"))
        .expect("written")
        .replace("SPACING 0.25 ", "SPACING 0.375 ");
    assert!(stretched.contains("SPACING 0.375 "), "{stretched}");
    std::fs::write(dir.join("b.vtk"), stretched).expect("write");
    std::fs::write(
        dir.join("m.series"),
        r#"{"file-series-version": "1.0", "files": [{"name": "a.vtk", "time": 0}, {"name": "b.vtk", "time": 1}]}"#,
    )
    .expect("write");
    let args = [
        "animate",
        "m.series",
        "-o",
        "frames/",
        "--renderer",
        "cpu",
        "--size",
        SIZE,
        "--clim=0,1",
    ];
    let stdout = ok(&dir, &args);
    assert!(stdout.contains("step 1: load"), "{stdout}");
    assert_eq!(stdout.matches("scene kept").count(), 0, "{stdout}");
    assert_ne!(
        rgb(&dir.join("frames/frame_0000.png")),
        rgb(&dir.join("frames/frame_0001.png"))
    );
}

/// Real time series: the crushed can (VTKHDF files whose points move over
/// the same cells, so each step is made anew from the first step's view;
/// the last step's topology is built too, because some of its cells are
/// folded, left out of the walk) and an Exodus file
/// with three steps (netCDF-4; the steps share the mesh, so the later ones
/// keep it) animate to MP4; ffprobe reads back one frame per step at the
/// size asked.
#[test]
fn real_time_series_animate_to_mp4() {
    let dir = scratch("animate", "real");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let cases = [
        (
            "data/real/series/can/can.hdf.series",
            "EQPS",
            "can.mp4",
            (0, 0),
        ),
        (
            "data/exodus/tet_wedge_netcdf4.exo",
            "",
            "exodus.mp4",
            (2, 0),
        ),
    ];
    for (file, scalar, out, (kept, topology)) in cases {
        let path = root.join(file);
        let mut args = vec![
            "animate",
            path.to_str().expect("UTF-8"),
            "-o",
            out,
            "--renderer",
            "cpu",
            "--size",
            SIZE,
        ];
        if !scalar.is_empty() {
            args.extend(["--scalar", scalar]);
        }
        let stdout = ok(&dir, &args);
        assert_eq!(
            stdout.matches("scene kept").count(),
            kept,
            "{file}: {stdout}"
        );
        let said = stdout.matches("scene (topology kept)").count();
        assert_eq!(said, topology, "{file}: {stdout}");
        assert_eq!(probe(&dir.join(out)), "40,32,3", "{file}");
    }
}
