//! `fairsub.Net`: a control net from arrays or a file, with what OpenSubdiv nets carry beside
//! their polygons (edge and vertex sharpness, holes, face-varying texture coordinates), in and
//! out as numpy arrays. The tags go through the library's own `PolyMesh::with_tags` (the OBJ
//! reader's path), the texture coordinates into `Extras::uv` as the OBJ reader stores `vt`; a
//! refined net hands back its refined sharpness and texture coordinates.

use super::{err, points_array, points_from};
use fairsub::cli::api;
use fairsub::mesh::tags::{CornerTag, CreaseTag, HoleTag, Tags, sharpness_value};
use fairsub::mesh::{FaceVarying, PolyMesh, SharpEdges};
use numpy::PyUntypedArrayMethods;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use std::path::Path;

/// Sharp edges as numpy arrays: (edges (m, 2), sharpness (m,)).
type SharpEdgeArrays<'py> = (Bound<'py, PyArray2<u32>>, Bound<'py, PyArray1<f32>>);
/// Face-varying values as numpy arrays: (values (t, 2), one index per face corner).
type UvArrays<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<u32>>);
/// Sharp vertices as numpy arrays: (vertices (k,), sharpness (k,)).
type SharpVertexArrays<'py> = (Bound<'py, PyArray1<u32>>, Bound<'py, PyArray1<f32>>);

/// `x` as a C-contiguous numpy array of `dtype` (numpy's own conversion: lists, tuples and
/// arrays of other dtypes are accepted as `numpy.ascontiguousarray` accepts them).
fn as_array<'py>(x: &Bound<'py, PyAny>, dtype: &str) -> PyResult<Bound<'py, PyAny>> {
    let np = x.py().import("numpy")?;
    np.call_method1("ascontiguousarray", (x, dtype))
}

/// A 1-D array of `dtype` as a vector, with the name of the argument and what its values are in
/// errors.
fn vector<T: numpy::Element + Copy>(
    x: &Bound<'_, PyAny>,
    dtype: &str,
    what: &str,
    values: &str,
) -> PyResult<Vec<T>> {
    let a = as_array(x, dtype)?;
    let a: PyReadonlyArray1<'_, T> = a
        .extract()
        .map_err(|_| PyValueError::new_err(format!("{what} must be a 1-D array of {values}")))?;
    Ok(a.as_slice()?.to_vec())
}

/// A 1-D integer array (indices).
fn indices(x: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<i64>> {
    vector(x, "int64", what, "integers")
}

/// A 1-D float array.
fn floats(x: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<f64>> {
    vector(x, "float64", what, "numbers")
}

/// An (n, k) float array as rows.
fn rows<const K: usize>(x: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<[f64; K]>> {
    let a = as_array(x, "float64")?;
    let a: PyReadonlyArray2<'_, f64> = a
        .extract()
        .map_err(|_| PyValueError::new_err(format!("{what} must be an array of shape (n, {K})")))?;
    let shape = a.shape();
    if shape[1] != K {
        return Err(PyValueError::new_err(format!(
            "{what} must have shape (n, {K}), not {shape:?}"
        )));
    }
    let v = a.as_array();
    Ok((0..shape[0])
        .map(|i| std::array::from_fn(|k| v[[i, k]]))
        .collect())
}

/// The two members of a `(first, second)` pair argument.
fn pair<'py>(
    x: &Bound<'py, PyAny>,
    what: &str,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
    let t = x
        .cast::<PyTuple>()
        .ok()
        .filter(|t| t.len() == 2)
        .ok_or_else(|| {
            PyValueError::new_err(format!("{what} must be a pair (a tuple of two arrays)"))
        })?;
    Ok((t.get_item(0)?, t.get_item(1)?))
}

/// An error unless there are as many sharpness values as tagged elements (`what`).
fn same_length(n: usize, what: &str, values: usize) -> PyResult<()> {
    if n == values {
        return Ok(());
    }
    Err(PyValueError::new_err(format!(
        "{n} {what} but {values} sharpness values"
    )))
}

/// An index that must lie in `0..n`, as `u32`.
fn index_in(i: i64, n: usize, what: &str, at: usize) -> PyResult<u32> {
    u32::try_from(i)
        .ok()
        .filter(|&v| (v as usize) < n)
        .ok_or_else(|| {
            PyValueError::new_err(format!(
                "{what}[{at}] is {i}, not one of the {n} allowed (0..{n})"
            ))
        })
}

/// A sharpness value as OpenSubdiv stores it (single precision, negative as 0); NaN refused.
fn sharpness(s: f64, what: &str, at: usize) -> PyResult<f32> {
    if s.is_nan() {
        return Err(PyValueError::new_err(format!("{what}[{at}] is NaN")));
    }
    Ok(sharpness_value(s))
}

/// The faces of the constructor: a list of vertex lists, or the flat pair (sizes, indices).
fn face_lists(faces: &Bound<'_, PyAny>) -> PyResult<Vec<Vec<usize>>> {
    if let Ok(t) = faces.cast::<PyTuple>()
        && t.len() == 2
        && t.iter().all(|x| x.hasattr("ndim").unwrap_or(false))
    {
        let sizes = indices(&t.get_item(0)?, "face sizes")?;
        let flat = indices(&t.get_item(1)?, "face indices")?;
        let total: i64 = sizes.iter().map(|&s| s.max(0)).sum();
        if sizes.iter().any(|&s| s < 0) || total != flat.len() as i64 {
            return Err(PyValueError::new_err(format!(
                "the face sizes add up to {total}, but {} face indices were given",
                flat.len()
            )));
        }
        let mut out = Vec::with_capacity(sizes.len());
        let mut k = 0;
        for &s in &sizes {
            let f = &flat[k..k + s as usize];
            k += s as usize;
            // negative indices become out of range (usize::MAX) and are reported by the mesh
            out.push(
                f.iter()
                    .map(|&v| usize::try_from(v).unwrap_or(usize::MAX))
                    .collect(),
            );
        }
        return Ok(out);
    }
    faces.extract::<Vec<Vec<usize>>>().map_err(|_| {
        PyValueError::new_err(
            "faces must be a list of vertex-index lists, or a pair (sizes, indices) of numpy arrays",
        )
    })
}

/// A control net: a validated polygon mesh, with the file or gallery name it was read from.
#[pyclass(module = "fairsub._fairsub", frozen)]
pub struct Net {
    pub(crate) mesh: PolyMesh,
    /// The file (or `gallery:NAME`) it was read from: commands re-read it the way the command
    /// line reads it for their scheme (tags, FCVs, non-manifold nets), so results are the CLI's.
    pub(crate) source: Option<String>,
    pub(crate) warnings: Vec<String>,
}

/// The tags of the constructor's `creases`, `corners` and `holes` (vertex and face numbering
/// as given, checked against the net's sizes).
fn tags(
    nv: usize,
    nf: usize,
    creases: Option<&Bound<'_, PyAny>>,
    corners: Option<&Bound<'_, PyAny>>,
    holes: Option<&Bound<'_, PyAny>>,
) -> PyResult<Tags> {
    let mut t = Tags::default();
    if let Some(c) = creases {
        let (e, s) = pair(c, "creases")?;
        let ends = rows::<2>(&e, "the crease edges")?;
        let s = floats(&s, "the crease sharpness")?;
        same_length(ends.len(), "crease edges", s.len())?;
        for (i, (ab, &x)) in ends.iter().zip(&s).enumerate() {
            let [a, b] = ab.map(|v| v as i64);
            t.creases.push(CreaseTag {
                a: index_in(a, nv, "crease edges", i)?,
                b: index_in(b, nv, "crease edges", i)?,
                sharpness: sharpness(x, "crease sharpness", i)?,
                line: 0,
            });
        }
    }
    if let Some(c) = corners {
        let (v, s) = pair(c, "corners")?;
        let v = indices(&v, "the corner vertices")?;
        let s = floats(&s, "the corner sharpness")?;
        same_length(v.len(), "corner vertices", s.len())?;
        for (i, (&v, &x)) in v.iter().zip(&s).enumerate() {
            t.corners.push(CornerTag {
                vertex: index_in(v, nv, "corner vertices", i)?,
                sharpness: sharpness(x, "corner sharpness", i)?,
                line: 0,
            });
        }
    }
    if let Some(h) = holes {
        for (i, &f) in indices(h, "holes")?.iter().enumerate() {
            t.holes.push(HoleTag {
                face: index_in(f, nf, "holes", i)?,
                line: 0,
            });
        }
    }
    Ok(t)
}

/// Face-varying texture coordinates from `(values (k, 2), indices (one per face corner))`.
fn face_varying(uv: &Bound<'_, PyAny>, corners: usize) -> PyResult<FaceVarying> {
    let (v, i) = pair(uv, "uv")?;
    let values = rows::<2>(&v, "the uv values")?;
    if let Some(k) = values
        .iter()
        .position(|t| !(t[0].is_finite() && t[1].is_finite()))
    {
        return Err(PyValueError::new_err(format!("uv value {k} is not finite")));
    }
    let idx = indices(&i, "the uv indices")?;
    if idx.len() != corners {
        return Err(PyValueError::new_err(format!(
            "the uv indices must give one value per face corner ({corners}), not {}",
            idx.len()
        )));
    }
    let corners = idx
        .iter()
        .enumerate()
        .map(|(k, &x)| index_in(x, values.len(), "uv indices", k))
        .collect::<PyResult<Vec<u32>>>()?;
    Ok(FaceVarying {
        values,
        corners,
        names: ["u".into(), "v".into()],
        classes: Vec::new(),
    })
}

#[pymethods]
impl Net {
    /// A net from vertices (n, 3) and faces (lists of vertex indices, counterclockwise, or the
    /// flat pair `(sizes, indices)` of numpy arrays), with optional OpenSubdiv tags:
    /// `creases=(edges (m, 2), sharpness (m,))`, `corners=(vertices (k,), sharpness (k,))`,
    /// `holes=faces`, and face-varying texture coordinates `uv=(values (t, 2), indices (one per
    /// face corner, face after face))`. `tolerant=True` accepts every net OpenSubdiv accepts
    /// (non-manifold edges and vertices, unused vertices kept in place). Raises ValueError
    /// naming the first problem (as `fairsub info` would).
    #[new]
    #[pyo3(signature = (vertices, faces, *, tolerant = false, creases = None, corners = None, holes = None, uv = None))]
    fn new(
        vertices: &Bound<'_, PyAny>,
        faces: &Bound<'_, PyAny>,
        tolerant: bool,
        creases: Option<&Bound<'_, PyAny>>,
        corners: Option<&Bound<'_, PyAny>>,
        holes: Option<&Bound<'_, PyAny>>,
        uv: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Net> {
        let arr = as_array(vertices, "float64")?;
        let arr: PyReadonlyArray2<'_, f64> = arr
            .extract()
            .map_err(|_| PyValueError::new_err("vertices must be an array of shape (n, 3)"))?;
        let pts = points_from(&arr, "vertices")?;
        let faces = face_lists(faces)?;
        let nv = pts.len();
        let mesh = if tolerant {
            let mut start = vec![0u32];
            let mut flat = Vec::new();
            for f in &faces {
                flat.extend(f.iter().map(|&v| u32::try_from(v).unwrap_or(u32::MAX)));
                start.push(flat.len() as u32);
            }
            PolyMesh::from_flat_general(pts, start, flat)
        } else {
            PolyMesh::new(pts, &faces)
        }
        .map_err(err)?;
        let t = tags(nv, mesh.num_faces(), creases, corners, holes)?;
        let mut mesh = mesh.with_tags(&t, Path::new("<array net>")).map_err(err)?;
        if let Some(uv) = uv {
            let fv = face_varying(uv, mesh.corners().len())?;
            let mut ex = mesh.take_extras().unwrap_or_default();
            ex.uv = Some(fv);
            mesh.set_extras(Some(ex));
        }
        Ok(Net {
            mesh,
            source: None,
            warnings: Vec::new(),
        })
    }

    /// The vertex positions, float64 array (n, 3).
    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        points_array(py, self.mesh.positions())
    }

    /// The faces, lists of vertex indices.
    #[getter]
    fn faces(&self) -> Vec<Vec<u32>> {
        self.mesh.faces().map(|f| f.to_vec()).collect()
    }

    /// The faces as the flat pair (sizes (f,), indices (sum of sizes,)) of uint32 arrays.
    #[getter]
    fn face_arrays<'py>(
        &self,
        py: Python<'py>,
    ) -> (Bound<'py, PyArray1<u32>>, Bound<'py, PyArray1<u32>>) {
        let sizes: Vec<u32> = self.mesh.faces().map(|f| f.len() as u32).collect();
        (
            sizes.into_pyarray(py),
            self.mesh.corners().to_vec().into_pyarray(py),
        )
    }

    /// The sharp edges as (edges (m, 2) uint32, sharpness (m,) float32): the tags given, or on
    /// a refined net of Catmull-Clark or Loop its refined sharpness, which includes OpenSubdiv's
    /// sharpening by topology (boundary and non-manifold edges infinitely sharp, 10).
    #[getter]
    fn creases<'py>(&self, py: Python<'py>) -> SharpEdgeArrays<'py> {
        let list: Vec<([u32; 2], f32)> = match self.mesh.extras().map(|e| &e.sharp_edges) {
            Some(SharpEdges::ById(v)) => v
                .iter()
                .map(|&(e, s)| (self.mesh.edge(e as usize), s))
                .collect(),
            Some(SharpEdges::ByPair(v)) => v.clone(),
            None => Vec::new(),
        };
        let flat: Vec<u32> = list.iter().flat_map(|(ab, _)| *ab).collect();
        let ends = Array2::from_shape_vec((list.len(), 2), flat).expect("m x 2");
        let s: Vec<f32> = list.iter().map(|p| p.1).collect();
        (ends.into_pyarray(py), s.into_pyarray(py))
    }

    /// The sharp vertices as (vertices (k,) uint32, sharpness (k,) float32) (see `creases`:
    /// on a refined net this includes the corners that the boundary rule sharpens).
    #[getter]
    fn corners<'py>(&self, py: Python<'py>) -> SharpVertexArrays<'py> {
        let v: &[(u32, f32)] = self
            .mesh
            .extras()
            .map(|e| e.sharp_vertices.as_slice())
            .unwrap_or(&[]);
        let idx: Vec<u32> = v.iter().map(|p| p.0).collect();
        let s: Vec<f32> = v.iter().map(|p| p.1).collect();
        (idx.into_pyarray(py), s.into_pyarray(py))
    }

    /// The hole faces (uint32 array).
    #[getter]
    fn holes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u32>> {
        self.mesh
            .extras()
            .map(|e| e.holes.clone())
            .unwrap_or_default()
            .into_pyarray(py)
    }

    /// The face-varying texture coordinates as (values (t, 2) float64, indices (one per face
    /// corner) uint32), or None; a refined net of Catmull-Clark or Loop carries its refined
    /// values (OpenSubdiv's face-varying rules, `fvar=` option).
    #[getter]
    fn uv<'py>(&self, py: Python<'py>) -> Option<UvArrays<'py>> {
        let fv = self.mesh.extras()?.uv.as_ref()?;
        let flat: Vec<f64> = fv.values.iter().flatten().copied().collect();
        let values = Array2::from_shape_vec((fv.values.len(), 2), flat).expect("t x 2");
        Some((values.into_pyarray(py), fv.corners.clone().into_pyarray(py)))
    }

    /// Number of vertices.
    #[getter]
    fn num_vertices(&self) -> usize {
        self.mesh.num_vertices()
    }

    /// Number of faces.
    #[getter]
    fn num_faces(&self) -> usize {
        self.mesh.num_faces()
    }

    /// The file or gallery name the net was read from (None for a net made from arrays).
    #[getter]
    fn source(&self) -> Option<String> {
        self.source.clone()
    }

    /// What the reader noted (dropped vertices, ignored statements).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }

    /// `fairsub info --json` of the net, as a JSON string.
    fn info_json(&self) -> String {
        api::info_json(self.source.as_deref().unwrap_or("<array net>"), &self.mesh)
    }

    /// Writes the net (.obj, .off, .ply, .bv by extension).
    fn write(&self, py: Python<'_>, path: &str) -> PyResult<()> {
        py.detach(|| fairsub::write_net(&self.mesh, Path::new(path)))
            .map_err(err)
    }

    fn __repr__(&self) -> String {
        format!(
            "Net({} vertices, {} faces{})",
            self.mesh.num_vertices(),
            self.mesh.num_faces(),
            self.source
                .as_deref()
                .map(|s| format!(", from {s}"))
                .unwrap_or_default()
        )
    }
}

impl Net {
    /// The NET word and the mesh that stands for it (None: the command re-reads the source).
    /// Where the library reads the net: its file (re-read for each scheme, the way the
    /// command line reads it), or the arrays.
    pub(crate) fn input(&self) -> fairsub::Source {
        match &self.source {
            Some(s) => fairsub::Source::Path(s.clone()),
            None => fairsub::Source::Net(Box::new(self.mesh.clone())),
        }
    }

    pub(crate) fn refined(mesh: PolyMesh) -> Net {
        Net {
            mesh,
            source: None,
            warnings: Vec::new(),
        }
    }
}
