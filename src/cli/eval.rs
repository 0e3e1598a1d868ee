//! `fairsub eval`: the exact surface of a net at parameters `(face, u, v)` of its input faces
//! (the library's [`crate::surface::eval`]): point, derivatives, normal, curvatures and the
//! patch each point lies in.

use super::spec::{self, SchemeOptions};
use crate::error::{Error, Result};
use crate::surface::ComplexOptions;
use crate::surface::eval::{Evaluation, Surface, evaluate_limit};
use std::path::PathBuf;

/// Most points one command evaluates (`--at` and `--at-file` together).
pub const MAX_POINTS: usize = 10_000_000;

/// Arguments of `fairsub eval`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The control net (file or gallery:NAME).
    pub net: String,
    /// Points `F:U:V` (input face, parameters), comma-separated; repeatable.
    #[arg(long)]
    pub at: Vec<String>,
    /// A file of points, one `F:U:V` (or `F U V`) per line; `#` starts a comment.
    #[arg(long)]
    pub at_file: Option<PathBuf>,
    /// The scheme (see `fairsub schemes`; eval takes Catmull-Clark, Loop, EG, the QAS+
    /// variants, guided bi-5/bi-6, Doo-Sabin, DS^CC, PGS and TPS).
    #[arg(long, short)]
    pub scheme: String,
    /// Evaluate the complex `subdivide --rings K` writes (same options); without it, the
    /// scheme's limit surface (as many rings as each point needs).
    #[arg(long, short)]
    pub rings: Option<usize>,
    /// With --rings: leave the hole inside the last ring open (points there are errors).
    #[arg(long, requires = "rings")]
    pub no_fill: bool,
    /// Print the evaluations as a JSON array.
    #[arg(long)]
    pub json: bool,
}

/// One point `F:U:V` (or `F U V`); `what` names it in errors.
fn parse_point(text: &str, what: &dyn Fn() -> String) -> Result<(u32, f64, f64)> {
    let parts: Vec<&str> = if text.contains(':') {
        text.split(':').map(str::trim).collect()
    } else {
        text.split_whitespace().collect()
    };
    let bad = |why: &str| {
        Error::InvalidArgument(format!("{}: '{text}' is not a point F:U:V ({why})", what()))
    };
    let [f, u, v] = parts[..] else {
        return Err(bad("three fields expected"));
    };
    let f = f
        .parse::<u32>()
        .map_err(|_| bad("the face is not a non-negative integer"))?;
    let num = |s: &str| s.parse::<f64>().ok().filter(|x| x.is_finite());
    let (Some(u), Some(v)) = (num(u), num(v)) else {
        return Err(bad("u and v must be finite numbers"));
    };
    Ok((f, u, v))
}

/// The points of `--at` and `--at-file`, in order.
fn points(a: &Args) -> Result<Vec<(u32, f64, f64)>> {
    let mut pts = Vec::new();
    let too_many = || {
        Error::InvalidArgument(format!(
            "more than {MAX_POINTS} points: split them over several runs"
        ))
    };
    for (i, item) in a.at.iter().flat_map(|s| s.split(',')).enumerate() {
        pts.push(parse_point(item, &|| format!("--at point {}", i + 1))?);
        if pts.len() > MAX_POINTS {
            return Err(too_many());
        }
    }
    if let Some(path) = &a.at_file {
        let text = crate::io::read_text(path)?;
        for (k, line) in text.lines().enumerate() {
            let line = line.split('#').next().unwrap_or("").trim();
            if line.is_empty() {
                continue;
            }
            pts.push(parse_point(line, &|| {
                format!("{}:{}", path.display(), k + 1)
            })?);
            if pts.len() > MAX_POINTS {
                return Err(too_many());
            }
        }
    }
    if pts.is_empty() {
        return Err(Error::InvalidArgument(
            "no points: give --at F:U:V[,F:U:V...] or --at-file FILE".into(),
        ));
    }
    Ok(pts)
}

/// `x y z` with 17 significant digits.
fn vec3(p: [f64; 3]) -> String {
    format!("{:.17e} {:.17e} {:.17e}", p[0], p[1], p[2])
}

/// The text line of one evaluation.
fn line(e: &Evaluation) -> String {
    format!(
        "{}:{}:{} patch {} at ({}, {}) point {} normal {} gauss {:.10e} mean {:.10e}",
        e.face,
        e.u,
        e.v,
        e.patch,
        e.patch_uv[0],
        e.patch_uv[1],
        vec3(e.point),
        vec3(e.normal),
        e.gauss,
        e.mean
    )
}

/// Runs `fairsub eval`.
pub fn run(a: Args) -> Result<()> {
    let spec = spec::resolve(&a.scheme, &SchemeOptions::default())?;
    let pts = points(&a)?;
    let mesh = super::load_net(&a.net)?.mesh;
    let build = |rings: usize, fill: bool| -> Result<Surface> {
        super::limits::check_complex(&spec, &mesh, rings, fill)?;
        Surface::build(&spec, &mesh, ComplexOptions { rings, fill })
    };
    let evals = match a.rings {
        Some(k) => {
            let s = build(k, !a.no_fill)?;
            s.evaluate_many(&pts)
                .into_iter()
                .enumerate()
                .map(|(i, r)| r.map_err(|e| at_point(e, i, pts.len())))
                .collect::<Result<Vec<_>>>()?
        }
        None => {
            let (evals, rings) = evaluate_limit(&pts, &mut |k| build(k, true))?;
            eprintln!("limit surface: {rings} rings");
            evals
        }
    };
    if a.json {
        let text = serde_json::to_string_pretty(&evals)
            .map_err(|e| Error::InvalidArgument(format!("JSON output: {e}")))?;
        say!("{text}");
    } else {
        for e in &evals {
            say!("{}", line(e));
        }
    }
    Ok(())
}

/// An evaluation error of point `i` (of `n`), naming the point when there are several.
fn at_point(e: Error, i: usize, n: usize) -> Error {
    if n == 1 {
        return e;
    }
    match e {
        Error::InvalidArgument(m) => Error::InvalidArgument(format!("point {}: {m}", i + 1)),
        other => other,
    }
}
