//! A table as a figure: a title, a header row and rows of text, with
//! columns sized to their longest entry.

use super::Svg;

/// Approximate advance of one character at the table's font size.
const CHAR_W: f64 = 7.0;
const ROW_H: f64 = 20.0;
const PAD: f64 = 12.0;

/// The SVG of a table; numeric-looking cells are right-aligned.
pub fn table_figure(title: &str, header: &[&str], rows: &[Vec<String>]) -> String {
    let columns = header.len();
    let widths: Vec<f64> = (0..columns)
        .map(|c| {
            let longest = rows
                .iter()
                .filter_map(|r| r.get(c))
                .map(|s| s.chars().count())
                .chain([header[c].chars().count()])
                .max()
                .unwrap_or(1);
            longest as f64 * CHAR_W + 2.0 * PAD
        })
        .collect();
    let width = widths.iter().sum::<f64>() + 2.0 * PAD;
    let height = 50.0 + ROW_H * (rows.len() + 1) as f64 + PAD;
    let mut svg = Svg::new(
        width.max(title.chars().count() as f64 * 8.5 + 2.0 * PAD),
        height,
    );
    svg.text((PAD, 24.0), 15.0, "start", 0.0, title);
    let top = 40.0;
    svg.rect(PAD, top, widths.iter().sum(), ROW_H, "#e8e8e8", "none");
    // The header (grey band) is never right-aligned.
    let mut draw_row = |cells: &[&str], y: f64, header: bool| {
        let mut x = PAD;
        for (c, w) in widths.iter().enumerate() {
            let text = cells.get(c).copied().unwrap_or("");
            let numeric = !header && text.parse::<f64>().is_ok();
            let (anchor, at) = if numeric {
                ("end", x + w - PAD)
            } else {
                ("start", x + PAD)
            };
            svg.text((at, y + 14.0), 12.0, anchor, 0.0, text);
            x += w;
        }
    };
    draw_row(header, top, true);
    for (i, row) in rows.iter().enumerate() {
        let cells: Vec<&str> = row.iter().map(String::as_str).collect();
        draw_row(&cells, top + ROW_H * (i + 1) as f64, false);
    }
    let bottom = top + ROW_H * (rows.len() + 1) as f64;
    svg.line((PAD, top), (PAD + widths.iter().sum::<f64>(), top), "#333");
    svg.line(
        (PAD, top + ROW_H),
        (PAD + widths.iter().sum::<f64>(), top + ROW_H),
        "#333",
    );
    svg.line(
        (PAD, bottom),
        (PAD + widths.iter().sum::<f64>(), bottom),
        "#333",
    );
    svg.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_has_every_cell() {
        let rows = vec![
            vec!["Blunt Fin".to_string(), "12.5".into()],
            vec!["a<b".to_string(), "3".into()],
        ];
        let svg = table_figure("timings", &["dataset", "fps"], &rows);
        for text in ["timings", "dataset", "fps", "Blunt Fin", "12.5", "a&lt;b"] {
            assert!(svg.contains(text), "{text}");
        }
        assert_eq!(svg.matches("text-anchor=\"end\"").count(), 2);
    }
}
