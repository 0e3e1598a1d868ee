//! The PLY writers: ascii, and binary little endian encoded in parallel.
//!
//! Both write `double` coordinates and `property list uchar int vertex_indices` (a wider count
//! or index type when a face or the vertex count needs it). The binary writer encodes blocks of
//! vertices and faces into buffers of about 1 MiB in parallel while the calling thread writes
//! the previous batch, so a refined net of hundreds of megabytes is written at the speed of the
//! output, with a few megabytes of buffers.

use super::super::Polygons;
use super::super::textout::ChunkedText;
use std::borrow::Cow;
use std::io::Write;

/// The PLY header for `p`; `format` is the `format` line's encoding name.
pub(super) fn header_text(p: &Polygons<'_>, format: &str) -> String {
    let count_type = if p.max_face <= u8::MAX as usize {
        "uchar"
    } else {
        "int"
    };
    let index_type = if p.positions.len() <= i32::MAX as usize {
        "int"
    } else {
        "uint"
    };
    format!(
        "ply\nformat {format} 1.0\ncomment written by fairsub\nelement vertex {}\n\
         property double x\nproperty double y\nproperty double z\nelement face {}\n\
         property list {count_type} {index_type} vertex_indices\nend_header\n",
        p.positions.len(),
        p.num_faces()
    )
}

/// Writes polygons as ascii PLY with round-trip precision.
pub(crate) fn write_ply_ascii_to(w: &mut dyn Write, p: &Polygons<'_>) -> std::io::Result<()> {
    let mut out = ChunkedText::new(w);
    out.buf.push_str(&header_text(p, "ascii"));
    out.point_lines("", p.positions)?;
    out.counted_face_lines(p.faces())?;
    out.finish()
}

/// Bytes of output per encoding job of the binary writer (above the 1 MiB of the atomic
/// writer's buffer, so jobs go straight to the file without another copy).
const JOB_BYTES: usize = 2 << 20;
/// Jobs encoded in parallel while the previous batch is written.
const JOBS_PER_BATCH: usize = 4;

/// The bytes of points (`3 x f64` each, no padding), in memory order.
#[cfg(target_endian = "little")]
fn point_bytes(points: &[crate::geom::Point]) -> &[u8] {
    // SAFETY: `[f64; 3]` has size 24, no padding and no invalid bit patterns as bytes; the
    // returned slice borrows `points` for its whole length, with byte alignment.
    unsafe { std::slice::from_raw_parts(points.as_ptr().cast::<u8>(), size_of_val(points)) }
}

/// Writes polygons as binary little-endian PLY (double coordinates).
///
/// The body is cut into jobs of about [`JOB_BYTES`]; batches of jobs are encoded in parallel
/// (rayon) while the calling thread writes the batch before, so encoding and writing overlap
/// and the buffers in flight stay at two batches.
pub(crate) fn write_ply_binary_to(w: &mut dyn Write, p: &Polygons<'_>) -> std::io::Result<()> {
    use rayon::prelude::*;
    w.write_all(header_text(p, "binary_little_endian").as_bytes())?;
    let wide_count = p.max_face > u8::MAX as usize;
    // Jobs: ranges of vertices, then ranges of faces.
    enum Job {
        Vertices(usize, usize),
        Faces(usize, usize),
    }
    let nv = p.positions.len();
    let nf = p.num_faces();
    let per_vertex = JOB_BYTES / 24;
    let mut jobs: Vec<Job> = (0..nv.div_ceil(per_vertex))
        .map(|k| Job::Vertices(k * per_vertex, ((k + 1) * per_vertex).min(nv)))
        .collect();
    let mut f = 0;
    while f < nf {
        // Cut face ranges by their encoded size (count byte(s) and 4 bytes per corner).
        let target = p.face_offset(f) + JOB_BYTES / 5;
        let g = if p.uniform != 0 {
            (f + (JOB_BYTES / 5).div_ceil(p.uniform)).min(nf)
        } else {
            let rest = &p.face_start[f + 1..];
            (f + 1 + rest.partition_point(|&s| (s as usize) < target)).min(nf)
        };
        jobs.push(Job::Faces(f, g));
        f = g;
    }
    let encode = |job: &Job| -> Cow<'_, [u8]> {
        match *job {
            // On a little-endian machine the points are already the file's bytes: written
            // straight from the mesh, no copy.
            #[cfg(target_endian = "little")]
            Job::Vertices(a, b) => Cow::Borrowed(point_bytes(&p.positions[a..b])),
            #[cfg(not(target_endian = "little"))]
            Job::Vertices(a, b) => {
                let mut buf = Vec::with_capacity(24 * (b - a));
                for q in &p.positions[a..b] {
                    buf.extend_from_slice(&q[0].to_le_bytes());
                    buf.extend_from_slice(&q[1].to_le_bytes());
                    buf.extend_from_slice(&q[2].to_le_bytes());
                }
                Cow::Owned(buf)
            }
            Job::Faces(a, b) => {
                let corners = p.face_offset(b) - p.face_offset(a);
                let count = if wide_count { 4 } else { 1 };
                let mut buf = Vec::with_capacity(count * (b - a) + 4 * corners);
                for f in a..b {
                    let face = p.face(f);
                    if wide_count {
                        buf.extend_from_slice(&(face.len() as i32).to_le_bytes());
                    } else {
                        buf.push(face.len() as u8);
                    }
                    for &v in face {
                        // `int` when the vertex count fits, else `uint`: same four bytes for
                        // valid indices.
                        buf.extend_from_slice(&v.to_le_bytes());
                    }
                }
                Cow::Owned(buf)
            }
        }
    };
    let encode_batch =
        |batch: &[Job]| -> Vec<Cow<'_, [u8]>> { batch.par_iter().map(encode).collect() };
    let mut batches = jobs.chunks(JOBS_PER_BATCH);
    let mut ready = batches.next().map(encode_batch).unwrap_or_default();
    loop {
        let next = batches.next();
        let mut encoded = None;
        let mut result = Ok(());
        rayon::in_place_scope(|s| {
            if let Some(batch) = next {
                let slot = &mut encoded;
                s.spawn(move |_| *slot = Some(encode_batch(batch)));
            }
            for buf in &ready {
                if result.is_ok() {
                    result = w.write_all(buf);
                }
            }
        });
        result?;
        match encoded {
            Some(e) => ready = e,
            None => return Ok(()),
        }
    }
}
