//! The options that decide a picture besides the surface ([`RenderOptions`]): their defaults
//! (the command line's: `fairsub render` reads its defaults from here), their limits and
//! their validation, in one place for every front end.
//!
//! A bad value is reported as a [`BadOption`]: which option ([`LookOption`]), the value and the
//! reason, so that each front end names the option the way its users spell it (`--stripe-width`
//! on the command line, `stripe_width` in Python) with one rule behind both.

use super::{Mode, Overlays, ShadeOptions, View};
use crate::error::{Error, Result};

/// Everything that decides a picture besides the surface: what `fairsub render`'s options
/// set, typed. The [`Default`] is the command's defaults (800 x 800 pixels, 2 x 2 samples per
/// pixel, shaded, azimuth -60, elevation 40, field of view 30 degrees, 12 stripes of width 0.5,
/// automatic curvature range, no overlays, a legend).
///
/// ```
/// use fairsub::{Mode, RenderOptions};
/// let mut o = RenderOptions {
///     width: 96,
///     height: 64,
///     mode: Mode::Highlight,
///     ..RenderOptions::default()
/// };
/// o.view.azimuth_deg = -30.0;
/// o.shade.stripes = 8.0;
/// assert!(o.check().is_ok());
/// o.shade.stripe_width = 1.5;
/// let bad = o.check().unwrap_err();
/// assert_eq!(bad.option, fairsub::LookOption::StripeWidth);
/// assert_eq!(bad.keyword_message(), "bad stripe_width=1.5: must lie strictly between 0 and 1");
/// ```
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

/// One option of a picture, as the front ends name it: [`LookOption::flag`] on the command
/// line, [`LookOption::keyword`] in Python.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LookOption {
    /// The mode ([`RenderOptions::mode`]).
    Mode,
    /// Width and height ([`RenderOptions::width`], [`RenderOptions::height`]).
    Size,
    /// Samples per pixel axis ([`RenderOptions::supersample`]).
    Aa,
    /// [`View::azimuth_deg`].
    Azimuth,
    /// [`View::elevation_deg`].
    Elevation,
    /// [`View::distance`].
    Distance,
    /// [`View::fov_deg`].
    Fov,
    /// [`View::focus`].
    Focus,
    /// [`View::zoom_rings`].
    ZoomRings,
    /// [`ShadeOptions::range`].
    Range,
    /// [`RenderOptions::overlays`].
    Overlay,
    /// [`ShadeOptions::stripes`].
    Stripes,
    /// [`ShadeOptions::stripe_width`].
    StripeWidth,
    /// [`ShadeOptions::light_angle_deg`].
    LightAngle,
    /// [`RenderOptions::legend`] (the command line's `--no-legend`).
    Legend,
    /// [`ShadeOptions::light_height`] (library only: no front end sets it).
    LightHeight,
    /// [`ShadeOptions::percentile`] (library only: no front end sets it).
    Percentile,
}

impl LookOption {
    /// The command line's option (`--stripe-width`); a library-only field by its name.
    pub fn flag(self) -> &'static str {
        match self {
            LookOption::Mode => "--mode",
            LookOption::Size => "--size",
            LookOption::Aa => "--aa",
            LookOption::Azimuth => "--azimuth",
            LookOption::Elevation => "--elevation",
            LookOption::Distance => "--distance",
            LookOption::Fov => "--fov",
            LookOption::Focus => "--focus",
            LookOption::ZoomRings => "--zoom-rings",
            LookOption::Range => "--range",
            LookOption::Overlay => "--overlay",
            LookOption::Stripes => "--stripes",
            LookOption::StripeWidth => "--stripe-width",
            LookOption::LightAngle => "--light-angle",
            LookOption::Legend => "--no-legend",
            LookOption::LightHeight => "light height",
            LookOption::Percentile => "percentile",
        }
    }

    /// The Python keyword (`stripe_width`).
    pub fn keyword(self) -> &'static str {
        match self {
            LookOption::Mode => "mode",
            LookOption::Size => "size",
            LookOption::Aa => "aa",
            LookOption::Azimuth => "azimuth",
            LookOption::Elevation => "elevation",
            LookOption::Distance => "distance",
            LookOption::Fov => "fov",
            LookOption::Focus => "focus",
            LookOption::ZoomRings => "zoom_rings",
            LookOption::Range => "range",
            LookOption::Overlay => "overlay",
            LookOption::Stripes => "stripes",
            LookOption::StripeWidth => "stripe_width",
            LookOption::LightAngle => "light_angle",
            LookOption::Legend => "legend",
            LookOption::LightHeight => "light_height",
            LookOption::Percentile => "percentile",
        }
    }
}

/// A bad value of one picture option: which option, the value as given, and why it is bad.
#[derive(Debug, Clone, PartialEq)]
pub struct BadOption {
    /// The option.
    pub option: LookOption,
    /// The value, as the user gave it (`4x800`, `1.5`).
    pub value: String,
    /// What is wrong, without the option's name (`must lie strictly between 0 and 1`).
    pub reason: String,
}

impl BadOption {
    fn new(option: LookOption, value: impl std::fmt::Display, reason: impl Into<String>) -> Self {
        BadOption {
            option,
            value: value.to_string(),
            reason: reason.into(),
        }
    }

    /// The command line's message: `bad --stripe-width 1.5: must lie strictly between 0 and 1`.
    pub fn cli_message(&self) -> String {
        format!("bad {} {}: {}", self.option.flag(), self.value, self.reason)
    }

    /// The message with the Python keyword: `bad stripe_width=1.5: must lie strictly between 0
    /// and 1`.
    pub fn keyword_message(&self) -> String {
        format!(
            "bad {}={}: {}",
            self.option.keyword(),
            self.value,
            self.reason
        )
    }
}

impl From<BadOption> for Error {
    /// [`Error::InvalidArgument`] with the command line's message.
    fn from(b: BadOption) -> Error {
        Error::InvalidArgument(b.cli_message())
    }
}

/// `Err` of a bad option.
fn bad<T>(
    option: LookOption,
    value: impl std::fmt::Display,
    reason: impl Into<String>,
) -> std::result::Result<T, BadOption> {
    Err(BadOption::new(option, value, reason))
}

impl RenderOptions {
    /// Checks sizes and numeric options; the error names the option and the reason.
    pub fn check(&self) -> std::result::Result<(), BadOption> {
        let (w, h) = (self.width, self.height);
        if w < 8 || h < 8 || w > MAX_SIZE || h > MAX_SIZE {
            return bad(
                LookOption::Size,
                format!("{w}x{h}"),
                format!("width and height must be between 8 and {MAX_SIZE} pixels"),
            );
        }
        let aa = self.supersample;
        if !(1..=8).contains(&aa) {
            return bad(LookOption::Aa, aa, "samples per pixel axis must be 1 to 8");
        }
        let samples = w * h * aa * aa;
        if samples > MAX_SAMPLES {
            return bad(
                LookOption::Aa,
                aa,
                format!(
                    "{w}x{h} pixels with {aa}x{aa} samples each is {samples} samples, more than {MAX_SAMPLES}: lower it or the size"
                ),
            );
        }
        self.view.check()?;
        self.shade.check()
    }

    /// [`RenderOptions::check`] as an [`Error`] with the command line's message.
    pub fn validate(&self) -> Result<()> {
        Ok(self.check()?)
    }
}

impl View {
    /// Checks the angles, the field of view, the distance and the rings.
    pub fn check(&self) -> std::result::Result<(), BadOption> {
        let finite = "must be a finite number of degrees";
        if !self.azimuth_deg.is_finite() {
            return bad(LookOption::Azimuth, self.azimuth_deg, finite);
        }
        if !self.elevation_deg.is_finite() {
            return bad(LookOption::Elevation, self.elevation_deg, finite);
        }
        if !(self.fov_deg > 1.0 && self.fov_deg < 170.0) {
            return bad(
                LookOption::Fov,
                self.fov_deg,
                "the field of view must be between 1 and 170 degrees",
            );
        }
        if let Some(d) = self.distance
            && !(d.is_finite() && d > 0.0)
        {
            return bad(LookOption::Distance, d, "must be a positive number");
        }
        if let Some((k, l)) = self.zoom_rings
            && (k == 0 || l < k)
        {
            return bad(
                LookOption::ZoomRings,
                format!("{k}..{l}"),
                "rings are numbered from 1 (outermost) and K <= L",
            );
        }
        Ok(())
    }

    /// [`View::check`] as an [`Error`] with the command line's message.
    pub fn validate(&self) -> Result<()> {
        Ok(self.check()?)
    }
}

impl ShadeOptions {
    /// Checks the numbers; the error names the option.
    pub fn check(&self) -> std::result::Result<(), BadOption> {
        if !(self.stripes.is_finite() && self.stripes > 0.0 && self.stripes <= 10_000.0) {
            return bad(
                LookOption::Stripes,
                self.stripes,
                "must be a positive number up to 10000",
            );
        }
        if !(self.stripe_width > 0.0 && self.stripe_width < 1.0) {
            return bad(
                LookOption::StripeWidth,
                self.stripe_width,
                "must lie strictly between 0 and 1",
            );
        }
        if !self.light_angle_deg.is_finite() {
            return bad(
                LookOption::LightAngle,
                self.light_angle_deg,
                "must be a finite number of degrees",
            );
        }
        if !(self.light_height.is_finite() && self.light_height > 0.0) {
            return bad(
                LookOption::LightHeight,
                self.light_height,
                "must be positive",
            );
        }
        if let Some(r) = self.range
            && !(r.is_finite() && r > 0.0)
        {
            return bad(
                LookOption::Range,
                r,
                "must be a positive number (the map shows [-r, r])",
            );
        }
        if !(self.percentile > 0.0 && self.percentile <= 1.0) {
            return bad(
                LookOption::Percentile,
                self.percentile,
                "must lie in (0, 1]",
            );
        }
        Ok(())
    }

    /// [`ShadeOptions::check`] as an [`Error`] with the command line's message.
    pub fn validate(&self) -> Result<()> {
        Ok(self.check()?)
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
