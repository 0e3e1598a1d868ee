//! The viewer's API: the scheme list, the net's info, the `check` summary and the surface as
//! binary buffers (a fine tessellation of the exact patches with per-vertex exact normals and
//! curvatures, patch boundaries, control net edges), computed on request and cached.
//!
//! Surface buffer layout (little-endian, 4-byte words): magic `FSV1`, then u32 counts
//! `vertices, triangles, boundary segments, net edges, patches`, f32 bounding box (min xyz,
//! max xyz); then f32 positions (3 per vertex), normals (3), Gauss curvature K (1), mean
//! curvature H (1), provenance (1: 0 regular, k ring k, 1000 cap, -1 unknown); u32 triangle
//! corners (3 per triangle); f32 boundary segments (6 each) and net edges (6 each).

use super::{Reply, ViewArgs};
use crate::cli::api::{self as cli_api, OptionWord};
use crate::cli::subdivide::Computed;
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::mesh::PolyMesh;
use crate::schemes::descriptor::ParamKind;
use crate::schemes::{Spec, registry};
use crate::surface::{PatchComplex, Provenance};
use rayon::prelude::*;
use std::collections::BTreeSet;

/// Default samples per patch edge of the tessellation.
pub const DEFAULT_TESS: usize = 8;
/// Most rings the page may ask for.
const MAX_RINGS: usize = 12;
/// Most levels of a scheme without exact patches (its refined net is shown).
const MAX_LEVELS: usize = 6;
/// Complexes kept for repeated requests (the page asks for surface and check of each).
const CACHE: usize = 4;

/// What the viewer shows.
enum Source {
    /// A control net, whose surface the page's scheme builds.
    Net(PolyMesh),
    /// The patches of a BezierView file (every kind), its polyhedron, if any, and what it held.
    Bv(PatchComplex, Option<PolyMesh>, Box<crate::io::BvCounts>),
}

/// A built surface and what was computed from it.
struct Built {
    key: String,
    /// The scheme that built it (`None` for a `.bv` file).
    spec: Option<Spec>,
    shown: Shown,
    notes: Vec<String>,
    buffer: Option<Vec<u8>>,
}

/// What a scheme made of the net: exact patches, or (for the schemes without them: sqrt(3),
/// modified butterfly) the net refined `levels` times, its points at their limit when `limit`.
enum Shown {
    Complex(PatchComplex),
    Mesh {
        mesh: PolyMesh,
        levels: usize,
        limit: bool,
    },
}

/// The server's state: the input, the start options and the cache of built surfaces.
pub struct State {
    input: String,
    source: Source,
    scheme: Option<String>,
    rings: usize,
    tess: usize,
    /// The start options with a value (`split-ratio`, `0.3`): the start URL carries them.
    start_values: Vec<(String, String)>,
    /// The file options of the command line (`q-file`, path): only the command line names
    /// files, the page cannot; they apply to the schemes that take them.
    files: Vec<(String, String)>,
    cache: Vec<Built>,
}

fn param<'a>(q: &'a [(String, String)], key: &str) -> Option<&'a str> {
    q.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str())
}

/// The option words of every scheme with patch output (the keys the page may send).
fn all_option_words() -> Vec<OptionWord> {
    let mut kinds: Vec<ParamKind> = Vec::new();
    for e in registry().entries() {
        for k in e.descriptor.params() {
            if !kinds.contains(k) {
                kinds.push(*k);
            }
        }
    }
    cli_api::option_words(&kinds)
}

impl State {
    /// Loads the input of `fairsub view` (a net, or a `.bv` file) and builds the start surface
    /// (so that a scheme or option the net cannot take stops the command with its message).
    pub fn load(a: &ViewArgs) -> Result<State> {
        let source = if super::super::render::is_bv(&a.input) {
            if a.scheme.is_some() || !a.options.words().is_empty() {
                return Err(Error::InvalidArgument(
                    "a .bv file holds its patches already: drop --scheme and the scheme options"
                        .into(),
                ));
            }
            let (c, net, kinds) = super::super::render::bv_complex(&a.input)?;
            Source::Bv(c, net, Box::new(kinds))
        } else {
            Source::Net(super::super::load_net(&a.input)?.mesh)
        };
        let scheme = match (&source, &a.scheme) {
            (Source::Bv(..), _) => None,
            (Source::Net(_), Some(s)) => Some(registry().lookup(s)?.name().to_string()),
            (Source::Net(m), None) => Some(first_scheme_for(m)?),
        };
        let files_named: Vec<String> = all_option_words()
            .into_iter()
            .filter(|w| w.file)
            .map(|w| w.name)
            .collect();
        let (mut start_values, mut files) = (Vec::new(), Vec::new());
        for pair in a.options.words().chunks(2) {
            let name = pair[0].trim_start_matches("--").to_string();
            let list = if files_named.contains(&name) {
                &mut files
            } else {
                &mut start_values
            };
            list.push((name, pair[1].clone()));
        }
        let mut s = State {
            input: a.input.clone(),
            source,
            scheme,
            rings: a.rings,
            tess: a.tess.max(1),
            start_values,
            files,
            cache: Vec::new(),
        };
        // The start surface with every option of the command line, files included.
        let q = s.start_values.clone();
        let files = s.files.clone();
        s.built_with(&q, &files)?;
        Ok(s)
    }

    /// The query of the start URL (`?scheme=..&rings=..` and the start options with a value;
    /// poles joined by `;`).
    pub fn start_query(&self) -> String {
        let Some(scheme) = &self.scheme else {
            return String::new();
        };
        let mut q = format!("?scheme={scheme}&rings={}", self.rings);
        let mut poles = Vec::new();
        for (k, v) in &self.start_values {
            if k == "pole" {
                poles.push(v.as_str());
            } else {
                q.push_str(&format!("&{k}={}", percent_encode(v)));
            }
        }
        if !poles.is_empty() {
            q.push_str(&format!("&pole={}", percent_encode(&poles.join(";"))));
        }
        q
    }

    /// Answers `/api/NAME`.
    pub fn api(&mut self, name: &str, q: &[(String, String)]) -> Reply {
        let r = match name {
            "schemes" => Ok(self.schemes()),
            "info" => Ok(self.info()),
            "check" => self.check(q),
            "surface" => self.surface(q),
            _ => return Reply::error(404, &format!("no such API route: /api/{name}")),
        };
        r.unwrap_or_else(|e| Reply::error(422, &e.to_string()))
    }

    fn rings(&self, q: &[(String, String)]) -> Result<usize> {
        let rings = match param(q, "rings").filter(|r| !r.is_empty()) {
            Some(r) => r
                .parse::<usize>()
                .map_err(|_| Error::InvalidArgument(format!("rings '{r}' is not a count")))?,
            None => self.rings,
        };
        if rings > MAX_RINGS {
            return Err(Error::InvalidArgument(format!(
                "rings {rings}: the viewer takes at most {MAX_RINGS}"
            )));
        }
        Ok(rings)
    }

    /// The words of `fairsub subdivide` for a query: the net, the scheme, the rings, the scheme
    /// options the query gives (by their command-line names: `split-ratio=0.3`, `pole=F:X,Y,Z`
    /// with several poles joined by `;`, `smooth-triangles=1`) and the command line's file
    /// options the scheme takes. An option the scheme does not take is the command's error.
    fn words(&self, q: &[(String, String)], files: &[(String, String)]) -> Result<Vec<String>> {
        let scheme = param(q, "scheme")
            .filter(|s| !s.is_empty())
            .map(str::to_string)
            .or_else(|| self.scheme.clone())
            .ok_or_else(|| Error::InvalidArgument("no scheme given".into()))?;
        let id = registry().lookup(&scheme)?.id;
        let patches = registry().entry(id).capabilities().patches;
        let rings = self.rings(q)?;
        if !patches && rings > MAX_LEVELS {
            return Err(Error::InvalidArgument(format!(
                "{scheme} has no exact patches and shows its refined net: at most {MAX_LEVELS} \
                 levels, not {rings}"
            )));
        }
        let mut w = vec![
            self.input.clone(),
            "--scheme".into(),
            scheme.clone(),
            if patches { "--rings" } else { "--levels" }.into(),
            rings.to_string(),
        ];
        let known = all_option_words();
        for (k, v) in q {
            let Some(o) = known.iter().find(|o| o.name == *k) else {
                continue;
            };
            let flag = format!("--{k}");
            if o.file {
                return Err(Error::InvalidArgument(format!(
                    "{flag} names a file: give it on the command line of `fairsub view`"
                )));
            } else if o.flag {
                if v == "1" || v == "true" {
                    w.push(flag);
                }
            } else if o.repeated {
                for p in v.split(';').map(str::trim).filter(|p| !p.is_empty()) {
                    w.extend([flag.clone(), p.to_string()]);
                }
            } else if !v.is_empty() {
                w.extend([flag, v.clone()]);
            }
        }
        let takes = cli_api::option_words(registry().descriptor(id).params());
        for (k, v) in files {
            if takes.iter().any(|o| o.name == *k) {
                w.extend([format!("--{k}"), v.clone()]);
            }
        }
        if !patches {
            // last: a scheme without limit masks is asked again without it
            w.push("--limit".into());
        }
        Ok(w)
    }

    /// The built surface of a query (built and cached when new).
    fn built(&mut self, q: &[(String, String)]) -> Result<&mut Built> {
        let files = self.files.clone();
        self.built_with(q, &files)
    }

    /// [`State::built`] with the file options `files`.
    fn built_with(
        &mut self,
        q: &[(String, String)],
        files: &[(String, String)],
    ) -> Result<&mut Built> {
        let words = match &self.source {
            Source::Bv(..) => Vec::new(),
            Source::Net(_) => self.words(q, files)?,
        };
        let key = words.join("\u{0}");
        if let Some(k) = self.cache.iter().position(|b| b.key == key) {
            let b = self.cache.remove(k);
            self.cache.push(b);
        } else {
            let (spec, shown, notes) = match &self.source {
                Source::Bv(c, _, _) => (None, Shown::Complex(c.clone()), Vec::new()),
                // `fairsub subdivide WORDS`'s own path: the same parsing, loading, limits and
                // construction as the command line and the Python package.
                Source::Net(_) => match cli_api::subdivide(&words, None) {
                    // a scheme without limit masks shows its refined net as it is
                    Err(Error::Unsupported(_)) if words.last().is_some_and(|w| w == "--limit") => {
                        let out = cli_api::subdivide(&words[..words.len() - 1], None)?;
                        (
                            Some(out.spec),
                            shown(out.computed, &words, false),
                            Vec::new(),
                        )
                    }
                    out => {
                        let out = out?;
                        let limit = words.iter().any(|w| w == "--limit");
                        let notes = match &out.computed {
                            Computed::Complex(_, notes) => notes.clone(),
                            _ => Vec::new(),
                        };
                        (Some(out.spec), shown(out.computed, &words, limit), notes)
                    }
                },
            };
            if let Shown::Complex(c) = &shown
                && c.is_empty()
            {
                return Err(Error::InvalidArgument("the scheme made no patches".into()));
            }
            if self.cache.len() == CACHE {
                self.cache.remove(0);
            }
            self.cache.push(Built {
                key,
                spec,
                shown,
                notes,
                buffer: None,
            });
        }
        Ok(self.cache.last_mut().expect("just pushed"))
    }

    fn net(&self) -> Option<&PolyMesh> {
        match &self.source {
            Source::Net(m) => Some(m),
            Source::Bv(_, p, _) => p.as_ref(),
        }
    }

    fn schemes(&self) -> Reply {
        let list: Vec<_> = registry()
            .entries()
            .iter()
            .filter(|e| {
                let c = e.descriptor.capabilities();
                c.patches || c.refine
            })
            .map(|e| {
                serde_json::json!({
                    "name": e.name,
                    "patches": e.descriptor.capabilities().patches,
                    "aliases": e.aliases,
                    "family": e.about.family,
                    "options": cli_api::option_words(e.descriptor.params()),
                })
            })
            .collect();
        Reply::json(&serde_json::json!({
            "input": self.input,
            "bv": matches!(self.source, Source::Bv(..)),
            "start": {
                "scheme": self.scheme,
                "rings": self.rings,
                "tess": self.tess,
                "files": self.files,
            },
            "schemes": list,
        }))
    }

    fn info(&self) -> Reply {
        match (&self.source, self.net()) {
            (Source::Bv(c, _, kinds), None) => Reply::json(&serde_json::json!({
                "source": self.input, "patches": c.len(), "kinds": kinds
            })),
            (_, Some(m)) => Reply::json(&super::super::info::report(&self.input, m)),
            (Source::Net(_), None) => unreachable!("a net source has its net"),
        }
    }

    fn check(&mut self, q: &[(String, String)]) -> Result<Reply> {
        let input = self.input.clone();
        let b = self.built(q)?;
        match &b.shown {
            // `fairsub check --json`'s own report of the same complex
            Shown::Complex(c) => Ok(Reply::json_text(super::super::check::report_json(
                &input,
                c,
                b.spec.as_ref(),
                b.notes.clone(),
            ))),
            Shown::Mesh {
                mesh,
                levels,
                limit,
            } => Ok(Reply::json(&serde_json::json!({
                "mesh": {
                    "levels": levels,
                    "limit": limit,
                    "vertices": mesh.num_vertices(),
                    "faces": mesh.num_faces(),
                },
                "notes": [format!(
                    "{} has no exact patches: the surface shown is the net refined {levels} \
                     times{}, with discrete normals and curvature (angle deficit, cotangent \
                     Laplacian)",
                    b.spec.as_ref().map_or("the scheme", |s| s.name()),
                    if *limit { ", every point at its limit position" } else { "" }
                )],
            }))),
        }
    }

    fn surface(&mut self, q: &[(String, String)]) -> Result<Reply> {
        let tess = self.tess;
        let net = self.net().cloned();
        let b = self.built(q)?;
        if b.buffer.is_none() {
            b.buffer = Some(match &b.shown {
                Shown::Complex(c) => {
                    super::super::limits::check_tessellation(c, tess)?;
                    surface_buffer(c, net.as_ref(), tess)
                }
                Shown::Mesh { mesh, .. } => super::mesh::mesh_buffer(mesh, net.as_ref()),
            });
        }
        Ok(Reply::binary(b.buffer.clone().expect("just built")))
    }
}

/// The shown surface of what `fairsub subdivide WORDS` computed.
fn shown(c: Computed, words: &[String], limit: bool) -> Shown {
    match c {
        Computed::Complex(c, _) => Shown::Complex(c),
        Computed::Net(mesh) | Computed::FcvNet(mesh) | Computed::LimitMesh(mesh, _) => {
            let levels = words
                .iter()
                .position(|w| w == "--levels")
                .and_then(|i| words.get(i + 1))
                .and_then(|l| l.parse().ok())
                .unwrap_or(0);
            Shown::Mesh {
                mesh,
                levels,
                limit,
            }
        }
    }
}

/// `%XX`-escapes what is not unreserved in a query value.
fn percent_encode(s: &str) -> String {
    s.bytes()
        .map(|b| match b {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'-' | b'.' | b'_' | b'~' | b',' | b':' => {
                (b as char).to_string()
            }
            _ => format!("%{b:02X}"),
        })
        .collect()
}

/// The first scheme with patch output that takes the net (the page's default).
fn first_scheme_for(m: &PolyMesh) -> Result<String> {
    registry()
        .entries()
        .iter()
        .find(|e| e.descriptor.capabilities().patches && e.descriptor.check_input(m).is_ok())
        .map(|e| e.name.to_string())
        .ok_or_else(|| Error::InvalidArgument("no scheme with patch output takes this net".into()))
}

/// The provenance code of the buffer (see the module notes).
fn provenance_code(p: &Provenance) -> f32 {
    match p {
        Provenance::Regular { .. } => 0.0,
        Provenance::Ring { ring, .. } => *ring as f32,
        Provenance::Cap { .. } => 1000.0,
        Provenance::Unknown => -1.0,
    }
}

fn push_points(out: &mut Vec<u8>, pts: impl IntoIterator<Item = Point>) {
    for p in pts {
        for x in p {
            out.extend_from_slice(&(x as f32).to_le_bytes());
        }
    }
}

/// The surface buffer of a complex (layout in the module notes).
pub fn surface_buffer(c: &PatchComplex, net: Option<&PolyMesh>, tess: usize) -> Vec<u8> {
    let t = crate::surface::tessellate::tessellate(c, tess);
    let curv: Vec<[f32; 2]> = (0..t.num_vertices())
        .into_par_iter()
        .map(|v| {
            let [u, w] = t.uv[v];
            let k = c.patches[t.patch_of_vertex[v] as usize].curvatures(u, w);
            [k.gauss as f32, k.mean as f32]
        })
        .collect();
    let mut boundary = Vec::new();
    for p in &c.patches {
        for side in crate::bezier::Side::ALL {
            let at = |k: usize| {
                let [u, v] = side.domain_point(k as f64 / tess as f64);
                p.eval(u, v)
            };
            for k in 0..tess {
                boundary.push(at(k));
                boundary.push(at(k + 1));
            }
        }
    }
    let prov: Vec<f32> = (0..t.num_vertices())
        .map(|v| provenance_code(&c.provenance[t.patch_of_vertex[v] as usize]))
        .collect();
    encode(&Shape {
        positions: &t.positions,
        normals: &t.normals,
        curvature: &curv,
        provenance: &prov,
        triangles: &t.triangles,
        boundary: &boundary,
        edges: &net_edges(net),
        patches: c.len(),
    })
}

/// The edges of `net` as point pairs (each once), for the net overlay.
pub(super) fn net_edges(net: Option<&PolyMesh>) -> Vec<Point> {
    let mut edges = Vec::new();
    if let Some(m) = net {
        let mut seen = BTreeSet::new();
        for f in m.faces() {
            for (i, &a) in f.iter().enumerate() {
                let b = f[(i + 1) % f.len()];
                if seen.insert((a.min(b), a.max(b))) {
                    edges.push(m.position(a as usize));
                    edges.push(m.position(b as usize));
                }
            }
        }
    }
    edges
}

/// What a surface buffer holds (layout in the module notes), per vertex and per triangle.
pub(super) struct Shape<'a> {
    pub positions: &'a [Point],
    pub normals: &'a [Point],
    /// Gauss and mean curvature.
    pub curvature: &'a [[f32; 2]],
    pub provenance: &'a [f32],
    pub triangles: &'a [[u32; 3]],
    /// Patch (or face) boundaries, two points per segment.
    pub boundary: &'a [Point],
    /// Net edges, two points per segment.
    pub edges: &'a [Point],
    /// Patches (or faces) shown.
    pub patches: usize,
}

/// The surface buffer of `s` (layout in the module notes).
pub(super) fn encode(s: &Shape) -> Vec<u8> {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in s.positions {
        for i in 0..3 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    let nv = s.positions.len();
    let mut out = Vec::with_capacity(48 + nv * 36 + s.triangles.len() * 12);
    out.extend_from_slice(b"FSV1");
    for n in [
        nv,
        s.triangles.len(),
        s.boundary.len() / 2,
        s.edges.len() / 2,
        s.patches,
    ] {
        out.extend_from_slice(&(n as u32).to_le_bytes());
    }
    push_points(&mut out, [lo, hi]);
    push_points(&mut out, s.positions.iter().copied());
    push_points(&mut out, s.normals.iter().copied());
    for k in 0..2 {
        for c in s.curvature {
            out.extend_from_slice(&c[k].to_le_bytes());
        }
    }
    for p in s.provenance {
        out.extend_from_slice(&p.to_le_bytes());
    }
    for tri in s.triangles {
        for i in tri {
            out.extend_from_slice(&i.to_le_bytes());
        }
    }
    push_points(&mut out, s.boundary.iter().copied());
    push_points(&mut out, s.edges.iter().copied());
    out
}
