//! Text on pictures: 8x8 bitmap glyphs (font8x8, ASCII) for labels, and the legend strip with
//! the numbers of a curvature colour map.
//!
//! Pictures without numbers invite wrong comparisons, so every curvature picture carries its
//! range as text; labels use integer scaling of one public-domain bitmap font, which keeps the
//! output free of font files and byte-for-byte deterministic.

use super::shade::diverging;
use super::{Image, Mode};

/// Glyph size in pixels at scale 1.
pub const GLYPH: usize = 8;

const INK: [u8; 3] = [20, 20, 20];

/// The 8 rows of a character (bit 0 of each row is the leftmost pixel); `?` for anything
/// outside ASCII.
pub fn glyph(ch: char) -> [u8; 8] {
    let k = if ch.is_ascii() {
        ch as usize
    } else {
        '?' as usize
    };
    font8x8::legacy::BASIC_LEGACY[k]
}

/// Width of a line of text in pixels.
pub fn text_width(s: &str, scale: usize) -> usize {
    s.chars().count() * GLYPH * scale
}

/// Draws text with its top-left corner at `(x, y)`, each glyph pixel a `scale x scale` square
/// (clipped to the image).
pub fn draw_text(img: &mut Image, x: usize, y: usize, s: &str, scale: usize, colour: [u8; 3]) {
    for (k, ch) in s.chars().enumerate() {
        let g = glyph(ch);
        for (r, bits) in g.iter().enumerate() {
            for c in 0..GLYPH {
                if bits >> c & 1 == 1 {
                    let px = x + (k * GLYPH + c) * scale;
                    let py = y + r * scale;
                    img.fill_rect(px, py, scale, scale, colour);
                }
            }
        }
    }
}

/// Draws text turned 90 degrees counter-clockwise (read from bottom to top); `(x, y)` is the
/// top-left corner of its `8 scale` wide and [`text_width`] high box.
pub fn draw_text_up(img: &mut Image, x: usize, y: usize, s: &str, scale: usize, colour: [u8; 3]) {
    let len = text_width(s, 1);
    for (k, ch) in s.chars().enumerate() {
        let g = glyph(ch);
        for (r, bits) in g.iter().enumerate() {
            for c in 0..GLYPH {
                if bits >> c & 1 == 1 {
                    let gx = k * GLYPH + c; // along the text
                    let px = x + r * scale;
                    let py = y + (len - 1 - gx) * scale;
                    img.fill_rect(px, py, scale, scale, colour);
                }
            }
        }
    }
}

/// `s` cut to at most `max_px` pixels of width at `scale` (with a trailing `.` when cut).
pub fn fit_text(s: &str, max_px: usize, scale: usize) -> String {
    let max_chars = max_px / (GLYPH * scale);
    if s.chars().count() <= max_chars {
        return s.to_string();
    }
    let mut t: String = s.chars().take(max_chars.saturating_sub(1)).collect();
    t.push('.');
    t
}

/// A number in at most three significant digits: plain between `1e-3` and `1e4`
/// (`0.013`, `2.5`, `120`), else with an exponent (`1.5e-5`).
pub fn format_number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return if x.is_nan() {
            "nan".into()
        } else {
            format!("{x}")
        };
    }
    let a = x.abs();
    if (1e-3..1e4).contains(&a) {
        let decimals = (2 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{x:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        let s = format!("{x:.1e}");
        s.replace(".0e", "e")
    }
}

/// Text scale for a picture of this width (2 from 600 pixels on).
pub fn scale_for(width: usize) -> usize {
    if width >= 600 { 2 } else { 1 }
}

/// A legend strip `width` pixels wide: the title of the mode, the colour bar of
/// [`diverging`] over `[-range, range]`, ticks and the numbers `-range`, `0`, `range`.
pub fn legend(width: usize, mode: Mode, range: f64) -> Image {
    let s = scale_for(width);
    let pad = 4 * s;
    let bar_h = 10 * s;
    let title_y = pad;
    let bar_y = title_y + GLYPH * s + 3 * s;
    let label_y = bar_y + bar_h + 4 * s;
    let height = label_y + GLYPH * s + pad;
    let mut img = Image::filled(width, height, super::BACKGROUND);
    let title = fit_text(mode.title(), width, s);
    let tw = text_width(&title, s);
    draw_text(
        &mut img,
        width.saturating_sub(tw) / 2,
        title_y,
        &title,
        s,
        INK,
    );
    let lo = format_number(-range);
    let hi = format_number(range);
    let margin = (width / 12).max(text_width(&lo, s) / 2 + 2).min(width / 3);
    let (x0, x1) = (margin, width.saturating_sub(margin));
    if x1 <= x0 + 2 {
        return img;
    }
    for x in x0..x1 {
        let t = 2.0 * (x - x0) as f64 / (x1 - 1 - x0) as f64 - 1.0;
        let c = diverging(t).map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
        for y in bar_y..bar_y + bar_h {
            img.set(x, y, c);
        }
    }
    // frame and ticks
    for x in x0..x1 {
        img.set(x, bar_y, INK);
        img.set(x, bar_y + bar_h - 1, INK);
    }
    let mid = (x0 + x1 - 1) / 2;
    for &x in &[x0, mid, x1 - 1] {
        for y in bar_y..bar_y + bar_h + 3 * s {
            img.set(x, y, INK);
        }
    }
    let put = |img: &mut Image, centre: usize, t: &str| {
        let w = text_width(t, s);
        let x = centre.saturating_sub(w / 2).min(width.saturating_sub(w));
        draw_text(img, x, label_y, t, s, INK);
    };
    put(&mut img, x0, &lo);
    put(&mut img, mid, "0");
    put(&mut img, x1 - 1, &hi);
    img
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn numbers_are_short() {
        assert_eq!(format_number(0.013), "0.013");
        assert_eq!(format_number(-2.5), "-2.5");
        assert_eq!(format_number(120.0), "120");
        assert_eq!(format_number(1.5e-5), "1.5e-5");
        assert_eq!(format_number(2e-7), "2e-7");
        assert_eq!(format_number(0.0), "0");
    }

    #[crate::unit::test]
    fn text_draws_ink_in_its_box_only() {
        let mut img = Image::filled(40, 12, [255; 3]);
        draw_text(&mut img, 2, 2, "H1", 1, [0; 3]);
        let mut inked = 0;
        for y in 0..12 {
            for x in 0..40 {
                let dark = img.get(x, y).unwrap() == [0; 3];
                if dark {
                    inked += 1;
                    assert!((2..18).contains(&x) && (2..10).contains(&y));
                }
            }
        }
        assert!(inked > 10);
        // rotated text occupies the transposed box
        let mut img = Image::filled(12, 40, [255; 3]);
        draw_text_up(&mut img, 2, 2, "H1", 1, [0; 3]);
        for y in 0..40 {
            for x in 0..12 {
                if img.get(x, y).unwrap() == [0; 3] {
                    assert!((2..10).contains(&x) && (2..18).contains(&y));
                }
            }
        }
    }

    #[crate::unit::test]
    fn legend_shows_the_colour_bar() {
        let img = legend(320, Mode::Mean, 0.5);
        assert_eq!(img.width, 320);
        // a bluish pixel on the left of the bar and a reddish one on the right
        let y = 4 + 8 + 3 + 5;
        let l = img.get(40, y).unwrap();
        let r = img.get(280, y).unwrap();
        assert!(l[2] > l[0], "{l:?}");
        assert!(r[0] > r[2], "{r:?}");
    }
}
