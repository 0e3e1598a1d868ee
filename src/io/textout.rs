//! Text output shared by the writers: numbers in shortest round-trip form, and a sink that
//! formats many small lines into large chunks, with the point and face lines that OBJ, OFF,
//! ascii PLY and `.bv` polyhedra have in common.

use crate::geom::Point;
use std::fmt::Display;
use std::io::Write;

/// Appends `x` to `s` so that it reads back as exactly the same `f64` (shortest round-trip form;
/// exponent notation for very large or small magnitudes).
pub(crate) fn push_f64(s: &mut String, x: f64) {
    use std::fmt::Write as _;
    let a = x.abs();
    if a == 0.0 || (1e-5..1e16).contains(&a) {
        let _ = write!(s, "{x}");
    } else {
        let _ = write!(s, "{x:e}");
    }
}

/// Appends `x y z` of a point.
pub(crate) fn push_point(s: &mut String, p: Point) {
    push_f64(s, p[0]);
    s.push(' ');
    push_f64(s, p[1]);
    s.push(' ');
    push_f64(s, p[2]);
}

/// A text sink that formats into a string and hands it to the writer in large chunks, so that
/// many small lines cost no dynamic calls each.
pub(crate) struct ChunkedText<'w> {
    pub buf: String,
    w: &'w mut dyn Write,
}

impl<'w> ChunkedText<'w> {
    const CHUNK: usize = 1 << 16;

    pub fn new(w: &'w mut dyn Write) -> Self {
        ChunkedText {
            buf: String::with_capacity(Self::CHUNK + 256),
            w,
        }
    }

    /// Flushes the buffer when it is full; call after each line.
    #[inline]
    pub fn maybe_flush(&mut self) -> std::io::Result<()> {
        if self.buf.len() >= Self::CHUNK {
            self.w.write_all(self.buf.as_bytes())?;
            self.buf.clear();
        }
        Ok(())
    }

    /// One line `prefix x y z` per point.
    pub fn point_lines(&mut self, prefix: &str, points: &[Point]) -> std::io::Result<()> {
        for &q in points {
            self.buf.push_str(prefix);
            push_point(&mut self.buf, q);
            self.buf.push('\n');
            self.maybe_flush()?;
        }
        Ok(())
    }

    /// One line per face: its corner count, then its corners (`n i1 .. in`, as OFF, ascii PLY
    /// and `.bv` polyhedra write them).
    pub fn counted_face_lines<F, T>(
        &mut self,
        faces: impl IntoIterator<Item = F>,
    ) -> std::io::Result<()>
    where
        F: AsRef<[T]>,
        T: Display,
    {
        use std::fmt::Write as _;
        for face in faces {
            let face = face.as_ref();
            let _ = write!(self.buf, "{}", face.len());
            for v in face {
                let _ = write!(self.buf, " {v}");
            }
            self.buf.push('\n');
            self.maybe_flush()?;
        }
        Ok(())
    }

    /// Writes the text so far, then `bytes` (for binary bodies after a text header).
    pub fn write_bytes(&mut self, bytes: &[u8]) -> std::io::Result<()> {
        self.w.write_all(self.buf.as_bytes())?;
        self.buf.clear();
        self.w.write_all(bytes)
    }

    /// Writes what is left.
    pub fn finish(mut self) -> std::io::Result<()> {
        self.w.write_all(self.buf.as_bytes())?;
        self.buf.clear();
        Ok(())
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn push_f64_roundtrips() {
        for x in [
            0.0,
            -0.0,
            1.0,
            0.1,
            1.0 / 3.0,
            -2.5e-300,
            1.7976931348623157e308,
            123_456_789.123_456_79,
            1e-5,
            9.99e-6,
            1e16,
        ] {
            let mut s = String::new();
            push_f64(&mut s, x);
            let y: f64 = s.parse().unwrap();
            assert_eq!(x.to_bits(), y.to_bits(), "{x} -> {s}");
        }
        let mut s = String::new();
        push_f64(&mut s, 1e-7);
        assert_eq!(s, "1e-7");
    }

    #[crate::unit::test]
    fn point_and_face_lines() {
        let mut bytes = Vec::new();
        let mut out = ChunkedText::new(&mut bytes);
        out.point_lines("v ", &[[0.5, -1.0, 1e20]]).unwrap();
        out.counted_face_lines([[0u32, 1, 2]]).unwrap();
        out.counted_face_lines(vec![vec![3usize, 4, 5, 6]]).unwrap();
        out.finish().unwrap();
        assert_eq!(
            String::from_utf8(bytes).unwrap(),
            "v 0.5 -1 1e20\n3 0 1 2\n4 3 4 5 6\n"
        );
    }
}
