//! Error types of fairsub.
//!
//! Every failure names the element it concerns (file line, face, vertex, edge) and the reason, so
//! that a user can find and mend the input. The CLI maps [`Error`] to exit code 1 (bad input) and
//! clap's usage errors to exit code 2.

use std::fmt;
use std::path::PathBuf;

/// A problem found while validating a control net. Indices are 0-based and refer to the faces and
/// vertices as given to [`crate::mesh::PolyMesh::new`] (for a file, in file order).
#[derive(Debug, Clone, PartialEq)]
pub enum MeshError {
    /// The mesh has no faces (or no vertices).
    Empty,
    /// A face has fewer than three corners.
    FaceTooSmall {
        /// Face index.
        face: usize,
        /// Number of corners it has.
        len: usize,
    },
    /// A face lists the same vertex twice.
    RepeatedVertex {
        /// Face index.
        face: usize,
        /// The repeated vertex.
        vertex: usize,
    },
    /// A face refers to a vertex that does not exist.
    IndexOutOfRange {
        /// Face index.
        face: usize,
        /// The offending index.
        index: i64,
        /// Number of vertices in the mesh.
        count: usize,
    },
    /// A vertex coordinate is NaN or infinite.
    NonFiniteCoordinate {
        /// Vertex index.
        vertex: usize,
    },
    /// More than two faces share an edge.
    NonManifoldEdge {
        /// Edge end points.
        edge: [usize; 2],
        /// The faces that share it.
        faces: Vec<usize>,
    },
    /// Two faces use an edge in the same direction: their orientations disagree.
    InconsistentOrientation {
        /// Edge end points (in the direction both faces use).
        edge: [usize; 2],
        /// The two faces.
        faces: [usize; 2],
    },
    /// The faces around a vertex form more than one fan (a "bow-tie" vertex).
    NonManifoldVertex {
        /// Vertex index.
        vertex: usize,
        /// Number of separate fans of faces around it.
        fans: usize,
    },
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeshError::Empty => write!(f, "the mesh is empty (no faces)"),
            MeshError::FaceTooSmall { face, len } => {
                write!(f, "face {face} has {len} corners; a face needs at least 3")
            }
            MeshError::RepeatedVertex { face, vertex } => {
                write!(f, "face {face} uses vertex {vertex} more than once")
            }
            MeshError::IndexOutOfRange { face, index, count } => write!(
                f,
                "face {face} refers to vertex {index}, but the mesh has {count} vertices (valid: 0..{})",
                count.saturating_sub(1)
            ),
            MeshError::NonFiniteCoordinate { vertex } => {
                write!(f, "vertex {vertex} has a NaN or infinite coordinate")
            }
            MeshError::NonManifoldEdge { edge, faces } => write!(
                f,
                "edge {}-{} is shared by {} faces {:?}; a manifold edge has at most 2",
                edge[0],
                edge[1],
                faces.len(),
                faces
            ),
            MeshError::InconsistentOrientation { edge, faces } => write!(
                f,
                "faces {} and {} both use edge {}->{} in the same direction: inconsistent orientation (flip one of them)",
                faces[0], faces[1], edge[0], edge[1]
            ),
            MeshError::NonManifoldVertex { vertex, fans } => write!(
                f,
                "vertex {vertex} joins {fans} separate fans of faces (non-manifold vertex)"
            ),
        }
    }
}

/// The error type of every fallible fairsub operation.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The control net is not a valid manifold polygon mesh.
    #[error("invalid mesh: {0}")]
    Mesh(MeshError),
    /// A file could not be parsed; `line` is 1-based. Shown as `path:line: msg`, or as
    /// `path: msg` when `line` is 0 (no line known, e.g. binary data).
    #[error("{}", parse_message(path, *line, msg))]
    Parse {
        /// The file.
        path: PathBuf,
        /// 1-based line (0 if not applicable, e.g. binary data: then no line is shown).
        line: usize,
        /// What is wrong.
        msg: String,
    },
    /// Reading or writing a file failed.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The input is valid but this operation does not support it (names the element and the way
    /// out).
    #[error("unsupported: {0}")]
    Unsupported(String),
    /// An argument is out of its range or inconsistent.
    #[error("invalid argument: {0}")]
    InvalidArgument(String),
    /// A scheme name that the registry does not know (for the purpose named, e.g. " for
    /// refinement"), with the names that would do.
    #[error("invalid argument: unknown scheme '{name}' (available{purpose}: {})", available.join(", "))]
    UnknownScheme {
        /// The name given.
        name: String,
        /// What the scheme was wanted for (`""`, `" for refinement"`, ...).
        purpose: &'static str,
        /// The names that offer it.
        available: Vec<&'static str>,
    },
    /// A scheme has no rules at this valence (or element size); the message names the element
    /// and the way out. Callers that fall back to other rules branch on this variant.
    #[error("unsupported: {msg}")]
    UnsupportedValence {
        /// The valence (or facet size).
        valence: usize,
        /// What is unsupported and what to do.
        msg: String,
    },
    /// The job would need more memory (or produce more elements) than the budget allows: the
    /// message gives the estimate, the budget and the options that lower the estimate or raise
    /// the budget (`--max-memory`). Nothing was allocated for it.
    #[error("too large: {0}")]
    TooLarge(String),
    /// An output would not be valid (geometry that cannot be represented, a tessellation that
    /// fairsub's own reader would reject); the message names the element. Nothing was written.
    #[error("invalid output: {0}")]
    InvalidOutput(String),
    /// A scheme cannot take a face of the net (its size or its neighbourhood).
    #[error("unsupported: {msg}")]
    UnsupportedFace {
        /// The face (input numbering).
        face: usize,
        /// What is unsupported and what to do.
        msg: String,
    },
}

/// The text of [`Error::Parse`]: `path:line: msg`, without the line when it is 0.
fn parse_message(path: &std::path::Path, line: usize, msg: &str) -> String {
    if line == 0 {
        format!("{}: {msg}", path.display())
    } else {
        format!("{}:{line}: {msg}", path.display())
    }
}

impl From<MeshError> for Error {
    fn from(e: MeshError) -> Self {
        Error::Mesh(e)
    }
}

/// Result alias used throughout the crate.
pub type Result<T> = std::result::Result<T, Error>;

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn parse_errors_show_a_line_only_when_known() {
        let at = |line| Error::Parse {
            path: PathBuf::from("net.obj"),
            line,
            msg: "bad".into(),
        };
        assert_eq!(at(7).to_string(), "net.obj:7: bad");
        assert_eq!(at(0).to_string(), "net.obj: bad");
    }
}
