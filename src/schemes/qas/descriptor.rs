//! The descriptors of QAS+ and its variants: exact patches (caps of bi-4 or bi-3 rings on
//! Catmull-Clark nets) and local analysis. QAS+ has no control net of its own to refine.

use super::surface::{Contraction, qas_bi3_complex, qas_complex_with};
use crate::bezier::BezierPatch;
use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::schemes::descriptor::{
    Capabilities, ComplexOptions, Computed, Descriptor, ExtraFacts, LocalRules, ParamKind,
    PatchRules, Published, Spec, SurfaceOutput,
};
use crate::schemes::eg::surface::EgOptions;
use crate::schemes::local::LocalMatrix;

/// Which QAS+ variant.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum QasVariant {
    /// QAS+^4, contraction 1/2.
    Bi4,
    /// QAS+^3 (bi-3 rings through T_3^4), contraction 1/2.
    Bi3,
    /// QAS+^4 with lambda 0.4.
    Fixed04,
    /// QAS+^4 with the gradual schedule 0.5 .. 0.4.
    Gradual,
}

/// A QAS+ scheme.
#[derive(Debug)]
pub struct QasDescriptor {
    /// The variant.
    pub variant: QasVariant,
}

/// The registry's QAS+ row.
pub static DESCRIPTOR: QasDescriptor = QasDescriptor {
    variant: QasVariant::Bi4,
};
/// The registry's QAS+^3 row.
pub static DESCRIPTOR_BI3: QasDescriptor = QasDescriptor {
    variant: QasVariant::Bi3,
};
/// The registry's QAS_0.4 row.
pub static DESCRIPTOR_04: QasDescriptor = QasDescriptor {
    variant: QasVariant::Fixed04,
};
/// The registry's QAS_{0.5,0.4} row.
pub static DESCRIPTOR_05_04: QasDescriptor = QasDescriptor {
    variant: QasVariant::Gradual,
};

impl Descriptor for QasDescriptor {
    fn capabilities(&self) -> Capabilities {
        Capabilities {
            refine: false,
            patches: true,
        }
    }

    fn params(&self) -> &'static [ParamKind] {
        match self.variant {
            QasVariant::Bi3 => &[ParamKind::Fallback],
            _ => &[ParamKind::Fallback, ParamKind::QFile],
        }
    }

    fn patch_rules(&self, spec: &Spec) -> Result<Option<Box<dyn PatchRules>>> {
        Ok(Some(Box::new(QasPatchRules {
            variant: self.variant,
            spec: spec.clone(),
        })))
    }

    fn local_rules(&self, _: &Spec) -> Result<Option<Box<dyn LocalRules>>> {
        Ok((self.variant != QasVariant::Gradual).then(|| {
            Box::new(QasLocal {
                variant: self.variant,
            }) as Box<dyn LocalRules>
        }))
    }
}

impl QasVariant {
    /// The contraction schedule of the variant.
    pub fn contraction(self) -> Contraction {
        match self {
            QasVariant::Bi4 | QasVariant::Bi3 => Contraction::Half,
            QasVariant::Fixed04 => Contraction::Fixed(0.4),
            QasVariant::Gradual => Contraction::Gradual,
        }
    }
}

/// QAS+'s exact surface: Catmull-Clark's adaptive loop with QAS+ caps (EG's at valence 3).
struct QasPatchRules {
    variant: QasVariant,
    spec: Spec,
}

impl PatchRules for QasPatchRules {
    fn build(
        &self,
        mesh: &PolyMesh,
        opts: ComplexOptions,
        progress: &mut dyn FnMut(usize),
    ) -> Result<SurfaceOutput> {
        let o = EgOptions {
            rings: opts.rings,
            fill: opts.fill,
            fallback: self.spec.params.fallback,
        };
        let c = self.variant.contraction();
        match self.variant {
            QasVariant::Bi3 => qas_bi3_complex(mesh, o, c, progress),
            _ => qas_complex_with(mesh, o, c, self.spec.params.q_overrides.clone(), progress),
        }
    }
}

/// QAS+'s local analysis (the gradual schedule has no stationary matrix).
struct QasLocal {
    variant: QasVariant,
}

impl QasLocal {
    fn lambda(&self) -> f64 {
        match self.variant {
            QasVariant::Fixed04 => 0.4,
            _ => 0.5,
        }
    }
}

impl LocalRules for QasLocal {
    fn matrix(&self, n: usize) -> Result<LocalMatrix> {
        match self.variant {
            QasVariant::Bi3 => super::local::local_matrix_bi3(n, self.lambda()),
            _ => super::local::local_matrix(n, self.lambda()),
        }
    }

    /// The paper's chi of Section 3 (n = 5..10), for QAS+^4.
    fn characteristic_ring(&self, n: usize) -> Result<(Vec<BezierPatch>, f64)> {
        match self.variant {
            QasVariant::Bi4 => super::local::characteristic_ring(n),
            _ => Err(crate::error::Error::Unsupported(format!(
                "valence {n}: the characteristic map of Section 3 is QAS+^4's"
            ))),
        }
    }

    fn published(&self, n: usize, _: &Computed<'_>) -> Result<Vec<Published>> {
        let rho = super::facts::rho_md_of_printed(n).filter(|_| self.variant == QasVariant::Bi4);
        let Some(p) = rho else {
            return Ok(Vec::new());
        };
        let f = super::local::facts(n, self.lambda())?;
        Ok(vec![Published::new(
            "spectral radius of M_d (papers README, from the K layout; paper: < 0.13621)",
            p,
            f.m_d_spectral_radius,
        )])
    }

    fn extra(&self, n: usize) -> Result<Option<ExtraFacts>> {
        let q = match self.variant {
            QasVariant::Bi3 => super::local::facts_bi3(n, self.lambda())?,
            _ => super::local::facts(n, self.lambda())?,
        };
        let lines = vec![format!(
            "QAS+: spectral radius of M_d {:.6}; M_q eigenvalues: C^2 {:?}, C^1 {} values, C^1-C^0 {} values (all 1, 1/2 x2, then 1/4)",
            q.m_d_spectral_radius,
            q.m_q_c2
                .iter()
                .map(|x| format!("{x:.4}"))
                .collect::<Vec<_>>(),
            q.m_q_c1.len(),
            q.m_q_c1c0.len()
        )];
        Ok(Some(ExtraFacts {
            key: "qas",
            value: serde_json::to_value(&q).expect("serialisable"),
            lines,
        }))
    }
}
