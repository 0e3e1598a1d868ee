//! The child faces of one dual step (the mesh layer's split: F-faces of the selected faces,
//! E-faces and their halves at sharp edges, V-faces of the vertices whose whole fan is
//! selected, one per sector between sharp edges) with what the scheme adds: each face's input
//! element and, with creases, the children's sharpness.

use super::*;

/// The input element of each child face of `o`'s split (whose points are made) and, with
/// creases, the child's sharpness.
pub(super) fn faces(
    inp: &StepIn<'_>,
    creases: Option<&Creases<'_>>,
    o: &mut StepOut,
) -> Result<()> {
    let split = &o.split;
    if !split.is_complete() {
        return Err(Error::Unsupported(
            "adaptive Doo-Sabin refinement met an inconsistent neighbourhood (a boundary edge \
             whose Chaikin points are unknown); refine the net once with --levels 1 and retry"
                .into(),
        ));
    }
    let m = inp.mesh;
    let face_origin = (0..split.num_faces())
        .map(|i| match split.face(i) {
            DualFace::Face(f) => inp.face_origin[f as usize],
            DualFace::Edge => None,
            DualFace::Vertex(vf) => {
                let size = split.face_start[i + 1] - split.face_start[i];
                (size != 4)
                    .then_some(inp.info[vf.vertex as usize].origin)
                    .flatten()
            }
        })
        .collect();
    if let Some(c) = creases {
        let mut scratch = Scratch::default();
        let mut sharp_edges: Vec<([u32; 2], f32)> = Vec::new();
        for (e, &pts) in split.edge_pt.iter().enumerate() {
            if pts[0] != NONE {
                let s = c.middle(e, &mut scratch);
                if s > 0.0 {
                    sharp_edges.push((pts, s));
                }
            }
        }
        let v0 = split.sel_faces.len() + split.num_e_faces;
        for (k, vf) in split.v_faces.iter().enumerate() {
            if vf.open != NONE && vf.close != NONE {
                let i = v0 + k;
                let poly =
                    &split.corners[split.face_start[i] as usize..split.face_start[i + 1] as usize];
                let ends = (vf.vertex as usize, vf.open, vf.close);
                sector_sharpness(c, ends, poly, o, &mut scratch, &mut sharp_edges);
            }
        }
        let mut sharp_vertices: Vec<(u32, f32)> = split
            .v_done
            .iter()
            .filter_map(|&v| {
                let s = c.child_vertex(v as usize);
                (split.kept[v as usize] != NONE && s > 0.0).then_some((split.kept[v as usize], s))
            })
            .collect();
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
    o.face_origin = face_origin;
    Ok(())
}

/// The child sharpness along the V-face of a sector of `v` between two sharp edges (`open`,
/// `close`): its chord (no kept point) or its two edges to the kept point.
fn sector_sharpness(
    c: &Creases<'_>,
    (v, open, close): (usize, u32, u32),
    poly: &[u32],
    o: &StepOut,
    scratch: &mut Scratch,
    out: &mut Vec<([u32; 2], f32)>,
) {
    let (first, n) = (poly[0], poly.len());
    let mut push = |a: u32, b: u32, x: f32| {
        if x > 0.0 {
            out.push(([a, b], x));
        }
    };
    if o.split.kept[v] != NONE {
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
