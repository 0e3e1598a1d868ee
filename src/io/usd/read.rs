//! The USD reader (see the module notes of [`super`]).

use super::super::text::file_error;
use super::super::{FileLines, LoadedMesh, finish_mesh};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::mesh::FaceVarying;
use crate::mesh::tags::{
    BoundaryInterpolation, CornerTag, CreaseTag, FvarInterpolation, HoleTag, Named, SubdOptions,
    Tags, TriangleSubdivision,
};
use openusd::sdf::Value;
use openusd::usd::{Prim, PrimPredicate, Stage};
use std::path::Path;

/// How the reader numbers elements, for messages.
const NOTE: &str = " (faces and points counted from 0, as in faceVertexCounts and points)";

/// One attribute's value at the default time, or its first time sample (noted in `warnings`).
fn value(
    prim: &Prim,
    name: &str,
    path: &Path,
    warnings: &mut Vec<String>,
) -> Result<Option<Value>> {
    let at = prim.path().to_string();
    let fail = |e: String| file_error(path, format!("{at}.{name}: {e}"));
    let attr = prim.attribute(name);
    if let Some(v) = attr.get::<Value>().map_err(|e| fail(e.to_string()))? {
        return Ok(Some(v));
    }
    let times = attr.time_sample_times().map_err(|e| fail(e.to_string()))?;
    let Some(&t) = times.first() else {
        return Ok(None);
    };
    let v = attr
        .get_at::<Value>(openusd::usd::TimeCode::new(t))
        .map_err(|e| fail(e.to_string()))?;
    if v.is_some() && times.len() > 1 {
        warnings.push(format!(
            "{at}.{name} is animated ({} time samples): the sample at time {t} is read",
            times.len()
        ));
    }
    Ok(v)
}

/// An error about an attribute of the mesh prim.
fn bad(path: &Path, prim: &Prim, name: &str, msg: impl std::fmt::Display) -> Error {
    file_error(path, format!("{}.{name}: {msg}", prim.path()))
}

/// An `int[]` attribute (empty when unauthored).
fn ints(prim: &Prim, name: &str, path: &Path, w: &mut Vec<String>) -> Result<Vec<i64>> {
    match value(prim, name, path, w)? {
        None => Ok(Vec::new()),
        Some(Value::IntVec(v)) => Ok(v.into_iter().map(i64::from).collect()),
        Some(Value::Int64Vec(v)) => Ok(v),
        Some(Value::UintVec(v)) => Ok(v.into_iter().map(i64::from).collect()),
        Some(other) => Err(bad(
            path,
            prim,
            name,
            format!("expected int[], found {}", kind(&other)),
        )),
    }
}

/// A `float[]` attribute (empty when unauthored).
fn floats(prim: &Prim, name: &str, path: &Path, w: &mut Vec<String>) -> Result<Vec<f64>> {
    match value(prim, name, path, w)? {
        None => Ok(Vec::new()),
        Some(Value::FloatVec(v)) => Ok(v.into_iter().map(f64::from).collect()),
        Some(Value::DoubleVec(v)) => Ok(v),
        Some(Value::HalfVec(v)) => Ok(v.into_iter().map(f64::from).collect()),
        Some(other) => Err(bad(
            path,
            prim,
            name,
            format!("expected float[], found {}", kind(&other)),
        )),
    }
}

/// A `token` attribute.
fn token(prim: &Prim, name: &str, path: &Path, w: &mut Vec<String>) -> Result<Option<String>> {
    match value(prim, name, path, w)? {
        None => Ok(None),
        Some(Value::Token(t)) => Ok(Some(t.as_str().to_string())),
        Some(Value::String(s)) => Ok(Some(s)),
        Some(other) => Err(bad(
            path,
            prim,
            name,
            format!("expected a token, found {}", kind(&other)),
        )),
    }
}

/// A short name of a value's type, for messages.
fn kind(v: &Value) -> String {
    let s = format!("{v:?}");
    s.split(['(', ' ', '{'])
        .next()
        .unwrap_or("a value")
        .to_string()
}

/// Points of any precision.
fn points(prim: &Prim, path: &Path, w: &mut Vec<String>) -> Result<Vec<Point>> {
    let f = |x: &[f64]| [x[0], x[1], x[2]];
    match value(prim, "points", path, w)? {
        None => Err(bad(path, prim, "points", "the mesh has no points")),
        Some(Value::Vec3fVec(v)) => Ok(v
            .iter()
            .map(|p| f(&[p.x.into(), p.y.into(), p.z.into()]))
            .collect()),
        Some(Value::Vec3dVec(v)) => Ok(v.iter().map(|p| [p.x, p.y, p.z]).collect()),
        Some(Value::Vec3hVec(v)) => Ok(v
            .iter()
            .map(|p| f(&[p.x.into(), p.y.into(), p.z.into()]))
            .collect()),
        Some(other) => Err(bad(
            path,
            prim,
            "points",
            format!("expected point3f[], found {}", kind(&other)),
        )),
    }
}

/// 2D values of any precision (the `st` primvar).
fn pairs(
    prim: &Prim,
    name: &str,
    path: &Path,
    w: &mut Vec<String>,
) -> Result<Option<Vec<[f64; 2]>>> {
    match value(prim, name, path, w)? {
        None => Ok(None),
        Some(Value::Vec2fVec(v)) => Ok(Some(v.iter().map(|p| [p.x.into(), p.y.into()]).collect())),
        Some(Value::Vec2dVec(v)) => Ok(Some(v.iter().map(|p| [p.x, p.y]).collect())),
        Some(Value::Vec2hVec(v)) => Ok(Some(v.iter().map(|p| [p.x.into(), p.y.into()]).collect())),
        Some(other) => Err(bad(
            path,
            prim,
            name,
            format!("expected texCoord2f[], found {}", kind(&other)),
        )),
    }
}

/// The `Mesh` prims of the composed stage, in traversal order.
fn mesh_prims(stage: &Stage, path: &Path) -> Result<Vec<Prim>> {
    let mut paths = Vec::new();
    stage
        .traverse(PrimPredicate::DEFAULT, |p| paths.push(p.clone()))
        .map_err(|e| file_error(path, format!("cannot traverse the stage: {e}")))?;
    let mut meshes = Vec::new();
    for p in paths {
        let prim = stage.prim(p);
        let ty = prim
            .type_name()
            .map_err(|e| file_error(path, format!("{}: {e}", prim.path())))?;
        if ty.is_some_and(|t| t.as_str() == "Mesh") {
            meshes.push(prim);
        }
    }
    Ok(meshes)
}

/// Reads the first `UsdGeomMesh` of a `.usd`, `.usda`, `.usdc` or `.usdz` file as a net with
/// its tags and texture coordinates; `tolerant` as [`crate::io::read_mesh_as`].
pub fn read_usd_with(path: &Path, tolerant: bool) -> Result<LoadedMesh> {
    let name = path.to_str().ok_or_else(|| {
        Error::InvalidArgument(format!(
            "'{}': the USD reader needs a UTF-8 path",
            path.display()
        ))
    })?;
    if let Err(e) = std::fs::metadata(path) {
        return Err(super::super::io_error(path, e));
    }
    let stage = Stage::open(name)
        .map_err(|e| file_error(path, format!("not a USD file it can read: {e:#}")))?;
    let meshes = mesh_prims(&stage, path)?;
    let Some(prim) = meshes.first() else {
        return Err(file_error(path, "no Mesh prim (UsdGeomMesh) in the stage"));
    };
    let mut w = Vec::new();
    if meshes.len() > 1 {
        w.push(format!(
            "{} Mesh prims: {} is read, the others are ignored (first of them: {})",
            meshes.len(),
            prim.path(),
            meshes[1].path()
        ));
    }
    let positions = points(prim, path, &mut w)?;
    let counts = ints(prim, "faceVertexCounts", path, &mut w)?;
    let indices = ints(prim, "faceVertexIndices", path, &mut w)?;
    let (mut face_start, mut corners) = faces(prim, path, &counts, &indices, positions.len())?;
    let left = token(prim, "orientation", path, &mut w)?.is_some_and(|o| o == "leftHanded");
    let mut uv = st(prim, path, &corners, positions.len(), &mut w)?;
    if left {
        reverse_faces(&face_start, &mut corners, uv.as_mut());
        w.push(format!(
            "{} has orientation leftHanded: its faces were reversed to fairsub's \
             counter-clockwise order",
            prim.path()
        ));
    }
    let mut tags = tags(prim, path, &mut w)?;
    if uv.is_some() && tags.options.fvar.is_none() {
        // USD's fallback (OpenSubdiv's own default is `all`)
        tags.options.fvar = Some(FvarInterpolation::CornersPlus1);
    }
    scheme_note(prim, path, &mut w)?;
    let none = |_: usize| None;
    let at = FileLines {
        face: &none,
        vertex: &none,
        note: NOTE,
    };
    let taken = std::mem::take(&mut face_start);
    let mesh = finish_mesh(path, positions, taken, corners, &at, &mut w, tolerant)?;
    let mut mesh = mesh.with_tags(&tags, path)?;
    if let Some(uv) = uv {
        let mut ex = mesh.take_extras().unwrap_or_default();
        ex.uv = Some(uv);
        mesh.set_extras(Some(ex));
    }
    Ok(LoadedMesh { mesh, warnings: w })
}

/// The face arrays, checked against each other and the point count.
fn faces(
    prim: &Prim,
    path: &Path,
    counts: &[i64],
    idx: &[i64],
    np: usize,
) -> Result<(Vec<u32>, Vec<u32>)> {
    let mut start = Vec::with_capacity(counts.len() + 1);
    start.push(0u32);
    let mut total: u64 = 0;
    for (f, &c) in counts.iter().enumerate() {
        if c < 3 {
            return Err(bad(
                path,
                prim,
                "faceVertexCounts",
                format!("face {f} has {c} corners; a face needs at least 3"),
            ));
        }
        total += c as u64;
        if total > idx.len() as u64 {
            return Err(bad(
                path,
                prim,
                "faceVertexCounts",
                format!(
                    "the counts add up to more than the {} faceVertexIndices (at face {f})",
                    idx.len()
                ),
            ));
        }
        start.push(total as u32);
    }
    if total != idx.len() as u64 {
        return Err(bad(
            path,
            prim,
            "faceVertexIndices",
            format!(
                "{} indices, but faceVertexCounts add up to {total}",
                idx.len()
            ),
        ));
    }
    let mut corners = Vec::with_capacity(idx.len());
    for (k, &i) in idx.iter().enumerate() {
        if i < 0 || i as u64 >= np as u64 {
            return Err(bad(
                path,
                prim,
                "faceVertexIndices",
                format!("index {k} is {i}, but the mesh has {np} points"),
            ));
        }
        corners.push(i as u32);
    }
    Ok((start, corners))
}

/// Reverses every face (keeping its first corner) and its face-varying values.
fn reverse_faces(start: &[u32], corners: &mut [u32], uv: Option<&mut FaceVarying>) {
    let mut uv = uv;
    for f in 0..start.len() - 1 {
        let (a, b) = (start[f] as usize, start[f + 1] as usize);
        corners[a + 1..b].reverse();
        if let Some(u) = uv.as_mut() {
            u.corners[a + 1..b].reverse();
        }
    }
}

/// The `st` primvar as face-varying texture coordinates.
fn st(
    prim: &Prim,
    path: &Path,
    corners: &[u32],
    np: usize,
    w: &mut Vec<String>,
) -> Result<Option<FaceVarying>> {
    let name = "primvars:st";
    let Some(values) = pairs(prim, name, path, w)? else {
        return Ok(None);
    };
    let interp = prim
        .attribute(name)
        .get_metadata::<Value>("interpolation")
        .map_err(|e| bad(path, prim, name, e))?;
    let interp = match interp {
        Some(Value::Token(t)) => t.as_str().to_string(),
        _ => "constant".to_string(),
    };
    let indices = ints(prim, "primvars:st:indices", path, w)?;
    let (n_elems, what) = match interp.as_str() {
        "faceVarying" => (corners.len(), "face corner"),
        "vertex" | "varying" => (np, "point"),
        other => {
            w.push(format!(
                "{}.{name} has {other} interpolation: texture coordinates ignored",
                prim.path()
            ));
            return Ok(None);
        }
    };
    // the value of each element (corner or point)
    let elem = |k: usize| -> Result<u32> {
        let v = if indices.is_empty() {
            k as i64
        } else {
            *indices.get(k).ok_or_else(|| {
                bad(
                    path,
                    prim,
                    "primvars:st:indices",
                    format!("{} indices for {n_elems} {what}s", indices.len()),
                )
            })?
        };
        if v < 0 || v as u64 >= values.len() as u64 {
            return Err(bad(
                path,
                prim,
                name,
                format!(
                    "{what} {k} names value {v}, but there are {} values",
                    values.len()
                ),
            ));
        }
        Ok(v as u32)
    };
    let uv_corners = match interp.as_str() {
        "faceVarying" => (0..corners.len()).map(elem).collect::<Result<Vec<_>>>()?,
        _ => corners
            .iter()
            .map(|&c| elem(c as usize))
            .collect::<Result<Vec<_>>>()?,
    };
    Ok(Some(FaceVarying {
        values,
        corners: uv_corners,
        names: ["s".into(), "t".into()],
        classes: Vec::new(),
    }))
}

/// The OpenSubdiv tags of the mesh.
fn tags(prim: &Prim, path: &Path, w: &mut Vec<String>) -> Result<Tags> {
    let mut t = Tags {
        creases: crease_tags(prim, path, w)?,
        corners: corner_tags(prim, path, w)?,
        ..Tags::default()
    };
    for &f in &ints(prim, "holeIndices", path, w)? {
        let face = u32::try_from(f).map_err(|_| {
            bad(
                path,
                prim,
                "holeIndices",
                format!("face index {f} is negative"),
            )
        })?;
        t.holes.push(HoleTag { face, line: 0 });
    }
    subd_options(prim, path, w, &mut t.options)?;
    Ok(t)
}

/// Sharpness `k` of attribute `name`: a number >= 0.
fn sharpness(prim: &Prim, path: &Path, name: &str, k: usize, x: f64) -> Result<f32> {
    if !x.is_finite() || x < 0.0 {
        return Err(bad(
            path,
            prim,
            name,
            format!("sharpness {k} is {x}; sharpness is a number >= 0"),
        ));
    }
    Ok(x as f32)
}

/// A vertex index of attribute `name`: not negative.
fn vertex_index(prim: &Prim, path: &Path, name: &str, v: i64) -> Result<u32> {
    u32::try_from(v).map_err(|_| bad(path, prim, name, format!("vertex index {v} is negative")))
}

/// The crease tags: `creaseIndices` cut into creases by `creaseLengths`, each edge with its
/// crease's sharpness or its own (`creaseSharpnesses`, one per crease or one per edge).
fn crease_tags(prim: &Prim, path: &Path, w: &mut Vec<String>) -> Result<Vec<CreaseTag>> {
    let mut creases = Vec::new();
    let (ci, cl, cs) = (
        ints(prim, "creaseIndices", path, w)?,
        ints(prim, "creaseLengths", path, w)?,
        floats(prim, "creaseSharpnesses", path, w)?,
    );
    let edges: i64 = cl.iter().map(|&l| (l - 1).max(0)).sum();
    let per_edge = cs.len() as i64 == edges && cs.len() != cl.len();
    if !(cs.len() == cl.len() || per_edge) {
        return Err(bad(
            path,
            prim,
            "creaseSharpnesses",
            format!(
                "{} values for {} creases of {edges} edges (give one per crease or one per edge)",
                cs.len(),
                cl.len()
            ),
        ));
    }
    let (mut at, mut e) = (0usize, 0usize);
    for (c, &len) in cl.iter().enumerate() {
        if len < 2 || at as i64 + len > ci.len() as i64 {
            return Err(bad(
                path,
                prim,
                "creaseLengths",
                format!(
                    "crease {c} has length {len}; the lengths must be >= 2 and add up to the {} creaseIndices",
                    ci.len()
                ),
            ));
        }
        for k in 0..len as usize - 1 {
            let s = if per_edge { cs[e] } else { cs[c] };
            creases.push(CreaseTag {
                a: vertex_index(prim, path, "creaseIndices", ci[at + k])?,
                b: vertex_index(prim, path, "creaseIndices", ci[at + k + 1])?,
                sharpness: sharpness(
                    prim,
                    path,
                    "creaseSharpnesses",
                    if per_edge { e } else { c },
                    s,
                )?,
                line: 0,
            });
            e += 1;
        }
        at += len as usize;
    }
    Ok(creases)
}

/// The corner tags: `cornerIndices` with one `cornerSharpnesses` value each.
fn corner_tags(prim: &Prim, path: &Path, w: &mut Vec<String>) -> Result<Vec<CornerTag>> {
    let mut corners = Vec::new();
    let (vi, vs) = (
        ints(prim, "cornerIndices", path, w)?,
        floats(prim, "cornerSharpnesses", path, w)?,
    );
    if vi.len() != vs.len() {
        return Err(bad(
            path,
            prim,
            "cornerSharpnesses",
            format!("{} values for {} cornerIndices", vs.len(), vi.len()),
        ));
    }
    for (k, (&v, &s)) in vi.iter().zip(&vs).enumerate() {
        corners.push(CornerTag {
            vertex: vertex_index(prim, path, "cornerIndices", v)?,
            sharpness: sharpness(prim, path, "cornerSharpnesses", k, s)?,
            line: 0,
        });
    }
    Ok(corners)
}

/// The options `interpolateBoundary`, `faceVaryingLinearInterpolation` and
/// `triangleSubdivisionRule`, where the file gives them.
fn subd_options(
    prim: &Prim,
    path: &Path,
    w: &mut Vec<String>,
    options: &mut SubdOptions,
) -> Result<()> {
    let opt = |name: &str, w: &mut Vec<String>| token(prim, name, path, w);
    let unknown = |name: &str, v: &str, choices: &str| {
        bad(path, prim, name, format!("'{v}' is not one of {choices}"))
    };
    if let Some(b) = opt("interpolateBoundary", w)? {
        options.boundary = Some(match b.as_str() {
            "none" => BoundaryInterpolation::None,
            "edgeOnly" => BoundaryInterpolation::EdgeOnly,
            "edgeAndCorner" => BoundaryInterpolation::EdgeAndCorner,
            v => {
                return Err(unknown(
                    "interpolateBoundary",
                    v,
                    "none, edgeOnly, edgeAndCorner",
                ));
            }
        });
    }
    if let Some(f) = opt("faceVaryingLinearInterpolation", w)? {
        let all = <FvarInterpolation as Named>::ALL;
        options.fvar = Some(
            all.iter()
                .copied()
                .find(|&v| super::write::fvar_token(v) == f)
                .ok_or_else(|| {
                    unknown(
                        "faceVaryingLinearInterpolation",
                        &f,
                        "none, cornersOnly, cornersPlus1, cornersPlus2, boundaries, all",
                    )
                })?,
        );
    }
    if let Some(r) = opt("triangleSubdivisionRule", w)? {
        options.triangles = Some(match r.as_str() {
            "catmullClark" => TriangleSubdivision::Catmark,
            "smooth" => TriangleSubdivision::Smooth,
            v => {
                return Err(unknown(
                    "triangleSubdivisionRule",
                    v,
                    "catmullClark, smooth",
                ));
            }
        });
    }
    Ok(())
}

/// A note when the file's `subdivisionScheme` is not Catmull-Clark's.
fn scheme_note(prim: &Prim, path: &Path, w: &mut Vec<String>) -> Result<()> {
    let s = token(prim, "subdivisionScheme", path, w)?;
    match s.as_deref() {
        None | Some("catmullClark") => {}
        // USD's token for Loop's scheme is the registry's name
        Some(s) if s == crate::schemes::options::ids::LOOP.name() => w.push(format!(
            "{} asks for subdivisionScheme {s}: give --scheme {s} to refine it as the file says",
            prim.path()
        )),
        Some(other) => w.push(format!(
            "{} has subdivisionScheme {other}: fairsub refines it with the scheme the command names",
            prim.path()
        )),
    }
    Ok(())
}
