//! `fairsub project`: the closest points of a net's exact surface to points in space, with the
//! input-face parameters `(face, u, v)` that `fairsub eval` takes
//! ([`crate::surface::closest`]).

use super::spec::{self, SchemeOptions};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::surface::ComplexOptions;
use crate::surface::closest::Closest;
use crate::surface::eval::Surface;
use std::path::{Path, PathBuf};

/// Most points one command projects.
pub const MAX_POINTS: usize = 10_000_000;

/// Arguments of `fairsub project`.
#[derive(Debug, clap::Args)]
pub struct ProjectArgs {
    /// The control net (file or gallery:NAME).
    pub net: String,
    /// The scheme (one that evaluates: see `fairsub eval --help`).
    #[arg(long, short)]
    pub scheme: String,
    /// Rings around extraordinary elements (the complex `subdivide --rings K` writes).
    #[arg(long, short, default_value_t = 6)]
    pub rings: usize,
    /// Leave the hole inside the last ring open.
    #[arg(long)]
    pub no_fill: bool,
    /// The points: text, one `X Y Z` per line (commas allowed, `#` starts a comment), or
    /// binary little-endian f64 triples when the name ends in `.bin` or `.f64`.
    #[arg(long)]
    pub points: PathBuf,
    /// Print the results as a JSON array.
    #[arg(long)]
    pub json: bool,
    /// Write binary records: per point 11 little-endian f64 (face, u, v, point x y z,
    /// distance, normal x y z, and 1 where the point is held on the boundary of its face's
    /// domain, else 0): `numpy.fromfile(FILE, "<f8").reshape(-1, 11)`.
    #[arg(long, conflicts_with = "json")]
    pub binary: bool,
}

/// Whether `path` names a binary points file.
fn is_binary(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("bin") || e.eq_ignore_ascii_case("f64"))
}

/// The points of `path` (see [`ProjectArgs::points`]).
pub fn read_points(path: &Path) -> Result<Vec<Point>> {
    super::limits::check_points_file(path)?;
    let too_many = || {
        Error::InvalidArgument(format!(
            "{}: more than {MAX_POINTS} points: split them over several runs",
            path.display()
        ))
    };
    if is_binary(path) {
        let bytes = std::fs::read(path).map_err(|e| crate::io::io_error(path, e))?;
        if bytes.len() % 24 != 0 {
            return Err(Error::InvalidArgument(format!(
                "{}: {} bytes is not a whole number of points (24 bytes each: three \
                 little-endian f64)",
                path.display(),
                bytes.len()
            )));
        }
        if bytes.len() / 24 > MAX_POINTS {
            return Err(too_many());
        }
        let f = |c: &[u8]| f64::from_le_bytes(c.try_into().expect("8 bytes"));
        return Ok(bytes
            .chunks_exact(24)
            .map(|c| [f(&c[..8]), f(&c[8..16]), f(&c[16..])])
            .collect());
    }
    let text = crate::io::read_text(path)?;
    let mut out = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("");
        let words: Vec<&str> = line
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|w| !w.is_empty())
            .collect();
        if words.is_empty() {
            continue;
        }
        let bad =
            |why: &str| Error::InvalidArgument(format!("{}:{}: {why}", path.display(), k + 1));
        if words.len() != 3 {
            return Err(bad(&format!(
                "expected X Y Z, found {} numbers",
                words.len()
            )));
        }
        let mut p = [0.0; 3];
        for (x, w) in p.iter_mut().zip(&words) {
            *x = w
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| bad(&format!("'{w}' is not a finite number")))?;
        }
        out.push(p);
        if out.len() > MAX_POINTS {
            return Err(too_many());
        }
    }
    if out.is_empty() {
        return Err(Error::InvalidArgument(format!(
            "{}: no points (one X Y Z per line)",
            path.display()
        )));
    }
    Ok(out)
}

/// The exact surface of `net` under `scheme` with `rings` (and the fill), ready to search.
pub fn build_surface(net: &str, scheme: &str, rings: usize, fill: bool) -> Result<Surface> {
    let spec = spec::resolve(scheme, &SchemeOptions::default())?;
    crate::surface::eval::supported(&spec)?;
    let mesh = super::load_net(net)?.mesh;
    let mut s = spec.clone();
    super::subdivide::features::patch_features(&mut s, &mesh, net)?;
    super::limits::check_complex(&s, &mesh, rings, fill)?;
    Surface::build(&s, &mesh, ComplexOptions { rings, fill })
}

/// One text line: `F:U:V point X Y Z distance D normal X Y Z` (and ` boundary`).
fn line(c: &Closest) -> String {
    let [x, y, z] = c.point;
    let [a, b, n] = c.normal;
    format!(
        "{}:{:?}:{:?} point {x:?} {y:?} {z:?} distance {:?} normal {a:?} {b:?} {n:?}{}",
        c.face,
        c.u,
        c.v,
        c.distance,
        if c.on_boundary { " boundary" } else { "" }
    )
}

/// Runs `fairsub project`.
pub fn run(a: ProjectArgs) -> Result<()> {
    if a.binary && std::io::IsTerminal::is_terminal(&std::io::stdout()) {
        return Err(Error::InvalidArgument(
            "--binary writes binary records: redirect the output to a file or a pipe".into(),
        ));
    }
    let points = read_points(&a.points)?;
    let s = build_surface(&a.net, &a.scheme, a.rings, !a.no_fill)?;
    let found = crate::surface::closest::closest_points(&s, &points)?;
    if a.json {
        super::say_json(&found);
    } else if a.binary {
        let mut out = Vec::with_capacity(96 * found.len());
        for c in &found {
            let rec = [
                f64::from(c.face),
                c.u,
                c.v,
                c.point[0],
                c.point[1],
                c.point[2],
                c.distance,
                c.normal[0],
                c.normal[1],
                c.normal[2],
                if c.on_boundary { 1.0 } else { 0.0 },
            ];
            for x in rec {
                out.extend_from_slice(&x.to_le_bytes());
            }
        }
        super::say_bytes(&out)?;
    } else {
        let mut text = String::with_capacity(120 * found.len());
        for c in &found {
            text.push_str(&line(c));
            text.push('\n');
        }
        super::say_bytes(text.as_bytes())?;
    }
    Ok(())
}
