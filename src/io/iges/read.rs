//! The validating IGES reader, for files of entity-128 Bezier surfaces such as fairsub writes:
//! the records and sections ([`Records`]), the terminate counts, the global section, the
//! directory entries with their parameter records, then each entity ([`super::entity`]).

use super::entity::{Bad, global_delimiters, split_params, surface_128};
use crate::error::{Error, Result};
use crate::io::text::{parse_error, read_file};
use crate::surface::{PatchComplex, Provenance};
use std::path::Path;

/// Reads an IGES file of entity-128 Bezier surfaces (see [`parse_iges`]).
pub fn read_iges(path: &Path) -> Result<PatchComplex> {
    // Non-ASCII bytes become U+FFFD here and are then rejected with their line.
    let bytes = read_file(path)?;
    parse_iges(&String::from_utf8_lossy(&bytes), path)
}

/// Parses IGES text holding entity-128 surfaces back into Bezier patches (with
/// [`Provenance::Unknown`]); `path` is used in messages only.
///
/// Checks the file structure strictly: every record has exactly 80 columns, sections come in the
/// order S, G, D, P, T with letters in column 73 and consecutive sequence numbers, the global
/// section parses, directory entries come in pairs whose two entity numbers agree, each entry's
/// parameter pointer and record count lie inside the P section, every P record carries the
/// sequence number of the entry that owns it and belongs to exactly one entry, and the T
/// record's counts match. Entity 128 surfaces must have a single span (`K = M`), clamped knots,
/// equal weights and the full parameter range; other entity types are rejected as unsupported.
pub fn parse_iges(text: &str, path: &Path) -> Result<PatchComplex> {
    let r = Records::new(text, path)?;
    r.check_terminate(path)?;
    let (pd, rd) = r.global(path)?;
    let entries = r.directory(path)?;
    r.entities(&entries, pd, rd, path)
}

/// The sections of an IGES file.
const ORDER: [char; 5] = ['S', 'G', 'D', 'P', 'T'];

/// The records of an IGES file, checked for width, section letters, section order and sequence
/// numbers: `lines[i]` is file line `i + 1` (without its line end), `sections[s]` holds the
/// indices of the records of section `ORDER[s]`.
struct Records<'a> {
    lines: Vec<&'a str>,
    sections: [Vec<usize>; 5],
}

/// One directory entry as read.
struct DirEntry {
    line: usize,
    seq: usize,
    entity: i64,
    p_start: usize,
    p_count: usize,
}

impl<'a> Records<'a> {
    /// Splits and checks the records; there must be S and G records and one T record.
    fn new(text: &'a str, path: &Path) -> Result<Self> {
        let mut lines: Vec<&str> = text
            .split('\n')
            .map(|l| l.strip_suffix('\r').unwrap_or(l))
            .collect();
        if lines.last().is_some_and(|l| l.is_empty()) {
            lines.pop();
        }
        let mut sections: [Vec<usize>; 5] = Default::default();
        let mut current = 0usize;
        for (i, &l) in lines.iter().enumerate() {
            let line_no = i + 1;
            if !l.is_ascii() {
                return Err(parse_error(
                    path,
                    line_no,
                    "non-ASCII character in an IGES record",
                ));
            }
            if l.len() != 80 {
                return Err(parse_error(
                    path,
                    line_no,
                    format!(
                        "record has {} columns; IGES records have exactly 80",
                        l.len()
                    ),
                ));
            }
            let letter = l.as_bytes()[72] as char;
            let Some(sec) = ORDER.iter().position(|&c| c == letter) else {
                return Err(match letter {
                    'C' | 'B' => Error::Unsupported(format!(
                        "{}:{line_no}: compressed or binary IGES is not supported",
                        path.display()
                    )),
                    _ => parse_error(
                        path,
                        line_no,
                        format!("column 73 holds '{letter}', not a section letter (S, G, D, P, T)"),
                    ),
                });
            };
            if sec < current {
                return Err(parse_error(
                    path,
                    line_no,
                    format!(
                        "'{letter}' record after the {} section: sections must come in the order S, G, D, P, T",
                        ORDER[current]
                    ),
                ));
            }
            current = sec;
            let seq_text = l[73..80].trim();
            let expected = sections[sec].len() + 1;
            match seq_text.parse::<usize>() {
                Ok(s) if s == expected => {}
                _ => {
                    return Err(parse_error(
                        path,
                        line_no,
                        format!(
                            "sequence number '{seq_text}' in columns 74-80; expected {expected} ({letter} records are numbered 1, 2, ...)"
                        ),
                    ));
                }
            }
            sections[sec].push(i);
        }
        let r = Records { lines, sections };
        if r.sections[0].is_empty() || r.sections[1].is_empty() {
            return Err(parse_error(
                path,
                1,
                "an IGES file starts with Start (S) and Global (G) records",
            ));
        }
        if r.sections[4].len() != 1 {
            return Err(parse_error(
                path,
                r.lines.len(),
                format!(
                    "expected exactly one Terminate (T) record at the end, found {}",
                    r.sections[4].len()
                ),
            ));
        }
        Ok(r)
    }

    /// Record `i` (0-based file line).
    fn rec(&self, i: usize) -> &'a str {
        self.lines[i]
    }

    /// The terminate record's counts must match the sections.
    fn check_terminate(&self, path: &Path) -> Result<()> {
        let [s_lines, g_lines, d_lines, p_lines, t_lines] = &self.sections;
        let rec = |i: usize| self.rec(i);
        let t = rec(t_lines[0]);
        let t_line_no = t_lines[0] + 1;
        for (k, (letter, actual)) in [
            ('S', s_lines.len()),
            ('G', g_lines.len()),
            ('D', d_lines.len()),
            ('P', p_lines.len()),
        ]
        .into_iter()
        .enumerate()
        {
            let field = &t[8 * k..8 * k + 8];
            let ok = field.starts_with(letter)
                && field[1..].trim().parse::<usize>().ok() == Some(actual);
            if !ok {
                return Err(parse_error(
                    path,
                    t_line_no,
                    format!(
                        "terminate record field {} is '{field}' but the file has {actual} {letter} records",
                        k + 1
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The delimiters of the global section, which must hold IGES 5.3's parameters.
    fn global(&self, path: &Path) -> Result<(char, char)> {
        let g_lines = &self.sections[1];
        let rec = |i: usize| self.rec(i);
        let gtext: String = g_lines.iter().map(|&i| &rec(i)[..72]).collect();
        let g0 = g_lines[0] + 1;
        let (pd, rd) = global_delimiters(&gtext).map_err(|m| parse_error(path, g0, m))?;
        let global = split_params(&gtext, pd, rd)
            .map_err(|m| parse_error(path, g0, format!("global section: {m}")))?;
        if global.len() < 23 {
            return Err(parse_error(
                path,
                g0,
                format!(
                    "global section has {} parameters; IGES 5.3 requires at least 23",
                    global.len()
                ),
            ));
        }
        Ok((pd, rd))
    }

    /// The directory entries, each with the parameter records it owns: every P record must
    /// belong to exactly one entry and carry its sequence number.
    fn directory(&self, path: &Path) -> Result<Vec<DirEntry>> {
        let (d_lines, p_lines) = (&self.sections[2], &self.sections[3]);
        let rec = |i: usize| self.rec(i);
        if d_lines.len() % 2 != 0 {
            return Err(parse_error(
                path,
                d_lines[d_lines.len() - 1] + 1,
                format!(
                    "the D section has {} records; directory entries are pairs of records",
                    d_lines.len()
                ),
            ));
        }
        let np = p_lines.len();
        let p_owner: Vec<usize> = p_lines
            .iter()
            .map(|&i| rec(i)[65..72].trim().parse::<usize>().unwrap_or(0))
            .collect();
        let mut claimed = vec![false; np];
        let mut entries = Vec::with_capacity(d_lines.len() / 2);
        for e in 0..d_lines.len() / 2 {
            let entry = self.dir_entry(e, path)?;
            claim_records(&entry, &p_owner, &mut claimed, p_lines, path)?;
            entries.push(entry);
        }
        if let Some(q) = claimed.iter().position(|c| !c) {
            return Err(parse_error(
                path,
                p_lines[q] + 1,
                format!("parameter record {} belongs to no directory entry", q + 1),
            ));
        }
        Ok(entries)
    }

    /// Directory entry `e` (its two records): the entity type, the same in both, and the
    /// parameter records it points to, inside the P section.
    fn dir_entry(&self, e: usize, path: &Path) -> Result<DirEntry> {
        let d_lines = &self.sections[2];
        let np = self.sections[3].len();
        let rec = |i: usize| self.rec(i);
        let (a, b) = (rec(d_lines[2 * e]), rec(d_lines[2 * e + 1]));
        let line = d_lines[2 * e] + 1;
        let seq = 2 * e + 1;
        let field = |r: &str, k: usize| r[8 * k..8 * k + 8].trim().to_string();
        let int = |r: &str, k: usize, l: usize| -> Result<i64> {
            let f = field(r, k);
            if f.is_empty() {
                return Ok(0);
            }
            f.parse::<i64>().map_err(|_| {
                parse_error(
                    path,
                    l,
                    format!(
                        "directory entry field {} is '{f}', not an integer",
                        k + 1 + if l == line { 0 } else { 10 }
                    ),
                )
            })
        };
        let entity = int(a, 0, line)?;
        let entity2 = int(b, 0, line + 1)?;
        if entity != entity2 {
            return Err(parse_error(
                path,
                line + 1,
                format!(
                    "directory entry {seq}: entity type {entity} in its first record but {entity2} in its second"
                ),
            ));
        }
        let p_start = int(a, 1, line)?;
        let p_count = int(b, 3, line + 1)?;
        if p_start < 1 || p_start as usize > np {
            return Err(parse_error(
                path,
                line,
                format!(
                    "directory entry {seq}: parameter data pointer {p_start} is outside the P section (1..={np})"
                ),
            ));
        }
        if p_count < 1 || (p_start + p_count - 1) as usize > np {
            return Err(parse_error(
                path,
                line + 1,
                format!(
                    "directory entry {seq}: parameter record count {p_count} from record {p_start} runs past the P section ({np} records)"
                ),
            ));
        }
        Ok(DirEntry {
            line,
            seq,
            entity,
            p_start: p_start as usize,
            p_count: p_count as usize,
        })
    }

    /// The patches of the entities (only entity 128 is read).
    fn entities(
        &self,
        entries: &[DirEntry],
        pd: char,
        rd: char,
        path: &Path,
    ) -> Result<PatchComplex> {
        let p_lines = &self.sections[3];
        let rec = |i: usize| self.rec(i);
        let mut out = PatchComplex::new();
        for e in entries {
            let first = p_lines[e.p_start - 1] + 1;
            if e.entity != 128 {
                return Err(Error::Unsupported(format!(
                    "{}:{}: entity type {} (directory entry {}) is not supported; only entity 128 (B-spline surface) is read",
                    path.display(),
                    e.line,
                    e.entity,
                    e.seq
                )));
            }
            let data: String = (e.p_start - 1..e.p_start - 1 + e.p_count)
                .map(|q| &rec(p_lines[q])[..64])
                .collect();
            let params = split_params(&data, pd, rd).map_err(|m| {
                parse_error(
                    path,
                    first,
                    format!("entity 128 (directory entry {}): {m}", e.seq),
                )
            })?;
            let patch = surface_128(&params).map_err(|m| match m {
                Bad::Parse(m) => parse_error(
                    path,
                    first,
                    format!("entity 128 (directory entry {}): {m}", e.seq),
                ),
                Bad::Unsupported(m) => Error::Unsupported(format!(
                    "{}:{first}: entity 128 (directory entry {}): {m}",
                    path.display(),
                    e.seq
                )),
            })?;
            out.push(patch, Provenance::Unknown);
        }
        Ok(out)
    }
}

/// Marks the parameter records of `entry` as claimed: each must name the entry in columns
/// 66-72 (`p_owner`) and belong to no other.
fn claim_records(
    entry: &DirEntry,
    p_owner: &[usize],
    claimed: &mut [bool],
    p_lines: &[usize],
    path: &Path,
) -> Result<()> {
    let (line, seq, p_start, p_count) = (entry.line, entry.seq, entry.p_start, entry.p_count);
    for q in p_start - 1..p_start - 1 + p_count {
        if p_owner[q] != seq {
            return Err(parse_error(
                path,
                p_lines[q] + 1,
                format!(
                    "parameter record {} names directory entry {} in columns 66-72, but directory entry {seq} (line {line}) points to it",
                    q + 1,
                    p_owner[q]
                ),
            ));
        }
        if claimed[q] {
            return Err(parse_error(
                path,
                p_lines[q] + 1,
                format!(
                    "parameter record {} belongs to two directory entries",
                    q + 1
                ),
            ));
        }
        claimed[q] = true;
    }
    Ok(())
}
