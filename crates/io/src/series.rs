//! Time series of files: ParaView's file series (`*.series`, JSON: a
//! `files` list of `{ "name": ..., "time": ... }`) and data collections
//! (`.pvd`, VTK XML `<VTKFile type="Collection">` whose `<DataSet>`s have
//! `timestep`, `part` and `file` attributes). Each step names one file, or
//! for a collection several parts, of any format tetray reads; paths are
//! relative to the folder of the series file. Steps are sorted by time
//! (stable), as ParaView presents them.

use std::path::{Path, PathBuf};

use quick_xml::Reader;
use quick_xml::events::Event;

/// One time step of a series: its time and the files it is made of.
#[derive(Debug, Clone, PartialEq)]
pub struct SeriesStep {
    pub time: f64,
    pub files: Vec<PathBuf>,
}

/// A series file that cannot be read; `file` is the series.
#[derive(Debug, thiserror::Error)]
#[error("{file}: {message}")]
pub struct SeriesError {
    pub file: String,
    pub message: String,
}

/// The largest series file read (a series names files; it is small).
const MAX_BYTES: u64 = 64 << 20;

/// Whether a name is a series: `.series` (ParaView's `name.ext.series`)
/// or `.pvd`.
pub(crate) fn is_series_name(name: &str) -> bool {
    let lower = name.to_ascii_lowercase();
    lower.ends_with(".series") || lower.ends_with(".pvd")
}

/// Whether the first bytes are a file series (JSON with a
/// `file-series-version`) or a VTK data collection.
pub(crate) fn is_series_content(head: &[u8]) -> bool {
    let text = String::from_utf8_lossy(head);
    (text.trim_start().starts_with('{') && text.contains("\"file-series-version\""))
        || (text.contains("<VTKFile") && text.contains("Collection"))
}

/// The steps of the series file at `path`, sorted by time.
///
/// # Errors
/// [`SeriesError`] for an unreadable or malformed file, a step without a
/// file, or a time that is not a number.
pub fn read_series(path: &Path) -> Result<Vec<SeriesStep>, SeriesError> {
    let file = path.display().to_string();
    let fail = |message: String| SeriesError {
        file: file.clone(),
        message,
    };
    let len = std::fs::metadata(path)
        .map_err(|e| fail(e.to_string()))?
        .len();
    if len > MAX_BYTES {
        return Err(fail(format!(
            "{len} bytes is too large for a series file (at most {MAX_BYTES})"
        )));
    }
    let bytes = std::fs::read(path).map_err(|e| fail(e.to_string()))?;
    let text = String::from_utf8_lossy(&bytes);
    let entries = if text.trim_start().starts_with('{') {
        json_entries(&text).map_err(fail)?
    } else {
        collection_entries(&text).map_err(fail)?
    };
    if entries.is_empty() {
        return Err(fail("the series names no file".into()));
    }
    let folder = path.parent().unwrap_or(Path::new("."));
    let mut steps: Vec<SeriesStep> = Vec::new();
    for (time, name) in entries {
        if !time.is_finite() {
            return Err(fail(format!("{name}: time {time} is not a finite number")));
        }
        let path = folder.join(&name);
        match steps.iter_mut().find(|s| s.time == time) {
            Some(step) => step.files.push(path),
            None => steps.push(SeriesStep {
                time,
                files: vec![path],
            }),
        }
    }
    steps.sort_by(|a, b| a.time.total_cmp(&b.time));
    Ok(steps)
}

/// `(time, file name)` of a `.series` JSON file; a file without a time
/// takes its position.
fn json_entries(text: &str) -> Result<Vec<(f64, String)>, String> {
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| format!("not a file series (JSON): {e}"))?;
    let files = value
        .get("files")
        .and_then(|f| f.as_array())
        .ok_or("a file series needs a \"files\" list")?;
    files
        .iter()
        .enumerate()
        .map(|(i, entry)| {
            let name = entry
                .get("name")
                .and_then(|n| n.as_str())
                .filter(|n| !n.is_empty())
                .ok_or_else(|| format!("entry {i} of \"files\" has no \"name\""))?;
            let time = match entry.get("time") {
                None => i as f64,
                Some(t) => t
                    .as_f64()
                    .ok_or_else(|| format!("{name}: \"time\" {t} is not a number"))?,
            };
            Ok((time, name.to_string()))
        })
        .collect()
}

/// `(time, file name)` of a `.pvd` collection's `<DataSet>` elements; a
/// data set without a `timestep` takes its position.
fn collection_entries(text: &str) -> Result<Vec<(f64, String)>, String> {
    let mut reader = Reader::from_str(text);
    let mut entries = Vec::new();
    let mut collection = false;
    loop {
        let event = reader
            .read_event()
            .map_err(|e| format!("not a VTK data collection (XML): {e}"))?;
        let element = match &event {
            Event::Start(e) | Event::Empty(e) => e,
            Event::Eof => break,
            _ => continue,
        };
        let attribute = |key: &str| -> Result<Option<String>, String> {
            for a in element.attributes() {
                let a = a.map_err(|e| format!("an attribute: {e}"))?;
                if a.key.as_ref() == key.as_bytes() {
                    let v = a
                        .normalized_value(quick_xml::XmlVersion::Implicit1_0)
                        .map_err(|e| format!("attribute {key}: {e}"))?;
                    return Ok(Some(v.into_owned()));
                }
            }
            Ok(None)
        };
        match element.name().as_ref() {
            b"VTKFile" => {
                let kind = attribute("type")?.unwrap_or_default();
                if kind != "Collection" {
                    return Err(format!(
                        "a VTK file of type \"{kind}\", not a data collection (\"Collection\")"
                    ));
                }
                collection = true;
            }
            b"DataSet" => {
                let i = entries.len();
                let name = attribute("file")?
                    .filter(|n| !n.is_empty())
                    .ok_or_else(|| format!("<DataSet> {i} has no file attribute"))?;
                let time = match attribute("timestep")? {
                    None => i as f64,
                    Some(t) => t
                        .trim()
                        .parse::<f64>()
                        .map_err(|_| format!("{name}: timestep \"{t}\" is not a number"))?,
                };
                entries.push((time, name));
            }
            _ => {}
        }
    }
    if !collection {
        return Err("no <VTKFile type=\"Collection\"> element".into());
    }
    Ok(entries)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_kinds_give_sorted_steps_and_parts() {
        let json = r#"{ "file-series-version": "1.0", "files": [
            { "name": "b.vtu", "time": 2.5 }, { "name": "a.vtu", "time": 0 } ] }"#;
        assert_eq!(
            json_entries(json).unwrap(),
            vec![(2.5, "b.vtu".into()), (0.0, "a.vtu".into())]
        );
        let pvd = r#"<?xml version="1.0"?><VTKFile type="Collection" version="0.1">
            <Collection>
              <DataSet timestep="0.5" part="0" file="s1_0.vtu"/>
              <DataSet timestep="0.5" part="1" file="s1_1.vtu"/>
              <DataSet timestep="0" part="0" file="s0.vtu"/>
            </Collection></VTKFile>"#;
        assert_eq!(
            collection_entries(pvd).unwrap(),
            vec![
                (0.5, "s1_0.vtu".into()),
                (0.5, "s1_1.vtu".into()),
                (0.0, "s0.vtu".into())
            ]
        );
        assert!(is_series_content(json.as_bytes()) && is_series_content(pvd.as_bytes()));
    }

    #[test]
    fn malformed_series_are_one_line_errors() {
        assert!(json_entries("{").unwrap_err().contains("JSON"));
        assert!(
            json_entries(r#"{"files": [{"time": 1}]}"#)
                .unwrap_err()
                .contains("name")
        );
        assert!(
            json_entries(r#"{"files": [{"name": "a", "time": "x"}]}"#)
                .unwrap_err()
                .contains("not a number")
        );
        let grid = r#"<VTKFile type="UnstructuredGrid"></VTKFile>"#;
        assert!(collection_entries(grid).unwrap_err().contains("Collection"));
        let bad = r#"<VTKFile type="Collection"><Collection><DataSet timestep="t" file="a.vtu"/>"#;
        assert!(
            collection_entries(bad)
                .unwrap_err()
                .contains("not a number")
        );
    }
}
