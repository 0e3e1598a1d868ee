//! Python's render keywords as the library's typed [`fairsub::RenderOptions`]: each keyword is
//! a [`LookOption`] by its [`LookOption::keyword`] (`stripe_width=0.3` sets the field
//! `shade.stripe_width`, as `--stripe-width 0.3` does on the command line); an omitted keyword
//! or `None` keeps the library's default, which is the command's. Values are converted here by
//! type (and strings by the library's own parsers); the library checks them
//! ([`RenderOptions::check`]) and a bad value is a `ValueError` naming the keyword.

use fairsub::render::camera::{parse_element, parse_rings};
use fairsub::render::parse_size;
use fairsub::{Element, LookOption, Mode, Overlays, RenderOptions};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyString};

/// The keywords Python offers: every option of `fairsub render`'s look, in its help's order.
const OFFERED: [LookOption; 15] = [
    LookOption::Mode,
    LookOption::Size,
    LookOption::Aa,
    LookOption::Azimuth,
    LookOption::Elevation,
    LookOption::Distance,
    LookOption::Fov,
    LookOption::Focus,
    LookOption::ZoomRings,
    LookOption::Range,
    LookOption::Overlay,
    LookOption::Stripes,
    LookOption::StripeWidth,
    LookOption::LightAngle,
    LookOption::Legend,
];

/// The keyword spelt as the command line's flag (`no_legend=True` is `--no-legend`).
const NO_LEGEND: &str = "no_legend";

/// `ValueError: bad KEYWORD=VALUE: expected WHAT`.
fn expected(key: LookOption, what: &str, v: &Bound<'_, PyAny>) -> PyErr {
    let shown = v.repr().map(|r| r.to_string()).unwrap_or_default();
    PyValueError::new_err(format!("bad {}={shown}: expected {what}", key.keyword()))
}

/// A library parser's error for the value of `key`, prefixed by the keyword (the reason of an
/// invalid argument without the command line's "invalid argument: ").
fn parsed<T>(key: LookOption, r: fairsub::Result<T>) -> PyResult<T> {
    r.map_err(|e| {
        let reason = match &e {
            fairsub::Error::InvalidArgument(m) => m.clone(),
            other => other.to_string(),
        };
        PyValueError::new_err(format!("{}: {reason}", key.keyword()))
    })
}

/// A string value, if it is one.
fn text(v: &Bound<'_, PyAny>) -> Option<String> {
    v.cast::<PyString>().ok().map(|s| s.to_string())
}

/// A number: a float or an int (not a bool), or a string that parses as one.
fn number(key: LookOption, v: &Bound<'_, PyAny>) -> PyResult<f64> {
    if let Some(s) = text(v) {
        return s.trim().parse().map_err(|_| expected(key, "a number", v));
    }
    if v.is_instance_of::<PyBool>() {
        return Err(expected(key, "a number", v));
    }
    v.extract::<f64>().map_err(|_| expected(key, "a number", v))
}

/// A whole number >= 0: an int (not a bool), or a string that parses as one.
fn count(key: LookOption, v: &Bound<'_, PyAny>) -> PyResult<usize> {
    let what = "a whole number >= 0";
    if let Some(s) = text(v) {
        return s.trim().parse().map_err(|_| expected(key, what, v));
    }
    if v.is_instance_of::<PyBool>() {
        return Err(expected(key, what, v));
    }
    v.extract::<usize>().map_err(|_| expected(key, what, v))
}

/// `(width, height)`, a number for a square, or `"WxH"`.
fn size(v: &Bound<'_, PyAny>) -> PyResult<(usize, usize)> {
    let key = LookOption::Size;
    if let Some(s) = text(v) {
        return parsed(key, parse_size(&s));
    }
    if let Ok((w, h)) = v.extract::<(Bound<'_, PyAny>, Bound<'_, PyAny>)>() {
        return Ok((count(key, &w)?, count(key, &h)?));
    }
    count(key, v)
        .map(|n| (n, n))
        .map_err(|_| expected(key, "(width, height), a number or 'WxH'", v))
}

/// A vertex index, or `"V"`, `"vertex:V"`, `"face:F"`.
fn focus(v: &Bound<'_, PyAny>) -> PyResult<Element> {
    let key = LookOption::Focus;
    if let Some(s) = text(v) {
        return parsed(key, parse_element(&s));
    }
    let n =
        count(key, v).map_err(|_| expected(key, "a vertex index, 'vertex:V' or 'face:F'", v))?;
    u32::try_from(n)
        .map(Element::Vertex)
        .map_err(|_| expected(key, "a vertex index below 2^32", v))
}

/// `(K, L)`, `K` for one ring, or `"K..L"`.
fn rings(v: &Bound<'_, PyAny>) -> PyResult<(u32, u32)> {
    let key = LookOption::ZoomRings;
    if let Some(s) = text(v) {
        return parsed(key, parse_rings(&s));
    }
    let what = "(K, L), K or 'K..L' with rings counted from 1";
    let ring = |x: &Bound<'_, PyAny>| {
        count(key, x)
            .ok()
            .and_then(|n| u32::try_from(n).ok())
            .ok_or_else(|| expected(key, what, v))
    };
    if let Ok((k, l)) = v.extract::<(Bound<'_, PyAny>, Bound<'_, PyAny>)>() {
        return Ok((ring(&k)?, ring(&l)?));
    }
    ring(v).map(|k| (k, k))
}

/// `"net,patches"` or a sequence of names.
fn overlays(v: &Bound<'_, PyAny>) -> PyResult<Overlays> {
    let key = LookOption::Overlay;
    let names: Vec<String> = match text(v) {
        Some(s) => vec![s],
        None => v
            .extract()
            .map_err(|_| expected(key, "'net', 'patches', 'net,patches' or a list of them", v))?,
    };
    parsed(key, Overlays::parse(&names))
}

/// A bool (not a number that is one).
fn flag(key: &str, v: &Bound<'_, PyAny>) -> PyResult<bool> {
    v.cast::<PyBool>().map(|b| b.is_true()).map_err(|_| {
        let shown = v.repr().map(|r| r.to_string()).unwrap_or_default();
        PyValueError::new_err(format!("bad {key}={shown}: expected True or False"))
    })
}

/// The options of render's keywords, checked by the library.
pub fn options(look: Option<&Bound<'_, PyDict>>) -> PyResult<RenderOptions> {
    let mut o = RenderOptions::default();
    let Some(look) = look else { return Ok(o) };
    for (k, v) in look.iter() {
        let key: String = k.extract()?;
        if v.is_none() {
            continue;
        }
        let v = &v;
        if key == NO_LEGEND {
            o.legend = !flag(NO_LEGEND, v)?;
            continue;
        }
        let Some(option) = OFFERED.into_iter().find(|x| x.keyword() == key) else {
            let names: Vec<&str> = OFFERED.iter().map(|x| x.keyword()).collect();
            return Err(PyValueError::new_err(format!(
                "unknown render option '{key}' (the options are {})",
                names.join(", ")
            )));
        };
        match option {
            LookOption::Mode => {
                let s = text(v).ok_or_else(|| expected(option, "a mode name", v))?;
                o.mode = parsed(option, s.parse::<Mode>())?;
            }
            LookOption::Size => (o.width, o.height) = size(v)?,
            LookOption::Aa => o.supersample = count(option, v)?,
            LookOption::Azimuth => o.view.azimuth_deg = number(option, v)?,
            LookOption::Elevation => o.view.elevation_deg = number(option, v)?,
            LookOption::Distance => o.view.distance = Some(number(option, v)?),
            LookOption::Fov => o.view.fov_deg = number(option, v)?,
            LookOption::Focus => o.view.focus = Some(focus(v)?),
            LookOption::ZoomRings => o.view.zoom_rings = Some(rings(v)?),
            LookOption::Range => o.shade.range = Some(number(option, v)?),
            LookOption::Overlay => o.overlays = overlays(v)?,
            LookOption::Stripes => o.shade.stripes = number(option, v)?,
            LookOption::StripeWidth => o.shade.stripe_width = number(option, v)?,
            LookOption::LightAngle => o.shade.light_angle_deg = number(option, v)?,
            LookOption::Legend => o.legend = flag(option.keyword(), v)?,
            LookOption::LightHeight | LookOption::Percentile => unreachable!("not offered"),
        }
    }
    o.check()
        .map_err(|b| PyValueError::new_err(b.keyword_message()))?;
    Ok(o)
}

/// The defaults of the keywords, as `fairsub.render_defaults()` gives them.
pub fn defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let o = RenderOptions::default();
    let d = PyDict::new(py);
    for option in OFFERED {
        let k = option.keyword();
        match option {
            LookOption::Mode => d.set_item(k, o.mode.name())?,
            LookOption::Size => d.set_item(k, (o.width, o.height))?,
            LookOption::Aa => d.set_item(k, o.supersample)?,
            LookOption::Azimuth => d.set_item(k, o.view.azimuth_deg)?,
            LookOption::Elevation => d.set_item(k, o.view.elevation_deg)?,
            LookOption::Distance => d.set_item(k, o.view.distance)?,
            LookOption::Fov => d.set_item(k, o.view.fov_deg)?,
            LookOption::Focus => d.set_item(
                k,
                o.view.focus.map(|e| match e {
                    Element::Vertex(v) => format!("vertex:{v}"),
                    Element::Face(f) => format!("face:{f}"),
                }),
            )?,
            LookOption::ZoomRings => d.set_item(k, o.view.zoom_rings)?,
            LookOption::Range => d.set_item(k, o.shade.range)?,
            LookOption::Overlay => {
                let mut names = Vec::new();
                if o.overlays.net {
                    names.push("net");
                }
                if o.overlays.patches {
                    names.push("patches");
                }
                d.set_item(k, names.join(","))?
            }
            LookOption::Stripes => d.set_item(k, o.shade.stripes)?,
            LookOption::StripeWidth => d.set_item(k, o.shade.stripe_width)?,
            LookOption::LightAngle => d.set_item(k, o.shade.light_angle_deg)?,
            LookOption::Legend => d.set_item(k, o.legend)?,
            LookOption::LightHeight | LookOption::Percentile => {}
        }
    }
    Ok(d)
}
