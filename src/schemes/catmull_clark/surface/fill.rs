//! The Hermite-Coons fill of the faces left after the last ring (the construction the module
//! documentation of [`super`] describes): one bi-3 Coons patch per face, its edge curves shared.

use super::*;

/// The Hermite-Coons fill of the marked faces of the last level; `emitted` lists the level's
/// emitted faces and their patches.
pub(super) fn fill(
    level: &Level,
    marked: &[(u32, Tag)],
    emitted: &[(u32, u32)],
    out: &mut PatchComplex,
) -> Result<()> {
    let m = &level.mesh;
    let mut jets = jets::Jets::new(m);
    let patch_of: HashMap<u32, u32> = emitted.iter().copied().collect();
    let mut curves: Curves<4> = HashMap::new();
    for &(f, tag) in marked {
        let face = m.face(f as usize);
        if face.len() != 4 {
            return Err(Error::Unsupported(format!(
                "the fill needs quads; face {f} of the last level has {} sides",
                face.len()
            )));
        }
        let mut sides = [[[0.0; 3]; 4]; 4];
        for k in 0..4 {
            let (a, b) = (face[k], face[(k + 1) % 4]);
            let key = (a.min(b), a.max(b));
            // an edge shared with an emitted patch takes that patch's side (the face across is
            // the only emitted face at the edge)
            if !curves.contains_key(&key)
                && let Some(t) = m.he_twin(m.face_halfedge(f as usize) + k as u32)
                && let Some(&p) = patch_of.get(&m.he_face(t))
            {
                let g = m.he_face(t) as usize;
                record_curves(m, g, &out.patches[p as usize], &mut curves);
            }
            let c = *curves.entry(key).or_insert_with(|| {
                let (lo, hi) = key;
                if let Some(c) = crease_curve(level, lo, hi) {
                    return c;
                }
                let (p0, d0) = jets.limit_and_derivative(lo as usize, hi as usize);
                let (p3, d3) = jets.limit_and_derivative(hi as usize, lo as usize);
                [
                    p0,
                    geom::axpy(p0, 1.0 / 3.0, d0),
                    geom::axpy(p3, 1.0 / 3.0, d3),
                    p3,
                ]
            });
            let mut c = c;
            if a > b {
                c.reverse();
            }
            sides[k] = c;
        }
        // sides: 0 = v0 (corner 0 -> 1), 1 = u1 (1 -> 2), 2 = v1 run backwards (2 -> 3), 3 = u0
        // run backwards (3 -> 0).
        let mut v1 = sides[2];
        v1.reverse();
        let mut u0 = sides[3];
        u0.reverse();
        let patch = BezierPatch::coons(3, &sides[0], &sides[1], &v1, &u0);
        let element = tag.element.unwrap_or(Element::Face(tag.input_face));
        // the fill patch has the face's own corners: its domain is the face's cell
        out.push_in(
            patch,
            Provenance::Cap {
                element,
                sector: tag.sector,
            },
            tag.domain,
        );
        sharp::mark_sides(level, f as usize, out);
    }
    Ok(())
}
