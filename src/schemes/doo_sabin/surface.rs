//! Doo-Sabin and DS^CC surfaces as exact patch complexes, by adaptive refinement.
//!
//! Both dual schemes ([`crate::schemes::doo_sabin`]) are uniform bi-2 B-spline refinement where
//! the net is a regular quad grid, so their limit there is the bi-2 B-spline surface of the net:
//! every *regular vertex* is the centre of a 3x3 net and one exact bi-2 patch. A vertex is
//! regular when it is an interior vertex with four quads, a boundary vertex with two quads, or a
//! corner (a boundary vertex with one quad). The patch of a vertex spans the four faces around
//! it: its corners are the faces' limit points (their centroids), the middle coefficients of its
//! sides the midpoints of the vertex's edges, its centre coefficient the vertex itself. The
//! coefficients come from the one B-spline to Bezier table,
//! [`crate::bezier::convert::biquadratic_bspline_stencils`].
//!
//! # Boundaries
//!
//! The boundary rules of [`crate::schemes::doo_sabin`] are bi-2 refinement of the net whose
//! boundary layer is doubled (a phantom copy of every boundary point, four copies of a corner).
//! So a regular boundary vertex's 3x3 net gets its missing row (and a corner's missing row and
//! column) as copies of the boundary row: the patch is the exact limit, its side on the boundary
//! is the quadratic B-spline of the boundary polygon (Chaikin's limit), the cross-boundary
//! derivative vanishes there (the doubled layer) and a corner patch interpolates its corner.
//! `u` runs along the outgoing boundary edge of the vertex, `v` into the surface.
//!
//! # Extraordinary elements, rings and layout
//!
//! The extraordinary elements of a dual scheme are facets with `n != 4` sides and vertices whose
//! neighbourhood is not regular (interior valence `n != 4`, boundary vertices with more than two
//! faces). A vertex that is not regular is refined with the scheme's own rules
//! ([`crate::schemes::doo_sabin::corner_point_stencil`], the Chaikin boundary points, kept
//! corners) together with the faces around it only (the rules are that local); its children
//! (one corner point per face, plus its Chaikin points and kept corner on the boundary) tile
//! its patch's region. Children that are regular are emitted as ring `l` at level `l`, the
//! others are refined again. After one step every interior vertex has four faces (boundary
//! vertices two, corners one), and every non-quad
//! face of level `l >= 1` descends from one input element: the F-face of an input n-gon
//! (`Element::Face`) or the V-face of an input vertex (`Element::Vertex`).
//!
//! Layout (tested): the ring at level `l` consists of the bi-2 patches of the level-`l`
//! vertices around the level-`l` n-gon that became regular at level `l`. Around an isolated
//! n-gon facet every corner of the n-gon has three regular children, so ring `l` holds `3 n`
//! patches for `l = 1 ..= K`, sector `s` (= corner `s` of the n-gon) three of them. An input
//! vertex of valence `n` becomes the n-gon V-face at level 1 that covers the same region, so
//! its ring 1 is empty and rings `2 ..= K` hold `3 n` patches each. Ring numbers equal
//! refinement levels, so patches of ring `l` have parameter size `2^-l` for every element. A
//! vertex next to several n-gons is attributed to the first one around it.
//!
//! # The centroid fill (fairsub's own, documented construction)
//!
//! After `K` levels each vertex still marked (a corner of a level-`K` n-gon) gets one bi-2
//! patch: the bi-2 conversion of its 3x3 net with the corner coefficient of every non-quad face
//! replaced by that face's centroid, which is the scheme's exact limit point of the facet
//! ([`crate::schemes::doo_sabin::face_limit_stencils`]). On quads this is the exact patch, so a
//! fill patch differs from the bi-2 B-spline only at the n-gon's centre. Every side of every
//! patch (regular or fill) is `centroid, edge midpoint, centroid` of the edge it crosses, so the
//! complex is C^0 by construction. Across the sides to the last ring the fill is C^1 (the
//! B-spline identities hold there because the faces on both sides are quads); across the spokes
//! between two fill patches the cross-derivatives agree at the outer end and differ by a term
//! `B^2_0(t)` that is largest at the centre, where all fill patches meet at the limit point of
//! the facet with tangents towards the n-gon's edge midpoints (a tangent plane exactly when the
//! level-`K` n-gon is planar, always for `n = 3`). `--rings 0` fills an n-gon facet the same
//! way but cannot fill an extraordinary vertex (its region is n-sided): that is an error naming
//! the vertex. `--no-fill` leaves the holes open.
//!
//! # The G^1 cap
//!
//! Where the hole of an element has complete ring data (every corner of the last level's
//! n-gon is interior, touches no other n-gon, and its outer neighbours are ring vertices), the
//! fill patches of the n-gon's corners are replaced by the G^1 cap of [`crate::bezier::g1`],
//! centred at the facet's limit point with the limit tangent plane: conditions, free
//! parameters and the extra levels that separate touching holes in `g1`. Only the other
//! elements keep the centroid fill above.
//!
//! # Face domains (evaluation)
//!
//! The patch of an input vertex covers the quarter of each of its faces at it (four at an
//! interior vertex; at a regular boundary vertex two, or one at a corner, the rest of its
//! patch lying in the doubled boundary layer beyond the boundary edges, over no face):
//! `emit` records them as [`Piece`]s of the patch. Every later vertex lies in one cell of
//! an input face, kept in its tag (`rot`: the corner of its patch's `(0, 0)`), and its children
//! get the cell's quarters (`refine::child_domain`); the fill and the G^1 cap sectors cover
//! their vertex's cell. The layout is in [`crate::bezier::domain`]. An input boundary vertex
//! that is refined (an extraordinary boundary element, or next to one) hands the quarters of
//! its faces to its corner points like an interior vertex; its Chaikin points and kept corner
//! lie beyond the faces' boundary edges (knot lines inside the surface), over no face, and are
//! not tracked.
//!
//! # Boundary modes
//!
//! `edge-only` needs nothing here but [`super::sharp::is_kept_corner`]: a corner that is not
//! kept has a triangle for V-face, an extraordinary element like any other. Under `none`
//! ([`super`]'s boundary modes) each level knows which of its points are rule-free
//! (`Level::rule_free`); a vertex on the boundary, and a regular vertex whose net has a point
//! that is not, writes no patch and is not refined; an element whose last-level corners are
//! not all rule-free gets no G^1 cap, and the centroid fill writes the rule-free corners only.
//!
//! # Other dual bi-2 schemes
//!
//! The machinery takes the scheme's rules as a [`DualRules`] value (the stencil of a new corner
//! point, which may read beyond its face, and the limit point of a facet for the fill), so the
//! point-augmented scheme PGS ([`crate::schemes::bi2::pgs`]) reuses it unchanged through
//! [`dual_complex_with`]: its surfaces are laid out exactly like Doo-Sabin's, patch for patch.

use super::fourier::{self, FaceCorners};
use super::{DooSabin, DooSabinCc, corner_point_stencil};
use crate::bezier::complex::{Domain, PatchComplex, Piece, Provenance};
use crate::bezier::convert::biquadratic_bspline_stencils;
use crate::bezier::{BezierPatch, Side};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::host::ComplexOptions;
use crate::host::adaptive::{self, AdaptiveRules, Cells, Info, Sink, Tag, input_vertex_info};
use crate::mesh::tags::BoundaryInterpolation;
use crate::mesh::{Element, PolyMesh};
use crate::schemes::options::ids;
use crate::schemes::sdc::crease::adaptive::{CALM, SPENT_BY_LEVEL, is_last_cap_level_calm};
use crate::stencil::Stencil;
use std::collections::HashMap;

/// The Doo-Sabin surface of `mesh` as a patch complex: bi-2 patches on regular vertices,
/// `opts.rings` rings of bi-2 patches around every extraordinary element and, if `opts.fill`, the
/// centroid fill (see the [module](self) documentation). `progress(level)` is called after each
/// refinement level.
///
/// # Errors
/// [`Error::Unsupported`] for an interior vertex of valence 2, and for an extraordinary vertex
/// with `opts.rings == 0` and `opts.fill`; both name the vertex and the way out.
pub fn doo_sabin_complex(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    let corner = |m: &PolyMesh, h: u32| corner_point_stencil(m, h, DooSabin::weights);
    let rules = DualRules {
        corner: &corner,
        face_corners: &fourier::doo_sabin,
        facet_limit: &centroid_stencil,
    };
    dual_complex_with(mesh, opts, &rules, ids::DOO_SABIN.name(), progress)
}

/// The DS^CC surface of `mesh` as a patch complex, laid out exactly like
/// [`doo_sabin_complex`] (same topology, same regular patches, same fill; only the rings differ
/// through the corner rule).
///
/// # Errors
/// As [`doo_sabin_complex`].
pub fn doo_sabin_cc_complex(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    let corner = |m: &PolyMesh, h: u32| corner_point_stencil(m, h, DooSabinCc::weights);
    let rules = DualRules {
        corner: &corner,
        face_corners: &fourier::doo_sabin_cc,
        facet_limit: &centroid_stencil,
    };
    dual_complex_with(mesh, opts, &rules, ids::DOO_SABIN_CC.name(), progress)
}

/// The rules of a dual (vertex-splitting) bi-2 scheme, as the adaptive refinement of this
/// module needs them. Doo-Sabin, DS^CC and the point-augmented scheme PGS
/// ([`crate::schemes::bi2::pgs`]) share the topology of one step and differ only here.
pub struct DualRules<'a> {
    /// The new point of face corner `h` (a half-edge) as a stencil over the mesh's vertices.
    /// It may read beyond the face (PGS reads the quads across a facet's edges).
    pub corner: &'a (dyn Fn(&PolyMesh, u32) -> Stencil + Sync),
    /// All new corners of face `f` at once as positions, for faces above
    /// [`fourier::LARGE_FACE`]: the same rule as `corner`, in time linear in the face size
    /// (`n` stencils of `n` entries would cost `n^2`).
    pub face_corners: &'a (dyn Fn(&PolyMesh, usize) -> FaceCorners + Sync),
    /// The limit point of a face that is not a quad (the centre of the fill): the centroid for
    /// Doo-Sabin and DS^CC, the point-augmented limit point (7) for PGS.
    pub facet_limit: &'a (dyn Fn(&PolyMesh, usize) -> Stencil + Sync),
}

/// The centroid of face `f` as a stencil: the limit point of a facet under Doo-Sabin and
/// DS^CC.
pub fn centroid_stencil(m: &PolyMesh, f: usize) -> Stencil {
    let face = m.face(f);
    let w = 1.0 / face.len() as f64;
    Stencil::from_pairs(face.iter().map(|&x| (x as usize, w)))
}

/// The nine bi-2 coefficients (row-major, `u` along the vertex's first outgoing half-edge, `v`
/// counter-clockwise from it) of the exact patch of a regular vertex: interior with four quads,
/// on the boundary with two quads, or a corner with one quad (missing rows are copies of the
/// boundary, see the module documentation). `None` for any other vertex. This is the regular
/// patch every bi-2 scheme of fairsub shares (Doo-Sabin, DS^CC, PGS, TPS, polar bi-2).
pub fn regular_vertex_patch(m: &PolyMesh, v: usize) -> Option<Vec<Stencil>> {
    let vn = vertex_net(m, v)?;
    if !vn.ngons.is_empty() {
        return None;
    }
    Some(biquadratic_bspline_stencils(&vn.net))
}

/// The dual-scheme surface of `mesh` under any corner rule: the machinery of
/// [`doo_sabin_complex`] (regular patches, rings, fill) with the rules of `rules`. `name` is
/// the scheme's command-line name, used in error messages.
///
/// # Errors
/// As [`doo_sabin_complex`].
pub fn dual_complex_with(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    rules: &DualRules<'_>,
    name: &str,
    progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    dual_complex(mesh, None, opts, rules, name, progress)
}

/// [`dual_complex_with`] on a net whose vertices' patches cover the cells `cells` of the
/// faces of an earlier net (one per vertex, `rot` the corner of the patch's `(0, 0)`;
/// untracked ones are not evaluated): a net made from that earlier net by whole-net dual
/// steps, whose cells [`step_cells`] gives (PGS after DS^CC steps).
///
/// # Errors
/// As [`doo_sabin_complex`].
pub fn dual_complex_in_cells(
    mesh: &PolyMesh,
    cells: &[Domain],
    opts: ComplexOptions,
    rules: &DualRules<'_>,
    name: &str,
    progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    dual_complex(mesh, Some(cells), opts, rules, name, progress)
}

/// One level of the adaptive refinement.
pub struct Level {
    mesh: PolyMesh,
    info: Vec<Info>,
    /// Input element of every non-quad face.
    face_origin: Vec<Option<Element>>,
    /// Vertices whose patches are still to be produced, with their tags. From level 1 on a
    /// tag's domain is the vertex's cell with `rot` the corner of its patch's `(0, 0)`
    /// ([`crate::bezier::domain`]; untracked for the boundary points, which lie over no face).
    active: Vec<(u32, Tag)>,
    /// Level 0: the input net, whose vertex patches cover quarters of four faces.
    first: bool,
    /// Boundary mode `none` (else `None`): per point, whether it is computed without any
    /// boundary rule (the module's boundary modes).
    rule_free: Option<Vec<bool>>,
    /// Where the level has sharp edges inside the surface (`None`: nowhere): the patches of
    /// the vertices of their faces wait until the crease is spent (fairsub's crease
    /// construction, [`crate::schemes::doo_sabin::sharp`]).
    creased: Option<super::sharp::LevelCreases>,
    /// Levels since the last one with a semi-sharp feature
    /// ([`crate::schemes::sdc::crease::adaptive::calm_after`]).
    calm: usize,
}

impl Level {
    /// A level from its net and bookkeeping; `parent_calm` is the parent level's `calm`
    /// ([`CALM`] for the input net).
    fn new(
        mesh: PolyMesh,
        info: Vec<Info>,
        face_origin: Vec<Option<Element>>,
        active: Vec<(u32, Tag)>,
        rule_free: Option<Vec<bool>>,
        parent_calm: usize,
        first: bool,
    ) -> Level {
        let (creased, calm) = super::sharp::level_creases(&mesh, parent_calm);
        Level {
            mesh,
            info,
            face_origin,
            active,
            first,
            rule_free,
            creased,
            calm,
        }
    }

    /// Whether a face of vertex `v` has a crease: its patch is not final yet.
    fn near_crease(&self, v: usize) -> bool {
        self.creased.as_ref().is_some_and(|c| {
            self.mesh
                .outgoing(v)
                .any(|h| c.faces[self.mesh.he_face(h) as usize])
        })
    }

    /// Whether `v` is an end of a sharp edge inside the surface.
    fn on_crease(&self, v: usize) -> bool {
        self.creased.as_ref().is_some_and(|c| c.vertices[v])
    }
}

impl Cells for Level {
    fn active(&self) -> &[(u32, Tag)] {
        &self.active
    }
}

fn dual_complex(
    mesh: &PolyMesh,
    cells: Option<&[Domain]>,
    opts: ComplexOptions,
    rules: &DualRules<'_>,
    name: &str,
    mut progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    let host = DualHost {
        rules,
        name,
        fill: opts.fill,
        cells,
    };
    adaptive::run(&host, mesh, opts, &mut progress)
}

/// A dual scheme's rules for the adaptive loop: cells are vertices (each regular vertex is one
/// bi-2 patch).
struct DualHost<'a, 'b> {
    rules: &'a DualRules<'b>,
    name: &'a str,
    /// Whether the holes are closed (then up to [`crate::host::adaptive::MAX_EXTRA_CAP_LEVELS`] more levels separate
    /// touching holes for their G^1 caps).
    fill: bool,
    /// The cells of the start net's vertices when it is not the input net ([`step_cells`]).
    cells: Option<&'a [Domain]>,
}

impl AdaptiveRules for DualHost<'_, '_> {
    type Level = Level;
    type Curves = ();

    fn start(&self, mesh: &PolyMesh, _opts: ComplexOptions) -> Result<Level> {
        let name = self.name;
        for v in 0..mesh.num_vertices() {
            if !mesh.is_boundary_vertex(v) && mesh.valence(v) < 3 {
                return Err(Error::Unsupported(format!(
                    "vertex {v} is an interior vertex of valence {}, which {name} patches do not \
                     take; refine the net once (fairsub subdivide --scheme {name} --levels 1) and use \
                     the refined net",
                    mesh.valence(v)
                )));
            }
        }
        // An input vertex's origin names the V-face of level 1.
        let info = input_vertex_info(mesh.num_vertices());
        let face_origin = (0..mesh.num_faces())
            .map(|f| (mesh.face_size(f) != 4).then_some(Element::Face(f as u32)))
            .collect();
        let active = (0..mesh.num_vertices() as u32)
            .map(|v| {
                let input_face = mesh.vertex_faces(v as usize).first().copied().unwrap_or(0);
                (
                    v,
                    Tag {
                        element: None,
                        sector: 0,
                        input_face,
                        domain: self
                            .cells
                            .and_then(|c| c.get(v as usize).copied())
                            .unwrap_or(Domain::UNTRACKED),
                    },
                )
            })
            .collect();
        let none = super::boundary_mode(mesh) == BoundaryInterpolation::None;
        // the crease data are checked here, once, with the element named
        super::sharp::step::Creases::of(mesh, name)?;
        let rule_free = none.then(|| vec![true; mesh.num_vertices()]);
        let first = self.cells.is_none();
        Ok(Level::new(
            mesh.clone(),
            info,
            face_origin,
            active,
            rule_free,
            CALM,
            first,
        ))
    }

    fn emit(&self, level: &Level, v: u32, prov: Provenance, to: Sink<()>) -> bool {
        let on_boundary =
            level.mesh.is_boundary_vertex(v as usize) && level.info[v as usize].fan_ok;
        if level.rule_free.is_some() && on_boundary {
            // boundary `none`: the region of a boundary vertex is not part of the surface
            return true;
        }
        if level.near_crease(v as usize) {
            return false;
        }
        let Some(p) = trusted_patch(level, v as usize) else {
            return false;
        };
        if !rule_free(level, v as usize, self.rules) {
            return true;
        }
        to.out.push(p, prov);
        mark_boundary_sides(&level.mesh, v as usize, to.out);
        if level.first {
            input_vertex_pieces(&level.mesh, v as usize, to.out);
        }
        true
    }

    fn retag(&self, level: &Level, v: u32, tag: Tag, l: usize) -> Tag {
        retag(level, v as usize, tag, l == 0)
    }

    /// The requested rings, the levels that spend semi-sharp creases, and up to
    /// [`crate::host::adaptive::MAX_EXTRA_CAP_LEVELS`] more while holes still touch (the decision Catmull-Clark and
    /// Loop make, [`is_last_cap_level_calm`]).
    /// After creases, a level may hold vertices that no patch can fill (a kept point of
    /// valence 3, a dart's tip): one more level makes them facets.
    fn is_last(&self, l: usize, rings: usize, level: &Level, marked: &[(u32, Tag)]) -> bool {
        let unfillable = || {
            level.calm < CALM
                && marked
                    .iter()
                    .any(|&(v, _)| vertex_net(&level.mesh, v as usize).is_none())
        };
        is_last_cap_level_calm((l, rings, self.fill), level.calm, || {
            g1::waiting(level, self.rules, marked)
        }) && (l > SPENT_BY_LEVEL || !unfillable())
    }

    fn fill(&self, level: &Level, marked: &[(u32, Tag)], to: Sink<()>) -> Result<()> {
        if level.rule_free.is_none() {
            let left = g1::g1_caps(level, self.rules, marked, to.out);
            return fill(level, &left, self.rules, to.out);
        }
        // boundary `none`: an element that touches a point made by a boundary rule has no
        // G^1 cap; the centroid fill writes the patches of its rule-free corners only
        let mut left = Vec::new();
        for (_, cells) in adaptive::by_element(marked) {
            if cells
                .iter()
                .all(|&(v, _)| rule_free(level, v as usize, self.rules))
            {
                left.extend(g1::g1_caps(level, self.rules, &cells, to.out));
            } else {
                left.extend(cells);
            }
        }
        left.retain(|&(v, _)| rule_free(level, v as usize, self.rules));
        fill(level, &left, self.rules, to.out)
    }

    fn refine_around(&self, level: &Level, marked: &[(u32, Tag)]) -> Result<Level> {
        refine_around(level, marked, self.rules, self.name)
    }
}

/// The tag of a marked vertex: at level 0 the vertex itself if its neighbourhood is not regular,
/// else its first non-quad face; later its first non-quad face with an input origin (the sector
/// is the vertex's corner index in that face). Otherwise the inherited tag.
fn retag(level: &Level, v: usize, tag: Tag, first: bool) -> Tag {
    let m = &level.mesh;
    // a crease vertex is an element too: the sectors of its V-face may be facets
    if first && (vertex_net(m, v).is_none() || level.on_crease(v)) {
        return Tag {
            element: Some(Element::Vertex(v as u32)),
            sector: 0,
            ..tag
        };
    }
    for h in m.outgoing(v) {
        let f = m.he_face(h) as usize;
        if let Some(element) = level.face_origin[f] {
            // The corner of h in its face (a face's half-edges are its corners in order): O(1),
            // where searching the face for v costs n for each of an n-gon's n corners.
            let sector = h - m.face_halfedge(f);
            return Tag {
                element: Some(element),
                sector,
                ..tag
            };
        }
    }
    tag
}

/// The centroid fill of the marked vertices of the last level that have no G^1 cap
/// ([`g1`]).
fn fill(
    level: &Level,
    marked: &[(u32, Tag)],
    rules: &DualRules<'_>,
    out: &mut PatchComplex,
) -> Result<()> {
    let m = &level.mesh;
    // Each n-gon's limit point once: it reads all n corners, and each of them has a patch.
    let mut limits: HashMap<u32, Point> = HashMap::new();
    for &(v, tag) in marked {
        let vn = vertex_net(m, v as usize).ok_or_else(|| {
            Error::Unsupported(format!(
                "vertex {v} has {} faces{}; its n-sided region has no one-patch fill, so at \
                 least one ring (--rings 1) is required",
                m.vertex_faces(v as usize).len(),
                if m.is_boundary_vertex(v as usize) {
                    " on the boundary"
                } else {
                    ""
                }
            ))
        })?;
        let mut cps: Vec<Point> = biquadratic_bspline_stencils(&vn.net)
            .iter()
            .map(|s| s.apply(m.positions()))
            .collect();
        for &(c, f) in &vn.ngons {
            cps[c] = *limits
                .entry(f)
                .or_insert_with(|| (rules.facet_limit)(m, f as usize).apply(m.positions()));
        }
        let p = BezierPatch::new(2, 2, cps);
        let element = tag.element.unwrap_or(Element::Vertex(v));
        // the vertex's own patch, in its own cell
        let sector = tag.sector;
        out.push_in(p, Provenance::Cap { element, sector }, tag.domain);
        mark_boundary_sides(m, v as usize, out);
    }
    Ok(())
}

/// Marks the sides of the last patch of `out`, the patch of vertex `v` ([`vertex_net`]'s
/// layout, shared by the ring host of the other bi-2 schemes), that lie on the net's boundary: `v = 0` at a boundary vertex, `u = 0` too at a
/// corner. On a net cut along its creases these are crease sides or the surface's boundary;
/// [`super::sharp::on_cut_net`] keeps the marks of the crease sides only (those that meet a
/// marked side of the other side of the cut) and clears the rest.
pub(crate) fn mark_boundary_sides(m: &PolyMesh, v: usize, out: &mut PatchComplex) {
    if !m.is_boundary_vertex(v) {
        return;
    }
    let last = out.len() - 1;
    out.mark_sharp(last, Side::V0.index());
    if m.is_corner(v) {
        out.mark_sharp(last, Side::U0.index());
    }
}

mod g1;
mod refine;
mod vertex;
pub use vertex::input_vertex_pieces;
pub(crate) use vertex::vertex_quarter_pieces;
use vertex::{trusted_patch, vertex_net};
pub(crate) mod step;
pub use refine::step_cells;
use refine::{refine_around, rule_free};
#[cfg(feature = "unit-tests")]
mod tests;
