//! Python keyword options as the library's typed [`fairsub::Options`]: each keyword is the
//! field of the same name (`split_ratio=0.3`, `boundary="edge-only"`, `pole=["0:0,0,1"]`);
//! values are checked here by type, and against the scheme by the library.

use fairsub::mesh::tags::Named;
use fairsub::{AlphaRule, Fallback, Options, Prepare, RulesChoice};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict};
use std::path::PathBuf;

/// The keywords, in the order the error message lists them.
const KEYWORDS: &[&str] = &[
    "lambda_",
    "fcv_scale",
    "fcv_file",
    "fallback",
    "q_file",
    "split_ratio",
    "alpha_rule",
    "pole",
    "rules",
    "prepare",
    "boundary",
    "crease_method",
    "smooth_triangles",
    "fvar",
    "creases",
];

fn bad(key: &str, what: &str, v: &Bound<'_, PyAny>) -> PyErr {
    PyValueError::new_err(format!("option {key}: expected {what}, not {v}"))
}

/// A number (a float, an int, or a string that parses as one).
fn number(key: &str, v: &Bound<'_, PyAny>) -> PyResult<f64> {
    if let Ok(s) = v.extract::<String>() {
        return s.trim().parse().map_err(|_| bad(key, "a number", v));
    }
    v.extract::<f64>().map_err(|_| bad(key, "a number", v))
}

/// A path (a string or an `os.PathLike`).
fn path(key: &str, v: &Bound<'_, PyAny>) -> PyResult<PathBuf> {
    v.extract::<PathBuf>().map_err(|_| bad(key, "a path", v))
}

/// One of the names `names` (as the command line spells the values), as `T`.
fn choice<T: Copy>(key: &str, v: &Bound<'_, PyAny>, names: &[(&str, T)]) -> PyResult<T> {
    let s: String = v.extract().map_err(|_| bad(key, "a string", v))?;
    names
        .iter()
        .find(|(n, _)| *n == s)
        .map(|(_, t)| *t)
        .ok_or_else(|| {
            let all: Vec<&str> = names.iter().map(|(n, _)| *n).collect();
            PyValueError::new_err(format!(
                "option {key}: '{s}' is not one of {}",
                all.join(", ")
            ))
        })
}

/// One of OpenSubdiv's option names.
fn named<T: Named>(key: &str, v: &Bound<'_, PyAny>) -> PyResult<T> {
    let s: String = v.extract().map_err(|_| bad(key, "a string", v))?;
    T::parse(&s).ok_or_else(|| {
        PyValueError::new_err(format!(
            "option {key}: '{s}' is not one of {}",
            T::choices()
        ))
    })
}

/// A pole: `"FACE:X,Y,Z"` or `(face, (x, y, z))`.
fn pole(v: &Bound<'_, PyAny>) -> PyResult<(usize, [f64; 3])> {
    if let Ok((f, p)) = v.extract::<(usize, [f64; 3])>() {
        return Ok((f, p));
    }
    let s: String = v
        .extract()
        .map_err(|_| bad("pole", "FACE:X,Y,Z or (face, (x, y, z))", v))?;
    let wrong = || {
        bad(
            "pole",
            "FACE:X,Y,Z (input face index, then the coordinates)",
            v,
        )
    };
    let (f, xyz) = s.split_once(':').ok_or_else(wrong)?;
    let f = f.trim().parse().map_err(|_| wrong())?;
    let c: Vec<f64> = xyz
        .split(',')
        .map(|t| t.trim().parse())
        .collect::<Result<_, _>>()
        .map_err(|_| wrong())?;
    match c[..] {
        [x, y, z] => Ok((f, [x, y, z])),
        _ => Err(wrong()),
    }
}

/// The options of a dict of keywords; `None` and `False` leave an option unset.
pub fn options(kw: Option<&Bound<'_, PyDict>>) -> PyResult<Options> {
    let mut o = Options::default();
    let Some(kw) = kw else { return Ok(o) };
    for (k, v) in kw.iter() {
        let key: String = k.extract()?;
        let unset = v.is_none() || (v.is_instance_of::<PyBool>() && !v.extract::<bool>()?);
        if unset {
            continue;
        }
        let v = &v;
        match key.as_str() {
            "lambda_" | "lambda" => o.lambda = Some(number(&key, v)?),
            "fcv_scale" => o.fcv_scale = Some(number(&key, v)?),
            "fcv_file" => o.fcv_file = Some(path(&key, v)?),
            "fallback" => {
                o.fallback = choice(
                    &key,
                    v,
                    &[
                        ("catmull-clark", Fallback::CatmullClark),
                        ("error", Fallback::Error),
                    ],
                )?
            }
            "q_file" => o.q_file = Some(path(&key, v)?),
            "split_ratio" => o.split_ratio = Some(number(&key, v)?),
            "alpha_rule" => {
                o.alpha_rule = Some(choice(
                    &key,
                    v,
                    &[
                        ("tps-limit-point", AlphaRule::TpsLimitPoint),
                        ("regular-spectrum", AlphaRule::RegularSpectrum),
                    ],
                )?)
            }
            "pole" => {
                let items: Vec<Bound<'_, PyAny>> = if v.extract::<String>().is_ok() {
                    vec![v.clone()]
                } else {
                    v.try_iter()?.collect::<PyResult<_>>()?
                };
                o.poles = items.iter().map(pole).collect::<PyResult<_>>()?;
            }
            "rules" => {
                o.rules = Some(choice(
                    &key,
                    v,
                    &[
                        ("printed", RulesChoice::Printed),
                        ("derived", RulesChoice::Derived),
                    ],
                )?)
            }
            "prepare" => {
                o.prepare = choice(&key, v, &[("auto", Prepare::Auto), ("none", Prepare::None)])?
            }
            "boundary" => o.boundary = Some(named(&key, v)?),
            "crease_method" => o.crease_method = Some(named(&key, v)?),
            "smooth_triangles" => {
                o.smooth_triangles = v.extract().map_err(|_| bad(&key, "a bool", v))?
            }
            "fvar" => o.fvar = Some(named(&key, v)?),
            "creases" => o.creases = Some(path(&key, v)?),
            _ => {
                return Err(PyValueError::new_err(format!(
                    "unknown option '{key}' (the options are {})",
                    KEYWORDS.join(", ")
                )));
            }
        }
    }
    Ok(o)
}
