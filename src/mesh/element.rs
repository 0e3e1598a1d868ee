//! The extraordinary elements of a control net (vertices and facets), which patches, rings,
//! caps and reports name.

use serde::Serialize;

/// An extraordinary element of an input net.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(tag = "type", content = "index", rename_all = "snake_case")]
pub enum Element {
    /// A vertex (extraordinary vertex / node, or a pole).
    Vertex(u32),
    /// A face (extraordinary facet).
    Face(u32),
}

impl Element {
    /// How messages name the element: `vertex 3`, `face 7`.
    pub fn describe(&self) -> String {
        match self {
            Element::Vertex(v) => format!("vertex {v}"),
            Element::Face(f) => format!("face {f}"),
        }
    }
}
