//! Derived QAS+ tables against the printed ones (Appendix C: `K^5..K^7`, `T_5..T_8`), in units
//! of 10^-5. Spectra (`rho(M_d)`) need the analysis layer and are compared in
//! `tests/it/derive.rs` and `examples/derived_rules.rs` against [`crate::schemes::qas::facts`].

use super::super::{QasRules, tables};
use super::derived_rules;
use crate::error::Result;
use crate::schemes::eg::derive::compare::{TableDeviation, median};
use serde::Serialize;

/// The comparison of the derived tables of one valence with the paper.
#[derive(Debug, Clone, Serialize)]
pub struct QasComparison {
    /// Valence.
    pub n: usize,
    /// The construction.
    pub construction: String,
    /// `K_11 .. K_32` (n = 5..7) and `T_n` (n = 5..8) that the paper prints.
    pub tables: Vec<TableDeviation>,
    /// Largest deviation over the printed K entries (units of 10^-5).
    pub k_max_e5: f64,
    /// Median deviation over the printed K entries.
    pub k_median_e5: f64,
    /// Largest deviation over the printed T entries.
    pub t_max_e5: f64,
    /// Median deviation over the printed T entries.
    pub t_median_e5: f64,
    /// The published bound on `rho(M_d)` when `n` is in 5..=10.
    pub published_rho_bound: Option<f64>,
    /// `rho(M_d)` of the printed tables (computed; see the facts' source).
    pub rho_of_printed: Option<f64>,
}

fn deviation(name: String, derived: &[f64], printed: &[i32], rows: usize) -> TableDeviation {
    let mut d: Vec<f64> = derived
        .iter()
        .zip(printed)
        .map(|(x, &p)| (x * 1e5 - p as f64).abs())
        .collect();
    let max = d.iter().copied().fold(0.0, f64::max);
    TableDeviation {
        table: name,
        rows: (0..rows).map(|r| (r, r)).collect(),
        entries: d.len(),
        max_e5: max,
        median_e5: median(&mut d),
        closest_row: None,
        note: None,
    }
}

/// Compares given tables with the paper at their valence.
pub fn compare_tables(r: &QasRules, construction: &str) -> QasComparison {
    let n = r.n;
    let mut out = QasComparison {
        n,
        construction: construction.into(),
        tables: Vec::new(),
        k_max_e5: 0.0,
        k_median_e5: 0.0,
        t_max_e5: 0.0,
        t_median_e5: 0.0,
        published_rho_bound: super::super::facts::BOUND_VALENCES
            .contains(&n)
            .then_some(super::super::facts::RHO_MD_BOUND),
        rho_of_printed: super::super::facts::rho_md_of_printed(n),
    };
    let t_printed = match n {
        5 => Some(&tables::T5),
        6 => Some(&tables::T6),
        7 => Some(&tables::T7),
        8 => Some(&tables::T8),
        _ => None,
    };
    let mut kall = Vec::new();
    if let Some((_, k4, k3)) = tables::printed(n) {
        for (m, name) in ["11", "22", "21", "12"].iter().enumerate() {
            let d: Vec<f64> = r.k4[m].iter().flatten().copied().collect();
            let p: Vec<i32> = k4[m].iter().flatten().copied().collect();
            let t = deviation(format!("K_{name}^{n}"), &d, &p, 5);
            kall.extend(d.iter().zip(&p).map(|(x, &y)| (x * 1e5 - y as f64).abs()));
            out.tables.push(t);
        }
        for (m, name) in ["31", "32"].iter().enumerate() {
            let d: Vec<f64> = r.k3[m].iter().flatten().copied().collect();
            let p: Vec<i32> = k3[m].iter().flatten().copied().collect();
            kall.extend(d.iter().zip(&p).map(|(x, &y)| (x * 1e5 - y as f64).abs()));
            out.tables
                .push(deviation(format!("K_{name}^{n}"), &d, &p, 5));
        }
    }
    if let Some(tp) = t_printed {
        let d: Vec<f64> = r.tau.iter().flatten().copied().collect();
        let p: Vec<i32> = tp.iter().flatten().copied().collect();
        let t = deviation(format!("T_{n}"), &d, &p, 6);
        out.t_max_e5 = t.max_e5;
        out.t_median_e5 = t.median_e5;
        out.tables.push(t);
    }
    out.k_max_e5 = kall.iter().copied().fold(0.0, f64::max);
    out.k_median_e5 = median(&mut kall);
    out
}

/// The comparison of the cached default derivation at valence `n` (3..=16) with the paper.
pub fn qas_comparison(n: usize) -> Result<QasComparison> {
    Ok(compare_tables(derived_rules(n)?, DESCRIPTION))
}

/// The default construction in one line.
pub const DESCRIPTION: &str = "qas-plus-derived: Section 3 chi (F_4), local bi-5 guide per sector with the q^s centre, \
L-net interpolation, F_4 on the unit square, ray nodes averaged with the mirror";
