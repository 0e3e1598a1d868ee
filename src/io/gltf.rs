//! glTF 2.0 output (`.glb` binary container, or `.gltf` JSON with the buffer embedded as a
//! base64 data URI): one scene, one node, one mesh of one triangle primitive.
//!
//! The JSON document is built with `gltf-json`'s typed structures (the glTF schema as Rust
//! types, from the `gltf` crate family), the binary buffer by hand: little-endian `f32`
//! attributes, `u32` indices, each buffer view 4-byte aligned, the GLB chunks padded as the
//! specification says (JSON with spaces, BIN with zeros).
//!
//! | attribute | from |
//! | --- | --- |
//! | `POSITION` (with `min`, `max`) | the points, rounded to `f32` |
//! | `NORMAL` | the unit vertex normals (a zero or non-finite normal: the face normals') |
//! | `TEXCOORD_0` | texture coordinates per face corner, with `v` flipped (`1 - v`: glTF's origin is the image's top left); a vertex is split where its corners' values differ |
//! | `COLOR_0` | per-vertex colours, when given |
//!
//! Polygons are split into triangles as fans from their first corner.

use super::scene::SceneMesh;
use super::write_bytes_atomically;
use crate::error::{Error, Result};
use crate::geom::norm;
use gltf_json as json;
use json::validation::{Checked::Valid, USize64};
use std::collections::HashMap;
use std::path::Path;

/// The glTF containers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GltfFlavor {
    /// `.glb`: the binary container.
    Glb,
    /// `.gltf`: JSON, buffer as a data URI.
    Gltf,
}

/// The glTF vertices of a mesh: one per distinct (point, texture value) pair.
struct Vertices {
    /// The point of each glTF vertex.
    point: Vec<u32>,
    /// Its texture value (when the mesh has texture coordinates).
    uv: Vec<u32>,
    /// The triangles, in glTF vertices.
    triangles: Vec<[u32; 3]>,
}

fn vertices(m: &SceneMesh) -> Vertices {
    let tris = m.triangles();
    let Some(uv) = &m.uv else {
        return Vertices {
            point: (0..m.positions.len() as u32).collect(),
            uv: Vec::new(),
            triangles: tris.iter().map(|t| [t[0].0, t[1].0, t[2].0]).collect(),
        };
    };
    let mut ids: HashMap<(u32, u32), u32> = HashMap::new();
    let mut v = Vertices {
        point: Vec::new(),
        uv: Vec::new(),
        triangles: Vec::with_capacity(tris.len()),
    };
    for t in &tris {
        let mut out = [0u32; 3];
        for (k, &(p, corner)) in t.iter().enumerate() {
            let key = (p, uv.corners[corner as usize]);
            out[k] = *ids.entry(key).or_insert_with(|| {
                v.point.push(key.0);
                v.uv.push(key.1);
                v.point.len() as u32 - 1
            });
        }
        v.triangles.push(out);
    }
    v
}

/// Appends `data` as a buffer view (4-byte aligned) and an accessor over it.
struct Builder {
    root: json::Root,
    bin: Vec<u8>,
}

impl Builder {
    fn accessor(
        &mut self,
        data: &[u8],
        count: usize,
        (ty, comp): (json::accessor::Type, json::accessor::ComponentType),
        target: json::buffer::Target,
        bounds: Option<(Vec<f32>, Vec<f32>)>,
    ) -> json::Index<json::Accessor> {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(data);
        let view = self.root.push(json::buffer::View {
            buffer: json::Index::new(0),
            byte_length: USize64::from(data.len()),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            name: None,
            target: Some(Valid(target)),
            extensions: None,
            extras: Default::default(),
        });
        let (min, max) = match bounds {
            Some((lo, hi)) => (Some(json::Value::from(lo)), Some(json::Value::from(hi))),
            None => (None, None),
        };
        self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64::from(count),
            component_type: Valid(json::accessor::GenericComponentType(comp)),
            extensions: None,
            extras: Default::default(),
            type_: Valid(ty),
            min,
            max,
            name: None,
            normalized: false,
            sparse: None,
        })
    }
}

fn f32_bytes(v: impl IntoIterator<Item = f32>) -> Vec<u8> {
    v.into_iter().flat_map(f32::to_le_bytes).collect()
}

/// The document and its binary buffer.
fn document(m: &SceneMesh, name: &str) -> Result<(json::Root, Vec<u8>)> {
    m.polygons()?;
    let v = vertices(m);
    if v.triangles.is_empty() {
        return Err(Error::InvalidArgument("glTF: the mesh has no faces".into()));
    }
    let mut b = Builder {
        root: json::Root::default(),
        bin: Vec::new(),
    };
    use json::accessor::{ComponentType as C, Type as T};
    use json::buffer::Target::ElementArrayBuffer;
    let attributes = vertex_attributes(&mut b, m, &v);
    let idx: Vec<u8> = v
        .triangles
        .iter()
        .flatten()
        .flat_map(|i| i.to_le_bytes())
        .collect();
    let indices = b.accessor(
        &idx,
        3 * v.triangles.len(),
        (T::Scalar, C::U32),
        ElementArrayBuffer,
        None,
    );
    scene(&mut b, name, attributes, indices);
    while !b.bin.len().is_multiple_of(4) {
        b.bin.push(0);
    }
    Ok((b.root, b.bin))
}

/// A primitive's attributes: the accessor of each semantic.
type Attributes = std::collections::BTreeMap<
    json::validation::Checked<json::mesh::Semantic>,
    json::Index<json::Accessor>,
>;

/// The accessors of the glTF vertices' attributes: positions (with their bounds), unit
/// normals (the face normals where the mesh's are not of unit length), texture coordinates
/// (t flipped) and colours when the mesh has them.
fn vertex_attributes(b: &mut Builder, m: &SceneMesh, v: &Vertices) -> Attributes {
    use json::accessor::{ComponentType as C, Type as T};
    use json::buffer::Target::ArrayBuffer;
    let pos: Vec<[f32; 3]> = v
        .point
        .iter()
        .map(|&p| m.positions[p as usize].map(|x| x as f32))
        .collect();
    let mut lo = vec![f32::INFINITY; 3];
    let mut hi = vec![f32::NEG_INFINITY; 3];
    for p in &pos {
        for c in 0..3 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    let n = pos.len();
    let mut attributes = std::collections::BTreeMap::new();
    let a = b.accessor(
        &f32_bytes(pos.into_iter().flatten()),
        n,
        (T::Vec3, C::F32),
        ArrayBuffer,
        Some((lo, hi)),
    );
    attributes.insert(Valid(json::mesh::Semantic::Positions), a);
    let fallback = m.face_normals();
    let normals = m.normals.as_ref().unwrap_or(&fallback);
    let nrm = v.point.iter().flat_map(|&p| {
        let q = normals[p as usize];
        let q = if (norm(q) - 1.0).abs() < 1e-6 {
            q
        } else {
            fallback[p as usize]
        };
        let q = q.map(|x| x as f32);
        let l = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
        q.map(|x| x / l)
    });
    let a = b.accessor(&f32_bytes(nrm), n, (T::Vec3, C::F32), ArrayBuffer, None);
    attributes.insert(Valid(json::mesh::Semantic::Normals), a);
    if let Some(uv) = &m.uv {
        let st = v.uv.iter().flat_map(|&k| {
            let t = uv.values[k as usize];
            [t[0] as f32, (1.0 - t[1]) as f32]
        });
        let a = b.accessor(&f32_bytes(st), n, (T::Vec2, C::F32), ArrayBuffer, None);
        attributes.insert(Valid(json::mesh::Semantic::TexCoords(0)), a);
    }
    if let Some(c) = &m.colors {
        let rgb = v
            .point
            .iter()
            .flat_map(|&p| c[p as usize].map(|x| x.clamp(0.0, 1.0)));
        let a = b.accessor(&f32_bytes(rgb), n, (T::Vec3, C::F32), ArrayBuffer, None);
        attributes.insert(Valid(json::mesh::Semantic::Colors(0)), a);
    }
    attributes
}

/// The mesh of one triangle primitive (`attributes`, `indices`), its node and scene, all
/// named `name`, and the asset's generator and version.
fn scene(
    b: &mut Builder,
    name: &str,
    attributes: Attributes,
    indices: json::Index<json::Accessor>,
) {
    let mesh = b.root.push(json::Mesh {
        extensions: None,
        extras: Default::default(),
        name: Some(name.to_string()),
        primitives: vec![json::mesh::Primitive {
            attributes,
            extensions: None,
            extras: Default::default(),
            indices: Some(indices),
            material: None,
            mode: Valid(json::mesh::Mode::Triangles),
            targets: None,
        }],
        weights: None,
    });
    let node = b.root.push(json::Node {
        mesh: Some(mesh),
        name: Some(name.to_string()),
        ..Default::default()
    });
    let scene = b.root.push(json::Scene {
        extensions: None,
        extras: Default::default(),
        name: Some(name.to_string()),
        nodes: vec![node],
    });
    b.root.scene = Some(scene);
    b.root.asset = json::Asset {
        copyright: None,
        extensions: None,
        extras: Default::default(),
        generator: Some(format!("fairsub {}", env!("CARGO_PKG_VERSION"))),
        min_version: None,
        version: "2.0".to_string(),
    };
}

/// The bytes of the file.
pub(crate) fn gltf_bytes(m: &SceneMesh, name: &str, flavor: GltfFlavor) -> Result<Vec<u8>> {
    let (mut root, bin) = document(m, name)?;
    let json_err = |e: json::Error| Error::InvalidArgument(format!("glTF JSON: {e}"));
    match flavor {
        GltfFlavor::Gltf => {
            root.buffers.push(json::Buffer {
                byte_length: USize64::from(bin.len()),
                name: None,
                uri: Some(format!(
                    "data:application/octet-stream;base64,{}",
                    base64(&bin)
                )),
                extensions: None,
                extras: Default::default(),
            });
            root.to_vec_pretty().map_err(json_err)
        }
        GltfFlavor::Glb => {
            root.buffers.push(json::Buffer {
                byte_length: USize64::from(bin.len()),
                name: None,
                uri: None,
                extensions: None,
                extras: Default::default(),
            });
            let mut text = root.to_vec().map_err(json_err)?;
            while !text.len().is_multiple_of(4) {
                text.push(b' ');
            }
            let total = 12 + 8 + text.len() + 8 + bin.len();
            let total = u32::try_from(total)
                .map_err(|_| Error::InvalidArgument("glTF: the mesh is over 4 GiB".into()))?;
            let mut out = Vec::with_capacity(total as usize);
            out.extend_from_slice(b"glTF");
            out.extend_from_slice(&2u32.to_le_bytes());
            out.extend_from_slice(&total.to_le_bytes());
            out.extend_from_slice(&(text.len() as u32).to_le_bytes());
            out.extend_from_slice(b"JSON");
            out.extend_from_slice(&text);
            out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
            out.extend_from_slice(b"BIN\0");
            out.extend_from_slice(&bin);
            Ok(out)
        }
    }
}

/// Standard base64 with padding (RFC 4648), for the data URI of `.gltf` files.
fn base64(data: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(data.len().div_ceil(3) * 4);
    for c in data.chunks(3) {
        let n = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            if k <= c.len() {
                s.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// Writes the mesh as glTF 2.0 (atomically).
pub fn write_gltf(path: &Path, m: &SceneMesh, flavor: GltfFlavor) -> Result<()> {
    let name = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("fairsub")
        .to_string();
    write_bytes_atomically(path, &gltf_bytes(m, &name, flavor)?)
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn base64_matches_rfc4648() {
        for (i, o) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(i.as_bytes()), o);
        }
    }

    #[crate::unit::test]
    fn glb_has_aligned_chunks_and_split_seams() {
        let net = crate::gallery::all().into_iter().next().unwrap().1;
        let mut m = SceneMesh::from_net(&net, None);
        // one texture value per corner: every corner its own glTF vertex
        let uv = crate::mesh::FaceVarying {
            values: (0..m.corners.len()).map(|k| [k as f64, 0.5]).collect(),
            corners: (0..m.corners.len() as u32).collect(),
            names: ["u".into(), "v".into()],
            classes: Vec::new(),
        };
        m.uv = Some(uv);
        let b = gltf_bytes(&m, "t", GltfFlavor::Glb).unwrap();
        assert_eq!(&b[..4], b"glTF");
        assert_eq!(
            u32::from_le_bytes(b[8..12].try_into().unwrap()) as usize,
            b.len()
        );
        let jl = u32::from_le_bytes(b[12..16].try_into().unwrap()) as usize;
        assert_eq!(jl % 4, 0);
        let doc: serde_json::Value = serde_json::from_slice(&b[20..20 + jl]).unwrap();
        assert_eq!(doc["accessors"][0]["count"], m.corners.len());
        assert_eq!(doc["asset"]["version"], "2.0");
    }
}
