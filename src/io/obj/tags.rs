//! OpenSubdiv's OBJ tag lines, `t NAME nints/nfloats/nstrings ints... floats... strings...`,
//! read into [`Tags`] (`crate::mesh::tags`). The same lines make the `--creases` side file of
//! OFF and PLY nets ([`read_tag_file`]).
//!
//! | tag | arguments | meaning |
//! | --- | --- | --- |
//! | `crease` | vertex pairs `a0 b0 a1 b1 ...`; one sharpness, or one per pair | edge sharpness |
//! | `corner` | vertices; one sharpness, or one per vertex | vertex sharpness |
//! | `hole` | faces | hole faces |
//! | `interpolateboundary` | 1 integer: 0 none, 1 edge-and-corner, 2 edge-only | boundary option |
//! | `facevaryinginterpolateboundary` | 1 integer: 0 none, 1 corners-only, 2 corners-plus1, 3 corners-plus2, 4 boundaries, 5 all | face-varying option |
//! | `creasemethod` | 1 string: `normal` (uniform) or `chaikin` | crease method |
//! | `smoothtriangles` | 1 string: `catmark` or `smooth` (or 1 integer 0 / 1) | triangle option (Catmull-Clark) |
//!
//! Vertex and face indices count from 0 (as in OpenSubdiv's shapes); a sharpness must be a
//! finite number >= 0 (OpenSubdiv clamps negative values to 0; fairsub names the line instead,
//! since a negative sharpness is a typing error more often than a request for 0), 10 and more
//! are infinitely sharp. `facevaryingpropagatecorners` (no counterpart
//! in OpenSubdiv 3) and the hierarchical edits (`vertexedit`, `edgeedit`, `faceedit`, which
//! OpenSubdiv 3 does not support either) are ignored with a warning, as is any other tag.

use crate::error::{Error, Result};
use crate::mesh::tags::{
    BoundaryInterpolation, CornerTag, CreaseMethod, CreaseTag, FvarInterpolation, HoleTag, Named,
    Tags, TriangleSubdivision, sharpness_value,
};
use std::path::Path;

/// Parses the arguments of one tag line (`tok[0]` is `t`) into `tags`; unsupported tags add a
/// warning. Errors name the line.
pub(crate) fn parse_tag(
    tok: &[&str],
    line: usize,
    path: &Path,
    tags: &mut Tags,
    warnings: &mut Vec<String>,
) -> Result<()> {
    let t = TagArgs::parse(tok, line, path)?;
    let name = t.name;
    match name {
        "crease" => t.creases(tags)?,
        "corner" => t.corners(tags)?,
        "hole" => {
            for &f in &t.ints {
                tags.holes.push(HoleTag {
                    face: t.index(f, "face")?,
                    line,
                });
            }
            tags.note_line(line);
        }
        "interpolateboundary" => tags.options.boundary = Some(t.boundary()?),
        "facevaryinginterpolateboundary" => tags.options.fvar = Some(t.fvar()?),
        "creasemethod" => tags.options.crease_method = Some(t.crease_method()?),
        "smoothtriangles" => {
            let v = match (&t.ints[..], t.strings) {
                ([0], []) => Some(TriangleSubdivision::Catmark),
                ([1], []) => Some(TriangleSubdivision::Smooth),
                ([], [s]) => TriangleSubdivision::parse(s),
                _ => None,
            };
            tags.options.triangles =
                Some(v.ok_or_else(|| {
                    t.err("smoothtriangles expects catmark or smooth".to_string())
                })?);
        }
        "facevaryingpropagatecorners" => warnings.push(format!(
            "line {line}: tag 'facevaryingpropagatecorners' ignored (OpenSubdiv 3 has no such \
             option; corners-plus2 propagates corners)"
        )),
        "vertexedit" | "edgeedit" | "faceedit" => warnings.push(format!(
            "line {line}: hierarchical edit tag '{name}' ignored (OpenSubdiv 3 does not support \
             hierarchical edits either)"
        )),
        other => warnings.push(format!("line {line}: unknown tag '{other}' ignored")),
    }
    Ok(())
}

/// A tag line's name and typed arguments, with the line for errors.
struct TagArgs<'a> {
    name: &'a str,
    ints: Vec<i64>,
    floats: Vec<f64>,
    strings: &'a [&'a str],
    line: usize,
    path: &'a Path,
}

impl<'a> TagArgs<'a> {
    /// Reads the name, the counts `ints/floats[/strings]` and as many arguments of each type.
    fn parse(tok: &'a [&'a str], line: usize, path: &'a Path) -> Result<TagArgs<'a>> {
        let err = |msg: String| super::parse_error(path, line, msg);
        if tok.len() < 3 {
            return Err(err(
                "a tag line needs a name and counts: t NAME ints/floats/strings ...".into(),
            ));
        }
        let name = tok[1];
        let counts: Vec<Option<usize>> = tok[2].split('/').map(|c| c.parse().ok()).collect();
        let (ni, nf, ns) = match counts[..] {
            [Some(i), Some(f), Some(s)] => (i, f, s),
            [Some(i), Some(f)] => (i, f, 0),
            _ => {
                return Err(err(format!(
                    "bad tag counts '{}' (expected ints/floats/strings, such as 2/1/0)",
                    tok[2]
                )));
            }
        };
        let args = &tok[3..];
        if args.len() != ni + nf + ns {
            return Err(err(format!(
                "tag '{name}' announces {} arguments ({}), but has {}",
                ni + nf + ns,
                tok[2],
                args.len()
            )));
        }
        let mut ints = Vec::with_capacity(ni);
        for t in &args[..ni] {
            ints.push(
                t.parse::<i64>()
                    .map_err(|_| err(format!("bad integer '{t}' in tag '{name}'")))?,
            );
        }
        let mut floats = Vec::with_capacity(nf);
        for t in &args[ni..ni + nf] {
            floats.push(
                t.parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| err(format!("bad number '{t}' in tag '{name}'")))?,
            );
        }
        Ok(TagArgs {
            name,
            ints,
            floats,
            strings: &args[ni + nf..],
            line,
            path,
        })
    }

    /// An error at the tag's line.
    fn err(&self, msg: String) -> Error {
        super::parse_error(self.path, self.line, msg)
    }

    /// A vertex or face index (`what`), which counts from 0.
    fn index(&self, i: i64, what: &str) -> Result<u32> {
        u32::try_from(i).map_err(|_| {
            self.err(format!(
                "tag '{}': {what} index {i} (indices count from 0)",
                self.name
            ))
        })
    }

    /// The sharpness of element `k` of `n`: one value for all elements, or one per element.
    fn value(&self, k: usize, n: usize) -> Result<f32> {
        let name = self.name;
        let floats = &self.floats;
        let x = match floats.len() {
            1 => floats[0],
            m if m == n => floats[k],
            m => {
                return Err(self.err(format!(
                    "tag '{name}' gives {m} sharpness values for {n} elements (give 1, or one each)"
                )));
            }
        };
        if x < 0.0 {
            return Err(self.err(format!(
                "tag '{name}': sharpness {x} is negative (0 is smooth, 10 and more infinitely \
                 sharp)"
            )));
        }
        Ok(sharpness_value(x))
    }

    /// The one integer of an option tag (`1/0/0`).
    fn one_int(&self) -> Result<i64> {
        match self.ints[..] {
            [i] if self.floats.is_empty() && self.strings.is_empty() => Ok(i),
            _ => Err(self.err(format!("tag '{}' expects 1 integer (1/0/0)", self.name))),
        }
    }

    /// The one string of an option tag (`0/0/1`).
    fn one_string(&self) -> Result<&'a str> {
        match (self.strings, self.ints.is_empty() && self.floats.is_empty()) {
            ([s], true) => Ok(*s),
            _ => Err(self.err(format!("tag '{}' expects 1 string (0/0/1)", self.name))),
        }
    }

    /// A `crease` tag: vertex pairs, each an edge with its sharpness.
    fn creases(&self, tags: &mut Tags) -> Result<()> {
        let (ints, line) = (&self.ints, self.line);
        if ints.is_empty() || ints.len() % 2 != 0 {
            return Err(
                self.err("a crease tag lists vertex pairs (an even number of integers)".into())
            );
        }
        let pairs = ints.len() / 2;
        for k in 0..pairs {
            tags.creases.push(CreaseTag {
                a: self.index(ints[2 * k], "vertex")?,
                b: self.index(ints[2 * k + 1], "vertex")?,
                sharpness: self.value(k, pairs)?,
                line,
            });
        }
        tags.note_line(line);
        Ok(())
    }

    /// A `corner` tag: vertices, each with its sharpness.
    fn corners(&self, tags: &mut Tags) -> Result<()> {
        let (ints, line) = (&self.ints, self.line);
        if ints.is_empty() {
            return Err(self.err("a corner tag lists vertices".into()));
        }
        for (k, &v) in ints.iter().enumerate() {
            tags.corners.push(CornerTag {
                vertex: self.index(v, "vertex")?,
                sharpness: self.value(k, ints.len())?,
                line,
            });
        }
        tags.note_line(line);
        Ok(())
    }

    /// The `interpolateboundary` option: 0 none, 1 edge-and-corner, 2 edge-only.
    fn boundary(&self) -> Result<BoundaryInterpolation> {
        Ok(match self.one_int()? {
            0 => BoundaryInterpolation::None,
            1 => BoundaryInterpolation::EdgeAndCorner,
            2 => BoundaryInterpolation::EdgeOnly,
            v => {
                return Err(self.err(format!(
                    "interpolateboundary {v}: expected 0 (none), 1 (edge-and-corner) or 2 \
                     (edge-only)"
                )));
            }
        })
    }

    /// The `facevaryinginterpolateboundary` option: 0..5 in [`FvarInterpolation::ALL`]'s order.
    fn fvar(&self) -> Result<FvarInterpolation> {
        let v = self.one_int()?;
        let all = FvarInterpolation::ALL;
        Ok(*usize::try_from(v)
            .ok()
            .and_then(|i| all.get(i))
            .ok_or_else(|| {
                self.err(format!(
                    "facevaryinginterpolateboundary {v}: expected 0..5 ({})",
                    FvarInterpolation::choices()
                ))
            })?)
    }

    /// The `creasemethod` option: `normal` (or `uniform`) or `chaikin`.
    fn crease_method(&self) -> Result<CreaseMethod> {
        Ok(match self.one_string()? {
            "normal" | "uniform" => CreaseMethod::Uniform,
            "chaikin" => CreaseMethod::Chaikin,
            s => {
                return Err(self.err(format!(
                    "creasemethod '{s}': expected normal (uniform) or chaikin"
                )));
            }
        })
    }
}

/// Reads a `--creases` side file: OpenSubdiv tag lines (`t ...`, as in OBJ files, indices
/// from 0), `#` comments and blank lines; anything else is an error naming the line.
pub fn read_tag_file(path: &Path) -> Result<(Tags, Vec<String>)> {
    let text = crate::io::read_text(path)?;
    let mut tags = Tags::default();
    let mut warnings = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("");
        let tok: Vec<&str> = line.split_whitespace().collect();
        match tok.first() {
            None => {}
            Some(&"t") => parse_tag(&tok, i + 1, path, &mut tags, &mut warnings)?,
            Some(other) => {
                return Err(Error::Parse {
                    path: path.to_path_buf(),
                    line: i + 1,
                    msg: format!(
                        "'{other}': a creases file holds OpenSubdiv tag lines \
                         ('t crease 2/1/0 A B SHARPNESS', 't corner 1/1/0 V SHARPNESS', \
                         't hole 1/0/0 F', 't interpolateboundary 1/0/0 N', ...)"
                    ),
                });
            }
        }
    }
    Ok((tags, warnings))
}
