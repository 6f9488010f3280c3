//! `tetray export-html` pages in headless Chromium (WebDriver, SwiftShader's
//! WebGPU adapter): the float image the page renders through its test hook
//! against `tetray render --renderer gpu` (lavapipe) for the same cameras
//! and integrators, on the Blunt Fin and on a torus shell whose rays leave
//! and re-enter the mesh.
//!
//! Tolerance 1e-5 per pixel and channel: both run the same WGSL on the
//! same buffers with the same frame parameters, and the camera is made in
//! the same arithmetic, so the walks agree step for step (the counters are
//! equal); what differs is two Vulkan compilers' exp, log and pow, a few
//! ulps each, about 1e-6 after compositing.

#[path = "support/browser.rs"]
mod browser;
mod support;

use std::path::{Path, PathBuf};

use browser::{Browser, WEBGPU_FLAGS};
use serde_json::{Value, json};
use support::{run, scratch, text};

const TOLERANCE: f32 = 1e-5;

fn export(dir: &Path, args: &[&str]) {
    let out = run(dir, &[&["export-html"], args].concat());
    assert!(
        out.status.success(),
        "export-html failed: {}",
        text(&out.stderr)
    );
}

fn url(path: &Path) -> String {
    format!("file://{}", path.display())
}

/// Headless Chromium with `flags` and an empty scratch folder for `test`;
/// `None` where the test skips (no adapter, or no browser where neither
/// is required).
fn start(test: &str, flags: &[&str]) -> Option<(Browser, PathBuf)> {
    if !support::have_gpu() {
        return None;
    }
    let browser = Browser::start(flags)?;
    Some((browser, scratch("web_page", test)))
}

/// `tetray generate solid --tets TETS -o torus.vtu` in `dir`.
fn torus(dir: &Path, tets: &str) {
    let out = run(
        dir,
        &["generate", "solid", "--tets", tets, "-o", "torus.vtu"],
    );
    assert!(out.status.success(), "generate: {}", text(&out.stderr));
}

/// What the page's start resolves to. Navigation can return before a large
/// page's script has run (seen once in a few runs with the 7 MB Blunt Fin
/// page): wait up to 60 s for the script to define `tetrayReady`.
const READY: &str = "for (let i = 0; i < 600 && !window.tetrayReady; i++) { \
                     await new Promise((r) => setTimeout(r, 100)); } \
                     return await window.tetrayReady;";

/// Opens the page and waits for its first frame.
fn open(browser: &Browser, page: &Path) -> Value {
    browser.open(&url(page));
    let ready = browser.eval(READY, json!(null));
    assert_eq!(ready["ok"], json!(true), "the page did not start: {ready}");
    ready
}

/// The page's float image and counters for `options` (see `window.tetray.render`).
fn page_render(browser: &Browser, options: Value) -> (Vec<f32>, Value) {
    use base64::Engine as _;
    let frame = browser.eval("return await window.tetray.render(args);", options);
    let bytes = base64::engine::general_purpose::STANDARD
        .decode(frame["pixels"].as_str().expect("pixels"))
        .expect("base64");
    let floats = bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    (floats, frame["counters"].clone())
}

/// The floats of a `.npy` float32 array, after its header.
fn read_npy(path: &Path) -> Vec<f32> {
    let bytes = std::fs::read(path).expect("read the .npy");
    assert_eq!(&bytes[..6], b"\x93NUMPY");
    let header = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    bytes[10 + header..]
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect()
}

/// `tetray render --renderer gpu` of `mesh` (None: the Blunt Fin): the
/// float image and (rays hit, segments, boundary entries).
fn cli_render(
    dir: &Path,
    mesh: Option<&str>,
    flags: &[String],
    name: &str,
) -> (Vec<f32>, [u64; 3]) {
    let output = format!("{name}.npy");
    let mut args: Vec<String> = ["render", "--renderer", "gpu", "-o", output.as_str()]
        .map(String::from)
        .to_vec();
    args.extend(mesh.map(String::from));
    args.extend(flags.iter().cloned());
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let out = run(dir, &args);
    let stdout = text(&out.stdout);
    assert!(out.status.success(), "render failed: {}", text(&out.stderr));
    let line = stdout
        .lines()
        .find(|l| l.starts_with("rendered "))
        .expect("a stats line");
    let count = |what: &str| -> u64 {
        let at = line
            .find(what)
            .unwrap_or_else(|| panic!("{what} in {line}"));
        let before = line[..at].trim_end();
        let word = before.rsplit([' ', ',']).next().expect("a number");
        word.parse()
            .unwrap_or_else(|_| panic!("{word:?} in {line}"))
    };
    let counts = [
        count(" hit the mesh"),
        count(" segments,"),
        count(" boundary entries"),
    ];
    (read_npy(&dir.join(output)), counts)
}

/// A camera as the page takes it and as `render` flags.
struct View {
    position: [f32; 3],
    focal: [f32; 3],
    up: [f32; 3],
    parallel_scale: Option<f32>,
    azimuth: f32,
    elevation: f32,
}

impl View {
    fn page(&self, size: (u32, u32), method: &str, scale: f32) -> Value {
        json!({
            "camera": {
                "position": self.position, "focal_point": self.focal, "view_up": self.up,
                "view_angle": 30.0, "parallel_scale": self.parallel_scale,
            },
            "azimuth": self.azimuth, "elevation": self.elevation,
            "width": size.0, "height": size.1, "method": method, "opacity_scale": scale,
        })
    }

    fn flags(&self, size: (u32, u32), method: &str) -> Vec<String> {
        let v = |p: [f32; 3]| format!("{},{},{}", p[0], p[1], p[2]);
        let mut flags = vec![
            format!("--camera-position={}", v(self.position)),
            format!("--focal-point={}", v(self.focal)),
            format!("--view-up={}", v(self.up)),
            format!("--azimuth={}", self.azimuth),
            format!("--elevation={}", self.elevation),
            format!("--size={}x{}", size.0, size.1),
            format!("--integrator={method}"),
        ];
        if let Some(s) = self.parallel_scale {
            flags.push(format!("--parallel-scale={s}"));
        }
        flags
    }
}

/// The page's image of `view` against the CLI's; returns the page's
/// counters.
#[allow(clippy::too_many_arguments)]
fn compare(
    browser: &Browser,
    dir: &Path,
    mesh: Option<&str>,
    view: &View,
    method: &str,
    scale: f32,
    extra: &[String],
    what: &str,
) -> Value {
    let size = (48, 40);
    let (page, counters) = page_render(browser, view.page(size, method, scale));
    let mut flags = view.flags(size, method);
    flags.extend(extra.iter().cloned());
    let (cli, [hit, segments, entries]) = cli_render(dir, mesh, &flags, what);
    assert_eq!(page.len(), cli.len(), "{what}: image sizes");
    let worst = page
        .iter()
        .zip(&cli)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0f32, f32::max);
    let lit = cli.chunks_exact(4).filter(|p| p[3] > 0.01).count();
    eprintln!("{what}: worst pixel difference {worst:.2e}, {lit} lit pixels, {segments} segments");
    assert!(
        lit > 100,
        "{what}: the view shows too little of the mesh ({lit} lit pixels)"
    );
    assert!(worst <= TOLERANCE, "{what}: page and CLI differ by {worst}");
    assert_eq!(counters["rays_hit"], json!(hit), "{what}: rays hit");
    // A denser medium is made two ways (attenuation times 2 in the page,
    // the unit distance halved in the CLI), which round differently: where
    // the light underflows to 0 a ray stops, a few segments apart.
    if scale == 1.0 {
        assert_eq!(counters["segments"], json!(segments), "{what}: segments");
        assert_eq!(
            counters["entries"],
            json!(entries),
            "{what}: boundary entries"
        );
    }
    counters
}

#[test]
fn blunt_fin_page_renders_as_the_gpu_ray_caster() {
    let Some((browser, dir)) = start("blunt_fin", &WEBGPU_FLAGS) else {
        return;
    };
    export(&dir, &["-o", "fin.html", "--size", "48x40"]);
    open(&browser, &dir.join("fin.html"));
    let views = [
        View {
            position: [20.0, -10.0, 15.0],
            focal: [3.0, 4.0, 3.0],
            up: [0.0, 0.0, 1.0],
            parallel_scale: None,
            azimuth: 0.0,
            elevation: 0.0,
        },
        View {
            position: [3.0, -30.0, 3.0],
            focal: [3.0, 4.0, 2.5],
            up: [0.0, 0.0, 1.0],
            parallel_scale: Some(9.0),
            azimuth: 35.0,
            elevation: 20.0,
        },
    ];
    for (i, view) in views.iter().enumerate() {
        for method in ["ppi", "exact", "preintegrated"] {
            compare(
                &browser,
                &dir,
                None,
                view,
                method,
                1.0,
                &[],
                &format!("fin-{i}-{method}"),
            );
        }
    }
}

#[test]
fn torus_page_renders_every_method_and_reentry_as_the_gpu_ray_caster() {
    let Some((browser, dir)) = start("torus", &WEBGPU_FLAGS) else {
        return;
    };
    torus(&dir, "20k");
    export(&dir, &["torus.vtu", "-o", "torus.html", "--size", "48x40"]);
    open(&browser, &dir.join("torus.html"));
    // Rays through the hole leave the shell and enter it again.
    let view = View {
        position: [0.5, -4.0, 1.5],
        focal: [0.0, 0.0, 0.0],
        up: [0.0, 0.0, 1.0],
        parallel_scale: None,
        azimuth: 10.0,
        elevation: -5.0,
    };
    let methods = browser.eval(
        "return window.tetray.manifest.methods.map((m) => m.name);",
        json!(null),
    );
    let methods: Vec<String> = serde_json::from_value(methods).expect("method names");
    assert_eq!(methods.len(), 8, "every GPU method: {methods:?}");
    for method in &methods {
        let counters = compare(
            &browser,
            &dir,
            Some("torus.vtu"),
            &view,
            method,
            1.0,
            &[],
            method,
        );
        assert!(
            counters["entries"].as_u64() > counters["rays_hit"].as_u64(),
            "no ray re-entered the torus: {counters}"
        );
    }
    // The opacity scale: attenuation (or the opacity's distance) times s is
    // the unit distance divided by s.
    let unit: f32 = browser
        .eval("return window.tetray.manifest.unit_distance;", json!(null))
        .as_f64()
        .expect("unit distance") as f32;
    let halved = [format!("--unit-distance={}", unit / 2.0)];
    for method in ["ppi", "lin-opacity"] {
        compare(
            &browser,
            &dir,
            Some("torus.vtu"),
            &view,
            method,
            2.0,
            &halved,
            &format!("{method}-x2"),
        );
    }
}

#[test]
fn folder_page_renders_as_the_single_file_and_the_benchmark_reports() {
    let Some((browser, dir)) = start("folder", &WEBGPU_FLAGS) else {
        return;
    };
    torus(&dir, "5k");
    let flags = ["torus.vtu", "--size", "32x32", "--bench", "2,3"];
    export(&dir, &[&flags[..], &["-o", "one.html"]].concat());
    export(&dir, &[&flags[..], &["-o", "site", "--folder"]].concat());
    assert!(dir.join("site/index.html").is_file() && dir.join("site/scene.js").is_file());
    let mut images = Vec::new();
    for page in ["one.html", "site/index.html"] {
        open(&browser, &dir.join(page));
        let bench = browser.eval("return await window.tetray.benchDone;", json!(null));
        eprintln!("{page} benchmark: {bench}");
        assert_eq!(bench["frames"], json!(6), "2 frames at 3 views: {bench}");
        assert!(bench["segments_per_second"].as_f64() > Some(0.0), "{bench}");
        assert!(bench["frames_per_second"].as_f64() > Some(0.0), "{bench}");
        let adapter = bench["adapter"].as_str().unwrap_or("");
        assert!(adapter.contains("swiftshader"), "adapter {adapter:?}");
        let stats = browser.eval(
            "return document.getElementById('stats').textContent;",
            json!(null),
        );
        assert!(
            stats.as_str().is_some_and(|s| s.contains("segments/s")),
            "{stats}"
        );
        images.push(page_render(&browser, json!({})).0);
    }
    assert!(
        images[0] == images[1],
        "the folder's page renders another image"
    );
}

#[test]
fn page_without_webgpu_says_so() {
    let Some((browser, dir)) = start("no_webgpu", &["--disable-features=WebGPU"]) else {
        return;
    };
    torus(&dir, "5k");
    export(&dir, &["torus.vtu", "-o", "page.html", "--size", "32x32"]);
    browser.open(&url(&dir.join("page.html")));
    let ready = browser.eval(READY, json!(null));
    assert_eq!(ready["ok"], json!(false), "{ready}");
    let status = browser.eval(
        "const s = document.getElementById('status'); return [s.className, s.textContent];",
        json!(null),
    );
    assert_eq!(status[0], json!("error"));
    let message = status[1].as_str().unwrap_or("");
    assert!(message.contains("WebGPU"), "the message: {message:?}");
}

#[test]
fn blunt_fin_page_is_small_and_shows_its_first_frame() {
    let Some((browser, dir)) = start("first_frame", &WEBGPU_FLAGS) else {
        return;
    };
    export(&dir, &["-o", "fin.html"]);
    let bytes = std::fs::metadata(dir.join("fin.html")).expect("page").len();
    eprintln!("Blunt Fin page: {bytes} bytes");
    assert!(bytes <= 12_000_000, "the Blunt Fin page is {bytes} bytes");
    open(&browser, &dir.join("fin.html"));
    let first = browser.eval("return window.tetray.firstFrameMs;", json!(null));
    let timings = browser.eval("return window.tetray.timings;", json!(null));
    eprintln!("first frame shown {first} ms after navigation (SwiftShader); stages: {timings}");
    assert!(first.as_f64().is_some_and(|ms| ms > 0.0), "{first}");
}

#[test]
fn mouse_and_controls_move_the_view_as_the_camera_flags_do() {
    let Some((browser, dir)) = start("controls", &WEBGPU_FLAGS) else {
        return;
    };
    torus(&dir, "5k");
    export(&dir, &["torus.vtu", "-o", "page.html", "--size", "40x40"]);
    open(&browser, &dir.join("page.html"));
    // A drag a quarter of the view to the right orbits the camera 50
    // degrees (200 per view, as the viewer), as --azimuth=-50 does.
    let dragged = browser.eval(
        r#"const canvas = document.getElementById("view");
           const rect = canvas.getBoundingClientRect();
           const at = (x) => ({ clientX: rect.left + x, clientY: rect.top + rect.height / 2,
                                button: 0, pointerId: 1, bubbles: true });
           canvas.dispatchEvent(new PointerEvent("pointerdown", at(10)));
           canvas.dispatchEvent(new PointerEvent("pointermove", at(10 + rect.width / 4)));
           canvas.dispatchEvent(new PointerEvent("pointerup", at(10 + rect.width / 4)));
           const select = (id, value) => {
             const element = document.getElementById(id);
             element.value = value;
             element.dispatchEvent(new Event(id === "opacity" ? "input" : "change"));
           };
           select("method", "exact");
           select("colormap", "Viridis");
           select("opacity", "0.3");
           return await window.tetray.render({ current: true });"#,
        json!(null),
    );
    let camera = browser.eval("return window.tetray.manifest.camera;", json!(null));
    let turned = browser.eval(
        "return await window.tetray.render({ camera: args, azimuth: -50, method: 'exact', \
         colormap: 'Viridis', opacity_scale: Math.fround(Math.pow(10, 0.3)) });",
        camera.clone(),
    );
    let still = browser.eval(
        "return await window.tetray.render({ method: 'exact', colormap: 'Viridis' });",
        json!(null),
    );
    assert_eq!(
        dragged["pixels"], turned["pixels"],
        "the drag is not --azimuth=-50"
    );
    assert_ne!(
        dragged["pixels"], still["pixels"],
        "the drag did not move the view"
    );
    let stats = browser.eval(
        "return document.getElementById('stats').textContent;",
        json!(null),
    );
    assert!(
        stats.as_str().is_some_and(|s| s.contains("segments/s")),
        "{stats}"
    );
}
