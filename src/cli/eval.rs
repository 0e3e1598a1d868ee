//! `fairsub eval`: the exact surface of a net at parameters `(face, u, v)` of its input faces
//! (the library's [`crate::surface::eval`]): point, derivatives, normal, curvatures and the
//! patch each point lies in.

use super::spec::{self, SchemeOptions};
use crate::error::{Error, Result};
use crate::surface::ComplexOptions;
use crate::surface::eval::{Surface, first_targets, limit_surface_from, quad_corner_targets};
use std::path::PathBuf;
use text::parse_point;

mod text;

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
    /// Print the evaluations as a JSON array (default: one line per point, `F:U:V patch P at
    /// (PU, PV) point X Y Z normal X Y Z gauss G mean M`). Every number is the shortest text
    /// that reads back to the same f64.
    #[arg(long)]
    pub json: bool,
    /// Write binary records instead of text: per point 29 little-endian f64 (face, u, v,
    /// patch, patch u, patch v, point x y z, du, dv, duu, duv, dvv (3 each), normal x y z,
    /// gauss, mean), exact and several times cheaper than printing the numbers
    /// (`numpy.fromfile(FILE, "<f8").reshape(-1, 29)`).
    #[arg(long, conflicts_with = "json")]
    pub binary: bool,
    /// Prepare a net the scheme's rules do not take (auto, the default) or refuse it (none),
    /// as `subdivide --prepare`: points stay on the input net's faces either way.
    #[arg(long, value_enum, default_value_t = spec::PrepareArg::Auto)]
    pub prepare: spec::PrepareArg,
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
        super::limits::check_points_file(path)?;
        let text = crate::io::read_text(path)?;
        let read = text::parse_file(&text, path)?;
        // (10^6 points: 24 MB not copied when there are no --at points)
        if pts.is_empty() {
            pts = read;
        } else {
            pts.extend(read);
        }
        if pts.len() > MAX_POINTS {
            return Err(too_many());
        }
    }
    if pts.is_empty() {
        return Err(Error::InvalidArgument(
            "no points: give --at F:U:V[,F:U:V...] or --at-file FILE".into(),
        ));
    }
    Ok(pts)
}

/// Runs `fairsub eval`.
pub fn run(a: Args) -> Result<()> {
    if a.binary && std::io::IsTerminal::is_terminal(&std::io::stdout()) {
        return Err(Error::InvalidArgument(
            "--binary writes binary records: redirect the output to a file or a pipe".into(),
        ));
    }
    let spec = spec::resolve(
        &a.scheme,
        &SchemeOptions {
            prepare: a.prepare.into(),
            ..SchemeOptions::default()
        },
    )?;
    let build = |mesh: &crate::mesh::PolyMesh, rings: usize, fill: bool| -> Result<Surface> {
        super::limits::check_complex(&spec, mesh, rings, fill)?;
        Surface::build(&spec, mesh, ComplexOptions { rings, fill })
    };
    // The points are read while the net is loaded and, with --rings, its surface is built
    // (both in parallel: the file of 10^6 points costs about as much as the construction);
    // a bad point is reported before an error of the net. Both run on the pool's threads,
    // which get this command's memory budget (it is kept per thread: without it there,
    // --max-memory was not seen by the checks).
    let max = super::limits::max_memory();
    let (pts, surface) = rayon::join(
        || super::limits::with_budget(max, || points(&a)),
        || {
            super::limits::with_budget(max, || -> Result<_> {
                let mesh = super::load_net(&a.net)?.mesh;
                let s = match a.rings {
                    Some(k) => Some(build(&mesh, k, !a.no_fill)?),
                    None => None,
                };
                Ok((mesh, s))
            })
        },
    );
    let pts = pts?;
    let (mesh, surface) = surface?;
    // every point is located before the first line is written (an error writes nothing);
    // the evaluations are then computed and formatted block by block, never all held
    let s = match surface {
        Some(s) => {
            if let Some((i, e)) = s.first_unlocated(&pts) {
                return Err(at_point(e, i, pts.len()));
            }
            s
        }
        None => {
            // Catmull-Clark refines each extraordinary vertex as far as its points need,
            // estimated from their distances to the quads' corners (and checked)
            let first = if spec.id == crate::schemes::options::ids::CATMULL_CLARK {
                quad_corner_targets(&mesh, &pts)
            } else {
                first_targets()
            };
            let (s, rings) = limit_surface_from(&pts, first, &mut |k| build(&mesh, k, true))?;
            eprintln!("limit surface: {rings} rings");
            s
        }
    };
    let eval = |i: usize| {
        let (f, u, v) = pts[i];
        s.evaluate(f, u, v).map_err(|e| at_point(e, i, pts.len()))
    };
    let face = |i: usize| pts[i].0;
    let mut write = super::say_bytes;
    let written = if a.json {
        text::write_json(pts.len(), &face, &eval, &mut write)
    } else if a.binary {
        text::write_binary(pts.len(), &face, &eval, &mut write)
    } else {
        text::write_lines(pts.len(), &face, &eval, &mut write)
    };
    // freeing the surface and the points (10^6 points: 12 ms) is left to a thread of its own:
    // a process ends without waiting for it, a caller in the same process gets the memory back
    std::thread::spawn(move || drop((s, pts, mesh)));
    written
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
