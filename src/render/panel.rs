//! Comparison panels: a labelled grid of cells, one row per scheme and one column per mode.
//!
//! Schemes are compared fairly only when every cell shares the camera, the lights and (per
//! mode) the curvature range; [`super::compare`] guarantees that and this module only lays the
//! cells out: mode names above the columns, scheme names (turned upward) left of the rows, and
//! under each curvature column the one legend that holds for all its cells.

use super::text::{GLYPH, draw_text, draw_text_up, fit_text, scale_for, text_width};
use super::{BACKGROUND, Image};

/// Gap between cells, in pixels.
pub const GAP: usize = 6;

const INK: [u8; 3] = [20, 20, 20];

/// Lays out `columns[c][r]` (column `c`, row `r`; cells of one row share a height, cells of one
/// column a width) with column titles, row labels and an optional legend under each column.
pub fn compose(
    columns: &[Vec<Image>],
    row_labels: &[String],
    col_labels: &[String],
    legends: &[Option<Image>],
) -> Image {
    let nrow = columns.iter().map(Vec::len).max().unwrap_or(0);
    let col_w: Vec<usize> = columns
        .iter()
        .map(|c| c.iter().map(|i| i.width).max().unwrap_or(0))
        .collect();
    let row_h: Vec<usize> = (0..nrow)
        .map(|r| {
            columns
                .iter()
                .filter_map(|c| c.get(r))
                .map(|i| i.height)
                .max()
                .unwrap_or(0)
        })
        .collect();
    let s = scale_for(col_w.iter().copied().min().unwrap_or(0));
    let left = GLYPH * s + 2 * GAP;
    let top = GLYPH * s + 2 * GAP;
    let legend_h = legends
        .iter()
        .flatten()
        .map(|l| l.height)
        .max()
        .unwrap_or(0);
    let width = left + col_w.iter().sum::<usize>() + GAP * col_w.len();
    let height = top + row_h.iter().sum::<usize>() + GAP * nrow.saturating_sub(1) + legend_h + GAP;
    let mut img = Image::filled(width, height, BACKGROUND);
    let mut x = left;
    for (c, col) in columns.iter().enumerate() {
        if let Some(label) = col_labels.get(c) {
            let t = fit_text(label, col_w[c], s);
            let tx = x + col_w[c].saturating_sub(text_width(&t, s)) / 2;
            draw_text(&mut img, tx, GAP, &t, s, INK);
        }
        let mut y = top;
        for (r, cell) in col.iter().enumerate() {
            img.blit(cell, x, y);
            y += row_h[r] + GAP;
        }
        if let Some(Some(l)) = legends.get(c) {
            img.blit(
                l,
                x,
                top + row_h.iter().sum::<usize>() + GAP * nrow.saturating_sub(1),
            );
        }
        x += col_w[c] + GAP;
    }
    let mut y = top;
    for (r, h) in row_h.iter().enumerate() {
        if let Some(label) = row_labels.get(r) {
            let t = fit_text(label, *h, s);
            let ty = y + h.saturating_sub(text_width(&t, s)) / 2;
            draw_text_up(&mut img, GAP, ty, &t, s, INK);
        }
        y += h + GAP;
    }
    img
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn cells_land_in_their_places() {
        let red = Image::filled(20, 10, [255, 0, 0]);
        let blue = Image::filled(20, 10, [0, 0, 255]);
        let img = compose(
            &[vec![red.clone(), blue.clone()], vec![blue, red]],
            &["a".into(), "b".into()],
            &["x".into(), "y".into()],
            &[None, None],
        );
        let (left, top) = (GLYPH + 2 * GAP, GLYPH + 2 * GAP);
        assert_eq!(img.get(left + 1, top + 1), Some([255, 0, 0]));
        assert_eq!(img.get(left + 1, top + 10 + GAP + 1), Some([0, 0, 255]));
        assert_eq!(img.get(left + 20 + GAP + 1, top + 1), Some([0, 0, 255]));
        assert_eq!(img.width, left + 2 * (20 + GAP));
        assert_eq!(img.height, top + 2 * 10 + GAP + GAP);
    }
}
