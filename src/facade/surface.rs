//! Exact surfaces (`fairsub subdivide --rings K`): the patch complex of a net with what can be
//! asked of it (evaluation, closest points, patch stencil table, continuity and moment
//! reports, tessellation, output).

use super::{Options, Source};
use crate::cli::Computed;
use crate::cli::subdivide::{self, Args, Prepared};
use crate::error::Result;
use crate::geom::Point;
use crate::mesh::PolyMesh;
use crate::schemes::Spec;
use crate::surface::PatchComplex;
use crate::surface::closest::Closest;
use crate::surface::eval::{self, Evaluation};
use crate::surface::table::PatchTable;
use std::path::Path;
use std::sync::OnceLock;

/// The exact patch complex of a net under a scheme, with its provenance and the net as the
/// scheme read it (the domain of [`Surface::evaluate`]).
#[derive(Debug)]
pub struct Surface {
    complex: PatchComplex,
    notes: Vec<String>,
    label: String,
    name: String,
    args: Args,
    prepared: Prepared,
    evaluator: OnceLock<eval::Surface>,
}

/// The exact surface of `net` under `scheme`: `rings` rings of patches around every
/// extraordinary element, the hole inside the last ring closed by the scheme's cap when
/// `fill` (`fairsub subdivide NET --scheme SCHEME --rings RINGS [--no-fill]`).
///
/// # Errors
/// An unknown scheme or one without exact patches, an option the scheme does not take, a net
/// the scheme does not take, or a complex over the memory budget.
///
/// ```
/// use fairsub::{Options, surface};
/// let s = surface("gallery:cnet-5-saddle", "catmull-clark", 3, true, &Options::default())?;
/// assert!(s.complex().len() > 0);
/// let p = s.evaluate(&[(0, 0.5, 0.5)])?;
/// assert!(p[0].point.iter().all(|x| x.is_finite()));
/// # Ok::<(), fairsub::Error>(())
/// ```
pub fn surface(
    net: impl Into<Source>,
    scheme: &str,
    rings: usize,
    fill: bool,
    options: &Options,
) -> Result<Surface> {
    let (name, given) = net.into().split();
    let mut a = options.args(name.clone(), scheme)?;
    a.rings = Some(rings);
    a.no_fill = !fill;
    a.output = "out.bv".into();
    let budget = crate::cli::limits::max_memory();
    crate::cli::limits::with_budget(budget, || {
        let prepared = subdivide::prepare(&a, given)?;
        let (computed, label) = subdivide::finish(&a, &prepared)?;
        let Computed::Complex(complex, notes) = computed else {
            unreachable!("a --rings job builds a complex")
        };
        Ok(Surface {
            complex,
            notes,
            label,
            name,
            args: a,
            prepared,
            evaluator: OnceLock::new(),
        })
    })
}

impl Surface {
    /// The Bezier patches with their provenance.
    pub fn complex(&self) -> &PatchComplex {
        &self.complex
    }

    /// The scheme with its typed options, as resolved.
    pub fn spec(&self) -> &Spec {
        &self.prepared.spec
    }

    /// The net as the scheme read it (FCV layout, tags): the domain of the evaluation.
    pub fn net(&self) -> &PolyMesh {
        &self.prepared.mesh
    }

    /// The scheme as reports name it.
    pub fn label(&self) -> &str {
        &self.label
    }

    /// The construction's notes (fallbacks, derived rules).
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// The evaluator of the surface at `(face, u, v)` of the input faces, built once.
    ///
    /// # Errors
    /// A scheme whose patches carry no input-face domains.
    pub fn evaluator(&self) -> Result<&eval::Surface> {
        if let Some(ev) = self.evaluator.get() {
            return Ok(ev);
        }
        eval::supported(self.spec())?;
        let ev = eval::Surface::of_scheme(self.spec(), self.net(), self.complex.clone())?;
        Ok(self.evaluator.get_or_init(|| ev))
    }

    /// The point, derivatives, normal and curvatures at each `(face, u, v)` (quads on
    /// `[0,1]^2`; an n-gon `u` in `[0, n]`, `v` in `[0, 1]`; a Loop triangle barycentric),
    /// as `fairsub eval` reports them, in parallel.
    ///
    /// # Errors
    /// The message of the first point that fails (a face that does not exist, a parameter
    /// outside its domain).
    pub fn evaluate(&self, points: &[(u32, f64, f64)]) -> Result<Vec<Evaluation>> {
        let ev = self.evaluator()?;
        let mut out = vec![Evaluation::default(); points.len()];
        ev.evaluate_into(points, &mut out).map_err(|(_, e)| e)?;
        Ok(out)
    }

    /// The closest point of the surface to each of `points` (`fairsub project`), in
    /// parallel, with its `(face, u, v)`.
    pub fn closest(&self, points: &[Point]) -> Result<Vec<Closest>> {
        crate::surface::closest::closest_points(self.evaluator()?, points)
    }

    /// The patch stencil table (`subdivide --rings K --stencils FILE`'s): the weights from the
    /// net's points to every Bezier coefficient, so that moved control points give their
    /// patches without building the surface again.
    ///
    /// ```
    /// use fairsub::{Options, surface};
    /// let s = surface("gallery:cnet-5-saddle", "catmull-clark", 2, true, &Options::default())?;
    /// let t = s.stencils()?;
    /// let again = t.apply(s.net().positions())?;
    /// assert_eq!(again.len(), s.complex().len());
    /// # Ok::<(), fairsub::Error>(())
    /// ```
    pub fn stencils(&self) -> Result<PatchTable> {
        subdivide::patch_table(&self.args, &self.prepared, &self.complex)
    }

    /// `fairsub check --json`'s report (continuity defects per kind of join, curvature per
    /// ring, notes) as JSON text.
    pub fn check_json(&self) -> String {
        crate::cli::check::report_json(
            &self.name,
            &self.complex,
            Some(self.spec()),
            self.notes.clone(),
        )
    }

    /// `fairsub measure --json`'s report (area to the relative `tolerance`, volume of a closed
    /// surface, centroids, inertia; with `per_face` the area over each input face) as JSON
    /// text.
    pub fn measure_json(&self, tolerance: f64, per_face: bool) -> Result<String> {
        crate::cli::api::measure_json(
            &self.name,
            &self.complex,
            self.spec(),
            self.net(),
            per_face,
            tolerance,
        )
    }

    /// The watertight tessellation `subdivide --rings K --tess n -o X.obj` writes, with `n`
    /// samples per patch edge.
    pub fn tessellate(&self, n: usize) -> Result<PolyMesh> {
        crate::cli::limits::check_tessellation(&self.complex, n)?;
        crate::surface::tessellate::tessellate(&self.complex, n).to_mesh(&self.complex)
    }

    /// Writes the surface as `subdivide --rings` does (`.bv`, `.igs`, `.step`, or a
    /// tessellated mesh with `tess` samples per patch edge), validated, atomically.
    pub fn write(&self, path: &Path, tess: usize) -> Result<()> {
        crate::cli::api::write_complex(&self.complex, path, tess)
    }
}
