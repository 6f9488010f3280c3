//! What the fuzz targets share: an input written as a file (or a folder of
//! files) for the readers that take paths, and the multi-file archive the
//! collection and case-folder targets split their input into.
//!
//! Archive: files separated by lines `@@@ NAME` (the first file's line may
//! be left out: it is then named by the target). Text separators survive
//! libFuzzer's mutations better than length prefixes.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

const SEPARATOR: &[u8] = b"\n@@@ ";

/// A fresh folder for one input, under the system's temporary folder (a
/// RAM disk where there is one), removed when dropped.
pub struct Scratch {
    pub dir: PathBuf,
}

impl Scratch {
    pub fn new() -> Scratch {
        static COUNT: AtomicU64 = AtomicU64::new(0);
        let base = if Path::new("/dev/shm").is_dir() {
            PathBuf::from("/dev/shm")
        } else {
            std::env::temp_dir()
        };
        let dir = base.join(format!(
            "tetray-fuzz-{}-{}",
            std::process::id(),
            COUNT.fetch_add(1, Ordering::Relaxed)
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("make the scratch folder");
        Scratch { dir }
    }

    /// Writes `bytes` as `name` (a relative path; folders are made) and
    /// returns its path; `None` for a name that leaves the folder.
    pub fn write(&self, name: &str, bytes: &[u8]) -> Option<PathBuf> {
        let relative = Path::new(name);
        let safe = !name.is_empty()
            && relative
                .components()
                .all(|c| matches!(c, std::path::Component::Normal(_)));
        if !safe {
            return None;
        }
        let path = self.dir.join(relative);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).ok()?;
        }
        std::fs::write(&path, bytes).ok()?;
        Some(path)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// The files of an archive: `(name, bytes)`; the first is `first_name`
/// unless the input starts with a separator line.
pub fn split_archive<'a>(data: &'a [u8], first_name: &str) -> Vec<(String, &'a [u8])> {
    let mut files = Vec::new();
    let mut name = first_name.to_string();
    let mut rest = data;
    if let Some(stripped) = rest.strip_prefix(&SEPARATOR[1..]) {
        let (line, after) = line_of(stripped);
        name = line;
        rest = after;
    }
    loop {
        match find(rest, SEPARATOR) {
            Some(at) => {
                files.push((name, &rest[..at]));
                let (line, after) = line_of(&rest[at + SEPARATOR.len()..]);
                name = line;
                rest = after;
            }
            None => {
                files.push((name, rest));
                return files;
            }
        }
    }
}

/// Joins files into an archive (for writing seeds).
pub fn join_archive(files: &[(String, Vec<u8>)]) -> Vec<u8> {
    let mut out = Vec::new();
    for (name, bytes) in files {
        out.extend_from_slice(&SEPARATOR[1..]);
        out.extend_from_slice(name.as_bytes());
        out.push(b'\n');
        out.extend_from_slice(bytes);
        out.push(b'\n');
    }
    out
}

fn line_of(bytes: &[u8]) -> (String, &[u8]) {
    let end = bytes
        .iter()
        .position(|&b| b == b'\n')
        .unwrap_or(bytes.len());
    let name = String::from_utf8_lossy(&bytes[..end]).trim().to_string();
    (name, bytes.get(end + 1..).unwrap_or(&[]))
}

fn find(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    haystack.windows(needle.len()).position(|w| w == needle)
}

/// Writes the archive's files into a scratch folder; the folder and the
/// path of the first file.
pub fn unpack(data: &[u8], first_name: &str) -> Option<(Scratch, PathBuf)> {
    let scratch = Scratch::new();
    let mut first = None;
    for (name, bytes) in split_archive(data, first_name) {
        let path = scratch.write(&name, bytes)?;
        first.get_or_insert(path);
    }
    let first = first?;
    Some((scratch, first))
}

/// Loads `path` as the CLI does (reader, cell assembly, topology checks);
/// every error is an answer, only a panic or a crash is a finding.
pub fn load(path: &Path) {
    let _ = tetray_io::load(path, &tetray_io::LoadOptions::default());
}

/// Writes `data` as a file with extension `ext` and loads it.
pub fn load_bytes_as(ext: &str, data: &[u8]) {
    let scratch = Scratch::new();
    if let Some(path) = scratch.write(&format!("input.{ext}"), data) {
        load(&path);
    }
}
