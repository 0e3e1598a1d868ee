//! The descriptors of guided subdivision's ring variants: exact patches (caps of rings sampled
//! from a guide, on Catmull-Clark nets) and local analysis. The guide degree and the contraction
//! are typed parameters (name suffixes `-g4`, `-g3`, `-half`; `--lambda 0.5`).

use super::rings::{GuidedOptions, RingDegree};
use super::surface::{GuidedComplexOptions, guided_complex};
use crate::bezier::BezierPatch;
use crate::error::Result;
use crate::schemes::descriptor::{
    Capabilities, Computed, Descriptor, LocalRules, ParamKind, PatchRules, Published, Spec,
    patch_fn,
};
use crate::schemes::local::{LocalMatrix, LocalOperator};

/// A guided scheme of one ring degree.
#[derive(Debug)]
pub struct GuidedDescriptor {
    /// Degree (or macro-patch layout) of the rings.
    pub ring: RingDegree,
}

/// The registry's guided bi-5 row.
pub static BI5: GuidedDescriptor = GuidedDescriptor {
    ring: RingDegree::Bi5,
};
/// The registry's guided bi-6 row.
pub static BI6: GuidedDescriptor = GuidedDescriptor {
    ring: RingDegree::Bi6,
};
/// The registry's guided bi-4 macro-patch row.
pub static BI4_MACRO: GuidedDescriptor = GuidedDescriptor {
    ring: RingDegree::Bi4Macro,
};
/// The registry's guided bi-3 macro-patch row.
pub static BI3_MACRO: GuidedDescriptor = GuidedDescriptor {
    ring: RingDegree::Bi3Macro,
};

impl Descriptor for GuidedDescriptor {
    /// Sharp features: as Catmull-Clark's host refines them (its rings and cap next to them).
    fn patches_take_features(&self) -> bool {
        true
    }

    /// Exact patches and evaluation: the rings and caps tile each sector's face in the c-net
    /// chart ([`super::surface`]'s parameter domain); the macro-patch variants' pieces and
    /// split caps cover the 2 x 2 quarters (bi-4) or 3 x 3 thirds (bi-3) of those squares.
    fn capabilities(&self) -> Capabilities {
        Capabilities::PATCHES_AND_EVAL
    }

    fn params(&self) -> &'static [ParamKind] {
        &[ParamKind::Fallback, ParamKind::Contraction]
    }

    /// Catmull-Clark's adaptive loop with guided caps.
    fn patch_rules(&self, spec: &Spec) -> Result<Option<Box<dyn PatchRules>>> {
        let (scheme, fallback) = (self.options(spec), spec.params.fallback);
        patch_fn(move |mesh, opts, progress| {
            guided_complex(
                mesh,
                GuidedComplexOptions {
                    rings: opts.rings,
                    cap: opts.fill,
                    scheme,
                    fallback,
                },
                progress,
            )
        })
    }

    fn local_rules(&self, spec: &Spec) -> Result<Option<Box<dyn LocalRules>>> {
        Ok(Some(Box::new(GuidedLocal {
            options: self.options(spec),
        })))
    }
}

impl GuidedDescriptor {
    /// The guided options a spec selects: this row's ring degree, the guide degree and
    /// characteristic map of the parameters.
    pub fn options(&self, spec: &Spec) -> GuidedOptions {
        GuidedOptions {
            ring: self.ring,
            guide: spec.params.guide.unwrap_or_default(),
            chi: spec.params.chi.unwrap_or_default(),
            ..GuidedOptions::default()
        }
    }
}

/// Guided subdivision's local analysis: the matrix on the guide's free set `P`.
struct GuidedLocal {
    options: GuidedOptions,
}

impl LocalRules for GuidedLocal {
    fn matrix(&self, n: usize) -> Result<LocalMatrix> {
        let o = self.options;
        super::local::local_matrix(n, o.guide, super::local::lambda(n, o.chi))
    }

    /// The bi-5 guide in the paper's coordinates (valences other than 4).
    fn own_blocks(&self, n: usize) -> bool {
        self.options.guide == super::guide::GuideDegree::Bi5 && n != 4
    }

    /// The dense matrix, or above the dense bound the Fourier blocks of the bi-5 guide's
    /// matrix ([`super::local::operator`]).
    fn operator(&self, n: usize, replicated_centre: bool) -> Result<Box<dyn LocalOperator>> {
        let o = self.options;
        if replicated_centre {
            return Ok(Box::new(self.matrix(n)?.replicated_centre()));
        }
        super::local::operator(n, o.guide, super::local::lambda(n, o.chi))
    }

    fn characteristic_ring(&self, n: usize) -> Result<(Vec<BezierPatch>, f64)> {
        super::local::characteristic_ring(n, self.options)
    }

    /// The matrix acts on the guide's free set `P`, whose first coordinate is the limit point;
    /// its stencil on the c-net (centre, then sector by sector) is the fit's first row (from
    /// the fit's frequency-0 part above the dense bound, [`super::rings::limit_stencil`]).
    fn limit_stencil(&self, n: usize, m: &dyn LocalOperator) -> Result<Vec<f64>> {
        if m.size() > crate::schemes::circulant::dense_rows() {
            return super::rings::limit_stencil(n, self.options).or_else(|_| m.limit_stencil());
        }
        match super::rings::Guided::new(n, self.options) {
            Ok(g) => Ok(g.fit.row(0).iter().copied().collect()),
            Err(_) => m.limit_stencil(),
        }
    }

    fn published(&self, n: usize, c: &Computed<'_>) -> Result<Vec<Published>> {
        let l = super::local::lambda(n, self.options.chi);
        let mut out = vec![Published::new(
            "lambda (Catmull-Clark's, or 1/2 with --lambda 0.5)",
            l,
            c.spectrum.lambda,
        )];
        // Table (5) is for extraordinary valences; at n = 4 (c = 0) the G^2 space is the larger
        // C^2 one (81 coordinates: lambda^3 x6, lambda^4 x9).
        if n != 4 {
            for (s, p, k) in super::local::table5(n, l, &c.matrix.eigenvalues()) {
                out.push(Published::new(
                    format!("multiplicity of lambda^{s} (table (5))"),
                    p as f64,
                    k as f64,
                ));
            }
        }
        Ok(out)
    }
}

/// The guided options a scheme selects (the name `guided-bi6-g4-half` looked up in the
/// registry gives a [`Spec`] with the suffixes' parameters), or `None` for a scheme that is not
/// a guided scheme.
pub fn options_of(spec: &Spec) -> Option<GuidedOptions> {
    use crate::schemes::options::ids;
    let d = match spec.id {
        ids::GUIDED_BI5 => &BI5,
        ids::GUIDED_BI6 => &BI6,
        ids::GUIDED_BI4_MACRO => &BI4_MACRO,
        ids::GUIDED_BI3_MACRO => &BI3_MACRO,
        _ => return None,
    };
    Some(d.options(spec))
}
