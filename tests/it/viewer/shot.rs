//! Screenshots of the viewer judged by their pixels: where the canvas is, light/dark
//! alternations, hues, coverage, differences between two pictures; and the automatic curvature
//! range recomputed from a surface buffer.

/// An RGB screenshot and where the canvas is in it.
pub struct Shot {
    pub w: usize,
    pub rgb: Vec<[u8; 3]>,
    /// The canvas: x0, y0, x1, y1 (exclusive).
    pub canvas: (usize, usize, usize, usize),
}

pub fn decode(png_bytes: &[u8], canvas: (usize, usize, usize, usize)) -> Shot {
    let dec = png::Decoder::new(std::io::Cursor::new(png_bytes));
    let mut r = dec.read_info().unwrap();
    let mut buf = vec![0; r.output_buffer_size().unwrap()];
    let info = r.next_frame(&mut buf).unwrap();
    let ch = info.color_type.samples();
    let rgb = buf[..info.buffer_size()]
        .chunks(ch)
        .map(|p| [p[0], p[1], p[2]])
        .collect();
    Shot {
        w: info.width as usize,
        rgb,
        canvas,
    }
}

impl Shot {
    pub fn at(&self, x: usize, y: usize) -> [u8; 3] {
        self.rgb[y * self.w + x]
    }
    pub fn lum(&self, x: usize, y: usize) -> f64 {
        let [r, g, b] = self.at(x, y);
        0.3 * r as f64 + 0.59 * g as f64 + 0.11 * b as f64
    }
    pub fn pixels(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        let (x0, y0, x1, y1) = self.canvas;
        (y0..y1).flat_map(move |y| (x0..x1).map(move |x| (x, y)))
    }
    /// The most light/dark alternations along one row of the canvas.
    pub fn max_alternations(&self) -> usize {
        let (x0, y0, x1, y1) = self.canvas;
        (y0..y1)
            .step_by(4)
            .map(|y| {
                let (mut n, mut last) = (0, None);
                for x in x0..x1 {
                    let l = self.lum(x, y);
                    let s = if l < 70.0 {
                        Some(false)
                    } else if l > 170.0 {
                        Some(true)
                    } else {
                        None
                    };
                    if s.is_some() && last.is_some() && s != last {
                        n += 1;
                    }
                    last = s.or(last);
                }
                n
            })
            .max()
            .unwrap_or(0)
    }
    /// Distinct hues (of 12 buckets) among saturated canvas pixels in rows y0..y1, each
    /// covering at least `min` pixels.
    pub fn hues(&self, y0: usize, y1: usize, min: usize) -> usize {
        let mut count = [0usize; 12];
        for (x, y) in self.pixels().filter(|&(_, y)| y >= y0 && y < y1) {
            if let Some(h) = hue(self.at(x, y)) {
                count[h] += 1;
            }
        }
        count.iter().filter(|&&c| c >= min).count()
    }
    /// Fraction of canvas pixels in canvas columns x0..x1 that are not the background.
    pub fn covered(&self, x0: usize, x1: usize) -> f64 {
        let (cx, y0, _, y1) = self.canvas;
        let mut n = 0;
        for y in y0..y1 {
            for x in cx + x0..cx + x1 {
                let [r, g, b] = self.at(x, y);
                if (r as i32 - 31).abs() + (g as i32 - 31).abs() + (b as i32 - 36).abs() > 12 {
                    n += 1;
                }
            }
        }
        n as f64 / ((x1 - x0) * (y1 - y0)) as f64
    }
    pub fn width(&self) -> usize {
        self.canvas.2 - self.canvas.0
    }
    /// Canvas pixels where the two shots differ by more than `tol` in a channel.
    pub fn changed(&self, other: &Shot, tol: i32) -> usize {
        assert_eq!(self.canvas, other.canvas);
        self.pixels()
            .filter(|&(x, y)| {
                let (a, b) = (self.at(x, y), other.at(x, y));
                (0..3).any(|c| (a[c] as i32 - b[c] as i32).abs() > tol)
            })
            .count()
    }
    /// Canvas pixels close to `rgb`.
    pub fn count_near(&self, rgb: [u8; 3], tol: i32) -> usize {
        self.pixels()
            .filter(|&(x, y)| {
                let a = self.at(x, y);
                (0..3).all(|c| (a[c] as i32 - rgb[c] as i32).abs() <= tol)
            })
            .count()
    }
    /// The centroid of the non-background canvas pixels.
    pub fn centroid(&self) -> (f64, f64) {
        let (mut sx, mut sy, mut n) = (0.0, 0.0, 0.0);
        for (x, y) in self.pixels() {
            let [r, g, b] = self.at(x, y);
            if (r as i32 - 31).abs() + (g as i32 - 31).abs() + (b as i32 - 36).abs() > 12 {
                sx += x as f64;
                sy += y as f64;
                n += 1.0;
            }
        }
        (sx / n, sy / n)
    }
}

/// The hue bucket (of 12) of a saturated colour.
pub fn hue(p: [u8; 3]) -> Option<usize> {
    let [r, g, b] = p.map(|c| c as f64 / 255.0);
    let (mx, mn) = (r.max(g).max(b), r.min(g).min(b));
    if mx - mn < 0.3 {
        return None;
    }
    let h = if mx == r {
        ((g - b) / (mx - mn)).rem_euclid(6.0)
    } else if mx == g {
        (b - r) / (mx - mn) + 2.0
    } else {
        (r - g) / (mx - mn) + 4.0
    };
    Some(((h / 6.0 * 12.0) as usize).min(11))
}

/// The area-weighted 98th percentile of |H| or |K| of a surface buffer (the page's automatic
/// range, computed here independently from the buffer).
pub fn weighted_percentile(body: &[u8], gauss: bool) -> f64 {
    let word = |i: usize| u32::from_le_bytes(body[4 * i..4 * i + 4].try_into().unwrap()) as usize;
    let float = |off: usize| f32::from_le_bytes(body[off..off + 4].try_into().unwrap()) as f64;
    let (nv, nt) = (word(1), word(2));
    let pos = |v: usize| [0, 1, 2].map(|i| float(48 + 12 * v + 4 * i));
    let val = |v: usize| float(48 + (if gauss { 24 } else { 28 }) * nv + 4 * v).abs();
    let mut area = vec![0.0; nv];
    let idx = 48 + 36 * nv;
    for t in 0..nt {
        let c = [0, 1, 2].map(|i| word(idx / 4 + 3 * t + i));
        let [a, p, q] = c.map(pos);
        let u = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
        let w = [q[0] - a[0], q[1] - a[1], q[2] - a[2]];
        let cr = [
            u[1] * w[2] - u[2] * w[1],
            u[2] * w[0] - u[0] * w[2],
            u[0] * w[1] - u[1] * w[0],
        ];
        let ar = (cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]).sqrt() / 6.0;
        for v in c {
            area[v] += ar;
        }
    }
    let mut vals: Vec<(f64, f64)> = (0..nv)
        .filter(|&v| !val(v).is_nan())
        .map(|v| (val(v), area[v]))
        .collect();
    vals.sort_by(|a, b| a.0.total_cmp(&b.0));
    let total: f64 = vals.iter().map(|v| v.1).sum();
    let mut acc = 0.0;
    for (v, w) in &vals {
        acc += w;
        if acc >= 0.98 * total {
            return *v;
        }
    }
    vals.last().unwrap().0
}
