//! STEP output (ISO 10303-21, AP214 `AUTOMOTIVE_DESIGN`): B-spline faces with B-rep topology.
//!
//! # What is written
//!
//! * **Header**: `FILE_DESCRIPTION`, `FILE_NAME` (the file name, the date in ISO 8601, UTC;
//!   `SOURCE_DATE_EPOCH` is honoured), `FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1
//!   1 }'))`.
//! * **Product chain**, without which CAD systems show nothing: `APPLICATION_CONTEXT`,
//!   `APPLICATION_PROTOCOL_DEFINITION`, `PRODUCT_CONTEXT`, `PRODUCT` (named after the file
//!   stem), `PRODUCT_RELATED_PRODUCT_CATEGORY('part')`, `PRODUCT_DEFINITION_FORMATION`,
//!   `PRODUCT_DEFINITION_CONTEXT`, `PRODUCT_DEFINITION`, `PRODUCT_DEFINITION_SHAPE` and the
//!   `SHAPE_DEFINITION_REPRESENTATION` that ties the product to the shape representation.
//! * **Context**: one complex instance `GEOMETRIC_REPRESENTATION_CONTEXT(3)`,
//!   `GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT` (the tolerance, an `UNCERTAINTY_MEASURE_WITH_UNIT`
//!   of `distance_accuracy_value`), `GLOBAL_UNIT_ASSIGNED_CONTEXT` (millimetre, radian,
//!   steradian: fairsub coordinates are unitless, one unit is written as one millimetre, as in
//!   IGES output) and `REPRESENTATION_CONTEXT`.
//! * **Shape**: one shell per connected component of the faces. When every shell is closed,
//!   an `ADVANCED_BREP_SHAPE_REPRESENTATION` of one `MANIFOLD_SOLID_BREP` per `CLOSED_SHELL`;
//!   otherwise a `MANIFOLD_SURFACE_SHAPE_REPRESENTATION` of a `SHELL_BASED_SURFACE_MODEL` of
//!   the `OPEN_SHELL`s and `CLOSED_SHELL`s. Both hold an `AXIS2_PLACEMENT_3D` at the origin.
//! * **Topology and geometry** ([`crate::surface::cad::brep`]): a `VERTEX_POINT` per vertex,
//!   an `EDGE_CURVE` (with its `B_SPLINE_CURVE_WITH_KNOTS`) per edge, used by its faces through
//!   `ORIENTED_EDGE`s in one `EDGE_LOOP` per face (`FACE_OUTER_BOUND`), and an `ADVANCED_FACE`
//!   with `same_sense = .T.` on a `B_SPLINE_SURFACE_WITH_KNOTS` (control points as
//!   `control_points_list[i][j]`, `i` along `u`; knot values with their multiplicities).
//!
//! Reals are written in shortest round-trip form with a decimal point and an `E` exponent
//! (`1.25E-3`, `-0.5`), so coordinates read back bit for bit.

use crate::error::Result;
use crate::io::write_bytes_atomically;
use crate::surface::cad::brep::Brep;
use crate::surface::cad::spline::{SplineCurve, SplineSurface, distinct};
use std::fmt::Write as _;
use std::path::Path;

/// A STEP real: shortest round-trip digits, always with a decimal point.
fn real(x: f64) -> String {
    let s = format!("{x:?}");
    if s.contains('e') {
        let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
        if m.contains('.') {
            format!("{m}E{e}")
        } else {
            format!("{m}.E{e}")
        }
    } else if s.contains('.') {
        s
    } else {
        format!("{s}.")
    }
}

/// A STEP string: ASCII letters, digits and a few safe characters.
fn string(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-' | ' ') {
                c
            } else {
                '_'
            }
        })
        .take(200)
        .collect()
}

/// The entity writer: numbers instances from `#1` in order.
struct Data {
    out: String,
    next: usize,
}

impl Data {
    /// Writes `body` as the next instance and returns its number.
    fn add(&mut self, body: &str) -> usize {
        let n = self.next;
        self.next += 1;
        let _ = writeln!(self.out, "#{n}={body};");
        n
    }

    fn point(&mut self, p: [f64; 3]) -> usize {
        self.add(&format!(
            "CARTESIAN_POINT('',({},{},{}))",
            real(p[0]),
            real(p[1]),
            real(p[2])
        ))
    }
}

/// `(#a,#b,...)`.
fn refs(ids: impl IntoIterator<Item = usize>) -> String {
    let v: Vec<String> = ids.into_iter().map(|i| format!("#{i}")).collect();
    format!("({})", v.join(","))
}

/// `(a,b,...)` of integers or reals.
fn list<T: ToString>(xs: impl IntoIterator<Item = T>) -> String {
    let v: Vec<String> = xs.into_iter().map(|x| x.to_string()).collect();
    format!("({})", v.join(","))
}

fn knots_and_mults(knots: &[f64]) -> (String, String) {
    let (vals, mult) = distinct(knots);
    (list(mult), list(vals.into_iter().map(real)))
}

fn curve(d: &mut Data, c: &SplineCurve) -> usize {
    let pts: Vec<usize> = c.cps.iter().map(|p| d.point(*p)).collect();
    let (m, k) = knots_and_mults(&c.knots);
    d.add(&format!(
        "B_SPLINE_CURVE_WITH_KNOTS('',{},{},.UNSPECIFIED.,.F.,.F.,{m},{k},.UNSPECIFIED.)",
        c.deg,
        refs(pts)
    ))
}

fn surface(d: &mut Data, s: &SplineSurface) -> usize {
    let [nu, nv] = s.counts();
    let mut rows = Vec::with_capacity(nu);
    for i in 0..nu {
        let row: Vec<usize> = (0..nv).map(|j| d.point(s.cp(i, j))).collect();
        rows.push(refs(row));
    }
    let (mu, ku) = knots_and_mults(&s.knots[0]);
    let (mv, kv) = knots_and_mults(&s.knots[1]);
    d.add(&format!(
        "B_SPLINE_SURFACE_WITH_KNOTS('',{},{},({}),.UNSPECIFIED.,.F.,.F.,.F.,{mu},{mv},{ku},{kv},.UNSPECIFIED.)",
        s.deg[0],
        s.deg[1],
        rows.join(",")
    ))
}

/// The file's date, `YYYY-MM-DDTHH:MM:SS` (UTC).
fn iso_date() -> String {
    let d = crate::io::iges::file_date(); // YYYYMMDD.HHNNSS
    format!(
        "{}-{}-{}T{}:{}:{}",
        &d[0..4],
        &d[4..6],
        &d[6..8],
        &d[9..11],
        &d[11..13],
        &d[13..15]
    )
}

/// The STEP text of `surfaces` with topology `brep`; `file_name` goes into the header and
/// names the product; `tolerance` is the file's distance accuracy.
pub fn step_to_string(
    surfaces: &[SplineSurface],
    brep: &Brep,
    file_name: &str,
    tolerance: f64,
) -> Result<String> {
    let stem = string(
        Path::new(file_name)
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("fairsub"),
    );
    let out = header(surfaces.len(), brep, file_name);
    let mut d = Data { out, next: 1 };
    let pds = product(&mut d, &stem);
    let ctx = representation_context(&mut d, tolerance);
    let origin = d.point([0.0; 3]);
    let z = d.add("DIRECTION('',(0.,0.,1.))");
    let x = d.add("DIRECTION('',(1.,0.,0.))");
    let axis = d.add(&format!("AXIS2_PLACEMENT_3D('',#{origin},#{z},#{x})"));
    let faces = advanced_faces(&mut d, surfaces, brep);
    let rep = shape_representation(&mut d, brep, &faces, &stem, (axis, ctx));
    d.add(&format!("SHAPE_DEFINITION_REPRESENTATION(#{pds},#{rep})"));
    let mut out = d.out;
    out.push_str("ENDSEC;\nEND-ISO-10303-21;\n");
    Ok(out)
}

/// The file's start: the `HEADER` section (what the file holds, its name and date, the AP214
/// schema) and the opening of the `DATA` section.
fn header(faces: usize, brep: &Brep, file_name: &str) -> String {
    let name = string(file_name);
    let closed = brep.is_closed();
    let mut out = String::with_capacity(200 * faces + 1000);
    out.push_str("ISO-10303-21;\nHEADER;\n");
    let _ = writeln!(
        out,
        "FILE_DESCRIPTION(('fairsub {}: {} B-spline faces, {} edges, {}'),'2;1');",
        env!("CARGO_PKG_VERSION"),
        faces,
        brep.edges.len(),
        if closed { "closed shell" } else { "open shell" }
    );
    let _ = writeln!(
        out,
        "FILE_NAME('{name}','{}',(''),(''),'fairsub {}','fairsub','');",
        iso_date(),
        env!("CARGO_PKG_VERSION")
    );
    out.push_str("FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n");
    out
}

/// The product named `stem` and its contexts, down to its shape's definition (returned).
fn product(d: &mut Data, stem: &str) -> usize {
    let app = d.add("APPLICATION_CONTEXT('core data for automotive mechanical design processes')");
    d.add(&format!(
        "APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app})"
    ));
    let pc = d.add(&format!("PRODUCT_CONTEXT('',#{app},'mechanical')"));
    let product = d.add(&format!("PRODUCT('{stem}','{stem}','',(#{pc}))"));
    d.add(&format!(
        "PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#{product}))"
    ));
    let pdf = d.add(&format!("PRODUCT_DEFINITION_FORMATION('','',#{product})"));
    let pdc = d.add(&format!(
        "PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design')"
    ));
    let pd = d.add(&format!("PRODUCT_DEFINITION('design','',#{pdf},#{pdc})"));
    d.add(&format!("PRODUCT_DEFINITION_SHAPE('','',#{pd})"))
}

/// The geometric context: millimetres, radians, steradians and the distance accuracy
/// `tolerance`.
fn representation_context(d: &mut Data, tolerance: f64) -> usize {
    let mm = d.add("(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))");
    let rad = d.add("(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.))");
    let sr = d.add("(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT())");
    let unc = d.add(&format!(
        "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE({}),#{mm},'distance_accuracy_value','maximum gap between faces')",
        real(tolerance)
    ));
    d.add(&format!(
        "(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{unc}))GLOBAL_UNIT_ASSIGNED_CONTEXT((#{mm},#{rad},#{sr}))REPRESENTATION_CONTEXT('',''))"
    ))
}

/// The topology: a vertex point per B-rep vertex, an edge curve per edge, and per surface an
/// advanced face bounded by its loop of oriented edges.
fn advanced_faces(d: &mut Data, surfaces: &[SplineSurface], brep: &Brep) -> Vec<usize> {
    let vertices: Vec<usize> = brep
        .vertices
        .iter()
        .map(|p| {
            let pt = d.point(*p);
            d.add(&format!("VERTEX_POINT('',#{pt})"))
        })
        .collect();
    let edges: Vec<usize> = brep
        .edges
        .iter()
        .map(|e| {
            let c = curve(d, &e.curve);
            d.add(&format!(
                "EDGE_CURVE('',#{},#{},#{c},.T.)",
                vertices[e.ends[0] as usize], vertices[e.ends[1] as usize]
            ))
        })
        .collect();
    let mut faces = Vec::with_capacity(surfaces.len());
    for (s, lp) in surfaces.iter().zip(&brep.loops) {
        let oes: Vec<usize> = lp
            .iter()
            .map(|&(e, sense)| {
                d.add(&format!(
                    "ORIENTED_EDGE('',*,*,#{},{})",
                    edges[e as usize],
                    if sense { ".T." } else { ".F." }
                ))
            })
            .collect();
        let lp = d.add(&format!("EDGE_LOOP('',{})", refs(oes)));
        let bound = d.add(&format!("FACE_OUTER_BOUND('',#{lp},.T.)"));
        let surf = surface(d, s);
        faces.push(d.add(&format!("ADVANCED_FACE('',(#{bound}),#{surf},.T.)")));
    }
    faces
}

/// One shell per connected component of `faces`: all closed, solids in an advanced B-rep
/// representation; otherwise a shell-based surface model; placed by `axis` in context `ctx`.
fn shape_representation(
    d: &mut Data,
    brep: &Brep,
    faces: &[usize],
    stem: &str,
    (axis, ctx): (usize, usize),
) -> usize {
    let closed = brep.is_closed();
    let shells: Vec<(usize, bool)> = brep
        .shell_faces()
        .iter()
        .zip(&brep.closed)
        .map(|(fs, &c)| {
            let kind = if c { "CLOSED_SHELL" } else { "OPEN_SHELL" };
            (
                d.add(&format!(
                    "{kind}('',{})",
                    refs(fs.iter().map(|&f| faces[f]))
                )),
                c,
            )
        })
        .collect();
    if closed {
        let solids: Vec<usize> = shells
            .iter()
            .map(|(s, _)| d.add(&format!("MANIFOLD_SOLID_BREP('{stem}',#{s})")))
            .collect();
        d.add(&format!(
            "ADVANCED_BREP_SHAPE_REPRESENTATION('{stem}',{},#{ctx})",
            refs(std::iter::once(axis).chain(solids))
        ))
    } else {
        let model = d.add(&format!(
            "SHELL_BASED_SURFACE_MODEL('{stem}',{})",
            refs(shells.iter().map(|(s, _)| *s))
        ));
        d.add(&format!(
            "MANIFOLD_SURFACE_SHAPE_REPRESENTATION('{stem}',(#{axis},#{model}),#{ctx})"
        ))
    }
}

/// Writes the faces with their topology as a STEP file (atomically).
pub fn write_step(
    path: &Path,
    surfaces: &[SplineSurface],
    brep: &Brep,
    tolerance: f64,
) -> Result<()> {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    write_bytes_atomically(
        path,
        step_to_string(surfaces, brep, &name, tolerance)?.as_bytes(),
    )
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::real;

    #[crate::unit::test]
    fn reals_have_a_point_and_read_back() {
        for x in [0.0, 1.0, -0.5, 1e-7, 1.25e-3, 123456789.0, -2.5e300, 0.1] {
            let s = real(x);
            assert!(s.contains('.'), "{s}");
            assert_eq!(s.parse::<f64>().unwrap(), x, "{s}");
        }
        assert_eq!(real(1e-7), "1.E-7");
        assert_eq!(real(1.0), "1.0");
    }
}
