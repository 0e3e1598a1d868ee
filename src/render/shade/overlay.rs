//! The overlays drawn over a shaded picture: patch boundaries and the control net (edges
//! projected, clipped to the image and drawn into the supersampled buffer).

use super::*;

/// Darkens samples where the patch changes to the right or below (both sides, so the line is
/// one pixel wide after filtering at 2x2 supersampling).
pub(super) fn patch_lines(frame: &Frame, cols: &mut [[u8; 3]]) {
    let (w, h) = (frame.width, frame.height);
    let both = frame.supersample > 1;
    let mut mark = vec![false; w * h];
    for y in 0..h {
        for x in 0..w {
            let a = frame.get(x, y).prim;
            if a == NONE {
                continue;
            }
            for (nx, ny) in [(x + 1, y), (x, y + 1)] {
                if nx < w && ny < h {
                    let b = frame.get(nx, ny).prim;
                    if b != NONE && b != a {
                        mark[y * w + x] = true;
                        if both {
                            mark[ny * w + nx] = true;
                        }
                    }
                }
            }
        }
    }
    for (c, m) in cols.iter_mut().zip(mark) {
        if m {
            *c = c.map(|x| (x as f64 * 0.3).round() as u8);
        }
    }
}

/// Draws the control net's edges and vertices on top (no depth test), clipped to the near
/// plane and the image.
pub(super) fn draw_net(
    net: &crate::mesh::PolyMesh,
    cam: &Camera,
    ss: usize,
    cols: &mut [[u8; 3]],
    w: usize,
    h: usize,
) {
    const EDGE: [u8; 3] = [28, 62, 170];
    const VERTEX: [u8; 3] = [10, 25, 90];
    let view: Vec<Point> = net.positions().iter().map(|&p| cam.to_view(p)).collect();
    let focal = cam.focal();
    let (cx, cy) = (0.5 * w as f64, 0.5 * h as f64);
    let proj = |v: Point| [cx + focal * v[0] / v[2], cy - focal * v[1] / v[2]];
    let mut stamp = |x: f64, y: f64, size: usize, c: [u8; 3]| {
        let half = size as f64 / 2.0;
        let (x0, y0) = ((x - half).round(), (y - half).round());
        for dy in 0..size {
            for dx in 0..size {
                let (px, py) = (x0 + dx as f64, y0 + dy as f64);
                if px >= 0.0 && py >= 0.0 && (px as usize) < w && (py as usize) < h {
                    cols[py as usize * w + px as usize] = c;
                }
            }
        }
    };
    for e in net.edges() {
        let (mut a, mut b) = (view[e[0] as usize], view[e[1] as usize]);
        if a[2] <= cam.near && b[2] <= cam.near {
            continue;
        }
        if a[2] <= cam.near || b[2] <= cam.near {
            let t = (cam.near - a[2]) / (b[2] - a[2]);
            let q = add(a, scale(sub(b, a), t));
            if a[2] <= cam.near {
                a = q;
            } else {
                b = q;
            }
        }
        let Some((p, q)) = clip_segment(proj(a), proj(b), w as f64, h as f64) else {
            continue;
        };
        let len = ((q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2)).sqrt();
        let steps = (2.0 * len).ceil().max(1.0) as usize;
        for k in 0..=steps {
            let t = k as f64 / steps as f64;
            stamp(p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), ss, EDGE);
        }
    }
    for v in &view {
        if v[2] > cam.near {
            let [x, y] = proj(*v);
            if x.is_finite() && y.is_finite() {
                stamp(x, y, 3 * ss, VERTEX);
            }
        }
    }
}

/// Liang-Barsky clipping of a segment to `[-1, w + 1] x [-1, h + 1]`.
pub(super) fn clip_segment(
    p: [f64; 2],
    q: [f64; 2],
    w: f64,
    h: f64,
) -> Option<([f64; 2], [f64; 2])> {
    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (pk, qk) in [
        (-dx, p[0] + 1.0),
        (dx, w + 1.0 - p[0]),
        (-dy, p[1] + 1.0),
        (dy, h + 1.0 - p[1]),
    ] {
        if pk == 0.0 {
            if qk < 0.0 {
                return None;
            }
        } else {
            let r = qk / pk;
            if pk < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    if t0.is_nan() || t1.is_nan() || t0 > t1 {
        return None;
    }
    Some((
        [p[0] + t0 * dx, p[1] + t0 * dy],
        [p[0] + t1 * dx, p[1] + t1 * dy],
    ))
}
