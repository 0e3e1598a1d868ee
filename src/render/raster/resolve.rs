//! Resolving a covered sample: the pixel rays of a camera, Newton's method for the exact
//! intersection of a ray with a Bezier patch ([`ray_patch`]), and the [`Sample`] of a patch or
//! mesh triangle at that point.

use super::*;

/// Pixel rays of a camera.
#[derive(Debug, Clone, Copy)]
pub(super) struct RayGen {
    pub(super) eye: Point,
    basis: [Point; 3],
    focal: f64,
    cx: f64,
    cy: f64,
}

impl RayGen {
    pub(super) fn new(cam: &Camera) -> RayGen {
        RayGen {
            eye: cam.eye,
            basis: cam.basis(),
            focal: cam.focal(),
            cx: 0.5 * cam.width as f64,
            cy: 0.5 * cam.height as f64,
        }
    }

    pub(super) fn dir(&self, x: f64, y: f64) -> Point {
        let [r, u, f] = self.basis;
        let a = (x - self.cx) / self.focal;
        let b = (self.cy - y) / self.focal;
        normalize(add(add(f, scale(r, a)), scale(u, b)))
    }
}

/// Largest Newton steps per sample.
const NEWTON_STEPS: usize = 6;

/// Newton's method for the intersection of the ray `eye + t dir` with a patch, from `uv0`:
/// returns the converged `(u, v)` clamped to the domain, with the derivatives there, or `None`
/// (no convergence, a singular Jacobian, or a step leaving the domain by more than 5%).
/// Converged means the patch point is within `tol` times its distance along the ray from the
/// ray.
pub fn ray_patch(
    patch: &BezierPatch,
    eye: Point,
    dir: Point,
    uv0: [f64; 2],
    tol: f64,
) -> Option<([f64; 2], Derivatives)> {
    // two directions orthogonal to the ray
    let helper = if dir[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let e1 = normalize(cross(dir, helper));
    let e2 = cross(dir, e1);
    let [mut u, mut v] = uv0;
    for _ in 0..NEWTON_STEPS {
        let d = patch.derivatives(u, v);
        let r = sub(d.p, eye);
        let (f1, f2) = (dot(r, e1), dot(r, e2));
        let along = dot(r, dir).abs().max(f64::MIN_POSITIVE);
        if (f1 * f1 + f2 * f2).sqrt() <= tol * along {
            let (cu, cv) = (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0));
            if (cu, cv) == (u, v) {
                return Some(([u, v], d));
            }
            return Some(([cu, cv], patch.derivatives(cu, cv)));
        }
        let (a, b) = (dot(d.du, e1), dot(d.dv, e1));
        let (c, e) = (dot(d.du, e2), dot(d.dv, e2));
        let det = a * e - b * c;
        if !det.is_finite() || det.abs() <= 1e-300 {
            return None;
        }
        u -= (e * f1 - b * f2) / det;
        v -= (a * f2 - c * f1) / det;
        if !(-0.05..=1.05).contains(&u) || !(-0.05..=1.05).contains(&v) {
            return None;
        }
    }
    None
}

/// The exact surface data of a patch sample.
pub(super) fn resolve_patch(
    patch: &BezierPatch,
    id: u32,
    rays: &RayGen,
    dir: Point,
    uv0: [f64; 2],
    origin: Point,
) -> (Sample, bool) {
    // converge to a ray offset of 1e-4 samples
    let tol = 1e-4 / rays.focal;
    let start = [uv0[0].clamp(0.0, 1.0), uv0[1].clamp(0.0, 1.0)];
    let (uv, d, ok) = match ray_patch(patch, rays.eye, dir, start, tol) {
        Some((uv, d)) => (uv, d, true),
        None => (start, patch.derivatives(start[0], start[1]), false),
    };
    let [u, v] = uv;
    let n = patch.normal_from(u, v, &d);
    let curv = d.curvature().unwrap_or_else(|| patch.curvatures(u, v));
    let p = sub(d.p, origin);
    (
        Sample {
            prim: id,
            uv: [u as f32, v as f32],
            p: p.map(|x| x as f32),
            n: n.map(|x| x as f32),
            gauss: curv.gauss as f32,
            mean: curv.mean as f32,
        },
        ok,
    )
}

/// The interpolated data of a mesh sample (`tri` a triangle index, `bary = (b1, b2)`).
pub(super) fn resolve_mesh(m: &MeshSurface, tri: u32, bary: [f64; 2], origin: Point) -> Sample {
    let t = m.triangles[tri as usize];
    let b = [1.0 - bary[0] - bary[1], bary[0], bary[1]];
    let mut p = [0.0; 3];
    let mut n = [0.0; 3];
    for k in 0..3 {
        p = add(p, scale(m.positions[t[k] as usize], b[k]));
        n = add(n, scale(m.normals[t[k] as usize], b[k]));
    }
    let n = if norm(n) > 0.0 { normalize(n) } else { n };
    Sample {
        prim: m.triangle_face.get(tri as usize).copied().unwrap_or(tri),
        uv: [bary[0] as f32, bary[1] as f32],
        p: sub(p, origin).map(|x| x as f32),
        n: n.map(|x| x as f32),
        gauss: f32::NAN,
        mean: f32::NAN,
    }
}
