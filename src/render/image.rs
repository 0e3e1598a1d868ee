//! The RGB8 image every picture is drawn into, with its PNG encoding.

use crate::error::{Error, Result};
use std::path::Path;

/// A flat RGB8 image, row-major, top row first.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// `3 * width * height` bytes, `r, g, b` per pixel.
    pub data: Vec<u8>,
}

/// White, the background of every picture.
pub const BACKGROUND: [u8; 3] = [255, 255, 255];

impl Image {
    /// An image filled with one colour.
    pub fn filled(width: usize, height: usize, colour: [u8; 3]) -> Image {
        let mut data = Vec::with_capacity(3 * width * height);
        for _ in 0..width * height {
            data.extend_from_slice(&colour);
        }
        Image {
            width,
            height,
            data,
        }
    }

    /// The colour at `(x, y)`; `None` outside the image.
    pub fn get(&self, x: usize, y: usize) -> Option<[u8; 3]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let k = 3 * (y * self.width + x);
        Some([self.data[k], self.data[k + 1], self.data[k + 2]])
    }

    /// Sets the colour at `(x, y)`; ignored outside the image.
    pub fn set(&mut self, x: usize, y: usize, c: [u8; 3]) {
        if x < self.width && y < self.height {
            let k = 3 * (y * self.width + x);
            self.data[k..k + 3].copy_from_slice(&c);
        }
    }

    /// Sets the colour at signed coordinates; ignored outside the image.
    pub fn set_i(&mut self, x: i64, y: i64, c: [u8; 3]) {
        if x >= 0 && y >= 0 {
            self.set(x as usize, y as usize, c);
        }
    }

    /// Fills the rectangle `[x, x + w) x [y, y + h)` (clipped to the image).
    pub fn fill_rect(&mut self, x: usize, y: usize, w: usize, h: usize, c: [u8; 3]) {
        for yy in y..(y + h).min(self.height) {
            for xx in x..(x + w).min(self.width) {
                self.set(xx, yy, c);
            }
        }
    }

    /// Copies `src` with its top-left corner at `(x, y)` (clipped to the image).
    pub fn blit(&mut self, src: &Image, x: usize, y: usize) {
        for sy in 0..src.height {
            let ty = y + sy;
            if ty >= self.height {
                break;
            }
            let w = src.width.min(self.width.saturating_sub(x));
            if w == 0 {
                break;
            }
            let s = 3 * sy * src.width;
            let t = 3 * (ty * self.width + x);
            self.data[t..t + 3 * w].copy_from_slice(&src.data[s..s + 3 * w]);
        }
    }

    /// The image stacked on top of `below` (widths padded with the background colour).
    pub fn stacked(&self, below: &Image) -> Image {
        let mut out = Image::filled(
            self.width.max(below.width),
            self.height + below.height,
            BACKGROUND,
        );
        out.blit(self, 0, 0);
        out.blit(below, 0, self.height);
        out
    }

    /// The image as PNG bytes (8-bit RGB, fixed compression and filter, no metadata: the same
    /// image always gives the same bytes).
    pub fn to_png(&self) -> Result<Vec<u8>> {
        let mut out = Vec::new();
        self.write_png_to(&mut out)?;
        Ok(out)
    }

    fn write_png_to(&self, w: &mut dyn std::io::Write) -> Result<()> {
        let png_err = |e: png::EncodingError| {
            Error::InvalidArgument(format!(
                "PNG encoding of a {}x{} image failed: {e}",
                self.width, self.height
            ))
        };
        if self.width == 0 || self.height == 0 || self.width > u32::MAX as usize {
            return Err(Error::InvalidArgument(format!(
                "cannot encode an image of {}x{} pixels",
                self.width, self.height
            )));
        }
        let mut enc = png::Encoder::new(w, self.width as u32, self.height as u32);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_compression(png::Compression::Balanced);
        enc.set_filter(png::Filter::Adaptive);
        let mut writer = enc.write_header().map_err(png_err)?;
        writer.write_image_data(&self.data).map_err(png_err)?;
        writer.finish().map_err(png_err)?;
        Ok(())
    }

    /// Writes the image as a PNG file, atomically (see [`crate::io::write_atomically`]).
    pub fn write_png(&self, path: &Path) -> Result<()> {
        crate::io::write_atomically(path, |w| self.write_png_to(w))
    }
}
