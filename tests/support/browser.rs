//! Headless Chromium under WebDriver (Debian's `chromium` and
//! `chromium-driver`), spoken to over plain HTTP: enough to open a page,
//! run a script in it and read back what the script returns.
//!
//! The WebGPU flags give Chromium's SwiftShader adapter, which runs compute
//! shaders on the CPU.

#![allow(dead_code)]

use std::io::{Read, Write};
use std::net::{TcpListener, TcpStream};
use std::path::PathBuf;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::{Value, json};

/// Chromium's flags for a working WebGPU adapter without a GPU.
pub const WEBGPU_FLAGS: [&str; 3] = [
    "--enable-unsafe-webgpu",
    "--enable-features=Vulkan",
    "--use-webgpu-adapter=swiftshader",
];

/// One browser at a time: the tests of a file run in parallel threads, and
/// several headless Chromiums compiling the kernel on a two-core machine
/// starve each other (and lavapipe) of time.
static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// The driver's and the browser's temp folder (`TMPDIR`): the profile
/// chromedriver makes for each browser, and the browser's own scratch,
/// which would otherwise outlive the test in the system temp folder. One
/// browser runs at a time, so one folder per test process serves them all,
/// removed after each. It stays in the system temp folder, whose path is
/// short: the browser binds a Unix socket in it, and such a path may not
/// exceed 107 bytes (a target folder deep in a checkout could).
fn scratch_dir() -> PathBuf {
    std::env::temp_dir().join(format!("tetray-chromium-{}", std::process::id()))
}

pub struct Browser {
    // Dropped last (fields drop in order): the browser and driver go first.
    driver: Child,
    port: u16,
    /// The driver's id of the browser it started (WebDriver's "sessionId").
    id: String,
    _turn: std::sync::MutexGuard<'static, ()>,
}

fn find(names: &[&str]) -> Option<String> {
    let path = std::env::var_os("PATH")?;
    names.iter().find_map(|name| {
        std::env::split_paths(&path)
            .map(|dir| dir.join(name))
            .find(|p| p.is_file())
            .map(|p| p.to_string_lossy().into_owned())
    })
}

impl Browser {
    /// Headless Chromium with `flags`; `None` (after saying why) when the
    /// browser or its driver is missing, which fails instead under
    /// `TETRAY_REQUIRE_GPU=1` (CI installs both).
    pub fn start(flags: &[&str]) -> Option<Browser> {
        let driver = std::env::var("CHROMEDRIVER")
            .ok()
            .or_else(|| find(&["chromedriver"]));
        let chromium = std::env::var("CHROMIUM")
            .ok()
            .or_else(|| find(&["chromium", "chromium-browser", "google-chrome"]));
        let (Some(driver), Some(chromium)) = (driver, chromium) else {
            let why = "chromium and chromedriver are not on PATH (Debian: apt-get install chromium \
                       chromium-driver)";
            if std::env::var("TETRAY_REQUIRE_GPU").as_deref() == Ok("1") {
                panic!("TETRAY_REQUIRE_GPU=1 but {why}");
            }
            eprintln!("\n!!! SKIPPING BROWSER TEST: {why} !!!\n");
            return None;
        };
        let turn = ONE_AT_A_TIME
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let port = TcpListener::bind("127.0.0.1:0")
            .and_then(|l| l.local_addr())
            .expect("a free port")
            .port();
        let scratch = scratch_dir();
        let _ = std::fs::remove_dir_all(&scratch);
        std::fs::create_dir_all(&scratch).expect("the browser's temp folder");
        let child = Command::new(&driver)
            .arg(format!("--port={port}"))
            .env("TMPDIR", &scratch)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap_or_else(|e| panic!("start {driver}: {e}"));
        let mut browser = Browser {
            driver: child,
            port,
            id: String::new(),
            _turn: turn,
        };
        let start = Instant::now();
        while browser.request("GET", "/status", None).is_err() {
            assert!(
                start.elapsed() < Duration::from_secs(30),
                "chromedriver did not answer"
            );
            std::thread::sleep(Duration::from_millis(100));
        }
        let mut args = vec!["--headless=new", "--no-sandbox", "--window-size=900,900"];
        args.extend_from_slice(flags);
        let caps = json!({"capabilities": {"alwaysMatch": {
            "browserName": "chrome",
            "timeouts": {"script": 600_000},
            "goog:chromeOptions": {"binary": chromium, "args": args},
        }}});
        let reply = browser
            .request("POST", "/session", Some(&caps))
            .expect("start the browser");
        browser.id = reply["value"]["sessionId"]
            .as_str()
            .unwrap_or_else(|| panic!("the driver started no browser: {reply}"))
            .to_string();
        Some(browser)
    }

    pub fn open(&self, url: &str) {
        let path = self.endpoint("/url");
        self.request("POST", &path, Some(&json!({"url": url})))
            .expect("open the page");
    }

    /// Runs `body` as an async function of `args` (it returns a value or a
    /// promise) and gives back what it resolves to.
    pub fn eval(&self, body: &str, args: Value) -> Value {
        let script = format!(
            "const done = arguments[arguments.length - 1]; \
             (async (args) => {{ {body} }})(arguments[0]).then(done, \
             (e) => done({{__error: String(e && e.stack || e)}}));"
        );
        let path = self.endpoint("/execute/async");
        let reply = self
            .request(
                "POST",
                &path,
                Some(&json!({"script": script, "args": [args]})),
            )
            .expect("run a script");
        let value = reply["value"].clone();
        if let Some(error) = value.get("__error") {
            panic!("the page's script failed: {error}");
        }
        value
    }

    /// A PNG of the window, as the browser draws it.
    pub fn screenshot(&self) -> Vec<u8> {
        use base64::Engine as _;
        let path = self.endpoint("/screenshot");
        let reply = self.request("GET", &path, None).expect("screenshot");
        let text = reply["value"].as_str().expect("base64 PNG");
        base64::engine::general_purpose::STANDARD
            .decode(text)
            .expect("base64")
    }

    /// The WebDriver path of this browser's `tail` (the protocol names
    /// the started browser a "session").
    fn endpoint(&self, tail: &str) -> String {
        format!("/session/{}{tail}", self.id)
    }

    fn request(&self, method: &str, path: &str, body: Option<&Value>) -> std::io::Result<Value> {
        let mut stream = TcpStream::connect(("127.0.0.1", self.port))?;
        stream.set_read_timeout(Some(Duration::from_secs(900)))?;
        let body = body.map(Value::to_string).unwrap_or_default();
        write!(
            stream,
            "{method} {path} HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nContent-Type: application/json\r\n\
             Content-Length: {}\r\nConnection: close\r\n\r\n{body}",
            self.port,
            body.len()
        )?;
        // The driver may keep the connection open: read the header, then
        // the body's Content-Length bytes.
        let mut reply = Vec::new();
        let mut chunk = [0u8; 65536];
        let split = loop {
            if let Some(at) = reply.windows(4).position(|w| w == b"\r\n\r\n") {
                break at;
            }
            let n = stream.read(&mut chunk)?;
            if n == 0 {
                return Err(std::io::Error::other(
                    "the connection closed before a header",
                ));
            }
            reply.extend_from_slice(&chunk[..n]);
        };
        let header = String::from_utf8_lossy(&reply[..split]).to_ascii_lowercase();
        let length: usize = header
            .lines()
            .find_map(|l| l.strip_prefix("content-length:"))
            .and_then(|v| v.trim().parse().ok())
            .ok_or_else(|| std::io::Error::other(format!("no Content-Length in {header}")))?;
        while reply.len() < split + 4 + length {
            let n = stream.read(&mut chunk)?;
            if n == 0 {
                return Err(std::io::Error::other(
                    "the connection closed inside the body",
                ));
            }
            reply.extend_from_slice(&chunk[..n]);
        }
        serde_json::from_slice(&reply[split + 4..split + 4 + length]).map_err(std::io::Error::other)
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        if !self.id.is_empty() {
            let _ = self.request("DELETE", &self.endpoint(""), None);
        }
        let _ = self.driver.kill();
        let _ = self.driver.wait();
        let _ = std::fs::remove_dir_all(scratch_dir());
    }
}
