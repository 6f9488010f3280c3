//! A labelled grid of 8-bit RGB pictures: one column per method,
//! one row per kind of picture (render, absolute error, perceptual error),
//! each row with its title and, where it has one, its colour bar.

use image::{Rgb, RgbImage};

use crate::font::{LINE, draw_text, text_width};

const GAP: u32 = 8;
const WHITE: Rgb<u8> = Rgb([255, 255, 255]);

/// One row of the sheet.
pub struct SheetRow {
    pub title: String,
    /// One picture per column; `None` leaves the cell empty.
    pub cells: Vec<Option<RgbImage>>,
    /// Drawn to the right of the row.
    pub colour_bar: Option<RgbImage>,
}

/// The grid: column labels on top, each row under its title. Cells may
/// differ in size; each column is as wide as its widest cell or label.
pub fn sheet(columns: &[String], rows: &[SheetRow]) -> RgbImage {
    let column_width = |c: usize| {
        let cells = rows
            .iter()
            .filter_map(|r| r.cells.get(c).and_then(Option::as_ref))
            .map(RgbImage::width);
        cells.chain([text_width(&columns[c], 1)]).max().unwrap_or(0)
    };
    let widths: Vec<u32> = (0..columns.len()).map(column_width).collect();
    let row_height = |r: &SheetRow| {
        let cells = r.cells.iter().flatten().map(RgbImage::height);
        let bar = r.colour_bar.iter().map(RgbImage::height);
        LINE + cells.chain(bar).max().unwrap_or(0)
    };
    let bars = rows
        .iter()
        .filter_map(|r| r.colour_bar.as_ref().map(RgbImage::width))
        .max()
        .map_or(0, |w| w + GAP);
    let width = GAP + widths.iter().map(|w| w + GAP).sum::<u32>() + bars;
    let title_width = rows
        .iter()
        .map(|r| text_width(&r.title, 1))
        .max()
        .unwrap_or(0);
    let width = width.max(title_width + 2 * GAP);
    let height = GAP + LINE + rows.iter().map(|r| row_height(r) + GAP).sum::<u32>();
    let mut out = RgbImage::from_pixel(width, height, WHITE);

    let mut x = GAP;
    for (label, w) in columns.iter().zip(&widths) {
        draw_text(&mut out, x, GAP, label, 1, [0, 0, 0]);
        x += w + GAP;
    }
    let mut y = GAP + LINE;
    for row in rows {
        draw_text(&mut out, GAP, y, &row.title, 1, [90, 90, 90]);
        let top = y + LINE;
        let mut x = GAP;
        for (cell, w) in row.cells.iter().zip(&widths) {
            if let Some(cell) = cell {
                paste(&mut out, cell, x, top);
            }
            x += w + GAP;
        }
        if let Some(bar) = &row.colour_bar {
            paste(&mut out, bar, x, top);
        }
        y += row_height(row) + GAP;
    }
    out
}

fn paste(out: &mut RgbImage, tile: &RgbImage, x0: u32, y0: u32) {
    for (x, y, p) in tile.enumerate_pixels() {
        if x0 + x < out.width() && y0 + y < out.height() {
            out.put_pixel(x0 + x, y0 + y, *p);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_land_in_their_columns_under_their_rows() {
        let red = RgbImage::from_pixel(10, 6, Rgb([255, 0, 0]));
        let blue = RgbImage::from_pixel(10, 6, Rgb([0, 0, 255]));
        let rows = [
            SheetRow {
                title: "render".into(),
                cells: vec![Some(red.clone()), Some(blue.clone())],
                colour_bar: None,
            },
            SheetRow {
                title: "error".into(),
                cells: vec![None, Some(red)],
                colour_bar: Some(blue),
            },
        ];
        let columns = ["a".to_string(), "b".to_string()];
        let out = sheet(&columns, &rows);
        // Column 0 at x = GAP, column 1 at GAP + 10 + GAP; row 0's cells
        // one label line below its title, under the column labels.
        let top0 = GAP + LINE + LINE;
        assert_eq!(out.get_pixel(GAP, top0).0, [255, 0, 0]);
        assert_eq!(out.get_pixel(2 * GAP + 10, top0).0, [0, 0, 255]);
        let top1 = top0 + 6 + GAP + LINE;
        assert_eq!(out.get_pixel(GAP, top1).0, [255, 255, 255], "empty cell");
        assert_eq!(out.get_pixel(2 * GAP + 10, top1).0, [255, 0, 0]);
        assert_eq!(out.get_pixel(3 * GAP + 20, top1).0, [0, 0, 255], "bar");
    }
}
