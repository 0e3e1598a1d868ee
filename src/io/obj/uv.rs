//! OBJ output with face-varying data: `vt u v` lines (one per value) and `f v/vt` corners.

use super::super::Polygons;
use super::super::textout::{ChunkedText, push_f64};
use crate::mesh::FaceVarying;
use std::io::Write;

/// Writes polygons as OBJ with texture coordinates: `uv.corners` has one value per face corner
/// (face after face, as the polygons' corners).
pub(crate) fn write_obj_uv_to(
    w: &mut dyn Write,
    p: &Polygons<'_>,
    uv: &FaceVarying,
) -> std::io::Result<()> {
    use std::fmt::Write as _;
    let mut out = ChunkedText::new(w);
    let _ = writeln!(
        out.buf,
        "# fairsub: {} vertices, {} texture coordinates, {} faces",
        p.positions.len(),
        uv.values.len(),
        p.num_faces()
    );
    out.point_lines("v ", p.positions)?;
    for t in &uv.values {
        out.buf.push_str("vt ");
        push_f64(&mut out.buf, t[0]);
        out.buf.push(' ');
        push_f64(&mut out.buf, t[1]);
        out.buf.push('\n');
        out.maybe_flush()?;
    }
    let mut k = 0;
    for face in p.faces() {
        out.buf.push('f');
        for &v in face {
            let _ = write!(out.buf, " {}/{}", v as u64 + 1, uv.corners[k] as u64 + 1);
            k += 1;
        }
        out.buf.push('\n');
        out.maybe_flush()?;
    }
    out.finish()
}
