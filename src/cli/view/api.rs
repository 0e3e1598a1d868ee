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
/// Complexes kept for repeated requests (the page asks for surface and check of each).
const CACHE: usize = 4;

/// What the viewer shows.
enum Source {
    /// A control net, whose surface the page's scheme builds.
    Net(PolyMesh),
    /// The patches of a BezierView file and its polyhedron, if any.
    Bv(PatchComplex, Option<PolyMesh>),
}

/// A built surface and what was computed from it.
struct Built {
    key: String,
    /// The scheme that built it (`None` for a `.bv` file).
    spec: Option<Spec>,
    complex: PatchComplex,
    notes: Vec<String>,
    buffer: Option<Vec<u8>>,
}

/// The server's state: the input, the start options and the cache of built surfaces.
pub struct State {
    input: String,
    source: Source,
    scheme: Option<String>,
    rings: usize,
    tess: usize,
    lambda: Option<f64>,
    rules: Option<super::super::spec::RulesArg>,
    cache: Vec<Built>,
}

/// The command-line name of an option kind (as `subdivide` spells it).
fn option_name(k: ParamKind) -> &'static str {
    match k {
        ParamKind::Fallback => "fallback",
        ParamKind::Contraction => "lambda",
        ParamKind::SplitRatio => "split-ratio",
        ParamKind::AlphaRule => "alpha-rule",
        ParamKind::Poles => "pole",
        ParamKind::QFile => "q-file",
        ParamKind::Fcv => "fcv",
        ParamKind::Rules => "rules",
        ParamKind::SharpFeatures => "creases",
        ParamKind::SmoothTriangles => "smooth-triangles",
    }
}

fn param<'a>(q: &'a [(String, String)], key: &str) -> Option<&'a str> {
    q.iter().find(|(k, _)| k == key).map(|(_, v)| v.as_str())
}

impl State {
    /// Loads the input of `fairsub view` (a net, or a `.bv` file) and checks the start scheme.
    pub fn load(a: &ViewArgs) -> Result<State> {
        let source = if super::super::render::is_bv(&a.input) {
            if a.scheme.is_some() {
                return Err(Error::InvalidArgument(
                    "a .bv file holds its patches already: drop --scheme".into(),
                ));
            }
            let scene = super::super::render::bv_scene(&a.input)?;
            let c = scene.complex().cloned().ok_or_else(|| {
                Error::InvalidArgument(format!("{}: no tensor-product patches to show", a.input))
            })?;
            Source::Bv(c, scene.net)
        } else {
            Source::Net(super::super::load_net(&a.input)?.mesh)
        };
        let scheme = match (&source, &a.scheme) {
            (Source::Bv(..), _) => None,
            (Source::Net(_), Some(s)) => Some(registry().lookup(s)?.name().to_string()),
            (Source::Net(m), None) => Some(first_scheme_for(m)?),
        };
        let s = State {
            input: a.input.clone(),
            source,
            scheme,
            rings: a.rings,
            tess: a.tess.max(1),
            lambda: a.lambda,
            rules: a.rules,
            cache: Vec::new(),
        };
        if let Some(name) = &s.scheme {
            s.spec(&[("scheme".into(), name.clone())])?;
        }
        Ok(s)
    }

    /// The query of the start URL (`?scheme=..&rings=..`).
    pub fn start_query(&self) -> String {
        match &self.scheme {
            Some(s) => format!("?scheme={s}&rings={}", self.rings),
            None => String::new(),
        }
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

    /// The scheme of a query with its options (the start options where the query has none).
    fn spec(&self, q: &[(String, String)]) -> Result<Spec> {
        let name = param(q, "scheme")
            .map(str::to_string)
            .or_else(|| self.scheme.clone())
            .ok_or_else(|| Error::InvalidArgument("no scheme given".into()))?;
        let lambda = match param(q, "lambda").filter(|s| !s.is_empty()) {
            Some(l) => Some(
                l.parse::<f64>()
                    .map_err(|_| Error::InvalidArgument(format!("lambda '{l}' is not a number")))?,
            ),
            None => self.lambda,
        };
        let rules = match param(q, "rules").filter(|s| !s.is_empty()) {
            Some(r) => Some(
                <super::super::spec::RulesArg as clap::ValueEnum>::from_str(r, true)
                    .map_err(|e| Error::InvalidArgument(format!("rules '{r}': {e}")))?,
            ),
            None => self.rules,
        };
        let o = super::super::spec::SchemeOptions {
            lambda,
            rules: rules.map(Into::into),
            ..Default::default()
        };
        super::super::spec::resolve(&name, &o)
    }

    fn rings(&self, q: &[(String, String)]) -> Result<usize> {
        let rings = match param(q, "rings") {
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

    /// The built surface of a query (built and cached when new).
    fn built(&mut self, q: &[(String, String)]) -> Result<&mut Built> {
        let key = match &self.source {
            Source::Bv(..) => "bv".to_string(),
            Source::Net(_) => {
                let spec = self.spec(q)?;
                format!("{spec:?}/{}", self.rings(q)?)
            }
        };
        if let Some(k) = self.cache.iter().position(|b| b.key == key) {
            let b = self.cache.remove(k);
            self.cache.push(b);
        } else {
            let (spec, complex, notes) = match &self.source {
                Source::Bv(c, _) => (None, c.clone(), Vec::new()),
                Source::Net(net) => {
                    let mut spec = self.spec(q)?;
                    registry().descriptor(spec.id).check_input(net)?;
                    super::super::subdivide::features::patch_features(&mut spec, net, &self.input)?;
                    let rings = self.rings(q)?;
                    let (c, n) =
                        super::super::subdivide::build_complex_noted(&spec, net, rings, true)?;
                    (Some(spec), c, n)
                }
            };
            if complex.is_empty() {
                return Err(Error::InvalidArgument("the scheme made no patches".into()));
            }
            if self.cache.len() == CACHE {
                self.cache.remove(0);
            }
            self.cache.push(Built {
                key,
                spec,
                complex,
                notes,
                buffer: None,
            });
        }
        Ok(self.cache.last_mut().expect("just pushed"))
    }

    fn net(&self) -> Option<&PolyMesh> {
        match &self.source {
            Source::Net(m) => Some(m),
            Source::Bv(_, p) => p.as_ref(),
        }
    }

    fn schemes(&self) -> Reply {
        let list: Vec<_> = registry()
            .entries()
            .iter()
            .filter(|e| e.descriptor.capabilities().patches)
            .map(|e| {
                let options: Vec<_> = e
                    .descriptor
                    .params()
                    .iter()
                    .map(|k| option_name(*k))
                    .collect();
                serde_json::json!({
                    "name": e.name,
                    "aliases": e.aliases,
                    "family": e.about.family,
                    "options": options,
                })
            })
            .collect();
        Reply::json(&serde_json::json!({
            "input": self.input,
            "bv": matches!(self.source, Source::Bv(..)),
            "start": { "scheme": self.scheme, "rings": self.rings, "tess": self.tess },
            "schemes": list,
        }))
    }

    fn info(&self) -> Reply {
        match (&self.source, self.net()) {
            (Source::Bv(c, _), None) => Reply::json(&serde_json::json!({
                "source": self.input, "patches": c.len()
            })),
            (_, Some(m)) => Reply::json(&super::super::info::report(&self.input, m)),
            (Source::Net(_), None) => unreachable!("a net source has its net"),
        }
    }

    fn check(&mut self, q: &[(String, String)]) -> Result<Reply> {
        let input = self.input.clone();
        let b = self.built(q)?;
        // `fairsub check --json`'s own report of the same complex
        let text =
            super::super::check::report_json(&input, &b.complex, b.spec.as_ref(), b.notes.clone());
        Ok(Reply::json_text(text))
    }

    fn surface(&mut self, q: &[(String, String)]) -> Result<Reply> {
        let tess = self.tess;
        let net = self.net().cloned();
        let b = self.built(q)?;
        if b.buffer.is_none() {
            super::super::limits::check_tessellation(&b.complex, tess)?;
            b.buffer = Some(surface_buffer(&b.complex, net.as_ref(), tess));
        }
        Ok(Reply::binary(b.buffer.clone().expect("just built")))
    }
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
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in &t.positions {
        for i in 0..3 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    let nv = t.num_vertices();
    let mut out = Vec::with_capacity(48 + nv * 36 + t.num_triangles() * 12);
    out.extend_from_slice(b"FSV1");
    for n in [
        nv,
        t.num_triangles(),
        boundary.len() / 2,
        edges.len() / 2,
        c.len(),
    ] {
        out.extend_from_slice(&(n as u32).to_le_bytes());
    }
    push_points(&mut out, [lo, hi]);
    push_points(&mut out, t.positions.iter().copied());
    push_points(&mut out, t.normals.iter().copied());
    let scalars = |out: &mut Vec<u8>, f: &dyn Fn(usize) -> f32| {
        for v in 0..nv {
            out.extend_from_slice(&f(v).to_le_bytes());
        }
    };
    scalars(&mut out, &|v| curv[v][0]);
    scalars(&mut out, &|v| curv[v][1]);
    scalars(&mut out, &|v| {
        provenance_code(&c.provenance[t.patch_of_vertex[v] as usize])
    });
    for tri in &t.triangles {
        for i in tri {
            out.extend_from_slice(&i.to_le_bytes());
        }
    }
    push_points(&mut out, boundary);
    push_points(&mut out, edges);
    out
}
