//! `fairsub eval`: the exact surface of a net at parameters `(face, u, v)` of its input faces
//! (the library's [`crate::surface::eval`]): point, derivatives, normal, curvatures and the
//! patch each point lies in.

use super::spec::{self, SchemeOptions};
use crate::error::{Error, Result};
use crate::surface::ComplexOptions;
use crate::surface::eval::{Evaluation, Surface, evaluate_limit};
use std::fmt::Write;
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
    /// variants, guided bi-5/bi-6, Doo-Sabin, DS^CC, PGS, PGS after DS^CC, the mixed bi-2
    /// net at its facets, and TPS).
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
    let bad = |why: &str| {
        Error::InvalidArgument(format!("{}: '{text}' is not a point F:U:V ({why})", what()))
    };
    // the three fields without collecting them (10^6 lines of `--at-file`)
    let mut parts: [&str; 3] = [""; 3];
    let mut count = 0;
    let fields: &mut dyn Iterator<Item = &str> = if text.contains(':') {
        &mut text.split(':').map(str::trim)
    } else {
        &mut text.split_whitespace()
    };
    for field in fields {
        if count < 3 {
            parts[count] = field;
        }
        count += 1;
    }
    if count != 3 {
        return Err(bad("three fields expected"));
    }
    let [f, u, v] = parts;
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

/// Appends `x y z` with 17 significant digits.
fn vec3(out: &mut String, p: [f64; 3]) {
    let _ = write!(out, "{:.17e} {:.17e} {:.17e}", p[0], p[1], p[2]);
}

/// Appends the text line of one evaluation (with its newline).
fn line(out: &mut String, e: &Evaluation) {
    let _ = write!(
        out,
        "{}:{}:{} patch {} at ({}, {}) point ",
        e.face, e.u, e.v, e.patch, e.patch_uv[0], e.patch_uv[1]
    );
    vec3(out, e.point);
    out.push_str(" normal ");
    vec3(out, e.normal);
    let _ = writeln!(out, " gauss {:.10e} mean {:.10e}", e.gauss, e.mean);
}

/// Prints the text lines of `evals`, formatted in parallel blocks and written a block at a
/// time.
fn print_lines(evals: &[Evaluation]) {
    use rayon::prelude::*;
    const BLOCK: usize = 4096;
    // a bounded number of blocks formatted ahead of the writer
    let mut pending = Vec::new();
    for group in evals.chunks(BLOCK * 64) {
        group
            .par_chunks(BLOCK)
            .map(|chunk| {
                let mut text = String::with_capacity(chunk.len() * 240);
                for e in chunk {
                    line(&mut text, e);
                }
                text
            })
            .collect_into_vec(&mut pending);
        for text in &pending {
            super::say_text(text);
        }
    }
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
            let mut out = vec![Evaluation::default(); pts.len()];
            s.evaluate_into(&pts, &mut out)
                .map_err(|(i, e)| at_point(e, i, pts.len()))?;
            out
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
        print_lines(&evals);
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
