//! The text of `fairsub eval`: its points read from `--at-file` and its evaluations written as
//! lines or JSON, both in parallel blocks (10^6 points must take well under a second).
//!
//! Every number is written as the shortest decimal text that reads back to the same `f64`
//! (zmij, the printer serde_json uses for `--json`): exact, and several times faster than
//! `{:.17e}`, whose 17-digit output often falls back to big-number arithmetic.

use crate::error::{Error, Result};
use crate::surface::eval::Evaluation;
use rayon::prelude::*;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Points per block formatted (or lines per block parsed) by one parallel task.
const BLOCK: usize = 4096;

/// Blocks per group of points: a group is evaluated in face order, then formatted; one group's
/// text is written while the next is computed (at most two groups of text held at once).
/// 16 blocks (65,536 points): on 10^6 points, 173 MB peak and 62k page faults against 313 MB
/// and 106k with 64 blocks, for the same time (the buffers are reused by more groups).
const AHEAD: usize = 16;

/// A point `F:U:V` of the command line or of a file.
pub type Point = (u32, f64, f64);

/// Appends `x` as the shortest text that reads back to the same `f64` (`NaN`, `inf`, `-inf`
/// for the non-finite values, which Rust's and Python's float parsers read).
/// Returns the text's length.
#[inline]
fn num(out: &mut Vec<u8>, x: f64) -> usize {
    let mut buf = zmij::Buffer::new();
    let text = buf.format(x).as_bytes();
    out.extend_from_slice(text);
    text.len()
}

/// Appends an unsigned integer.
#[inline]
fn int(out: &mut Vec<u8>, mut k: u64) {
    let mut digits = [0u8; 20];
    let mut i = digits.len();
    loop {
        i -= 1;
        digits[i] = b'0' + (k % 10) as u8;
        k /= 10;
        if k == 0 {
            break;
        }
    }
    out.extend_from_slice(&digits[i..]);
}

/// Appends ` x y z`.
fn vec3(out: &mut Vec<u8>, p: [f64; 3]) {
    for x in p {
        out.push(b' ');
        num(out, x);
    }
}

/// Appends the text line of one evaluation (with its newline):
/// `F:U:V patch P at (PU, PV) point X Y Z normal X Y Z gauss G mean M`.
pub fn line(out: &mut Vec<u8>, e: &Evaluation) {
    int(out, u64::from(e.face));
    out.push(b':');
    let u_start = out.len();
    num(out, e.u);
    out.push(b':');
    let v_len = num(out, e.v);
    let (u_end, v_start, v_end) = (out.len() - v_len - 1, out.len() - v_len, out.len());
    out.extend_from_slice(b" patch ");
    int(out, e.patch as u64);
    out.extend_from_slice(b" at (");
    // a patch covering its face whole has the face's parameters: their text again
    if e.patch_uv[0].to_bits() == e.u.to_bits() {
        out.extend_from_within(u_start..u_end);
    } else {
        num(out, e.patch_uv[0]);
    }
    out.extend_from_slice(b", ");
    if e.patch_uv[1].to_bits() == e.v.to_bits() {
        out.extend_from_within(v_start..v_end);
    } else {
        num(out, e.patch_uv[1]);
    }
    out.extend_from_slice(b") point");
    vec3(out, e.point);
    out.extend_from_slice(b" normal");
    vec3(out, e.normal);
    out.extend_from_slice(b" gauss ");
    num(out, e.gauss);
    out.extend_from_slice(b" mean ");
    num(out, e.mean);
    out.push(b'\n');
}

/// One evaluation as `serde_json::to_string_pretty` writes it inside the array (indented one
/// level, no separator).
fn json_item(out: &mut Vec<u8>, e: &Evaluation) -> Result<()> {
    let mut item = Vec::with_capacity(640);
    serde_json::to_writer_pretty(&mut item, e)
        .map_err(|err| Error::InvalidArgument(format!("JSON output: {err}")))?;
    // no strings inside: every newline is a line break of the layout
    for &b in &item {
        out.push(b);
        if b == b'\n' {
            out.extend_from_slice(b"  ");
        }
    }
    Ok(())
}

/// The evaluation of point `i` (of the command's points, in order).
pub type EvalFn<'a> = dyn Fn(usize) -> Result<Evaluation> + Sync + 'a;

/// Where formatted text goes, a block of whole lines at a time.
pub type WriteFn<'a> = dyn FnMut(&[u8]) -> Result<()> + 'a;

/// Appends the text of evaluation `i` (the whole array's `i`-th item).
type FormatFn = dyn Fn(&mut Vec<u8>, usize, &Evaluation) -> Result<()> + Sync;

/// The locality key of point `i`: its input face. Points are evaluated in order of it.
pub type KeyFn<'a> = dyn Fn(usize) -> u32 + Sync + 'a;

/// Evaluates and formats points `0..n` in groups of [`BLOCK`] x [`AHEAD`] points and hands the
/// text, in the points' order, to `write` a block of [`BLOCK`] lines at a time. Within a group
/// the points are evaluated in parallel in the order of `key` (their face: the points of one
/// face, so of a few patches, one after another; in the order given, random points miss the
/// cache on every patch, which cost a third of the time on 10^6 random points), into a
/// buffer of the group's evaluations reused by every group; the group is then formatted in
/// parallel blocks in the points' order. The first error by point index stops it.
fn blocks(
    n: usize,
    key: &KeyFn,
    eval: &EvalFn,
    format: &FormatFn,
    write: &mut WriteFn,
) -> Result<()> {
    let group_len = (BLOCK * AHEAD).min(n);
    let per_group = n.div_ceil(BLOCK).min(AHEAD);
    // the buffers are allocated once and reused by every group (fresh megabyte buffers per
    // block cost a page fault per page and an unmapping per block); while one group's text is
    // written (on this thread: `write` may be bound to it), the next is computed
    let mut work = Group {
        texts: vec![Vec::new(); per_group],
        blocks: 0,
        order: Vec::with_capacity(group_len),
        slot: vec![0; group_len],
        evals: Vec::with_capacity(group_len),
    };
    let mut ready: Vec<Vec<u8>> = vec![Vec::new(); per_group];
    let mut ready_blocks = 0;
    for group in (0..n).step_by(BLOCK * AHEAD) {
        let end = (group + BLOCK * AHEAD).min(n);
        // a rayon scope: the group is computed by the pool (this thread joins in when its
        // text is written), never by a thread that would wait for a pool this one may be the
        // only worker of
        let mut computed = Ok(());
        let written = rayon::in_place_scope(|s| {
            let (work, computed) = (&mut work, &mut computed);
            s.spawn(move |_| *computed = work.compute(group..end, key, eval, format));
            ready[..ready_blocks].iter().try_for_each(|t| write(t))
        });
        written?;
        computed?;
        std::mem::swap(&mut ready, &mut work.texts);
        ready_blocks = work.blocks;
    }
    ready[..ready_blocks].iter().try_for_each(|t| write(t))
}

/// Points ahead whose evaluation [`Group::compute`] asks the cache for while it formats one.
const PREFETCH: usize = 8;

/// Asks the cache for the lines of `x` (read in an order unrelated to where they lie: the
/// evaluations of a group in the points' order); a hint only.
#[inline]
fn prefetch<T>(x: &T) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let p = (x as *const T).cast::<i8>();
        for line in (0..std::mem::size_of::<T>()).step_by(64) {
            // SAFETY: a prefetch never faults; the addresses lie within `x`
            unsafe { _mm_prefetch::<_MM_HINT_T0>(p.wrapping_add(line)) };
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = x;
}

/// The buffers of one group of points in [`blocks`].
struct Group {
    /// The text of each block of the group.
    texts: Vec<Vec<u8>>,
    /// Blocks of the group.
    blocks: usize,
    /// The group's points sorted by key: `key << 32 | position in the group`.
    order: Vec<u64>,
    /// Per point of the group its place in `order` (and `evals`).
    slot: Vec<u32>,
    /// The evaluations in `order` (a failed point's: a default, never formatted).
    evals: Vec<Evaluation>,
}

impl Group {
    /// Evaluates the points `range` in order of `key` and formats them in their order into
    /// `texts`; the first error by point index.
    fn compute(
        &mut self,
        range: std::ops::Range<usize>,
        key: &KeyFn,
        eval: &EvalFn,
        format: &FormatFn,
    ) -> Result<()> {
        let (group, len) = (range.start, range.len());
        self.order.clear();
        self.order.par_extend(
            (0..len as u64)
                .into_par_iter()
                .map(|i| (u64::from(key(group + i as usize)) << 32) | i),
        );
        self.order.par_sort_unstable();
        for (k, &o) in self.order.iter().enumerate() {
            self.slot[(o & 0xffff_ffff) as usize] = k as u32;
        }
        // a failed point is noted by its index (the least one wins) and evaluated again for
        // its error: no `Result` stored per point, and no pass over the evaluations to find it
        let failed = AtomicUsize::new(usize::MAX);
        self.order
            .par_iter()
            .map(|&o| {
                let i = group + (o & 0xffff_ffff) as usize;
                eval(i).unwrap_or_else(|_| {
                    failed.fetch_min(i, Ordering::Relaxed);
                    Evaluation::default()
                })
            })
            .collect_into_vec(&mut self.evals);
        let failed = failed.into_inner();
        if failed != usize::MAX {
            return Err(eval(failed).err().unwrap_or_else(|| {
                Error::InvalidArgument(format!("point {}: no evaluation", failed + 1))
            }));
        }
        // `slot` has room for a whole group: a shorter (last) group uses its first `len`
        // entries, the rest are stale (looking ahead into them indexed past `evals`)
        let (evals, slot) = (&self.evals, &self.slot[..len]);
        self.blocks = len.div_ceil(BLOCK);
        self.texts[..self.blocks]
            .par_iter_mut()
            .enumerate()
            .map(|(b, text)| {
                let first = b * BLOCK;
                let last = (first + BLOCK).min(len);
                text.clear();
                text.reserve((last - first) * 300);
                for i in first..last {
                    if let Some(&ahead) = slot.get(i + PREFETCH) {
                        prefetch(&evals[ahead as usize]);
                    }
                    format(text, group + i, &evals[slot[i] as usize])?;
                }
                Ok(())
            })
            .collect::<Result<()>>()
    }
}

/// Writes the text lines of the evaluations of points `0..n` through `write`, a block of
/// lines at a time.
pub fn write_lines(n: usize, key: &KeyFn, eval: &EvalFn, write: &mut WriteFn) -> Result<()> {
    blocks(
        n,
        key,
        eval,
        &|out, _, e| {
            line(out, e);
            Ok(())
        },
        write,
    )
}

/// Numbers per point of [`write_binary`].
pub const BINARY_FIELDS: usize = 29;

/// Appends the binary record of one evaluation: [`BINARY_FIELDS`] little-endian `f64` (face,
/// u, v, patch, patch u, patch v, point x y z, du, dv, duu, duv, dvv (3 each), normal x y z,
/// gauss, mean); the face and patch indices are exact as `f64` (below 2^53).
pub fn record(out: &mut Vec<u8>, e: &Evaluation) {
    let start = out.len();
    let head = [
        f64::from(e.face),
        e.u,
        e.v,
        e.patch as f64,
        e.patch_uv[0],
        e.patch_uv[1],
    ];
    let vectors = [e.point, e.du, e.dv, e.duu, e.duv, e.dvv, e.normal];
    for x in head
        .into_iter()
        .chain(vectors.into_iter().flatten())
        .chain([e.gauss, e.mean])
    {
        out.extend_from_slice(&x.to_le_bytes());
    }
    debug_assert_eq!(out.len() - start, BINARY_FIELDS * 8);
}

/// Writes the evaluations of points `0..n` as binary records ([`record`]: every number of the
/// evaluation, exact, without the cost of printing it) through `write`.
pub fn write_binary(n: usize, key: &KeyFn, eval: &EvalFn, write: &mut WriteFn) -> Result<()> {
    blocks(
        n,
        key,
        eval,
        &|out, _, e| {
            record(out, e);
            Ok(())
        },
        write,
    )
}

/// Writes the evaluations of points `0..n` as `serde_json::to_string_pretty` writes their
/// array (byte for byte), then a newline, through `write`.
pub fn write_json(n: usize, key: &KeyFn, eval: &EvalFn, write: &mut WriteFn) -> Result<()> {
    if n == 0 {
        return write(b"[]\n");
    }
    write(b"[")?;
    blocks(
        n,
        key,
        eval,
        &|out, i, e| {
            out.extend_from_slice(if i == 0 { b"\n  " } else { b",\n  " });
            json_item(out, e)
        },
        write,
    )?;
    write(b"\n]\n")
}

/// One point `F:U:V` (or `F U V`); `what` names it in errors.
pub fn parse_point(text: &str, what: &dyn Fn() -> String) -> Result<Point> {
    let bad = |why: &str| {
        Error::InvalidArgument(format!("{}: '{text}' is not a point F:U:V ({why})", what()))
    };
    // the three fields without collecting them (10^6 lines of `--at-file`)
    let fields = match text.split_once(':') {
        Some((f, rest)) => rest
            .split_once(':')
            .filter(|(_, v)| !v.contains(':'))
            .map(|(u, v)| [f.trim(), u.trim(), v.trim()]),
        None => {
            let mut words = text.split_whitespace();
            match (words.next(), words.next(), words.next(), words.next()) {
                (Some(f), Some(u), Some(v), None) => Some([f, u, v]),
                _ => None,
            }
        }
    };
    let Some([f, u, v]) = fields else {
        return Err(bad("three fields expected"));
    };
    let f = f
        .parse::<u32>()
        .map_err(|_| bad("the face is not a non-negative integer"))?;
    let num = |s: &str| s.parse::<f64>().ok().filter(|x| x.is_finite());
    let (Some(u), Some(v)) = (num(u), num(v)) else {
        return Err(bad("u and v must be finite numbers"));
    };
    Ok((f, u, v))
}

/// The lines of a block of a points file as `str::lines` cuts them, each with its point when
/// it is exactly `F:U:V` (no spaces, comment or carriage return: what programs write).
///
/// One pass over the bytes finds a line's end and its first two colons (10^6 lines: `lines`
/// and two `split_once` cost three searches a line, a third of the parse); a plain line's
/// fields are then parsed without the general path's trimming. Any other line (the number
/// parsers refuse spaces, `#`, `\r` and a third colon) comes with `None` and takes
/// [`parse_point`].
struct Lines<'a> {
    text: &'a str,
    at: usize,
}

impl<'a> Lines<'a> {
    fn new(text: &'a str) -> Self {
        Lines { text, at: 0 }
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = (&'a str, Option<Point>);

    fn next(&mut self) -> Option<Self::Item> {
        let (text, start) = (self.text, self.at);
        let bytes = &text.as_bytes()[start..];
        if bytes.is_empty() {
            return None;
        }
        let mut colons = [0usize; 2];
        let mut found = 0;
        let mut end = bytes.len();
        for (i, &b) in bytes.iter().enumerate() {
            if b == b'\n' {
                end = i;
                break;
            }
            if b == b':' && found < 2 {
                colons[found] = i;
                found += 1;
            }
        }
        self.at = (start + end + 1).min(text.len());
        // ASCII positions: every slice below lies on character boundaries
        let line = &text[start..start + end];
        let plain = (found == 2)
            .then(|| {
                let f = face_number(&bytes[..colons[0]])?;
                let u = line[colons[0] + 1..colons[1]].parse::<f64>().ok()?;
                let v = line[colons[1] + 1..].parse::<f64>().ok()?;
                (u.is_finite() && v.is_finite()).then_some((f, u, v))
            })
            .flatten();
        // `str::lines` drops a carriage return before a newline only
        let line = match end < bytes.len() {
            true => line.strip_suffix('\r').unwrap_or(line),
            false => line,
        };
        Some((line, plain))
    }
}

/// The face of a plain line: decimal digits after an optional `+`, as `u32` reads them
/// (`None` for anything else, which the general path then reads or refuses).
#[inline]
fn face_number(text: &[u8]) -> Option<u32> {
    let digits = text.strip_prefix(b"+").unwrap_or(text);
    if digits.is_empty() {
        return None;
    }
    let mut f: u32 = 0;
    for &d in digits {
        if !d.is_ascii_digit() {
            return None;
        }
        f = f.checked_mul(10)?.checked_add(u32::from(d - b'0'))?;
    }
    Some(f)
}

/// The content of a line of a points file: without its `#` comment, trimmed.
fn content(line: &str) -> &str {
    line.split('#').next().unwrap_or("").trim()
}

/// The points of a points file's `text` (read from `path`), in order, parsed in parallel blocks
/// of lines; an error names the file and line of the first bad point.
///
/// Each block parses into its own stretch of the one vector returned, a slot per line (its
/// lines counted first): 10^6 points cost no second copy and no per-block vectors (24 MB of
/// fresh pages each); blank and comment lines leave slots that are closed up afterwards.
pub fn parse_file(text: &str, path: &Path) -> Result<Vec<Point>> {
    // blocks of about BLOCK lines (80 bytes each is generous), cut after a newline
    let bytes = text.as_bytes();
    let mut cuts = vec![0];
    while let Some(&last) = cuts.last() {
        let mut end = (last + BLOCK * 80).min(bytes.len());
        while end < bytes.len() && bytes[end - 1] != b'\n' {
            end += 1;
        }
        cuts.push(end);
        if end == bytes.len() {
            break;
        }
    }
    // lines per block (`str::lines`: a last line without its newline counts)
    let lines: Vec<usize> = cuts
        .par_windows(2)
        .map(|w| {
            let b = &bytes[w[0]..w[1]];
            bytecount(b) + usize::from(b.last().is_some_and(|&c| c != b'\n'))
        })
        .collect();
    let mut pts = vec![(0u32, 0.0f64, 0.0f64); lines.iter().sum()];
    let mut stretches = Vec::with_capacity(lines.len());
    let mut rest = pts.as_mut_slice();
    for &n in &lines {
        let (stretch, tail) = rest.split_at_mut(n);
        stretches.push(stretch);
        rest = tail;
    }
    // per block: the points it holds (at the start of its stretch), the first bad line
    let parsed: Vec<(usize, Option<usize>)> = cuts
        .par_windows(2)
        .zip(stretches)
        .map(|(w, stretch)| {
            let mut held = 0;
            for (k, (line, plain)) in Lines::new(&text[w[0]..w[1]]).enumerate() {
                let point = match plain {
                    Some(p) => p,
                    None => {
                        let line = content(line);
                        if line.is_empty() {
                            continue;
                        }
                        match parse_point(line, &String::new) {
                            Ok(p) => p,
                            Err(_) => return (held, Some(k)),
                        }
                    }
                };
                stretch[held] = point;
                held += 1;
            }
            (held, None)
        })
        .collect();
    let mut first_line = 0;
    let mut len = 0;
    for ((block, &(held, bad)), &n) in cuts.windows(2).zip(&parsed).zip(&lines) {
        if let Some(k) = bad {
            // parsed again, alone, for its message with the file and line
            let line = text[block[0]..block[1]].lines().nth(k).unwrap_or("");
            let at = first_line + k + 1;
            return Err(
                parse_point(content(line), &|| format!("{}:{at}", path.display()))
                    .err()
                    .unwrap_or_else(|| {
                        Error::InvalidArgument(format!("{}:{at}: bad point", path.display()))
                    }),
            );
        }
        // the block's points follow the previous blocks' (a no-op without skipped lines)
        pts.copy_within(first_line..first_line + held, len);
        len += held;
        first_line += n;
    }
    pts.truncate(len);
    Ok(pts)
}

/// Newlines in `b`.
fn bytecount(b: &[u8]) -> usize {
    b.iter().filter(|&&c| c == b'\n').count()
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn binary_records_hold_every_number_bit_for_bit() {
        let evals = sample();
        let bytes =
            collect_bytes(|w| write_binary(evals.len(), &|i| evals[i].face, &|i| Ok(evals[i]), w));
        assert_eq!(bytes.len(), evals.len() * BINARY_FIELDS * 8);
        for (rec, e) in bytes.chunks(BINARY_FIELDS * 8).zip(&evals) {
            let x: Vec<f64> = rec
                .chunks(8)
                .map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")))
                .collect();
            let want: Vec<f64> = [e.face as f64, e.u, e.v, e.patch as f64]
                .into_iter()
                .chain(e.patch_uv)
                .chain(
                    [e.point, e.du, e.dv, e.duu, e.duv, e.dvv, e.normal]
                        .into_iter()
                        .flatten(),
                )
                .chain([e.gauss, e.mean])
                .collect();
            for (a, b) in x.iter().zip(&want) {
                assert_eq!(a.to_bits(), b.to_bits());
            }
        }
    }

    fn collect_bytes(run: impl FnOnce(&mut WriteFn) -> Result<()>) -> Vec<u8> {
        let mut out = Vec::new();
        run(&mut |b: &[u8]| {
            out.extend_from_slice(b);
            Ok(())
        })
        .expect("written");
        out
    }

    fn sample() -> Vec<Evaluation> {
        (0..9000)
            .map(|i| {
                let x = f64::from(i);
                Evaluation {
                    face: i,
                    u: x / 7.0,
                    v: 1.0 / (x + 3.0),
                    patch: 3 * i as usize,
                    // a third of the points on patches covering their face whole
                    patch_uv: match i % 3 {
                        0 => [x / 7.0, 1.0 / (x + 3.0)],
                        1 => [x / 7.0, 1e-300 * x],
                        _ => [x.sin(), 1e-300 * x],
                    },
                    point: [x.cos(), -x * 1e17, 0.1 + x],
                    normal: [0.0, -0.0, 1.0],
                    gauss: if i % 5 == 0 { f64::NAN } else { x.sqrt() },
                    mean: -x.exp(),
                    ..Default::default()
                }
            })
            .collect()
    }

    fn collect(f: impl FnOnce(&mut WriteFn) -> Result<()>) -> String {
        String::from_utf8(collect_bytes(f)).expect("utf-8")
    }

    /// Several groups, the last one short, of points whose faces are scrambled (evaluated in
    /// another order than written): every line in its point's place (the look-ahead of the
    /// short group once read stale places of the group before and indexed past it).
    #[crate::unit::test]
    fn groups_of_any_length_keep_the_points_order() {
        let n = 2 * BLOCK * AHEAD + 12_345;
        let face = |i: usize| ((i as u64 * 2_654_435_761) % 9973) as u32;
        let eval = |i: usize| {
            Ok(Evaluation {
                face: face(i),
                u: i as f64,
                ..Default::default()
            })
        };
        let text = collect(|w| write_lines(n, &face, &eval, w));
        let mut lines = 0;
        for (i, l) in text.lines().enumerate() {
            let mut f = l.split(':');
            assert_eq!(f.next().map(str::parse::<u32>), Some(Ok(face(i))), "{l}");
            assert_eq!(f.next().map(str::parse::<f64>), Some(Ok(i as f64)), "{l}");
            lines += 1;
        }
        assert_eq!(lines, n);
        // the failure of least index stops the run, in whichever order the group evaluated
        let bad = [BLOCK * AHEAD + 9000, n - 5, BLOCK * AHEAD + 7];
        let failing = |i: usize| {
            if bad.contains(&i) {
                Err(Error::InvalidArgument(format!("point {i}")))
            } else {
                eval(i)
            }
        };
        let mut written = 0;
        let e = write_lines(n, &face, &failing, &mut |b: &[u8]| {
            written += b.iter().filter(|&&c| c == b'\n').count();
            Ok(())
        })
        .expect_err("a point fails");
        assert_eq!(e.to_string(), format!("invalid argument: point {}", bad[2]));
        assert_eq!(written, BLOCK * AHEAD, "the groups before the failing one");
    }

    #[crate::unit::test]
    fn json_is_serde_jsons_pretty_array() {
        let evals = sample();
        for n in [1, 2, 4096, 4097, evals.len()] {
            let got = collect(|w| write_json(n, &|i| evals[i].face, &|i| Ok(evals[i]), w));
            let want = serde_json::to_string_pretty(&evals[..n]).expect("json") + "\n";
            assert!(got == want, "{n} evaluations");
        }
    }

    #[crate::unit::test]
    fn lines_read_back_to_the_same_bits() {
        let evals = sample();
        let text = collect(|w| write_lines(evals.len(), &|i| evals[i].face, &|i| Ok(evals[i]), w));
        assert_eq!(text.lines().count(), evals.len());
        let same = |a: f64, b: &str| {
            let b: f64 = b.parse().expect("number");
            a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
        };
        for (e, l) in evals.iter().zip(text.lines()) {
            let w: Vec<&str> = l
                .split([' ', ':', '(', ')', ','])
                .filter(|w| !w.is_empty())
                .collect();
            assert_eq!(w[0].parse::<u32>(), Ok(e.face));
            assert!(same(e.u, w[1]) && same(e.v, w[2]), "{l}");
            assert_eq!((w[3], w[4].parse::<usize>()), ("patch", Ok(e.patch)));
            assert!(
                same(e.patch_uv[0], w[6]) && same(e.patch_uv[1], w[7]),
                "{l}"
            );
            for k in 0..3 {
                assert!(
                    same(e.point[k], w[9 + k]) && same(e.normal[k], w[13 + k]),
                    "{l}"
                );
            }
            assert!(same(e.gauss, w[17]) && same(e.mean, w[19]), "{l}");
        }
    }

    #[crate::unit::test]
    fn plain_lines_read_as_the_general_parser_reads_them() {
        for line in [
            "0:0.5:0.25",
            "12:1e-3:-0",
            "7:+0.5:1E0",
            "3:.5:5.",
            "4294967295:1:0",
            "4294967296:1:0",
            "00000000042:1:0",
            "+:1:0",
            "-1:0.5:0.5",
            "1:0.5",
            "1:0.5:0.5:0.5",
            "1::0.5",
            "1:e:0.5",
            "1:1e999:0",
            "1:--1:0",
            "1.5:0:0",
            "+1:0.5:0.5",
            "1:inf:0",
            "1:0:NaN",
            "1:infinity:0",
            "1:0x1p3:0",
            "1:0.5:1:2",
            "1:0,5:0",
            "\u{661}:0:0",
        ] {
            let general = parse_point(line, &String::new).ok();
            let plain = plain_point(line);
            assert!(plain.is_none() || plain == general, "{line}");
            assert_eq!(plain_point(&format!("{line}\n")), plain, "{line}");
            assert_eq!(plain.is_some(), general.is_some(), "{line}");
        }
        // anything else (spaces, comments, carriage returns) takes the general path
        for line in [
            "1 0.5 0.5",
            "1:0.5:0.5 # c",
            "1:0.5:0.5#c",
            "1:0.5:0.5\r",
            " 1:0.5:0.5",
            "1: 0.5:0.5",
            "1:0.5:0.5\t",
        ] {
            assert_eq!(plain_point(line), None, "{line}");
            assert!(parse_point(content(line), &String::new).is_ok(), "{line}");
        }
    }

    /// The point of the first line of `text` by the plain path, if it takes it.
    fn plain_point(text: &str) -> Option<Point> {
        Lines::new(text).next().and_then(|(_, p)| p)
    }

    #[crate::unit::test]
    fn lines_are_cut_as_str_lines_cuts_them() {
        for text in [
            "",
            "\n",
            "a\nb",
            "a\r\nb\r",
            "1:2:3\r\n\n4:5:6",
            "x\r\r\n:\n::",
        ] {
            let ours: Vec<&str> = Lines::new(text).map(|(l, _)| l).collect();
            assert_eq!(ours, text.lines().collect::<Vec<_>>(), "{text:?}");
        }
    }

    #[crate::unit::test]
    fn file_points_and_their_errors_keep_their_lines() {
        let mut text = String::from("# header\n\n");
        for i in 0..20_000u32 {
            text.push_str(&format!("{i}:{}:0.25  # c\r\n", f64::from(i) / 20_000.0));
        }
        let path = Path::new("pts.txt");
        let pts = parse_file(&text, path).expect("parses");
        assert_eq!(pts.len(), 20_000);
        assert_eq!(pts[12_345], (12_345, 12_345.0 / 20_000.0, 0.25));
        // blank and comment lines in every block, no newline after the last point: each
        // block's points close up behind the previous blocks'
        let mut sparse = String::new();
        for i in 0..30_000u32 {
            match i % 7 {
                0 => sparse.push_str("\n# note\n"),
                3 => sparse.push_str("   \n"),
                _ => {}
            }
            sparse.push_str(&format!("{i}:0.5:{}\n", f64::from(i) / 30_000.0));
        }
        sparse.pop();
        let got = parse_file(&sparse, path).expect("parses");
        assert_eq!(got.len(), 30_000);
        assert!(
            got.iter()
                .enumerate()
                .all(|(i, &p)| p == (i as u32, 0.5, i as f64 / 30_000.0))
        );
        for empty in ["", "\n\n", "# only a comment"] {
            assert_eq!(parse_file(empty, path).expect("parses"), vec![]);
        }
        let bad = text.replacen("15000:", "15000:x:", 1);
        let e = parse_file(&bad, path).expect_err("bad line").to_string();
        assert!(
            e.contains("pts.txt:15003:") && e.contains("three fields"),
            "{e}"
        );
        let bad = text.replacen("3:", "-3:", 1);
        let e = parse_file(&bad, path).expect_err("bad line").to_string();
        assert!(e.contains("pts.txt:6:") && e.contains("face"), "{e}");
    }
}
