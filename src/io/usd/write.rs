//! The USD writer: one layer with a root `Xform` (the layer's `defaultPrim`, named after the
//! file) holding one `Mesh`, built as Sdf specs and encoded by `openusd` as `.usda` text, or a
//! `.usdz` package of that text layer.

use super::super::scene::{NetTags, SceneMesh};
use super::super::write_bytes_atomically;
use super::UsdFlavor;
use crate::error::{Error, Result};
use crate::mesh::tags::{BoundaryInterpolation, FvarInterpolation, TriangleSubdivision};
use openusd::gf::{Vec2f, Vec3f};
use openusd::sdf::{self, ChildrenKey, FieldKey, SpecType, Specifier, Value, Variability};
use std::path::Path;

/// An attribute to write: name, USD type, value, and whether it is `uniform`, and its
/// interpolation metadata (primvars and normals).
struct Attr {
    name: String,
    type_name: &'static str,
    value: Value,
    uniform: bool,
    interpolation: Option<&'static str>,
}

fn attr(name: &str, type_name: &'static str, value: Value) -> Attr {
    Attr {
        name: name.to_string(),
        type_name,
        value,
        uniform: false,
        interpolation: None,
    }
}

fn vec3(p: &[crate::geom::Point]) -> Value {
    Value::Vec3fVec(
        p.iter()
            .map(|q| Vec3f::from([q[0] as f32, q[1] as f32, q[2] as f32]))
            .collect(),
    )
}

fn ints(v: impl IntoIterator<Item = u32>) -> Value {
    Value::IntVec(v.into_iter().map(|x| x as i32).collect())
}

/// USD's token of a boundary interpolation.
fn boundary_token(b: BoundaryInterpolation) -> &'static str {
    match b {
        BoundaryInterpolation::None => "none",
        BoundaryInterpolation::EdgeOnly => "edgeOnly",
        BoundaryInterpolation::EdgeAndCorner => "edgeAndCorner",
    }
}

/// USD's token of a face-varying interpolation.
pub(super) fn fvar_token(f: FvarInterpolation) -> &'static str {
    match f {
        FvarInterpolation::None => "none",
        FvarInterpolation::CornersOnly => "cornersOnly",
        FvarInterpolation::CornersPlus1 => "cornersPlus1",
        FvarInterpolation::CornersPlus2 => "cornersPlus2",
        FvarInterpolation::Boundaries => "boundaries",
        FvarInterpolation::All => "all",
    }
}

/// The attributes of the mesh (see the module notes of [`super`]).
fn mesh_attrs(m: &SceneMesh) -> Result<Vec<Attr>> {
    let p = m.polygons()?;
    let (lo, hi) = m.extent();
    let mut a = vec![
        attr("points", "point3f[]", vec3(&m.positions)),
        attr("extent", "float3[]", vec3(&[lo, hi])),
        attr(
            "faceVertexCounts",
            "int[]",
            ints((0..p.num_faces()).map(|f| m.face(f).len() as u32)),
        ),
        attr(
            "faceVertexIndices",
            "int[]",
            ints(m.corners.iter().copied()),
        ),
    ];
    let scheme = m.net.as_ref().map_or("none", |t| t.scheme);
    a.push(Attr {
        uniform: true,
        ..attr("subdivisionScheme", "token", Value::Token(scheme.into()))
    });
    if let Some(n) = &m.normals {
        a.push(Attr {
            interpolation: Some("vertex"),
            ..attr("normals", "normal3f[]", vec3(n))
        });
    }
    if let Some(uv) = &m.uv {
        let st = uv
            .values
            .iter()
            .map(|t| Vec2f::from([t[0] as f32, t[1] as f32]))
            .collect();
        a.push(Attr {
            interpolation: Some("faceVarying"),
            ..attr("primvars:st", "texCoord2f[]", Value::Vec2fVec(st))
        });
        a.push(attr(
            "primvars:st:indices",
            "int[]",
            ints(uv.corners.iter().copied()),
        ));
    }
    for (name, v) in &m.scalars {
        a.push(Attr {
            interpolation: Some("vertex"),
            ..attr(
                &format!("primvars:{name}"),
                "float[]",
                Value::FloatVec(v.iter().map(|&x| x as f32).collect()),
            )
        });
    }
    if let Some(c) = &m.colors {
        let c = c.iter().map(|&x| Vec3f::from(x)).collect();
        a.push(Attr {
            interpolation: Some("vertex"),
            ..attr("primvars:displayColor", "color3f[]", Value::Vec3fVec(c))
        });
    }
    if let Some(t) = &m.net {
        net_attrs(&mut a, t);
    }
    Ok(a)
}

/// The attributes of a control net's tags: creases (each sharp edge its own crease of two
/// vertices), corners, holes, the boundary and face-varying interpolation, and Catmull-Clark's
/// triangle rule.
fn net_attrs(a: &mut Vec<Attr>, t: &NetTags) {
    if !t.creases.is_empty() {
        // every sharp edge its own crease of two vertices
        let idx = t.creases.iter().flat_map(|(e, _)| *e);
        a.push(attr("creaseIndices", "int[]", ints(idx)));
        a.push(attr(
            "creaseLengths",
            "int[]",
            ints(t.creases.iter().map(|_| 2)),
        ));
        let s = t.creases.iter().map(|&(_, s)| s).collect();
        a.push(attr("creaseSharpnesses", "float[]", Value::FloatVec(s)));
    }
    if !t.corners.is_empty() {
        a.push(attr(
            "cornerIndices",
            "int[]",
            ints(t.corners.iter().map(|c| c.0)),
        ));
        let s = t.corners.iter().map(|c| c.1).collect();
        a.push(attr("cornerSharpnesses", "float[]", Value::FloatVec(s)));
    }
    if !t.holes.is_empty() {
        a.push(attr("holeIndices", "int[]", ints(t.holes.iter().copied())));
    }
    let o = &t.options;
    let token = |name: &str, v: &str| attr(name, "token", Value::Token(v.into()));
    a.push(token("interpolateBoundary", boundary_token(o.boundary())));
    a.push(token(
        "faceVaryingLinearInterpolation",
        fvar_token(o.fvar()),
    ));
    if t.scheme == "catmullClark" {
        let rule = match o.triangles() {
            TriangleSubdivision::Catmark => "catmullClark",
            TriangleSubdivision::Smooth => "smooth",
        };
        a.push(token("triangleSubdivisionRule", rule));
    }
}

/// A USD prim name from a file stem: letters, digits and `_`, not starting with a digit.
fn prim_name(path: &Path) -> String {
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
    let mut s: String = stem
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert_str(0, "fairsub_");
    }
    s
}

/// The layer of one mesh: `/NAME` (Xform, default prim) with `/NAME/mesh`.
fn layer(m: &SceneMesh, name: &str) -> Result<sdf::Data> {
    let bad = |e: String| Error::InvalidArgument(format!("USD layer: {e}"));
    let mut data = sdf::Data::new();
    let root = data.create_spec(sdf::Path::abs_root(), SpecType::PseudoRoot);
    root.add(
        ChildrenKey::PrimChildren,
        Value::TokenVec(vec![name.into()]),
    );
    root.add(FieldKey::DefaultPrim, Value::Token(name.into()));
    root.add("upAxis", Value::Token("Y".into()));
    root.add("metersPerUnit", Value::Double(1.0));
    root.add(
        FieldKey::Documentation,
        Value::String(format!("written by fairsub {}", env!("CARGO_PKG_VERSION"))),
    );
    let xform = sdf::path(format!("/{name}")).map_err(|e| bad(e.to_string()))?;
    let x = data.create_spec(xform.clone(), SpecType::Prim);
    x.add(FieldKey::Specifier, Value::Specifier(Specifier::Def));
    x.add(FieldKey::TypeName, Value::Token("Xform".into()));
    x.add(
        ChildrenKey::PrimChildren,
        Value::TokenVec(vec!["mesh".into()]),
    );
    let mesh = sdf::path(format!("/{name}/mesh")).map_err(|e| bad(e.to_string()))?;
    let attrs = mesh_attrs(m)?;
    let spec = data.create_spec(mesh.clone(), SpecType::Prim);
    spec.add(FieldKey::Specifier, Value::Specifier(Specifier::Def));
    spec.add(FieldKey::TypeName, Value::Token("Mesh".into()));
    let names = attrs.iter().map(|a| a.name.as_str().into()).collect();
    spec.add(ChildrenKey::PropertyChildren, Value::TokenVec(names));
    for a in attrs {
        let path = mesh
            .append_property(&a.name)
            .map_err(|e| bad(e.to_string()))?;
        let s = data.create_spec(path, SpecType::Attribute);
        s.add(FieldKey::TypeName, Value::Token(a.type_name.into()));
        s.add(FieldKey::Custom, Value::Bool(false));
        s.add(FieldKey::Default, a.value);
        if a.uniform {
            s.add(
                FieldKey::Variability,
                Value::Variability(Variability::Uniform),
            );
        }
        if let Some(i) = a.interpolation {
            s.add("interpolation", Value::Token(i.into()));
        }
    }
    Ok(data)
}

/// The bytes of the file (`flavor`'s encoding).
pub(super) fn usd_bytes(m: &SceneMesh, path: &Path, flavor: UsdFlavor) -> Result<Vec<u8>> {
    let data = layer(m, &prim_name(path))?;
    let fail = |e: String| Error::InvalidArgument(format!("{}: {e}", path.display()));
    let mut text = Vec::new();
    openusd::usda::TextWriter::write(&data, &mut text).map_err(|e| fail(e.to_string()))?;
    match flavor {
        UsdFlavor::Usda => Ok(text),
        UsdFlavor::Usdz => {
            let mut z = openusd::usdz::ArchiveWriter::new(std::io::Cursor::new(Vec::new()));
            let name = format!("{}.usda", prim_name(path));
            z.add_layer(&name, &text).map_err(|e| fail(e.to_string()))?;
            Ok(z.finish().map_err(|e| fail(e.to_string()))?.into_inner())
        }
    }
}

/// Writes the mesh as USD (atomically).
pub fn write_usd(path: &Path, m: &SceneMesh, flavor: UsdFlavor) -> Result<()> {
    let bytes = usd_bytes(m, path, flavor)?;
    write_bytes_atomically(path, &bytes)
}
