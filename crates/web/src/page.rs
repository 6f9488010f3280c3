//! The HTML: the template with the manifest, the ray caster's WGSL (as
//! `tetray_gpu::shaders::raycast_source` puts it together), the page script
//! and the buffers (in the page, or in a `scene.js` beside it).

use base64::Engine as _;

use crate::WebError;
use crate::bundle::{Bundle, StoredBuffer};

const TEMPLATE: &str = include_str!("../page/page.html");
/// The page script, in the order its parts depend on each other.
const SCRIPTS: [&str; 4] = [
    include_str!("../page/camera.js"),
    include_str!("../page/buffers.js"),
    include_str!("../page/gpu.js"),
    include_str!("../page/app.js"),
];

/// V8's longest string (2^29 - 24 characters): a buffer's base64 text must
/// fit in one.
pub const MAX_BUFFER_TEXT: usize = (1 << 29) - 24;

/// Where the buffers go.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    /// One self-contained HTML file.
    SingleFile,
    /// `index.html` and `scene.js` (the buffers), in a folder.
    Folder,
}

/// The files of a page: `index.html` (or the single file) and, for a
/// folder, `scene.js`.
#[derive(Debug, Clone)]
pub struct PageFiles {
    pub html: String,
    pub scene_js: Option<String>,
}

impl PageFiles {
    /// Bytes of all the files.
    pub fn bytes(&self) -> usize {
        self.html.len() + self.scene_js.as_ref().map_or(0, String::len)
    }
}

/// The page of `bundle`.
pub fn page(bundle: &Bundle, layout: Layout) -> Result<PageFiles, WebError> {
    let manifest = serde_json::to_string(&bundle.manifest)
        .map_err(|e| WebError::Setup(format!("the manifest: {e}")))?
        .replace("</", "<\\/");
    let wgsl = tetray_gpu::shaders::raycast_source();
    if wgsl.contains("</") {
        return Err(WebError::Setup("the WGSL source holds \"</\"".into()));
    }
    let mut texts = Vec::with_capacity(bundle.buffers.len());
    for buffer in &bundle.buffers {
        texts.push((buffer, base64_text(buffer)?));
    }
    let (data, scene_js) = match layout {
        Layout::SingleFile => {
            let mut data = String::new();
            for (buffer, text) in &texts {
                data.push_str(&format!(
                    "<script type=\"application/octet-stream\" id=\"tetray-buffer-{}\">{text}</script>\n",
                    buffer.id
                ));
            }
            (data, None)
        }
        Layout::Folder => {
            let mut js = String::from("window.tetrayBuffers = {\n");
            for (buffer, text) in &texts {
                js.push_str(&format!("  \"{}\": \"{text}\",\n", buffer.id));
            }
            js.push_str("};\n");
            ("<script src=\"scene.js\"></script>".to_string(), Some(js))
        }
    };
    let m = &bundle.manifest;
    let html = fill(
        TEMPLATE,
        &[
            ("{{TITLE}}", &escape_html(&m.name)),
            ("{{WIDTH}}", &m.size[0].to_string()),
            ("{{HEIGHT}}", &m.size[1].to_string()),
            ("{{MANIFEST}}", &manifest),
            ("{{WGSL}}", &wgsl),
            ("{{DATA}}", &data),
            ("{{SCRIPT}}", &SCRIPTS.join("\n")),
        ],
    );
    Ok(PageFiles { html, scene_js })
}

fn base64_text(buffer: &StoredBuffer) -> Result<String, WebError> {
    let text = base64::engine::general_purpose::STANDARD.encode(&buffer.deflated);
    if text.len() > MAX_BUFFER_TEXT {
        return Err(WebError::TooLarge(format!(
            "the {} buffer is {} bytes ({} as base64 text); a browser's longest string is {} \
             characters",
            buffer.id,
            buffer.bytes,
            text.len(),
            MAX_BUFFER_TEXT
        )));
    }
    Ok(text)
}

/// `template` with each marker replaced by its value, markers found in the
/// template only (never in a value put in).
fn fill(template: &str, values: &[(&str, &str)]) -> String {
    let mut out =
        String::with_capacity(template.len() + values.iter().map(|v| v.1.len()).sum::<usize>());
    let mut rest = template;
    while let Some(start) = rest.find("{{") {
        out.push_str(&rest[..start]);
        let after = &rest[start..];
        match values.iter().find(|(marker, _)| after.starts_with(marker)) {
            Some((marker, value)) => {
                out.push_str(value);
                rest = &after[marker.len()..];
            }
            None => {
                out.push_str("{{");
                rest = &after[2..];
            }
        }
    }
    out.push_str(rest);
    out
}

fn escape_html(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markers_are_replaced_in_the_template_only() {
        let out = fill(
            "a {{X}} b {{Y}} {{Z}}",
            &[("{{X}}", "{{Y}}"), ("{{Y}}", "y")],
        );
        assert_eq!(out, "a {{Y}} b y {{Z}}");
    }

    #[test]
    fn names_are_escaped() {
        assert_eq!(escape_html("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }
}
