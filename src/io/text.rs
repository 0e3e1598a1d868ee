//! The text rule every reader follows, and the errors readers report.
//!
//! One decoding rule for every text format fairsub reads (OBJ, OFF, ascii PLY, `.bv`, FCV side
//! files): the *content* of a line must be UTF-8, while its *comment* (from `#` to the end of
//! the line; in PLY a `comment` or `obj_info` header line) may hold any bytes, since nothing
//! in it is interpreted. An invalid byte outside a comment is an error naming the file, the line
//! and the column ([`line_text`]). `#` is ASCII, so a comment is found before decoding. IGES
//! records are ASCII by definition; its reader rejects every other byte with its line.
//!
//! Errors name the file and a 1-based line ([`parse_error`]); where no line applies (binary
//! PLY data) they name the file and the element ([`file_error`]).

use crate::error::{Error, Result};
use std::io::Read;
use std::path::Path;

/// `Error::Io` for `path`.
pub(crate) fn io_error(path: &Path, source: std::io::Error) -> Error {
    Error::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// `Error::Parse` for `path` at 1-based `line`.
pub(crate) fn parse_error(path: &Path, line: usize, msg: impl Into<String>) -> Error {
    debug_assert!(line >= 1, "parse errors name a line >= 1");
    Error::Parse {
        path: path.to_path_buf(),
        line,
        msg: msg.into(),
    }
}

/// An error about the contents of `path` where no line applies (binary data): shown as
/// `path: msg`. It is an [`Error::Io`] of kind `InvalidData`, the kind the standard library
/// gives data that cannot be what the reader expects; `msg` names the element.
pub(crate) fn file_error(path: &Path, msg: impl Into<String>) -> Error {
    io_error(
        path,
        std::io::Error::new(std::io::ErrorKind::InvalidData, msg.into()),
    )
}

/// All bytes of `reader` (`path` names it in errors).
pub(crate) fn read_all<R: Read>(mut reader: R, path: &Path) -> Result<Vec<u8>> {
    let mut bytes = Vec::new();
    reader
        .read_to_end(&mut bytes)
        .map_err(|e| io_error(path, e))?;
    Ok(bytes)
}

/// All bytes of the file `path`.
pub(crate) fn read_file(path: &Path) -> Result<Vec<u8>> {
    std::fs::read(path).map_err(|e| io_error(path, e))
}

/// Reads a text file by the text rule, for side files that other layers parse from text (the
/// q-files of the QAS schemes, for example): invalid UTF-8 inside a `#` comment is replaced
/// by U+FFFD (the line structure stays), anywhere else it is an error naming the file, line
/// and column.
pub fn read_text(path: &Path) -> Result<String> {
    decode_text(read_file(path)?, path)
}

/// `bytes` as text by the text rule (see [`read_text`]).
pub(crate) fn decode_text(bytes: Vec<u8>, path: &Path) -> Result<String> {
    match String::from_utf8(bytes) {
        Ok(s) => Ok(s),
        Err(e) => {
            let bytes = e.into_bytes();
            for l in Lines::new(&bytes, path) {
                l?;
            }
            Ok(String::from_utf8_lossy(&bytes).into_owned())
        }
    }
}

/// Where the `#` comment of `line` starts (its length when it has none).
#[inline]
pub(crate) fn hash_comment(line: &[u8]) -> usize {
    line.iter().position(|&b| b == b'#').unwrap_or(line.len())
}

/// The content of a line, its first `end` bytes (where its comment starts), as text: invalid
/// UTF-8 there is an error naming the file, line and column; the comment is not looked at.
pub(crate) fn line_text<'a>(
    line: &'a [u8],
    end: usize,
    path: &Path,
    line_no: usize,
) -> Result<&'a str> {
    std::str::from_utf8(&line[..end]).map_err(|e| {
        let col = e.valid_up_to();
        parse_error(
            path,
            line_no,
            format!(
                "invalid UTF-8 at column {} (byte 0x{:02X}): fairsub reads text as UTF-8 and \
                 allows other bytes only in comments",
                col + 1,
                line[col]
            ),
        )
    })
}

/// Removes one line ending (`\n`, and a `\r` before it) from the end of `line`.
#[inline]
pub(crate) fn strip_line_end(line: &[u8]) -> &[u8] {
    let line = line.strip_suffix(b"\n").unwrap_or(line);
    line.strip_suffix(b"\r").unwrap_or(line)
}

/// The lines of a text as `(1-based number, content before '#')`, decoded by the text rule.
/// Lines end at `\n` (with an optional `\r` before it), as in `str::lines`.
pub(crate) struct Lines<'a> {
    rest: &'a [u8],
    line: usize,
    path: &'a Path,
}

impl<'a> Lines<'a> {
    /// The lines of `bytes`; `path` names the file in errors.
    pub fn new(bytes: &'a [u8], path: &'a Path) -> Self {
        Lines {
            rest: bytes,
            line: 0,
            path,
        }
    }

    /// The number of the last line returned; once the text is exhausted, its number of lines
    /// (at least 1, so that an error at the end of an empty file still names a line).
    pub fn end_line(&self) -> usize {
        self.line.max(1)
    }

    /// The next line whose content is not blank, trimmed, with its number.
    pub fn next_content(&mut self) -> Result<Option<(usize, &'a str)>> {
        for l in self.by_ref() {
            let (n, text) = l?;
            let text = text.trim();
            if !text.is_empty() {
                return Ok(Some((n, text)));
            }
        }
        Ok(None)
    }

    /// The next line whose content is not blank (see [`Lines::next_content`]); at the end of the
    /// text an error at its last line saying what is `missing`.
    pub fn require(&mut self, missing: impl FnOnce() -> String) -> Result<(usize, &'a str)> {
        match self.next_content()? {
            Some(l) => Ok(l),
            None => Err(parse_error(self.path, self.end_line(), missing())),
        }
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = Result<(usize, &'a str)>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.rest.is_empty() {
            return None;
        }
        let (raw, rest) = match self.rest.iter().position(|&b| b == b'\n') {
            Some(i) => self.rest.split_at(i + 1),
            None => (self.rest, &b""[..]),
        };
        self.rest = rest;
        self.line += 1;
        let raw = strip_line_end(raw);
        Some(line_text(raw, hash_comment(raw), self.path, self.line).map(|t| (self.line, t)))
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    fn lines(b: &[u8]) -> Vec<(usize, String)> {
        Lines::new(b, Path::new("t.txt"))
            .map(|l| l.map(|(n, s)| (n, s.to_string())).unwrap())
            .collect()
    }

    #[crate::unit::test]
    fn lines_split_like_str_lines_and_drop_comments() {
        let got = lines(b"a b # c\r\n\n# only\nlast");
        assert_eq!(
            got,
            [
                (1, "a b ".to_string()),
                (2, String::new()),
                (3, String::new()),
                (4, "last".to_string())
            ]
        );
        assert!(lines(b"").is_empty());
        assert_eq!(lines(b"x\n"), [(1, "x".to_string())]);
    }

    #[crate::unit::test]
    fn invalid_utf8_is_allowed_in_comments_only() {
        // In a comment: fine.
        assert_eq!(lines(b"1 2 # caf\xe9\n3")[1], (2, "3".to_string()));
        // In the content: an error with line and column.
        let mut it = Lines::new(b"ok\n1 \xe9 2\n", Path::new("t.txt"));
        assert!(it.next().unwrap().is_ok());
        let e = it.next().unwrap().unwrap_err().to_string();
        assert_eq!(
            e,
            "t.txt:2: invalid UTF-8 at column 3 (byte 0xE9): fairsub reads text as UTF-8 and \
             allows other bytes only in comments"
        );
    }

    #[crate::unit::test]
    fn next_content_skips_blank_lines_and_counts_to_the_end() {
        let mut it = Lines::new(b"\n  \n# c\n x \n\n", Path::new("t"));
        assert_eq!(it.next_content().unwrap(), Some((4, "x")));
        assert_eq!(it.next_content().unwrap(), None);
        assert_eq!(it.end_line(), 5);
        assert_eq!(Lines::new(b"", Path::new("t")).end_line(), 1);
    }

    #[crate::unit::test]
    fn whole_texts_follow_the_rule() {
        let p = Path::new("q.txt");
        let t = decode_text(b"vertex 3 # caf\xe9\np 1 2 3\n".to_vec(), p).unwrap();
        assert_eq!(t, "vertex 3 # caf\u{fffd}\np 1 2 3\n");
        let e = decode_text(b"vertex 3\np 1 \xe92 3\n".to_vec(), p).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("q.txt:2: invalid UTF-8 at column 5"),
            "{e}"
        );
    }

    #[crate::unit::test]
    fn file_errors_name_the_file_without_a_line() {
        let e = file_error(Path::new("m.ply"), "binary data ends early");
        assert_eq!(e.to_string(), "m.ply: binary data ends early");
    }
}
