//! The comparison of a refined net written by fairsub (OBJ) with the peer's (text): parsers for
//! both outputs and `compare`, which matches vertices by position (coincident points in
//! clusters), faces as cluster cycles and UVs per corner. See tests/it/osd_peer.rs for the rules.

use std::collections::HashMap;

/// Absolute tolerance for points and UVs.
pub const TOL: f64 = 1e-6;

/// A refined net as either program wrote it: points, faces (with a hole flag), UVs.
#[derive(Debug, Default, Clone)]
pub struct Refined {
    /// Points (limit points for the peer with `--limit`).
    pub points: Vec<[f64; 3]>,
    /// Faces as vertex cycles.
    pub faces: Vec<Vec<usize>>,
    /// Hole flag per face (always false for fairsub).
    pub hole: Vec<bool>,
    /// Face-varying values.
    pub uvs: Vec<[f64; 2]>,
    /// Value index per face corner (empty without UVs).
    pub face_uvs: Vec<Vec<usize>>,
}

fn nums<const N: usize>(tok: &[&str], what: &str) -> Result<[f64; N], String> {
    let mut a = [0.0; N];
    for (k, x) in a.iter_mut().enumerate() {
        let t = tok.get(k).ok_or(format!("{what}: too few numbers"))?;
        *x = t.parse().map_err(|_| format!("{what}: bad number '{t}'"))?;
    }
    Ok(a)
}

/// Reads the peer's text output (format at the top of tests/peer/osd_refine.cpp); with `limit`,
/// the points are the limit points.
pub fn parse_peer(text: &str, limit: bool) -> Result<Refined, String> {
    let mut r = Refined::default();
    let (mut lp, mut ended) = (Vec::new(), false);
    let mut counts: HashMap<&str, usize> = HashMap::new();
    for (i, line) in text.lines().enumerate() {
        let tok: Vec<&str> = line.split_whitespace().collect();
        let what = format!("peer output line {}", i + 1);
        let idx = |t: &[&str]| -> Result<Vec<usize>, String> {
            t.iter()
                .map(|s| s.parse().map_err(|_| format!("{what}: bad index '{s}'")))
                .collect()
        };
        match tok.first().copied() {
            Some("v") => r.points.push(nums::<3>(&tok[1..], &what)?),
            Some("f") => {
                r.hole.push(tok.get(1) == Some(&"1"));
                r.faces.push(idx(&tok[2..])?);
            }
            Some("vt") => r.uvs.push(nums::<2>(&tok[1..], &what)?),
            Some("fv") => r.face_uvs.push(idx(&tok[1..])?),
            Some("lp") => lp.push(nums::<3>(&tok[1..], &what)?),
            Some("end") => ended = true,
            Some(k @ ("vertices" | "faces" | "fvar-values")) => {
                let n = tok.get(1).and_then(|s| s.parse().ok());
                counts.insert(k, n.ok_or(format!("{what}: bad count"))?);
            }
            _ => {}
        }
    }
    if !ended {
        return Err("peer output is truncated (no 'end')".into());
    }
    let expect = [
        ("vertices", r.points.len()),
        ("faces", r.faces.len()),
        ("fvar-values", r.uvs.len()),
    ];
    for (k, n) in expect {
        if counts.get(k) != Some(&n) {
            return Err(format!(
                "peer output: header {k} {:?}, found {n}",
                counts.get(k)
            ));
        }
    }
    if limit {
        if lp.len() != r.points.len() {
            return Err("peer output: --limit without limit points".into());
        }
        r.points = lp;
    }
    Ok(r)
}

/// Reads an OBJ as fairsub writes it (`v`, `vt`, `f v`, `f v/vt`, `f v/vt/vn`, `f v//vn`).
pub fn parse_obj(text: &str) -> Result<Refined, String> {
    let mut r = Refined::default();
    for (i, line) in text.lines().enumerate() {
        let tok: Vec<&str> = line.split_whitespace().collect();
        let what = format!("fairsub OBJ line {}", i + 1);
        match tok.first().copied() {
            Some("v") => r.points.push(nums::<3>(&tok[1..], &what)?),
            Some("vt") => r.uvs.push(nums::<2>(&tok[1..], &what)?),
            Some("f") => {
                let (mut f, mut ft) = (Vec::new(), Vec::new());
                for c in &tok[1..] {
                    let mut parts = c.split('/');
                    let resolve = |s: &str, n: usize| -> Result<usize, String> {
                        let k: i64 = s.parse().map_err(|_| format!("{what}: bad index '{c}'"))?;
                        let j = if k > 0 { k - 1 } else { n as i64 + k };
                        if j < 0 || j >= n as i64 {
                            return Err(format!("{what}: index '{c}' out of range"));
                        }
                        Ok(j as usize)
                    };
                    f.push(resolve(parts.next().unwrap_or(""), r.points.len())?);
                    if let Some(t) = parts.next().filter(|t| !t.is_empty()) {
                        ft.push(resolve(t, r.uvs.len())?);
                    }
                }
                if !ft.is_empty() && ft.len() != f.len() {
                    return Err(format!("{what}: some corners without vt"));
                }
                r.faces.push(f);
                r.hole.push(false);
                if !ft.is_empty() {
                    r.face_uvs.push(ft);
                }
            }
            _ => {}
        }
    }
    if !r.face_uvs.is_empty() && r.face_uvs.len() != r.faces.len() {
        return Err("fairsub OBJ: faces with and without vt".into());
    }
    Ok(r)
}

fn dist<const N: usize>(a: &[f64; N], b: &[f64; N]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// For each point of `a`, the indices of the points of `b` within `tol` (grid hashing).
fn neighbours(a: &[[f64; 3]], b: &[[f64; 3]], tol: f64) -> Vec<Vec<usize>> {
    let cell = (tol * 4.0).max(1e-12);
    let key = |p: &[f64; 3]| p.map(|x| (x / cell).floor() as i64);
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (j, p) in b.iter().enumerate() {
        grid.entry(key(p)).or_default().push(j);
    }
    a.iter()
        .map(|p| {
            let k = key(p);
            let mut out = Vec::new();
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        if let Some(js) = grid.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) {
                            out.extend(js.iter().copied().filter(|&j| dist(p, &b[j]) <= tol));
                        }
                    }
                }
            }
            out
        })
        .collect()
}

/// The smallest rotation of a cycle (orientation kept) and the offset it starts at.
fn canonical(c: &[usize]) -> (Vec<usize>, usize) {
    (0..c.len())
        .map(|s| {
            (
                (0..c.len())
                    .map(|i| c[(s + i) % c.len()])
                    .collect::<Vec<_>>(),
                s,
            )
        })
        .min()
        .unwrap_or_default()
}

/// Compares fairsub's net (`got`) with the peer's (`want`); returns the largest deviation of
/// matched vertices and (when the net has UVs) of the UVs of matched face corners, or what
/// differs.
pub fn compare(got: &Refined, want: &Refined) -> Result<f64, String> {
    // The peer's written faces and the vertices they use; its isolated vertices.
    let used = |r: &Refined, written_only: bool| {
        let mut u = vec![false; r.points.len()];
        for (i, f) in r.faces.iter().enumerate() {
            if !(written_only && r.hole.get(i) == Some(&true)) {
                f.iter().for_each(|&v| u[v] = true);
            }
        }
        u
    };
    let (w_written, w_any, g_used) = (used(want, true), used(want, false), used(got, false));
    let w_faces: Vec<usize> = (0..want.faces.len()).filter(|&f| !want.hole[f]).collect();
    if got.faces.len() != w_faces.len() {
        return Err(format!(
            "faces: fairsub {}, OpenSubdiv {} (+{} holes)",
            got.faces.len(),
            w_faces.len(),
            want.faces.len() - w_faces.len()
        ));
    }
    let w_ref: Vec<usize> = (0..want.points.len()).filter(|&v| w_written[v]).collect();
    let w_iso: Vec<usize> = (0..want.points.len()).filter(|&v| !w_any[v]).collect();
    let g_ref: Vec<usize> = (0..got.points.len()).filter(|&v| g_used[v]).collect();
    let g_unref: Vec<usize> = (0..got.points.len()).filter(|&v| !g_used[v]).collect();
    if g_ref.len() != w_ref.len() {
        return Err(format!(
            "vertices used by faces: fairsub {}, OpenSubdiv {}",
            g_ref.len(),
            w_ref.len()
        ));
    }
    if g_unref.len() != w_iso.len() && g_unref.len() != want.points.len() - w_ref.len() {
        return Err(format!(
            "vertices used by no written face: fairsub {}, OpenSubdiv {} isolated ({} with hole support)",
            g_unref.len(),
            w_iso.len(),
            want.points.len() - w_ref.len()
        ));
    }
    // Clusters over both sets: ids 0..g for fairsub's used vertices, g.. for the peer's.
    let gp: Vec<[f64; 3]> = g_ref.iter().map(|&v| got.points[v]).collect();
    let wp: Vec<[f64; 3]> = w_ref.iter().map(|&v| want.points[v]).collect();
    let near = neighbours(&gp, &wp, TOL);
    let n = gp.len();
    let mut parent: Vec<usize> = (0..2 * n).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    let mut worst = 0.0f64;
    for (i, js) in near.iter().enumerate() {
        if js.is_empty() {
            let best = wp
                .iter()
                .map(|q| dist(&gp[i], q))
                .fold(f64::INFINITY, f64::min);
            return Err(format!(
                "fairsub vertex {} {:?} has no OpenSubdiv vertex within {TOL:e} (nearest at {best:.3e})",
                g_ref[i], gp[i]
            ));
        }
        for &j in js {
            worst = worst.max(dist(&gp[i], &wp[j]));
            let (a, b) = (find(&mut parent, i), find(&mut parent, n + j));
            parent[a] = b;
        }
    }
    let mut balance: HashMap<usize, i64> = HashMap::new();
    for x in 0..2 * n {
        *balance.entry(find(&mut parent, x)).or_default() += if x < n { 1 } else { -1 };
    }
    if let Some((&c, &b)) = balance.iter().find(|&(_, &b)| b != 0) {
        let who = if c < n {
            got.points[g_ref[c]]
        } else {
            want.points[w_ref[c - n]]
        };
        return Err(format!(
            "coincident-point cluster near {who:?}: {b:+} fairsub vertices"
        ));
    }
    let mut cluster_of_g = vec![usize::MAX; got.points.len()];
    let mut cluster_of_w = vec![usize::MAX; want.points.len()];
    for (k, &v) in g_ref.iter().enumerate() {
        cluster_of_g[v] = find(&mut parent, k);
    }
    for (k, &v) in w_ref.iter().enumerate() {
        cluster_of_w[v] = find(&mut parent, n + k);
    }
    // Isolated vertices: each of the peer's needs a fairsub vertex no face uses.
    let gu: Vec<[f64; 3]> = g_unref.iter().map(|&v| got.points[v]).collect();
    let wi: Vec<[f64; 3]> = w_iso.iter().map(|&v| want.points[v]).collect();
    if let Some(k) = neighbours(&wi, &gu, TOL)
        .iter()
        .position(|js| js.is_empty())
    {
        return Err(format!(
            "isolated vertex {:?} missing in fairsub's output",
            wi[k]
        ));
    }
    // Faces as cluster cycles.
    let mut pool: HashMap<Vec<usize>, Vec<(usize, usize)>> = HashMap::new();
    for &f in &w_faces {
        let cyc: Vec<usize> = want.faces[f].iter().map(|&v| cluster_of_w[v]).collect();
        let (key, rot) = canonical(&cyc);
        pool.entry(key).or_default().push((f, rot));
    }
    let has_uv = !want.uvs.is_empty();
    if has_uv && got.face_uvs.is_empty() {
        return Err("the net has UVs; fairsub wrote none".into());
    }
    let (mut g_vals, mut w_vals) = (vec![false; got.uvs.len()], vec![false; want.uvs.len()]);
    for (f, face) in got.faces.iter().enumerate() {
        let cyc: Vec<usize> = face.iter().map(|&v| cluster_of_g[v]).collect();
        let (key, mut rot) = canonical(&cyc);
        // Points of different kinds may coincide (the vertex and face points of a flat pillow
        // of two faces), so a cycle can match several peer faces, or one in several rotations:
        // with UVs, take the face and rotations whose UVs agree, if any.
        let choice = pool.get_mut(&key).and_then(|cands| {
            let hit = has_uv
                .then(|| {
                    let rots = |c: &[usize]| -> Vec<usize> {
                        let m = c.len();
                        (0..m)
                            .filter(|&r| (0..m).all(|i| c[(r + i) % m] == key[i]))
                            .collect()
                    };
                    let m = face.len();
                    cands.iter().enumerate().find_map(|(j, &(pf, _))| {
                        let wc: Vec<usize> =
                            want.faces[pf].iter().map(|&v| cluster_of_w[v]).collect();
                        let rw = rots(&wc);
                        rots(&cyc).into_iter().find_map(|rg| {
                            rw.iter()
                                .copied()
                                .find(|&r| {
                                    (0..m).all(|i| {
                                        let gu = got.face_uvs[f][(rg + i) % m];
                                        let wu = want.face_uvs[pf][(r + i) % m];
                                        dist(&got.uvs[gu], &want.uvs[wu]) <= TOL
                                    })
                                })
                                .map(|r| (j, rg, r))
                        })
                    })
                })
                .flatten();
            match hit {
                Some((j, rg, rw)) => {
                    rot = rg;
                    Some((cands.swap_remove(j).0, rw))
                }
                None => cands.pop(),
            }
        });
        let Some((pf, prot)) = choice else {
            let pts: Vec<[f64; 3]> = face.iter().map(|&v| got.points[v]).collect();
            return Err(format!(
                "fairsub face {f} {pts:?} is not an OpenSubdiv face"
            ));
        };
        if has_uv {
            let m = face.len();
            for i in 0..m {
                let gu = got.face_uvs[f][(rot + i) % m];
                let wu = want.face_uvs[pf][(prot + i) % m];
                g_vals[gu] = true;
                w_vals[wu] = true;
                let d = dist(&got.uvs[gu], &want.uvs[wu]);
                worst = worst.max(d);
                if d > TOL {
                    return Err(format!(
                        "UV of fairsub face {f} corner {}: {:?}, OpenSubdiv {:?} (off by {d:.3e})",
                        (rot + i) % m,
                        got.uvs[gu],
                        want.uvs[wu]
                    ));
                }
            }
        }
    }
    if has_uv {
        let count = |u: &[bool]| u.iter().filter(|&&b| b).count();
        if count(&g_vals) != count(&w_vals) {
            return Err(format!(
                "distinct UV values: fairsub {}, OpenSubdiv {}",
                count(&g_vals),
                count(&w_vals)
            ));
        }
    }
    Ok(worst)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2x1 quad strip with UVs, in the peer's layout, plus an isolated vertex and a hole face.
    fn strip() -> Refined {
        Refined {
            points: vec![
                [0., 0., 0.],
                [1., 0., 0.],
                [2., 0., 0.],
                [0., 1., 0.],
                [1., 1., 0.],
                [2., 1., 0.],
                [5., 5., 5.],
                [3., 0., 0.],
            ],
            faces: vec![vec![0, 1, 4, 3], vec![1, 2, 5, 4], vec![2, 7, 5]],
            hole: vec![false, false, true],
            uvs: vec![
                [0., 0.],
                [0.5, 0.],
                [1., 0.],
                [0., 1.],
                [0.5, 1.],
                [1., 1.],
                [9., 9.],
            ],
            face_uvs: vec![vec![0, 1, 4, 3], vec![1, 2, 5, 4], vec![2, 6, 5]],
        }
    }

    /// `strip()` as fairsub might write it: vertices permuted, faces rotated, hole dropped.
    fn strip_permuted() -> Refined {
        let w = strip();
        let perm = [4, 0, 5, 2, 1, 3, 6]; // new index -> old index (the hole-only vertex 7 dropped)
        let inv = |old: usize| perm.iter().position(|&p| p == old).unwrap();
        Refined {
            points: perm.iter().map(|&o| w.points[o]).collect(),
            faces: vec![
                vec![inv(5), inv(4), inv(1), inv(2)],
                vec![inv(4), inv(3), inv(0), inv(1)],
            ],
            hole: vec![false, false],
            uvs: vec![[0.5, 1.], [1., 1.], [0.5, 0.], [1., 0.], [0., 0.], [0., 1.]],
            face_uvs: vec![vec![1, 0, 2, 3], vec![0, 5, 4, 2]],
        }
    }

    #[test]
    fn comparer_accepts_a_permuted_rotated_copy() {
        assert_eq!(compare(&strip_permuted(), &strip()), Ok(0.0));
    }

    #[test]
    fn comparer_rejects_moved_points_faces_and_uvs() {
        let w = strip();
        let mut g = strip_permuted();
        g.points[0][2] += 2e-6;
        assert!(
            compare(&g, &w)
                .unwrap_err()
                .contains("no OpenSubdiv vertex")
        );
        let mut g = strip_permuted();
        g.points[0][2] += 5e-7;
        assert!((compare(&g, &w).unwrap() - 5e-7).abs() < 1e-12);
        let mut g = strip_permuted();
        g.faces[0].reverse(); // orientation flipped
        assert!(
            compare(&g, &w)
                .unwrap_err()
                .contains("is not an OpenSubdiv face")
        );
        let mut g = strip_permuted();
        g.uvs[3][0] += 1e-3;
        assert!(compare(&g, &w).unwrap_err().contains("UV of fairsub face"));
        let mut g = strip_permuted();
        g.face_uvs.clear();
        g.uvs.clear();
        assert!(compare(&g, &w).unwrap_err().contains("wrote none"));
        let mut g = strip_permuted();
        g.points.pop(); // the isolated vertex lost
        assert!(
            compare(&g, &w)
                .unwrap_err()
                .contains("used by no written face")
        );
        let mut g = strip_permuted();
        g.faces.pop();
        g.face_uvs.pop();
        assert!(compare(&g, &w).unwrap_err().contains("faces: fairsub 1"));
    }

    #[test]
    fn comparer_counts_coincident_points_per_cluster() {
        // Two peer vertices at one place (2 and 7), used by a written face: fairsub must write two.
        let mut w = strip();
        w.points[7] = w.points[2];
        w.hole[2] = false;
        w.face_uvs[2] = vec![2, 2, 5];
        let mut g = strip_permuted(); // old 2 -> new 3, old 5 -> new 2
        g.points.push(w.points[2]);
        let extra = g.points.len() - 1;
        g.faces.push(vec![3, extra, 2]);
        g.face_uvs.push(vec![3, 3, 1]);
        assert_eq!(compare(&g, &w), Ok(0.0));
        // Three fairsub vertices at that place and none at peer vertex 5's.
        let mut g1 = g.clone();
        g1.points[2] = w.points[2];
        assert!(compare(&g1, &w).unwrap_err().contains("cluster"));
    }
}
