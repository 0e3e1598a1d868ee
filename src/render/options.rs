//! The options that decide a picture besides the surface ([`RenderOptions`]), their limits and
//! their validation.

use super::{Mode, Overlays, ShadeOptions, View};
use crate::error::{Error, Result};

/// Everything that decides a picture besides the surface.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderOptions {
    /// Image width in pixels (of one cell for panels).
    pub width: usize,
    /// Image height in pixels (without the legend strip).
    pub height: usize,
    /// Samples per pixel along each axis (`aa x aa` samples, box-filtered).
    pub supersample: usize,
    /// What to show.
    pub mode: Mode,
    /// Camera placement.
    pub view: View,
    /// Light lines, stripes and curvature range.
    pub shade: ShadeOptions,
    /// Patch boundaries and control net.
    pub overlays: Overlays,
    /// Append a legend strip with the numbers under curvature pictures.
    pub legend: bool,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 800,
            height: 800,
            supersample: 2,
            mode: Mode::Shaded,
            view: View::default(),
            shade: ShadeOptions::default(),
            overlays: Overlays::default(),
            legend: true,
        }
    }
}

/// Largest width or height accepted.
pub const MAX_SIZE: usize = 16384;
/// Largest number of samples (`width * height * aa^2`) of one picture (about 3 GB of buffers).
pub const MAX_SAMPLES: usize = 1 << 26;

impl RenderOptions {
    /// Checks sizes and numeric options; the error names the option and the reason.
    pub fn validate(&self) -> Result<()> {
        let bad = |m: String| Err(Error::InvalidArgument(m));
        if self.width < 8 || self.height < 8 || self.width > MAX_SIZE || self.height > MAX_SIZE {
            return bad(format!(
                "bad size {}x{}: width and height must be between 8 and {MAX_SIZE} pixels",
                self.width, self.height
            ));
        }
        if !(1..=8).contains(&self.supersample) {
            return bad(format!(
                "bad --aa {}: samples per pixel axis must be 1 to 8",
                self.supersample
            ));
        }
        let samples = self.width * self.height * self.supersample * self.supersample;
        if samples > MAX_SAMPLES {
            return bad(format!(
                "{}x{} pixels with {}x{} samples each is {samples} samples, more than {MAX_SAMPLES}: lower --aa or the size",
                self.width, self.height, self.supersample, self.supersample
            ));
        }
        self.view.validate()?;
        self.shade.validate()
    }
}

/// Parses `WxH` (or a single number for a square).
pub fn parse_size(s: &str) -> Result<(usize, usize)> {
    let bad = || {
        Error::InvalidArgument(format!(
            "bad size '{s}': expected WIDTHxHEIGHT in pixels, e.g. 800x600"
        ))
    };
    let t = s.trim().to_ascii_lowercase();
    let (w, h) = match t.split_once('x') {
        Some((w, h)) => (w.trim(), h.trim()),
        None => (t.as_str(), t.as_str()),
    };
    let w: usize = w.parse().map_err(|_| bad())?;
    let h: usize = h.parse().map_err(|_| bad())?;
    Ok((w, h))
}
