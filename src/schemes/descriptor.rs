//! What the rest of fairsub needs to know about a scheme, in one trait per scheme.
//!
//! A scheme is named by a [`SchemeId`] (its canonical command-line name, spelled in
//! [`super::options::ids`] and its family's `entry.rs`) and configured by typed [`Params`]; the two together are a
//! [`Spec`]. Its registry row carries the catalogue text ([`super::entry::About`]); its [`Descriptor`] says
//! which typed options it takes ([`ParamKind`]) and hands out its rules:
//!
//! * mesh rules ([`super::Scheme`]: whole-net refinement, limit masks) for `--levels`;
//! * patch rules ([`PatchRules`]: the exact surface as a patch complex) for `--rings`;
//! * local rules ([`LocalRules`]: the subdivision matrix at one valence on the scheme's local
//!   net, the characteristic ring, the published numbers) for `analyze` and `charmap`.
//!
//! The front ends (CLI, demo, Python) and the surface and analysis layers only ever look a
//! scheme up in the registry and ask its descriptor; nothing matches on scheme names.

use super::Scheme;
use super::circulant::{SparseLocal, choose};
use super::local::{LocalMatrix, LocalOperator};
use crate::bezier::BezierPatch;
use crate::error::{Error, Result};
use crate::mesh::PolyMesh;

pub use crate::host::{ComplexOptions, Fallback, SurfaceOutput};
use serde::Serialize;

pub use super::options::{
    AlphaRule, ChiKind, GuideDegree, ParamKind, Params, QSpec, RulesChoice, SchemeId, Spec,
};

/// Where the rules a scheme uses at one valence come from ([`Descriptor::valence_rules`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum RulesOrigin {
    /// The paper's printed rules.
    Printed,
    /// fairsub's derivation (a reconstruction, measured against the paper).
    Derived,
    /// The regular rules (valence 4: uniform refinement).
    Regular,
    /// Another scheme's rules (QAS+ uses EG's at valence 3).
    Borrowed,
    /// No construction covers the valence: the fallback (`--fallback`).
    Fallback,
}

/// The rules a scheme uses at one valence, as `fairsub info` and `fairsub schemes` report them.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct ValenceRules {
    /// Valence.
    pub valence: usize,
    /// Where the rules come from.
    pub origin: RulesOrigin,
    /// The rules in words (e.g. `eg (derived rules, n = 7)`, `Catmull-Clark rings and fill`).
    pub rules: String,
}

/// What a scheme offers, known without building anything.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Capabilities {
    /// Whole-net refinement (`--levels`).
    pub refine: bool,
    /// Exact patch output (`--rings`).
    pub patches: bool,
    /// Evaluation at `(face, u, v)` (`fairsub eval`): its patches lie in input faces and carry
    /// their domains ([`crate::bezier::domain`]).
    pub eval: bool,
}

impl Capabilities {
    /// Exact patches only: the cap schemes, which have no net of their own to refine (the
    /// [`Descriptor::capabilities`] default).
    pub const PATCHES: Capabilities = Capabilities {
        refine: false,
        patches: true,
        eval: false,
    };
    /// Exact patches with evaluation, without whole-net refinement: the cap schemes on
    /// Catmull-Clark's host (EG, QAS+, guided), whose rings and caps tile the input faces.
    pub const PATCHES_AND_EVAL: Capabilities = Capabilities {
        eval: true,
        ..Capabilities::PATCHES
    };
    /// Whole-net refinement only: schemes without exact patches (sqrt(3), the modified
    /// butterfly), so no `--rings`.
    pub const REFINE: Capabilities = Capabilities {
        refine: true,
        patches: false,
        eval: false,
    };
    /// Whole-net refinement and exact patches, without evaluation.
    pub const REFINE_AND_PATCHES: Capabilities = Capabilities {
        refine: true,
        ..Capabilities::PATCHES
    };
}

/// A scheme's exact surfaces of whole nets.
pub trait PatchRules: Sync {
    /// The patch complex of `mesh`: regular patches, `opts.rings` rings around every
    /// extraordinary element and the scheme's fill (or the hole left open). `progress(ring)` is
    /// called as rings are produced.
    fn build(
        &self,
        mesh: &PolyMesh,
        opts: ComplexOptions,
        progress: &mut dyn FnMut(usize),
    ) -> Result<SurfaceOutput>;

    /// The complex of [`PatchRules::build`] with its patch stencil table's rows tracked beside
    /// the points, in factored form (the layout of `surface::table::PatchTable::from_layered`),
    /// when the scheme tracks every step it took for this net; `None` otherwise (the table is
    /// then probed).
    fn build_tracked(
        &self,
        mesh: &PolyMesh,
        opts: ComplexOptions,
    ) -> Result<Option<(SurfaceOutput, crate::stencil::LayeredTable)>> {
        let _ = (mesh, opts);
        Ok(None)
    }
}

/// [`PatchRules`] that are one function call (see [`patch_fn`]).
struct PatchFn<F>(F);

impl<F> PatchRules for PatchFn<F>
where
    F: Fn(&PolyMesh, ComplexOptions, &mut dyn FnMut(usize)) -> Result<SurfaceOutput> + Sync,
{
    fn build(
        &self,
        mesh: &PolyMesh,
        opts: ComplexOptions,
        progress: &mut dyn FnMut(usize),
    ) -> Result<SurfaceOutput> {
        (self.0)(mesh, opts, progress)
    }
}

/// What [`Descriptor::patch_rules`] returns for a scheme whose exact surface is the call
/// `build(mesh, opts, progress)`.
pub fn patch_fn<F>(build: F) -> Result<Option<Box<dyn PatchRules>>>
where
    F: Fn(&PolyMesh, ComplexOptions, &mut dyn FnMut(usize)) -> Result<SurfaceOutput>
        + Sync
        + 'static,
{
    Ok(Some(Box::new(PatchFn(build))))
}

/// A published value next to the computed one.
#[derive(Debug, Clone, Serialize)]
pub struct Published {
    /// What is compared (with its source in the paper).
    pub quantity: String,
    /// The paper's value.
    pub published: f64,
    /// fairsub's value.
    pub computed: f64,
    /// `|published - computed|`.
    pub difference: f64,
}

impl Published {
    /// A comparison.
    pub fn new(quantity: impl Into<String>, published: f64, computed: f64) -> Published {
        Published {
            quantity: quantity.into(),
            published,
            computed,
            difference: (published - computed).abs(),
        }
    }
}

/// What the analysis computed from a local matrix, handed to [`LocalRules::published`].
#[derive(Debug, Clone)]
pub struct Computed<'a> {
    /// The matrix (dense, or its Fourier blocks at large valences).
    pub matrix: &'a dyn LocalOperator,
    /// Its spectrum.
    pub spectrum: &'a super::local::Spectrum,
    /// The limit-point stencil reported.
    pub limit_stencil: &'a [f64],
}

/// Extra facts a scheme reports beside its spectrum (for example QAS+'s `M_d` and `M_q`):
/// a JSON value under `key` and lines for the text report.
#[derive(Debug, Clone)]
pub struct ExtraFacts {
    /// Key in the JSON report.
    pub key: &'static str,
    /// The facts.
    pub value: serde_json::Value,
    /// The text report's lines.
    pub lines: Vec<String>,
}

/// A scheme's local rules at one valence, for analysis.
pub trait LocalRules: Sync {
    /// The subdivision matrix at valence `n` on the scheme's local net (centre points first,
    /// then sector by sector), from the scheme's own stencils.
    fn matrix(&self, n: usize) -> Result<LocalMatrix>;

    /// The same matrix as sparse rows, for schemes whose matrix is block-circulant (`None`:
    /// the dense matrix only).
    fn sparse(&self, n: usize) -> Result<Option<SparseLocal>> {
        let _ = n;
        Ok(None)
    }

    /// Whether [`LocalRules::operator`] takes valence `n` by Fourier blocks of its own (without
    /// sparse rows, like guided subdivision's Bloch basis) above
    /// [`crate::linalg::MAX_DENSE_EIGEN_ROWS`] rows, so that the limits bound it by valence
    /// rather than by rows.
    fn own_blocks(&self, n: usize) -> bool {
        let _ = n;
        false
    }

    /// The matrix the analysis decomposes at valence `n`: [`LocalRules::matrix`] within
    /// [`crate::linalg::MAX_DENSE_EIGEN_ROWS`] rows or without sparse rows, its Fourier blocks
    /// ([`super::circulant`]) above; with `replicated_centre`, its replicated-centre form.
    fn operator(&self, n: usize, replicated_centre: bool) -> Result<Box<dyn LocalOperator>> {
        match self.sparse(n)? {
            Some(rows) => choose(&rows, replicated_centre, || self.matrix(n)),
            None => {
                let lm = self.matrix(n)?;
                Ok(Box::new(if replicated_centre {
                    lm.replicated_centre()
                } else {
                    lm
                }))
            }
        }
    }

    /// The planar characteristic ring at valence `n` (patches of one ring of the
    /// characteristic map) and its contraction lambda.
    fn characteristic_ring(&self, n: usize) -> Result<(Vec<BezierPatch>, f64)> {
        Err(Error::Unsupported(format!(
            "valence {n}: this scheme has no characteristic map"
        )))
    }

    /// The limit-point stencil reported beside the matrix (default: the left eigenvector of 1
    /// of `m`).
    fn limit_stencil(&self, n: usize, m: &dyn LocalOperator) -> Result<Vec<f64>> {
        let _ = n;
        m.limit_stencil()
    }

    /// The paper's numbers at valence `n` beside fairsub's.
    fn published(&self, n: usize, c: &Computed<'_>) -> Result<Vec<Published>> {
        let _ = (n, c);
        Ok(Vec::new())
    }

    /// Extra facts beside the spectrum.
    fn extra(&self, n: usize) -> Result<Option<ExtraFacts>> {
        let _ = n;
        Ok(None)
    }

    /// All extra facts (several keys); the default is [`LocalRules::extra`]'s one.
    fn extras(&self, n: usize) -> Result<Vec<ExtraFacts>> {
        Ok(self.extra(n)?.into_iter().collect())
    }
}

/// [`LocalRules`] that give the matrix (and possibly its sparse rows) only (see
/// [`matrix_only`], [`matrix_and_rows`]).
struct MatrixOnly(
    fn(usize) -> Result<LocalMatrix>,
    Option<fn(usize) -> Result<SparseLocal>>,
);

impl LocalRules for MatrixOnly {
    fn matrix(&self, n: usize) -> Result<LocalMatrix> {
        (self.0)(n)
    }

    fn sparse(&self, n: usize) -> Result<Option<SparseLocal>> {
        self.1.map(|f| f(n)).transpose()
    }
}

/// What [`Descriptor::local_rules`] returns for a scheme whose analysis is its matrix at each
/// valence (`matrix(n)`), with the defaults for the rest.
pub fn matrix_only(
    matrix: fn(usize) -> Result<LocalMatrix>,
) -> Result<Option<Box<dyn LocalRules>>> {
    Ok(Some(Box::new(MatrixOnly(matrix, None))))
}

/// [`matrix_only`] for a block-circulant matrix with its sparse rows (`rows(n)`, whose
/// [`SparseLocal::to_matrix`] is `matrix(n)`), so that large valences are analysed by Fourier
/// blocks.
pub fn matrix_and_rows(
    matrix: fn(usize) -> Result<LocalMatrix>,
    rows: fn(usize) -> Result<SparseLocal>,
) -> Result<Option<Box<dyn LocalRules>>> {
    Ok(Some(Box::new(MatrixOnly(matrix, Some(rows)))))
}

/// Everything the rest of fairsub needs to know about one scheme (its catalogue text, [`super::entry::About`],
/// is in its registry row).
pub trait Descriptor: Sync + Send {
    /// What it offers (default: exact patches only).
    fn capabilities(&self) -> Capabilities {
        Capabilities::PATCHES
    }

    /// Whether the scheme takes the net at all (for front ends that try every scheme on one
    /// net, like the demo); the error names the element it cannot take.
    fn check_input(&self, mesh: &PolyMesh) -> Result<()> {
        let _ = mesh;
        Ok(())
    }

    /// The typed options it takes.
    fn params(&self) -> &'static [ParamKind] {
        &[]
    }

    /// Whole-net refinement with these parameters (`None`: the scheme has no net of its own to
    /// refine).
    fn mesh_rules(&self, spec: &Spec) -> Result<Option<Box<dyn Scheme>>> {
        let _ = spec;
        Ok(None)
    }

    /// Exact patch output with these parameters (`None`: no patch output).
    fn patch_rules(&self, spec: &Spec) -> Result<Option<Box<dyn PatchRules>>> {
        let _ = spec;
        Ok(None)
    }

    /// Whether the scheme's patches join C^1 only up to a per-piece affine reparametrisation
    /// (the bi-2 family, whose polar and adjustable rings shrink differently along and across
    /// their sides), so `check` reports that certificate too.
    fn joins_up_to_scaling(&self) -> bool {
        false
    }

    /// Whether the scheme's patch output (`patch_rules`) honours OpenSubdiv's sharp features
    /// (creases, corners, holes, the boundary options); front ends refuse nets with sharp
    /// features for patch output otherwise.
    fn patches_take_features(&self) -> bool {
        false
    }

    /// The input faces of `mesh` as fan triangles of the faces the patches' domains refer
    /// to, when those differ (`nonbox-4dir` builds its complex on the polygons of a triangle
    /// mesh; [`crate::surface::eval::Surface::of_scheme`]); `None` (the default): the domains
    /// refer to the input faces.
    ///
    /// # Errors
    /// When the scheme cannot read the net.
    fn eval_faces(
        &self,
        spec: &Spec,
        mesh: &PolyMesh,
    ) -> Result<Option<Vec<crate::bezier::domain::FanTriangle>>> {
        let _ = (spec, mesh);
        Ok(None)
    }

    /// What the scheme's rules need of a net for `purpose`, each need with the step that meets
    /// it ([`super::prepare`]; applied by [`super::prepare::prepare`], which front ends call
    /// before the rules); empty (the default): the rules take every net the scheme accepts, or
    /// refuse it with a reason no preparation removes.
    fn preparation(
        &self,
        spec: &Spec,
        purpose: super::needs::Purpose,
    ) -> Vec<super::needs::Requirement> {
        let _ = (spec, purpose);
        Vec::new()
    }

    /// Local rules for analysis with these parameters (`None`: no analysis).
    fn local_rules(&self, spec: &Spec) -> Result<Option<Box<dyn LocalRules>>> {
        let _ = spec;
        Ok(None)
    }

    /// Which rules the scheme uses at valence `n` with these parameters, for schemes whose
    /// rules differ in origin from valence to valence (printed, derived, regular, fallback);
    /// `None`: the scheme has one kind of rules for every valence it takes.
    fn valence_rules(&self, spec: &Spec, n: usize) -> Option<ValenceRules> {
        let _ = (spec, n);
        None
    }
}
