//! The child faces of one dual step: F-faces of the selected faces, E-faces (halves at sharp
//! edges), V-faces of the vertices whose whole fan is selected (one per sector between sharp
//! edges), and with creases the children's sharpness.

use super::*;

/// The child faces: F-faces of the selected faces, E-faces (halves at sharp edges), V-faces of
/// the vertices with their whole fan selected (one per sector between sharp edges); with
/// creases also the child's sharpness.
pub(super) fn faces(
    inp: &StepIn<'_>,
    sel: &[bool],
    whole_fan: &dyn Fn(usize) -> bool,
    creases: Option<&Creases<'_>>,
    o: &mut StepOut,
) -> Result<()> {
    let m = inp.mesh;
    let mut sharp_edges: Vec<([u32; 2], f32)> = Vec::new();
    let mut sharp_vertices: Vec<(u32, f32)> = Vec::new();
    let mut scratch = Scratch::default();
    for &f in &o.sel_faces.clone() {
        let h0 = m.face_halfedge(f as usize);
        for h in h0..h0 + m.face_size(f as usize) as u32 {
            o.corners.push(o.corner_pt[h as usize]);
        }
        o.face_start.push(o.corners.len() as u32);
        o.face_origin.push(inp.face_origin[f as usize]);
    }
    for e in 0..m.num_edges() {
        let h = m.edge_halfedge(e);
        let pts = o.edge_pt[e];
        let half = |s: u32, o: &StepOut| {
            let (near_from, near_to) = if s == h {
                (pts[0], pts[1])
            } else {
                (pts[1], pts[0])
            };
            [
                o.corner_pt[m.he_next(s) as usize],
                o.corner_pt[s as usize],
                near_from,
                near_to,
            ]
        };
        let mut quads: Vec<[u32; 4]> = Vec::new();
        match m.he_twin(h) {
            Some(t) if pts[0] != UNSET => {
                // a crease: one half per selected side
                for s in [h, t] {
                    if sel[m.he_face(s) as usize] {
                        quads.push(half(s, o));
                    }
                }
            }
            Some(t) if sel[m.he_face(h) as usize] && sel[m.he_face(t) as usize] => {
                quads.push([
                    o.corner_pt[m.he_next(h) as usize],
                    o.corner_pt[h as usize],
                    o.corner_pt[m.he_next(t) as usize],
                    o.corner_pt[t as usize],
                ]);
            }
            None if pts[0] != UNSET => quads.push(half(h, o)),
            _ => continue,
        }
        if let Some(c) = creases
            && pts[0] != UNSET
        {
            let s = c.middle(e, &mut scratch);
            if s > 0.0 {
                sharp_edges.push((pts, s));
            }
        }
        for q in quads {
            o.corners.extend_from_slice(&q);
            o.face_start.push(o.corners.len() as u32);
            o.face_origin.push(None);
        }
    }
    let mut done = vec![false; m.num_vertices()];
    for &f in &o.sel_faces.clone() {
        for &x in m.face(f as usize) {
            let v = x as usize;
            if done[v] || !whole_fan(v) {
                continue;
            }
            done[v] = true;
            let hs = m.outgoing_halfedges(v);
            let sectors = match creases {
                Some(c) => c.sectors(v, &hs),
                None => plain_sectors(m, v, &hs),
            };
            for sector in &sectors {
                let poly = sector_face(m, v, &hs, sector, o);
                if poly.len() < 3 {
                    // interior valence 2: the 2-sided V-face is dropped
                    continue;
                }
                if let Some(c) = creases {
                    sector_sharpness(c, v, sector, &poly, o, &mut scratch, &mut sharp_edges);
                }
                let size = poly.len();
                o.corners.extend_from_slice(&poly);
                o.face_start.push(o.corners.len() as u32);
                o.face_origin
                    .push(if size != 4 { inp.info[v].origin } else { None });
            }
            if let Some(c) = creases {
                let s = c.child_vertex(v);
                if o.kept[v] != UNSET && s > 0.0 {
                    sharp_vertices.push((o.kept[v], s));
                }
            }
        }
    }
    if o.corners.contains(&UNSET) {
        return Err(Error::Unsupported(
            "adaptive Doo-Sabin refinement met an inconsistent neighbourhood (a boundary edge \
             whose Chaikin points are unknown); refine the net once with --levels 1 and retry"
                .into(),
        ));
    }
    if creases.is_some() {
        sharp_vertices.sort_unstable_by_key(|p| p.0);
        let options = m.extras().map(|e| e.options).unwrap_or_default();
        o.extras = Some(Extras {
            sharp_edges: SharpEdges::ByPair(sharp_edges),
            sharp_vertices,
            sharpened: true,
            options: SubdOptions {
                boundary: options.boundary,
                crease_method: options.crease_method,
                ..SubdOptions::default()
            },
            ..Extras::default()
        });
    }
    Ok(())
}

/// The one sector of a vertex without creases: its whole fan, between its boundary edges on
/// the boundary.
fn plain_sectors(m: &PolyMesh, v: usize, hs: &[u32]) -> Vec<Sector> {
    let boundary = m.is_boundary_vertex(v).then(|| {
        let last = *hs.last().expect("a vertex has a face");
        (m.he_edge(hs[0]), m.he_edge(m.he_prev(last)))
    });
    vec![Sector {
        faces: (0..hs.len()).collect(),
        open: boundary.map(|b| b.0),
        close: boundary.map(|b| b.1),
    }]
}

/// The Chaikin point of edge `e` near its end `v`.
fn near(m: &PolyMesh, o: &StepOut, e: u32, v: usize) -> u32 {
    let k = usize::from(m.he_from(m.edge_halfedge(e as usize)) as usize != v);
    o.edge_pt[e as usize][k]
}

/// The V-face of one sector of `v`: the Chaikin point of its opening edge near `v`, its
/// corner points, the Chaikin point of its closing edge (once at a dart) and the kept point.
fn sector_face(m: &PolyMesh, v: usize, hs: &[u32], s: &Sector, o: &StepOut) -> Vec<u32> {
    let mut poly = Vec::with_capacity(s.faces.len() + 3);
    if let Some(e) = s.open {
        poly.push(near(m, o, e, v));
    }
    poly.extend(s.faces.iter().map(|&i| o.corner_pt[hs[i] as usize]));
    if let Some(e) = s.close
        && s.open != Some(e)
    {
        poly.push(near(m, o, e, v));
    }
    if o.kept[v] != UNSET {
        poly.push(o.kept[v]);
    }
    poly
}

/// The child sharpness along one sector's V-face: its chord (no kept point) or its two edges
/// to the kept point.
fn sector_sharpness(
    c: &Creases<'_>,
    v: usize,
    s: &Sector,
    poly: &[u32],
    o: &StepOut,
    scratch: &mut Scratch,
    out: &mut Vec<([u32; 2], f32)>,
) {
    let (Some(open), Some(close)) = (s.open, s.close) else {
        return;
    };
    let (first, n) = (poly[0], poly.len());
    let mut push = |a: u32, b: u32, x: f32| {
        if x > 0.0 {
            out.push(([a, b], x));
        }
    };
    if o.kept[v] != UNSET {
        let kp = poly[n - 1];
        let before = poly[n - 2];
        push(before, kp, c.half(close as usize, v, scratch));
        push(kp, first, c.half(open as usize, v, scratch));
    } else if open != close {
        push(
            poly[n - 1],
            first,
            c.chord(open as usize, close as usize, v, scratch),
        );
    }
}
