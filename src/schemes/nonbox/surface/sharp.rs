//! Sharp features in the non-box surfaces ([`crate::schemes::nonbox::sharp`], fairsub's
//! construction): which cells of a level wait for a semi-sharp feature, and the level cut
//! along its infinitely sharp creases.
//!
//! - A cell with a corner within one face of a vertex where a *semi-sharp* feature lies (or an
//!   infinitely sharp crease, while the level is not cut) is refined further (its patches are
//!   not final until the feature is spent), as Catmull-Clark's host does; the levels go on until every finite sharpness is spent
//!   ([`crate::schemes::sdc::crease::adaptive::is_last_cap_level_calm`]).
//! - Once a level holds no semi-sharp value, it is cut along its *infinitely sharp* creases
//!   (at level 0 when the net has no semi-sharp feature): the non-box boundary rules are the
//!   crease rules ([`crate::schemes::nonbox::sharp`]), so each side is a boundary of the cut
//!   net, refined and patched by the boundary rules and the ghost FCVs of
//!   [`crate::schemes::nonbox::bezier::corner_fcvs`], and both sides end on the cubic B-spline
//!   of the crease polygon. The vertices OpenSubdiv's rules make corners (a tag, three or more
//!   sharp edges, boundary edges included) are tagged on the cut net and stay put; the cut
//!   net's boundary is interpolated edge-only otherwise, so a copy with one face where a crease
//!   passes follows the crease. A cell is regular there when each corner is interior of
//!   valence 4, on the boundary with two faces and not a corner, or on the boundary with one
//!   face and a corner ([`crate::schemes::nonbox::sharp::is_regular`]).
//! - Chains of infinitely sharp creases that end at a dart are not cut for refinement: the
//!   dart takes the smooth V rule, where a slit's end in a cut net would take the boundary
//!   rule. Such a level keeps its uncut net for refinement, and its patches are read off a
//!   copy cut along every crease, the dart chains too; a cell's patch there reads no child of
//!   the dart, so it is exact, and the dart is capped (`super::g1`).

use crate::error::Result;
use crate::host::adaptive::Info;
use crate::mesh::tags::{BoundaryInterpolation, SubdOptions};
use crate::mesh::{Extras, PolyMesh};
use crate::schemes::nonbox::FcvNet;
use crate::schemes::nonbox::sharp::NonBoxCreases;
use crate::schemes::sdc::crease::INFINITE;
use crate::schemes::sdc::crease::adaptive::calm_after;

/// What one level's sharp features ask of the host.
pub(super) struct LevelSharp {
    /// Per vertex: within one face of a vertex with a semi-sharp feature or a crease inside
    /// the surface (`None`: none): its cells wait.
    pub near_semi: Option<Vec<bool>>,
    /// The level's `calm` (levels since the last semi-sharp one).
    pub calm: usize,
    /// Per edge: an infinitely sharp crease inside the surface, to cut along once the level
    /// holds no semi-sharp value (`None`: none).
    pub cut: Option<Vec<bool>>,
    /// Per edge: an infinitely sharp crease inside the surface that is not cut (a chain ending
    /// at a dart): the fill's sides along it are sharp joins (`None`: none).
    pub uncut: Option<Vec<bool>>,
}

/// The sharp features of a level of `net` after a parent level with `parent_calm`.
///
/// # Errors
/// Those of reading the net's tags ([`NonBoxCreases::of`]).
pub(super) fn level_sharp(net: &FcvNet, parent_calm: usize) -> Result<LevelSharp> {
    let m = &net.mesh;
    let Some(c) = NonBoxCreases::of(m) else {
        return Ok(LevelSharp {
            near_semi: None,
            calm: calm_after(parent_calm, &[], &[]),
            cut: None,
            uncut: None,
        });
    };
    let nv = m.num_vertices();
    let mut semi = vec![false; nv];
    let mut cut = vec![false; m.num_edges()];
    let mut values = Vec::new();
    for e in 0..m.num_edges() {
        let s = c.edge(e);
        let h = m.edge_halfedge(e);
        if s <= 0.0 || m.he_twin(h).is_none() {
            continue;
        }
        values.push(s);
        // until the level is cut, the cells near an infinitely sharp crease wait too
        cut[e] = s >= INFINITE;
        semi[m.he_from(h) as usize] = true;
        semi[m.he_to(h) as usize] = true;
    }
    for (v, flag) in semi.iter_mut().enumerate() {
        let s = c.vertex(v);
        if s > 0.0 {
            values.push(s);
            *flag |= s < INFINITE;
        }
    }
    let infinite = cut.clone();
    prune_darts(m, &mut cut);
    let uncut: Vec<bool> = infinite.iter().zip(&cut).map(|(&i, &c)| i && !c).collect();
    let calm = calm_after(parent_calm, &values, &[]);
    let near_semi = semi.contains(&true).then(|| {
        let mut out = semi.clone();
        for f in 0..m.num_faces() {
            if m.face(f).iter().any(|&v| semi[v as usize]) {
                for &v in m.face(f) {
                    out[v as usize] = true;
                }
            }
        }
        out
    });
    Ok(LevelSharp {
        near_semi,
        calm,
        cut: cut.contains(&true).then_some(cut),
        uncut: uncut.contains(&true).then_some(uncut),
    })
}

/// Leaves out of the cut the chains of infinitely sharp creases that end at a dart (an interior
/// vertex with one of them): cut there, the net would get a slit whose end the boundary rules
/// do not refine as OpenSubdiv's dart rule does. Such a level keeps its uncut net for
/// refinement, and its patches are read off a copy cut along every crease (`super::Level`).
fn prune_darts(m: &PolyMesh, cut: &mut [bool]) {
    let mut valence = vec![0u32; m.num_vertices()];
    for e in (0..cut.len()).filter(|&e| cut[e]) {
        let h = m.edge_halfedge(e);
        valence[m.he_from(h) as usize] += 1;
        valence[m.he_to(h) as usize] += 1;
    }
    let mut stack: Vec<usize> = (0..valence.len())
        .filter(|&v| valence[v] == 1 && !m.is_boundary_vertex(v))
        .collect();
    while let Some(v) = stack.pop() {
        for h in m.outgoing_halfedges(v) {
            let e = m.he_edge(h) as usize;
            if cut[e] {
                cut[e] = false;
                valence[v] -= 1;
                let w = m.he_to(h) as usize;
                valence[w] -= 1;
                if valence[w] == 1 && !m.is_boundary_vertex(w) {
                    stack.push(w);
                }
            }
        }
    }
}

/// `net` cut along the edges `cut` flags, with the trust of its points (`info`: vertices, then
/// FCVs) carried to the copies, and each vertex's origin in `net`; the cut net's extras tag
/// OpenSubdiv's corners (see the [module](self) documentation) and keep the crease method.
///
/// # Errors
/// Those of building the cut net.
pub(super) fn cut_net(
    net: &FcvNet,
    info: &[Info],
    cut: &[bool],
) -> Result<(FcvNet, Vec<Info>, Vec<u32>)> {
    let m = &net.mesh;
    let c = NonBoxCreases::of(m);
    let nv = m.num_vertices();
    let corner: Vec<bool> = (0..nv)
        .map(|v| c.as_ref().is_some_and(|c| c.is_corner(v)))
        .collect();
    let cut = crate::schemes::doo_sabin::sharp::cut(m, cut);
    let tags: Vec<(u32, f32)> = (0..cut.positions.len() as u32)
        .filter(|&x| corner[cut.origin[x as usize] as usize])
        .map(|x| (x, INFINITE))
        .collect();
    let extras = Extras {
        sharp_vertices: tags,
        sharpened: false,
        options: SubdOptions {
            boundary: Some(BoundaryInterpolation::EdgeOnly),
            crease_method: m.extras().and_then(|e| e.options.crease_method),
            ..SubdOptions::default()
        },
        ..Extras::default()
    };
    let mesh =
        PolyMesh::from_partial_refinement(cut.positions, m.face_starts().to_vec(), cut.corners)?
            .with_extras(Some(extras));
    let mut cut_info: Vec<Info> = cut.origin.iter().map(|&o| info[o as usize]).collect();
    cut_info.extend_from_slice(&info[nv..]);
    let net = FcvNet {
        mesh,
        fcv: net.fcv.clone(),
    };
    Ok((net, cut_info, cut.origin))
}
