//! `fairsub info`: what a control net consists of and what stands in the way of each scheme.
//!
//! The net is read with the general reader (every net OpenSubdiv accepts, as Catmull-Clark and
//! Loop refine them and `subdivide --levels` writes them): a non-manifold net's non-manifold
//! edges, vertices and faces that repeat a vertex are reported as such, and the per-vertex
//! statistics (valences, extraordinary vertices, boundary loops) cover its manifold vertices.

use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::schemes::descriptor::{RulesOrigin, Spec, ValenceRules};
use crate::schemes::prepare::Applied;
use crate::schemes::registry;
use serde::Serialize;
use std::collections::BTreeMap;

/// An extraordinary vertex in the report.
#[derive(Debug, Serialize)]
struct ExtraordinaryVertex {
    vertex: usize,
    valence: usize,
    boundary: bool,
}

/// An extraordinary facet in the report.
#[derive(Debug, Serialize)]
struct ExtraordinaryFace {
    face: usize,
    sides: usize,
}

/// A non-manifold edge in the report: its ends and the faces using it.
#[derive(Debug, Serialize)]
struct NonManifoldEdge {
    edge: [u32; 2],
    faces: Vec<u32>,
}

/// The non-manifold part of a net (all empty for a manifold net).
#[derive(Debug, Default, Serialize)]
struct NonManifoldReport {
    /// Edges used by more than two faces, twice in one direction, or twice by one face.
    edges: Vec<NonManifoldEdge>,
    /// Vertices on such edges, joining separate fans of faces, or used by no face.
    vertices: Vec<u32>,
    /// Faces that name one vertex more than once.
    repeated_vertex_faces: Vec<usize>,
}

impl NonManifoldReport {
    fn of(m: &PolyMesh) -> NonManifoldReport {
        let mut r = NonManifoldReport {
            repeated_vertex_faces: (0..m.num_faces())
                .filter(|&f| {
                    let mut c = m.face(f).to_vec();
                    c.sort_unstable();
                    c.windows(2).any(|w| w[0] == w[1])
                })
                .collect(),
            ..NonManifoldReport::default()
        };
        if let Some(nm) = &m.topology().nm {
            r.vertices = nm.vertices.clone();
            r.edges = nm
                .edges
                .iter()
                .map(|&e| NonManifoldEdge {
                    edge: m.edge(e as usize),
                    faces: nm.edge_sides(e).iter().map(|&h| m.he_face(h)).collect(),
                })
                .collect();
        }
        r
    }

    fn is_empty(&self) -> bool {
        self.edges.is_empty() && self.vertices.is_empty() && self.repeated_vertex_faces.is_empty()
    }
}

/// The `info` report.
#[derive(Debug, Serialize)]
pub struct InfoReport {
    source: String,
    vertices: usize,
    edges: usize,
    faces: usize,
    euler_characteristic: i64,
    all_quads: bool,
    all_triangles: bool,
    face_sizes: BTreeMap<usize, usize>,
    interior_valences: BTreeMap<usize, usize>,
    boundary_valences: BTreeMap<usize, usize>,
    boundary_loops: Vec<usize>,
    extraordinary_vertices: Vec<ExtraordinaryVertex>,
    extraordinary_faces: Vec<ExtraordinaryFace>,
    bounding_box: [[f64; 3]; 2],
    /// Per scheme whose rules differ by valence (EG, QAS+): the rules it uses at each
    /// extraordinary valence of the net (vertices, and face centres after a Catmull-Clark step).
    #[serde(skip_serializing_if = "BTreeMap::is_empty")]
    rules_by_valence: BTreeMap<&'static str, Vec<ValenceRules>>,
    problems: Vec<String>,
    dropped_vertices: Vec<usize>,
    /// The non-manifold edges, vertices and repeated-vertex faces (omitted when there are none).
    #[serde(skip_serializing_if = "NonManifoldReport::is_empty")]
    non_manifold: NonManifoldReport,
    /// With `--scheme`: what would be prepared for it.
    #[serde(skip_serializing_if = "Option::is_none")]
    preparation: Option<PreparationReport>,
}

/// What `--prepare auto` would do to the net for one scheme.
#[derive(Debug, Serialize)]
pub struct PreparationReport {
    scheme: String,
    /// For patches (`--rings`), evaluation and patch tables.
    patches: Vec<Applied>,
    /// For net refinement (`--levels`); empty for schemes without it.
    levels: Vec<Applied>,
    /// The prepared net for patches: vertices and faces (the input's when nothing applies).
    prepared_vertices: usize,
    prepared_faces: usize,
}

/// What would be prepared for `scheme` on `m` (see [`crate::schemes::prepare`]).
///
/// # Errors
/// An unknown scheme; those of a preparation step.
pub fn preparation(scheme: &str, m: &PolyMesh) -> Result<PreparationReport> {
    use crate::schemes::prepare::{Purpose, prepare};
    let spec = registry().lookup(scheme)?;
    let entry = registry().entry(spec.id);
    let caps = entry.capabilities();
    let patches = if caps.patches {
        prepare(entry.descriptor, &spec, m, Purpose::Patches)?
    } else {
        crate::schemes::prepare::Prepared::unchanged(m)
    };
    let levels = if caps.refine {
        prepare(entry.descriptor, &spec, m, Purpose::Refine)?.applied
    } else {
        Vec::new()
    };
    Ok(PreparationReport {
        scheme: spec.name().to_string(),
        prepared_vertices: patches.mesh.num_vertices(),
        prepared_faces: patches.mesh.num_faces(),
        patches: patches.applied,
        levels,
    })
}

/// The valences a quad scheme's caps meet: interior vertices of valence other than 4, and the
/// centres of non-quad faces (valence = size) after a Catmull-Clark step; with an example
/// element of each.
fn cap_valences(m: &PolyMesh) -> BTreeMap<usize, Vec<String>> {
    let mut out: BTreeMap<usize, Vec<String>> = BTreeMap::new();
    for v in (0..m.num_vertices()).filter(|&v| !m.is_nonmanifold_vertex(v)) {
        let n = m.valence(v);
        if !m.is_boundary_vertex(v) && n != 4 {
            out.entry(n).or_default().push(format!("vertex {v}"));
        }
    }
    for f in 0..m.num_faces() {
        let n = m.face_size(f);
        if n != 4 {
            out.entry(n).or_default().push(format!("face {f}"));
        }
    }
    out
}

/// The rules each scheme with per-valence rules uses at the valences of the net, and the
/// problems: valences no construction covers, where the scheme falls back.
fn rules_by_valence(
    m: &PolyMesh,
    problems: &mut Vec<String>,
) -> BTreeMap<&'static str, Vec<ValenceRules>> {
    let valences = cap_valences(m);
    let mut out = BTreeMap::new();
    let mut fallback: BTreeMap<Vec<usize>, Vec<&'static str>> = BTreeMap::new();
    for e in registry().entries() {
        let spec = Spec::new(e.id);
        let rows: Vec<ValenceRules> = valences
            .keys()
            .filter_map(|&n| e.descriptor.valence_rules(&spec, n))
            .collect();
        if rows.is_empty() {
            continue;
        }
        let missing: Vec<usize> = rows
            .iter()
            .filter(|r| r.origin == RulesOrigin::Fallback)
            .map(|r| r.valence)
            .collect();
        if !missing.is_empty() {
            fallback.entry(missing).or_default().push(e.name);
        }
        out.insert(e.name, rows);
    }
    for (ns, schemes) in fallback {
        let at: Vec<String> = ns
            .iter()
            .flat_map(|n| {
                valences[n]
                    .iter()
                    .take(5)
                    .map(move |el| format!("{el} (n={n})"))
            })
            .take(10)
            .collect();
        problems.push(format!(
            "{} have no rules at valence {}: Catmull-Clark rings and fill there (or stop with \
             --fallback error): {}",
            schemes.join(", "),
            ns.iter()
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join(", "),
            at.join(", ")
        ));
    }
    out
}

/// How many faces have each number of sides.
fn face_sizes(m: &PolyMesh) -> BTreeMap<usize, usize> {
    let mut face_sizes = BTreeMap::new();
    for f in 0..m.num_faces() {
        *face_sizes.entry(m.face_size(f)).or_insert(0) += 1;
    }
    face_sizes
}

/// A non-manifold vertex has no single fan: its valence and boundary are not defined.
fn is_manifold_vertex(m: &PolyMesh, v: usize) -> bool {
    !m.is_nonmanifold_vertex(v)
}

/// How many interior and how many boundary (manifold) vertices have each valence.
fn valence_counts(m: &PolyMesh) -> (BTreeMap<usize, usize>, BTreeMap<usize, usize>) {
    let mut interior_valences = BTreeMap::new();
    let mut boundary_valences = BTreeMap::new();
    for v in (0..m.num_vertices()).filter(|&v| is_manifold_vertex(m, v)) {
        let map = if m.is_boundary_vertex(v) {
            &mut boundary_valences
        } else {
            &mut interior_valences
        };
        *map.entry(m.valence(v)).or_insert(0) += 1;
    }
    (interior_valences, boundary_valences)
}

/// The manifold vertices that are not regular for the net's kind (all triangles: valence 6
/// inside, 3 or 4 on the boundary; otherwise the regular quad vertex).
fn extraordinary_vertices(m: &PolyMesh, tri: bool) -> Vec<ExtraordinaryVertex> {
    let regular = |v: usize| -> bool {
        if tri {
            let n = m.valence(v);
            if m.is_boundary_vertex(v) {
                n == 4 || n == 3
            } else {
                n == 6
            }
        } else {
            m.is_regular_quad_vertex(v)
        }
    };
    (0..m.num_vertices())
        .filter(|&v| is_manifold_vertex(m, v))
        .filter(|&v| !regular(v))
        .map(|v| ExtraordinaryVertex {
            vertex: v,
            valence: m.valence(v),
            boundary: m.is_boundary_vertex(v),
        })
        .collect()
}

/// The notes on extraordinary elements that keep schemes from taking the net as it is:
/// adjacent extraordinary vertices, extraordinary boundary vertices and non-quad faces (a
/// quad-dominant net), or an irregular boundary vertex (a triangle net).
fn layout_problems(
    m: &PolyMesh,
    quad: bool,
    tri: bool,
    evs: &[ExtraordinaryVertex],
    problems: &mut Vec<String>,
) {
    if !tri {
        // Adjacent extraordinary vertices: the c-net based schemes need them separated.
        let is_ev: Vec<bool> = {
            let mut b = vec![false; m.num_vertices()];
            for e in evs {
                b[e.vertex] = true;
            }
            b
        };
        let mut adjacent = 0;
        let mut example = None;
        for &[a, b] in m.edges() {
            if is_ev[a as usize] && is_ev[b as usize] {
                adjacent += 1;
                example.get_or_insert((a, b));
            }
        }
        if let Some((a, b)) = example {
            problems.push(format!(
                "{adjacent} edge(s) join two extraordinary vertices (e.g. {a}-{b}): EG, QAS+ and guided \
                 subdivision first apply one Catmull-Clark step to separate them"
            ));
        }
        for e in evs.iter().filter(|e| e.boundary) {
            problems.push(format!(
                "vertex {} is an extraordinary boundary vertex (valence {}): only the classic schemes \
                 have boundary rules for it",
                e.vertex, e.valence
            ));
        }
        if !quad && evs.iter().all(|e| !e.boundary) {
            let ngons = (0..m.num_faces()).filter(|&f| m.face_size(f) != 4).count();
            problems.push(format!(
                "{ngons} face(s) are not quads: quad schemes start with one Catmull-Clark step"
            ));
        }
    } else if let Some(e) = evs.iter().find(|e| e.boundary) {
        problems.push(format!(
            "vertex {} is an irregular boundary vertex (valence {})",
            e.vertex, e.valence
        ));
    }
}

/// Builds the report of a net.
pub fn report(source: &str, m: &PolyMesh) -> InfoReport {
    let face_sizes = face_sizes(m);
    let (interior_valences, boundary_valences) = valence_counts(m);
    let quad = m.is_all_quads();
    let tri = m.is_all_triangles();
    let evs = extraordinary_vertices(m, tri);
    let mut problems = Vec::new();
    layout_problems(m, quad, tri, &evs, &mut problems);
    let non_manifold = NonManifoldReport::of(m);
    if !m.is_manifold() {
        problems.push(format!(
            "the net is not manifold ({} non-manifold edge(s), {} non-manifold vertex(es)): only \
             Catmull-Clark and Loop refine it (subdivide --levels); valences and boundary loops \
             cover the manifold vertices",
            non_manifold.edges.len(),
            non_manifold.vertices.len()
        ));
    }
    let rules_by_valence = rules_by_valence(m, &mut problems);
    let (lo, hi) = m.bounding_box();
    InfoReport {
        source: source.to_string(),
        vertices: m.num_vertices(),
        edges: m.num_edges(),
        faces: m.num_faces(),
        euler_characteristic: m.num_vertices() as i64 - m.num_edges() as i64 + m.num_faces() as i64,
        all_quads: quad,
        all_triangles: tri,
        face_sizes,
        interior_valences,
        boundary_valences,
        // The loops walk vertex fans, which a non-manifold vertex does not have.
        boundary_loops: if m.is_manifold() {
            m.boundary_loops().iter().map(|l| l.len()).collect()
        } else {
            Vec::new()
        },
        extraordinary_faces: (0..m.num_faces())
            .filter(|&f| !tri && m.face_size(f) != 4)
            .map(|f| ExtraordinaryFace {
                face: f,
                sides: m.face_size(f),
            })
            .collect(),
        extraordinary_vertices: evs,
        bounding_box: [lo, hi],
        rules_by_valence,
        problems,
        dropped_vertices: m.dropped_vertices().to_vec(),
        non_manifold,
        preparation: None,
    }
}

/// Runs `fairsub info` (with `scheme`: what would be prepared for it).
pub fn run(net: &str, scheme: Option<&str>, json: bool) -> Result<()> {
    let loaded = super::load_net_as(net, true)?;
    let mut r = report(net, &loaded.mesh);
    if let Some(s) = scheme {
        r.preparation = Some(preparation(s, &loaded.mesh)?);
    }
    if json {
        super::say_json(&r);
        return Ok(());
    }
    say_counts(&r);
    for (scheme, rows) in &r.rules_by_valence {
        let words: Vec<String> = rows
            .iter()
            .map(|v| format!("n={}: {}", v.valence, v.rules))
            .collect();
        say!("  {scheme} rules: {}", words.join("; "));
    }
    say_non_manifold(&r.non_manifold);
    for p in &r.problems {
        say!("  note: {p}");
    }
    if let Some(p) = &r.preparation {
        say_preparation(p);
    }
    Ok(())
}

/// The text report of the net's counts: elements, face sizes, valences, boundary loops,
/// extraordinary elements, bounding box and dropped vertices.
fn say_counts(r: &InfoReport) {
    say!("{}", r.source);
    say!(
        "  {} vertices, {} edges, {} faces (Euler characteristic {})",
        r.vertices,
        r.edges,
        r.faces,
        r.euler_characteristic
    );
    let fmt = |m: &BTreeMap<usize, usize>| {
        m.iter()
            .map(|(k, c)| format!("{k}: {c}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    say!("  face sizes:          {}", fmt(&r.face_sizes));
    say!("  interior valences:   {}", fmt(&r.interior_valences));
    if !r.boundary_valences.is_empty() {
        say!("  boundary valences:   {}", fmt(&r.boundary_valences));
    }
    say!(
        "  boundary loops:      {} {:?}",
        r.boundary_loops.len(),
        r.boundary_loops
    );
    let evs: Vec<String> = r
        .extraordinary_vertices
        .iter()
        .take(20)
        .map(|e| {
            format!(
                "{}(n={}{})",
                e.vertex,
                e.valence,
                if e.boundary { ",b" } else { "" }
            )
        })
        .collect();
    say!(
        "  extraordinary vertices: {}{}{}",
        r.extraordinary_vertices.len(),
        if evs.is_empty() { "" } else { ": " },
        evs.join(" ")
    );
    if !r.extraordinary_faces.is_empty() {
        let fs: Vec<String> = r
            .extraordinary_faces
            .iter()
            .take(20)
            .map(|f| format!("{}({}-gon)", f.face, f.sides))
            .collect();
        say!(
            "  extraordinary faces: {}: {}",
            r.extraordinary_faces.len(),
            fs.join(" ")
        );
    }
    say!(
        "  bounding box: {:?} .. {:?}",
        r.bounding_box[0],
        r.bounding_box[1]
    );
    if !r.dropped_vertices.is_empty() {
        say!("  dropped unused vertices: {:?}", r.dropped_vertices);
    }
}

/// The text report of the non-manifold edges, vertices and faces (up to 20 of each).
fn say_non_manifold(nm: &NonManifoldReport) {
    if !nm.edges.is_empty() {
        let es: Vec<String> = nm
            .edges
            .iter()
            .take(20)
            .map(|e| format!("{}-{}(faces {:?})", e.edge[0], e.edge[1], e.faces))
            .collect();
        say!("  non-manifold edges: {}: {}", nm.edges.len(), es.join(" "));
    }
    if !nm.vertices.is_empty() {
        let vs: Vec<String> = nm.vertices.iter().take(20).map(|v| v.to_string()).collect();
        say!(
            "  non-manifold vertices: {}: {}",
            nm.vertices.len(),
            vs.join(" ")
        );
    }
    if !nm.repeated_vertex_faces.is_empty() {
        let fs: Vec<String> = nm
            .repeated_vertex_faces
            .iter()
            .take(20)
            .map(|f| f.to_string())
            .collect();
        say!(
            "  faces repeating a vertex: {}: {}",
            nm.repeated_vertex_faces.len(),
            fs.join(" ")
        );
    }
}

/// The text report of what would be prepared.
fn say_preparation(p: &PreparationReport) {
    use crate::schemes::prepare::Kind;
    for (what, steps) in [("patches", &p.patches), ("levels", &p.levels)] {
        if steps.is_empty() {
            say!("  {} {what}: nothing to prepare", p.scheme);
            continue;
        }
        for a in steps {
            let how = match a.kind {
                Kind::Applied => "applied",
                Kind::Own => "taken by the scheme's own construction",
                Kind::Skipped => "not applied (it does not carry the net's sharp-feature tags)",
            };
            say!(
                "  {} {what}: {} ({how}); {} {} ({}{})",
                p.scheme,
                a.step,
                p.scheme,
                a.need,
                a.elements.join(", "),
                if a.count > a.elements.len() {
                    format!(" and {} more", a.count - a.elements.len())
                } else {
                    String::new()
                }
            );
        }
    }
    if !p.patches.is_empty() {
        say!(
            "  {} prepared net: {} vertices, {} faces",
            p.scheme,
            p.prepared_vertices,
            p.prepared_faces
        );
    }
}
