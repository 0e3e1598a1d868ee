//! Patch stencil tables: the sparse linear map from the control points of a net to every Bezier
//! coefficient of its exact patch complex, built once and re-applied to moved control points
//! (animation, shape optimisation) without redoing the construction.
//!
//! Every scheme in fairsub is linear in its control points: each coefficient of the complex
//! `subdivide --rings K` writes is a fixed affine combination of the net's points. A
//! [`PatchTable`] holds these combinations as one [`StencilTable`] (one row per coefficient, in
//! the complex's patch order, `b[i][j]` of a patch at row `first + i * (deg_v + 1) + j`).
//!
//! # Where the table comes from: the construction itself
//!
//! The table is read off the scheme's own construction ([`crate::surface::build`], the code
//! that writes the patches), never from a second copy of its rules: [`PatchTable::build`]
//! runs the construction on the net with its points displaced, one colour class of points at a
//! time (points of one class are far enough apart in the net that no coefficient depends on two
//! of them), and reads each coefficient's weights off the differences; [`probe`] documents the
//! encoding. The result is then checked: applied to the net's points it must give the
//! construction's complex, and applied to randomly moved points the complex the construction
//! computes from them (else the build fails, naming the deviation). So one mechanism serves
//! every scheme, present and future, and the table is exact to rounding.
//!
//! # Steps that are not linear
//!
//! * **G^1 caps** ([`crate::bezier::g1`]) fit their spoke tangents in the limit tangent plane,
//!   whose normal is a cross product of two linear vectors, and project onto it: not linear in
//!   the points (and not the same map for x, y, z). The complex records each cap as a
//!   [`CapStep`] (hole data and two plane vectors, all linear); the table tabulates those data
//!   and repeats the cap itself ([`crate::bezier::g1::ring::cap_in_plane`], the same code) at
//!   [`PatchTable::apply`], which costs one small matrix product per cap.
//! * **Geometry-dependent branches.** The construction's structure (which elements get a G^1
//!   cap and which a C^0 fill, the cap's compatibility check) is decided on the net's points;
//!   the table keeps that structure. If moved points would make the construction choose
//!   otherwise, [`PatchTable::apply`] reports the cap that fails (rebuild the table then).
//! * **Non-box's Hermite fill at an extraordinary boundary vertex** takes the edge derivative as
//!   the chord projected onto the limit tangent plane (`nonbox::surface`'s `edge_derivative`):
//!   not linear. The build refuses such a net with an error naming the fill patch (gallery:
//!   `tri-grid`'s corners); everywhere else non-box is linear and tabulated.
//! * **Fixed points given as options** (`--pole FACE:X,Y,Z` of polar-bi2, QAS+'s `--q-file`
//!   expansions) do not move with the net: they make the map affine, and the table carries
//!   their contribution as a constant per coefficient ([`PatchTable::constants`]).
//!
//! # Other per-point data
//!
//! [`PatchTable::apply_data`] maps any per-point data of dimension `d` (colours, texture
//! coordinates with one value per vertex, ...) through the same rows. A G^1 cap there uses the
//! same cap map with spoke tangents fitted in the data's own space
//! ([`crate::bezier::g1::ring::data_tangents`]): only positions have a tangent plane. Data that
//! are not continuous across edges (face-varying values with seams) need their own net.

use crate::bezier::BezierPatch;
use crate::bezier::complex::{CapStep, Domain, PatchComplex, Piece, Provenance};
use crate::bezier::g1::{cap_choice, hole_cap_map, ring};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::stencil::{LayeredTable, StencilTable};
use rows::{Layout, Rows};

mod holes;
pub mod probe;
mod reapply;
mod rows;

use holes::hole_from;
pub(crate) use holes::hole_points;
pub use holes::{HoleShape, TableCap};

/// The sparse map from a net's control points to every Bezier coefficient of its patch complex
/// (see the [module](self) documentation). Two tables are equal when their rows in expanded
/// form ([`PatchTable::rows`]) and everything else are.
#[derive(Debug, Clone)]
pub struct PatchTable {
    /// One row per coefficient of every patch (cap patches: empty rows), then the caps' data
    /// rows; or the same in factored form ([`rows`]).
    rows: Rows,
    /// Per patch `(deg_u, deg_v)`.
    shapes: Vec<(u32, u32)>,
    /// Per patch, its first row (and one past the last patch's rows at the end).
    first_row: Vec<u32>,
    /// Whether each patch is computed by a cap step (its rows are empty).
    in_cap: Vec<bool>,
    /// The caps, in the complex's order.
    caps: Vec<TableCap>,
    /// The part of each row that does not depend on the points (options that fix points);
    /// empty when there is none.
    constants: Vec<Point>,
    /// Provenance of each patch.
    provenance: Vec<Provenance>,
    /// Input-face domain of each patch, where known.
    domains: Vec<Option<Domain>>,
    /// Parts of patches covering several cells, as the complex has them.
    pieces: Vec<Piece>,
    /// Sharp sides, as the complex has them.
    sharp_sides: Vec<(u32, u8)>,
}

impl PatchTable {
    /// Assembles a table from its parts (checked: row counts, cap ranges). `template` gives
    /// the patches' degrees, provenance, domains, sharp sides and caps; `rows` has one row per
    /// coefficient (cap patches' rows empty) followed by the caps' data rows in order.
    pub fn from_parts(
        template: &PatchComplex,
        rows: StencilTable,
        constants: Vec<Point>,
    ) -> Result<PatchTable> {
        Self::assemble(template, Rows::Expanded(rows), constants)
    }

    /// Assembles a table whose rows are factored ([`LayeredTable`]): per patch of `template`
    /// that is not a cap patch (each a bi-3 patch) the 16 rows of its B-spline net, then the
    /// caps' data rows in order. [`PatchTable::apply`] converts each net's points to Bezier
    /// form; [`PatchTable::rows`] expands the rows to one per coefficient when asked.
    ///
    /// # Errors
    /// When a patch that is not a cap patch is not bi-3, or the row counts do not match.
    pub fn from_layered(template: &PatchComplex, rows: LayeredTable) -> Result<PatchTable> {
        Self::assemble(
            template,
            Rows::Nets {
                layered: rows,
                net_first: Vec::new(),
                expanded: std::sync::OnceLock::new(),
            },
            Vec::new(),
        )
    }

    /// [`PatchTable::from_parts`] for either form of rows.
    fn assemble(template: &PatchComplex, rows: Rows, constants: Vec<Point>) -> Result<PatchTable> {
        let mut first_row = Vec::with_capacity(template.len() + 1);
        let mut shapes = Vec::with_capacity(template.len());
        let mut r = 0u64;
        for p in &template.patches {
            first_row.push(r as u32);
            shapes.push((p.deg_u as u32, p.deg_v as u32));
            r += ((p.deg_u + 1) * (p.deg_v + 1)) as u64;
        }
        let mut in_cap = vec![false; template.len()];
        let mut caps = Vec::with_capacity(template.caps.len());
        for step in &template.caps {
            let range = step.first as usize..(step.first + step.count) as usize;
            if range.end > template.len() || in_cap[range.clone()].iter().any(|&c| c) {
                return Err(Error::InvalidArgument(format!(
                    "cap patches {range:?} overlap or lie outside the complex"
                )));
            }
            in_cap[range].iter_mut().for_each(|c| *c = true);
            // the degree and centre the cap map chose depend on the hole's shape only (the
            // template's cap was built from it), so the cap is not built again here
            let (_, _, degree, centre) = cap_choice(&step.hole, step.options)?;
            let cap = TableCap {
                step: step.clone(),
                data_row: r as u32,
                degree,
                centre,
            };
            r += cap.data_len() as u64;
            caps.push(cap);
        }
        if r > u32::MAX as u64 {
            return Err(Error::InvalidArgument(format!("{r} rows")));
        }
        let data = (r - caps.first().map_or(r, |c| c.data_row as u64)) as usize;
        let rows = match rows {
            Rows::Expanded(t) if t.num_rows() as u64 != r => {
                return Err(Error::InvalidArgument(format!(
                    "the table has {} rows, the complex needs {r}",
                    t.num_rows()
                )));
            }
            Rows::Nets { layered, .. } => {
                let n = layered.num_rows();
                let layout = Layout {
                    shapes: &shapes,
                    in_cap: &in_cap,
                };
                Rows::nets(layered, &layout, data).ok_or_else(|| {
                    Error::InvalidArgument(format!(
                        "the factored table's {n} rows are not 16 per bi-3 patch and {data} \
                         cap data rows"
                    ))
                })?
            }
            rows => rows,
        };
        if !constants.is_empty() && constants.len() as u64 != r {
            return Err(Error::InvalidArgument(format!(
                "{} constants for {r} rows",
                constants.len(),
            )));
        }
        first_row.push(caps.first().map_or(r as u32, |c| c.data_row));
        Ok(PatchTable {
            rows,
            shapes,
            first_row,
            in_cap,
            caps,
            constants,
            provenance: template.provenance.clone(),
            domains: template.domains.clone(),
            pieces: template.pieces.clone(),
            sharp_sides: template.sharp_sides.clone(),
        })
    }

    /// Builds the table of the complex `surface::build(spec, mesh, opts)` writes (see
    /// [`probe`]).
    ///
    /// # Errors
    /// Whatever the construction reports; [`Error::Unsupported`] when the construction is not
    /// linear in the points or changes its structure under displacement (naming what differs).
    pub fn build(
        spec: &crate::schemes::Spec,
        mesh: &crate::mesh::PolyMesh,
        opts: super::ComplexOptions,
    ) -> Result<PatchTable> {
        Self::build_with(spec, mesh, opts).map(|(_, t)| t)
    }

    /// The complex `surface::build(spec, mesh, opts)` writes and its table: tracked beside the
    /// points where the scheme tracks every step it takes ([`PatchTable::tracked`]), else
    /// probed ([`PatchTable::build_probed`]).
    ///
    /// # Errors
    /// As [`PatchTable::build`].
    pub fn build_with(
        spec: &crate::schemes::Spec,
        mesh: &crate::mesh::PolyMesh,
        opts: super::ComplexOptions,
    ) -> Result<(PatchComplex, PatchTable)> {
        if let Some(built) = Self::tracked(spec, mesh, opts)? {
            return Ok(built);
        }
        let complex = super::build(spec, mesh, opts, &mut |_| {})?.complex;
        let table = probe::build_from(mesh, &complex, &|m| {
            super::build(spec, m, opts, &mut |_| {}).map(|o| o.complex)
        })?;
        Ok((complex, table))
    }

    /// The table read off the construction by [`probe`] (one construction per colour class,
    /// then checked at the net's and at moved points): the reference the tracked tables are
    /// tested against, and the table of every scheme or net without tracking.
    ///
    /// # Errors
    /// As [`PatchTable::build`].
    pub fn build_probed(
        spec: &crate::schemes::Spec,
        mesh: &crate::mesh::PolyMesh,
        opts: super::ComplexOptions,
    ) -> Result<PatchTable> {
        probe::build(mesh, &|m| {
            super::build(spec, m, opts, &mut |_| {}).map(|o| o.complex)
        })
    }

    /// The complex and its table with the rows tracked beside the points during the one
    /// construction ([`crate::schemes::descriptor::PatchRules::build_tracked`]: Catmull-Clark, its caps
    /// included; not its Hermite-Coons fill, nor the cap schemes), or `None` where the scheme
    /// does not track every step it takes for this net, or `FAIRSUB_TABLE_PROBE` is set (the
    /// probe's table then). With `FAIRSUB_TABLE_CHECK` set, the tracked table is compared with
    /// the probed one (relative `1e-12`) and the build fails on a difference.
    ///
    /// # Errors
    /// As [`PatchTable::build`].
    pub fn tracked(
        spec: &crate::schemes::Spec,
        mesh: &crate::mesh::PolyMesh,
        opts: super::ComplexOptions,
    ) -> Result<Option<(PatchComplex, PatchTable)>> {
        if std::env::var_os("FAIRSUB_TABLE_PROBE").is_some() {
            return Ok(None);
        }
        let descriptor = crate::schemes::registry::registry().descriptor(spec.id);
        // a prepared net's table holds the preparation's stencils too: probed
        if super::prepare(spec, mesh)?.changed() {
            return Ok(None);
        }
        let Some(rules) = descriptor.patch_rules(spec)? else {
            return Err(super::no_patch_output(spec.name()));
        };
        let Some((out, rows)) = rules.build_tracked(mesh, opts)? else {
            return Ok(None);
        };
        let table = PatchTable::from_layered(&out.complex, rows)?;
        if std::env::var_os("FAIRSUB_TABLE_CHECK").is_some() {
            let probed = probe::build_from(mesh, &out.complex, &|m| {
                super::build(spec, m, opts, &mut |_| {}).map(|o| o.complex)
            })?;
            let d = table.rows_deviation(&probed);
            if d > 1e-12 {
                return Err(Error::Unsupported(format!(
                    "the tracked patch table differs from the probed one by {d:.3e}"
                )));
            }
        }
        Ok(Some((out.complex, table)))
    }

    /// The largest difference between the weights of two tables of one layout (relative to the
    /// largest weight; infinite when their rows or caps differ in number).
    pub fn rows_deviation(&self, other: &PatchTable) -> f64 {
        let (a, b) = (self.rows(), other.rows());
        if a.num_rows() != b.num_rows() || self.caps.len() != other.caps.len() {
            return f64::INFINITY;
        }
        let (mut worst, mut scale) = (0.0f64, 0.0f64);
        let mut acc: std::collections::HashMap<u32, f64> = std::collections::HashMap::new();
        for r in 0..a.num_rows() {
            acc.clear();
            let (i, w) = a.row(r);
            for (&i, &w) in i.iter().zip(w) {
                *acc.entry(i).or_default() += w;
                scale = scale.max(w.abs());
            }
            let (i, w) = b.row(r);
            for (&i, &w) in i.iter().zip(w) {
                *acc.entry(i).or_default() -= w;
            }
            worst = acc.values().fold(worst, |m, d| m.max(d.abs()));
        }
        worst / scale.max(f64::MIN_POSITIVE)
    }

    /// Number of control points the table reads.
    pub fn num_sources(&self) -> usize {
        self.rows.num_sources()
    }

    /// The shapes and cap flags of the patches, as the rows see them.
    fn layout(&self) -> Layout<'_> {
        Layout {
            shapes: &self.shapes,
            in_cap: &self.in_cap,
        }
    }

    /// The factored rows of a tracked Catmull-Clark table (per bi-3 patch its net's 16 rows,
    /// then the caps' data rows, over a stack of refinement levels), `None` for a table of
    /// expanded rows.
    pub fn layered(&self) -> Option<&LayeredTable> {
        match &self.rows {
            Rows::Nets { layered, .. } => Some(layered),
            Rows::Expanded(_) => None,
        }
    }

    /// Number of patches.
    pub fn num_patches(&self) -> usize {
        self.shapes.len()
    }

    /// The rows: one per coefficient in patch order (empty for cap patches), then the caps'
    /// data rows (a factored table composes them on the first call: the cost of the old
    /// tracking, paid only by readers that want this form).
    pub fn rows(&self) -> &StencilTable {
        self.rows.expanded(&self.layout())
    }

    /// `(deg_u, deg_v)` of each patch.
    pub fn shapes(&self) -> &[(u32, u32)] {
        &self.shapes
    }

    /// The first row of each patch's coefficients.
    pub fn first_row(&self, patch: usize) -> usize {
        self.first_row[patch] as usize
    }

    /// Whether patch `p` is computed by a G^1 cap step.
    pub fn is_cap_patch(&self, p: usize) -> bool {
        self.in_cap[p]
    }

    /// The G^1 caps the table repeats.
    pub fn caps(&self) -> &[TableCap] {
        &self.caps
    }

    /// The constant part of each row (empty when the map is linear).
    pub fn constants(&self) -> &[Point] {
        &self.constants
    }

    /// Provenance of each patch.
    pub fn provenance(&self) -> &[Provenance] {
        &self.provenance
    }

    /// Input-face domain of each patch, where known (may be shorter than the patches).
    pub fn domains(&self) -> &[Option<Domain>] {
        &self.domains
    }

    /// The parts of patches that cover several cells ([`PatchComplex::pieces`]).
    pub fn pieces(&self) -> &[Piece] {
        &self.pieces
    }

    /// Sharp sides of the complex.
    pub fn sharp_sides(&self) -> &[(u32, u8)] {
        &self.sharp_sides
    }

    /// Bytes held by the rows (the factored form without its expanded copy).
    pub fn heap_bytes(&self) -> usize {
        self.rows.heap_bytes() + 24 * self.constants.len() + 16 * self.shapes.len()
    }

    /// The complex of the control points `points` (one per source, as the net was read by the
    /// scheme): the same patches, degrees, provenance and domains as the construction's.
    ///
    /// # Errors
    /// When `points` has the wrong length, or a G^1 cap cannot be built for the moved points
    /// (the construction would then take another branch: rebuild the table).
    pub fn apply(&self, points: &[Point]) -> Result<PatchComplex> {
        let (mut patches, data) = self.values(points)?;
        self.build_caps(&data, &mut patches)?;
        Ok(self.complex_of(patches, &data))
    }

    /// An error unless `points` has one point per source.
    fn check_points(&self, points: &[Point]) -> Result<()> {
        if points.len() != self.num_sources() {
            return Err(Error::InvalidArgument(format!(
                "the table takes {} points, not {}",
                self.num_sources(),
                points.len()
            )));
        }
        Ok(())
    }

    /// Where cap `cap`'s data start in the caps' data values.
    fn data_index(&self, cap: &TableCap) -> usize {
        (cap.data_row - self.first_row[self.num_patches()]) as usize
    }

    /// The rows applied to `points` (plus the constants): the patches (cap patches empty) and
    /// the caps' data values.
    fn values(&self, points: &[Point]) -> Result<(Vec<BezierPatch>, Vec<Point>)> {
        self.check_points(points)?;
        if self.constants.is_empty() {
            return Ok(self.rows.values(&self.layout(), points));
        }
        // constants come with expanded rows only (probed tables)
        let mut vals = self.rows().apply(points);
        for (v, c) in vals.iter_mut().zip(&self.constants) {
            *v = crate::geom::add(*v, *c);
        }
        let (patches, data0) = rows::expanded_patches(&self.layout(), &vals);
        Ok((patches, vals[data0..].to_vec()))
    }

    /// Puts the patches of cap `k` in place, checking their degrees against the table's.
    fn place_cap(
        &self,
        k: usize,
        cap: &TableCap,
        mut built: Vec<BezierPatch>,
        patches: &mut [BezierPatch],
    ) -> Result<()> {
        if let Some(kept) = &cap.step.kept {
            // a partly kept cap: built whole, its kept sectors placed
            built = holes::kept_sectors(built, kept)
                .ok_or_else(|| Error::Unsupported(format!("cap {k} now lacks a kept sector")))?;
        }
        if built.len() != cap.step.count as usize {
            return Err(Error::Unsupported(format!(
                "cap {k} now has {} patches, the table {}",
                built.len(),
                cap.step.count
            )));
        }
        for (i, p) in built.into_iter().enumerate() {
            let at = cap.step.first as usize + i;
            if self.shapes[at] != (p.deg_u as u32, p.deg_v as u32) {
                return Err(Error::Unsupported(format!(
                    "cap {k} now has degree ({}, {}), the table ({}, {})",
                    p.deg_u, p.deg_v, self.shapes[at].0, self.shapes[at].1
                )));
            }
            patches[at] = p;
        }
        Ok(())
    }

    /// The complex of the patches with the table's provenance, domains, sharp sides and caps
    /// (their data from `vals`).
    fn complex_of(&self, patches: Vec<BezierPatch>, data: &[Point]) -> PatchComplex {
        let caps = self.cap_steps(data);
        PatchComplex {
            patches,
            provenance: self.provenance.clone(),
            sharp_sides: self.sharp_sides.clone(),
            domains: self.domains.clone(),
            pieces: self.pieces.clone(),
            caps,
            // the construction's notes on holes without a cap are not repeated
            uncapped: Vec::new(),
        }
    }

    /// The caps' steps with their holes and planes from the caps' data values `data`.
    fn cap_steps(&self, data: &[Point]) -> Vec<CapStep> {
        self.caps
            .iter()
            .map(|cap| {
                let r = self.data_index(cap);
                let (hole, plane) =
                    hole_from(&data[r..r + cap.data_len()], &cap.shape(), &cap.step.hole);
                CapStep {
                    hole,
                    plane,
                    ..cap.step.clone()
                }
            })
            .collect()
    }

    /// Per-point data of dimension `d` (`data[i * d .. (i + 1) * d]` for point `i`) mapped to
    /// every patch: per patch its `(deg_u + 1) (deg_v + 1)` coefficients of dimension `d`, row
    /// major. G^1 caps apply the construction's cap map with spoke tangents from the data
    /// ([`ring::data_tangents`]; no tangent plane, no compatibility check: the data's ring is
    /// compatible because the positions' is, the map being the same); the constants of fixed
    /// points are not added (they are positions).
    ///
    /// # Errors
    /// When the data do not hold `d` values per point, or a cap's map cannot be applied.
    pub fn apply_data(&self, data: &[f64], d: usize) -> Result<Vec<Vec<f64>>> {
        if d == 0 || data.len() != d * self.num_sources() {
            return Err(Error::InvalidArgument(format!(
                "the table takes {} points of dimension {d}: {} values, not {}",
                self.num_sources(),
                d * self.num_sources(),
                data.len()
            )));
        }
        let chunks = d.div_ceil(3);
        let mut out: Vec<Vec<f64>> = self
            .shapes
            .iter()
            .map(|&(du, dv)| vec![0.0; ((du + 1) * (dv + 1)) as usize * d])
            .collect();
        for c in 0..chunks {
            let w = (d - 3 * c).min(3);
            let pts: Vec<Point> = (0..self.num_sources())
                .map(|i| {
                    let mut p = [0.0; 3];
                    p[..w].copy_from_slice(&data[i * d + 3 * c..i * d + 3 * c + w]);
                    p
                })
                .collect();
            let (mut patches, data) = self.rows.values(&self.layout(), &pts);
            for (k, cap) in self.caps.iter().enumerate() {
                let r = self.data_index(cap);
                let (mut hole, plane) =
                    hole_from(&data[r..r + cap.data_len()], &cap.shape(), &cap.step.hole);
                hole.tangents = ring::hole_data_tangents(&hole, plane)?;
                let map = hole_cap_map(&hole, cap.degree, cap.centre)?;
                let built = map.apply(&hole).map_err(|e| cap_failed(k, cap, e))?;
                self.place_cap(k, cap, built, &mut patches)?;
            }
            for (o, p) in out.iter_mut().zip(&patches) {
                for (i, q) in p.cps.iter().enumerate() {
                    o[i * d + 3 * c..i * d + 3 * c + w].copy_from_slice(&q[..w]);
                }
            }
        }
        Ok(out)
    }
}

impl PartialEq for PatchTable {
    fn eq(&self, other: &PatchTable) -> bool {
        self.rows() == other.rows()
            && self.shapes == other.shapes
            && self.first_row == other.first_row
            && self.in_cap == other.in_cap
            && self.caps == other.caps
            && self.constants == other.constants
            && self.provenance == other.provenance
            && self.domains == other.domains
            && self.pieces == other.pieces
            && self.sharp_sides == other.sharp_sides
    }
}

/// The error of a cap that cannot be repeated for moved points.
fn cap_failed(k: usize, cap: &TableCap, e: Error) -> Error {
    Error::Unsupported(format!(
        "the G^1 cap {k} (patches {}..{}) cannot be built for these points ({e}); the \
         construction would take another branch here: build the table again",
        cap.step.first,
        cap.step.first + cap.step.count
    ))
}
