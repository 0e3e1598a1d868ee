//! fairsub's Python bindings (the extension module `fairsub._fairsub`): thin PyO3 wrappers over
//! the library's API (`fairsub::{refine, surface, level_stencils, analyze, schemes, render,
//! ...}`), numpy arrays in and out. Keyword options become typed values: the scheme options
//! `fairsub::Options` (`options.rs`), render's look `fairsub::RenderOptions` (`look.rs`). The
//! library runs the command line's own code paths, so every option, default and limit is the
//! command line's and so are the messages (a bad render value names the keyword instead of
//! the flag); no rule is written here. Long work runs with the GIL released.

mod batch;
mod evaluate;
mod look;
mod net;
mod options;
mod shape;
mod table;

use net::Net;

use fairsub::StencilTable;
use fairsub::surface::eval;
use numpy::PyUntypedArrayMethods;
use numpy::ndarray::{Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::Path;

/// A fairsub error as Python's `ValueError`, with the command line's message.
fn err(e: fairsub::Error) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// Points as a C-contiguous float64 array of shape (n, 3).
fn points_array<'py>(py: Python<'py>, pts: &[[f64; 3]]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = pts.iter().flatten().copied().collect();
    Array2::from_shape_vec((pts.len(), 3), flat)
        .expect("n x 3")
        .into_pyarray(py)
}

/// Points from a float64 array of shape (n, 3).
fn points_from(a: &PyReadonlyArray2<'_, f64>, what: &str) -> PyResult<Vec<[f64; 3]>> {
    let shape = a.shape();
    if shape.len() != 2 || shape[1] != 3 {
        return Err(PyValueError::new_err(format!(
            "{what} must have shape (n, 3), not {shape:?}"
        )));
    }
    let v = a.as_array();
    Ok((0..shape[0])
        .map(|i| [v[[i, 0]], v[[i, 1]], v[[i, 2]]])
        .collect())
}

/// A tessellation as arrays: vertices (n, 3), triangles (m, 3).
type Tessellated<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray2<u32>>);

/// A stencil table in CSR form: (indptr, indices, weights).
type Csr<'py> = (
    Bound<'py, PyArray1<u64>>,
    Bound<'py, PyArray1<u32>>,
    Bound<'py, PyArray1<f64>>,
);

/// A stencil table's rows as numpy arrays (indptr, indices, weights).
fn csr_arrays<'py>(py: Python<'py>, table: &StencilTable) -> Csr<'py> {
    let mut indptr = Vec::with_capacity(table.num_rows() + 1);
    let mut idx = Vec::with_capacity(table.num_entries());
    let mut w = Vec::with_capacity(table.num_entries());
    indptr.push(0u64);
    for r in 0..table.num_rows() {
        let (i, ws) = table.row(r);
        idx.extend_from_slice(i);
        w.extend_from_slice(ws);
        indptr.push(idx.len() as u64);
    }
    (
        indptr.into_pyarray(py),
        idx.into_pyarray(py),
        w.into_pyarray(py),
    )
}

/// Reads a net (.obj, .off, .ply or `gallery:NAME`) as `fairsub info` reads it: strictly,
/// or with `tolerant` every net OpenSubdiv accepts (non-manifold, unused vertices kept).
#[pyfunction]
#[pyo3(signature = (path, tolerant = false))]
fn read(py: Python<'_>, path: &str, tolerant: bool) -> PyResult<Net> {
    let (mesh, warnings) = py
        .detach(|| fairsub::read_net(path, tolerant))
        .map_err(err)?;
    Ok(Net {
        mesh,
        source: Some(path.to_string()),
        warnings,
    })
}

/// An exact patch complex with its provenance, built by a scheme on a net.
#[pyclass(module = "fairsub._fairsub", frozen)]
pub struct Surface {
    inner: fairsub::Surface,
}

/// The `(face, u, v)` triples of three parallel arrays (the shortest length; faces clamped
/// to `u32`), for the timing and comparison hooks.
fn parameter_points(
    face: &PyReadonlyArray1<'_, i64>,
    u: &PyReadonlyArray1<'_, f64>,
    v: &PyReadonlyArray1<'_, f64>,
) -> Vec<(u32, f64, f64)> {
    let (f, u, v) = (face.as_array(), u.as_array(), v.as_array());
    (0..f.len().min(u.len()).min(v.len()))
        .map(|i| (f[i].clamp(0, i64::from(u32::MAX)) as u32, u[i], v[i]))
        .collect()
}

impl Surface {
    /// The evaluator of the complex, built once (the input faces as the scheme evaluates them).
    fn evaluator(&self) -> PyResult<&eval::Surface> {
        self.inner.evaluator().map_err(err)
    }
}

#[pymethods]
impl Surface {
    /// The patch stencil table of this surface (`subdivide ... --rings K --stencils FILE`'s,
    /// by the same code path): `apply(points)` maps moved control points to the patches.
    fn stencils(&self, py: Python<'_>) -> PyResult<table::PatchTable> {
        let t = py.detach(|| self.inner.stencils()).map_err(err)?;
        Ok(table::PatchTable { table: t })
    }

    /// Number of patches.
    fn __len__(&self) -> usize {
        self.inner.complex().len()
    }

    /// The Bezier patches: a list of float64 arrays of shape (deg_u + 1, deg_v + 1, 3),
    /// `b[i, j]` the coefficient of `B_i(u) B_j(v)`.
    #[getter]
    fn patches<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyArray3<f64>>> {
        self.inner
            .complex()
            .patches
            .iter()
            .map(|p| {
                let flat: Vec<f64> = p.cps.iter().flatten().copied().collect();
                Array3::from_shape_vec((p.deg_u + 1, p.deg_v + 1, 3), flat)
                    .expect("patch shape")
                    .into_pyarray(py)
            })
            .collect()
    }

    /// The provenance of every patch as JSON, as `check --json` names it: `{"kind": "regular",
    /// "face": F}`, `{"kind": "ring", "element": {"type": "vertex", "index": V}, "ring": K,
    /// "sector": S}`, `{"kind": "cap", ...}`.
    fn provenance_json(&self) -> String {
        serde_json::to_string(&self.inner.complex().provenance).expect("serialisable")
    }

    /// The scheme's notes (fallbacks, derived rules).
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.inner.notes().to_vec()
    }

    /// The scheme as reports name it.
    #[getter]
    fn scheme(&self) -> String {
        self.inner.label().to_string()
    }

    /// `fairsub check NET --scheme S --rings K --json` of the complex, as a JSON string.
    fn check_json(&self, py: Python<'_>) -> String {
        py.detach(|| self.inner.check_json())
    }

    /// `fairsub measure NET --scheme S --rings K --json [--per-face]` of the surface, as a
    /// JSON string: area, volume (closed surfaces), centroids, inertia tensors, exact from the
    /// patches (the area to the relative `tolerance`).
    #[pyo3(signature = (tolerance = 1e-14, per_face = false))]
    fn measure_json(&self, py: Python<'_>, tolerance: f64, per_face: bool) -> PyResult<String> {
        if !(tolerance > 0.0 && tolerance < 1.0) {
            return Err(PyValueError::new_err(format!(
                "tolerance {tolerance} must lie between 0 and 1 (relative)"
            )));
        }
        py.detach(|| self.inner.measure_json(tolerance, per_face))
            .map_err(err)
    }

    /// The closest points of the surface to `points` (n, 3), in parallel: a dict of arrays
    /// face (n, uint32), u, v, distance (n, float64), point, normal (n, 3) and on_boundary
    /// (n, bool), the parameters as `evaluate` takes them.
    fn closest_arrays<'py>(
        &self,
        py: Python<'py>,
        points: PyReadonlyArray2<'_, f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let pts = points_from(&points, "points")?;
        let found = py.detach(|| self.inner.closest(&pts)).map_err(err)?;
        let d = PyDict::new(py);
        let col = |f: &dyn Fn(&fairsub::surface::closest::Closest) -> f64| -> Vec<f64> {
            found.iter().map(f).collect()
        };
        d.set_item(
            "face",
            found
                .iter()
                .map(|c| c.face)
                .collect::<Vec<u32>>()
                .into_pyarray(py),
        )?;
        d.set_item("u", col(&|c| c.u).into_pyarray(py))?;
        d.set_item("v", col(&|c| c.v).into_pyarray(py))?;
        d.set_item("distance", col(&|c| c.distance).into_pyarray(py))?;
        let pt: Vec<[f64; 3]> = found.iter().map(|c| c.point).collect();
        let nm: Vec<[f64; 3]> = found.iter().map(|c| c.normal).collect();
        d.set_item("point", points_array(py, &pt))?;
        d.set_item("normal", points_array(py, &nm))?;
        let b: Vec<bool> = found.iter().map(|c| c.on_boundary).collect();
        d.set_item("on_boundary", b.into_pyarray(py))?;
        Ok(d)
    }

    /// Writes the complex as `subdivide --rings` does (.bv, .igs, or a tessellated .obj/.ply
    /// with `tess` samples per patch edge).
    #[pyo3(signature = (path, tess = 8))]
    fn write(&self, py: Python<'_>, path: &str, tess: usize) -> PyResult<()> {
        py.detach(|| self.inner.write(Path::new(path), tess))
            .map_err(err)
    }

    /// The watertight tessellation `subdivide --rings K --tess n -o X.obj` writes:
    /// (vertices (n, 3) float64, triangles (m, 3) uint32).
    fn tessellate<'py>(&self, py: Python<'py>, n: usize) -> PyResult<Tessellated<'py>> {
        let mesh = py.detach(|| self.inner.tessellate(n)).map_err(err)?;
        let tris: Vec<u32> = mesh.corners().to_vec();
        let m = tris.len() / 3;
        let f = Array2::from_shape_vec((m, 3), tris)
            .expect("triangles")
            .into_pyarray(py);
        Ok((points_array(py, mesh.positions()), f))
    }

    /// The tessellation of `tessellate(n)` with, per vertex, the exact normal, patch, patch
    /// domain point and Gauss and mean curvature: a dict of arrays vertices, normals, patch_uv
    /// (n, 3 / 2), patch, gauss, mean (n), triangles (m, 3), triangle_patch (m).
    fn tessellation<'py>(&self, py: Python<'py>, n: usize) -> PyResult<Bound<'py, PyDict>> {
        shape::tessellation(py, self.inner.complex(), n)
    }

    /// Evaluates the complex at parameters (u, v) of input faces (arrays of equal length), in
    /// parallel: a dict of C-contiguous arrays point, du, dv, duu, duv, dvv, normal (n, 3),
    /// gauss, mean, u, v (n, float64), face (n, uint32), patch (n, int64), patch_uv (n, 2).
    /// Raises ValueError with the message of a point that fails.
    fn evaluate_arrays<'py>(
        &self,
        py: Python<'py>,
        face: PyReadonlyArray1<'_, i64>,
        u: PyReadonlyArray1<'_, f64>,
        v: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let (f, u, v) = (face.as_slice()?, u.as_slice()?, v.as_slice()?);
        if f.len() != u.len() || u.len() != v.len() {
            return Err(PyValueError::new_err(format!(
                "face, u and v must have the same length ({}, {}, {})",
                f.len(),
                u.len(),
                v.len()
            )));
        }
        let ev = self.evaluator()?;
        evaluate::evaluate_arrays(py, ev, f, u, v)
    }

    /// Seconds the Rust evaluation alone takes at the points (`evaluate_into` a buffer
    /// allocated before the clock starts: no array conversion, no allocation): the reference
    /// of `python/bench_evaluate.py`.
    fn _rust_evaluate_seconds(
        &self,
        py: Python<'_>,
        face: PyReadonlyArray1<'_, i64>,
        u: PyReadonlyArray1<'_, f64>,
        v: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<f64> {
        let pts = parameter_points(&face, &u, &v);
        let ev = self.evaluator()?;
        let mut out = vec![eval::Evaluation::default(); pts.len()];
        Ok(py.detach(|| {
            let t = std::time::Instant::now();
            let r = ev.evaluate_into(&pts, &mut out);
            let s = t.elapsed().as_secs_f64();
            drop(r);
            s
        }))
    }

    /// The Rust call's own results at the points, one row each (face, u, v, patch,
    /// patch_uv (2), point, du, dv, duu, duv, dvv, normal (3 each), gauss, mean: 29 columns),
    /// from `evaluate_into` a `Vec` of `Evaluation`s: what the tests compare `evaluate` with.
    fn _rust_evaluations<'py>(
        &self,
        py: Python<'py>,
        face: PyReadonlyArray1<'_, i64>,
        u: PyReadonlyArray1<'_, f64>,
        v: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let pts = parameter_points(&face, &u, &v);
        let ev = self.evaluator()?;
        let mut out = vec![eval::Evaluation::default(); pts.len()];
        py.detach(|| ev.evaluate_into(&pts, &mut out))
            .map_err(|(_, e)| err(e))?;
        let mut rows = Vec::with_capacity(29 * out.len());
        for e in &out {
            rows.extend([f64::from(e.face), e.u, e.v, e.patch as f64]);
            rows.extend(e.patch_uv);
            for p in [e.point, e.du, e.dv, e.duu, e.duv, e.dvv, e.normal] {
                rows.extend(p);
            }
            rows.extend([e.gauss, e.mean]);
        }
        Ok(Array2::from_shape_vec((out.len(), 29), rows)
            .expect("n x 29")
            .into_pyarray(py))
    }

    fn __repr__(&self) -> String {
        format!(
            "Surface({} patches, {})",
            self.inner.complex().len(),
            self.inner.label()
        )
    }
}

/// `fairsub subdivide NET --scheme SCHEME` on `net` with typed options: with `rings`, the
/// exact Surface (`--rings`, `fill=False`: `--no-fill`); else the net refined `levels` times
/// (`--levels`, `limit`: `--limit`): a Net, or a (Net, normals) pair (non-box limit mesh with
/// its exact normals).
#[pyfunction]
#[pyo3(signature = (net, scheme, levels = None, rings = None, limit = false, fill = true, options = None))]
#[allow(clippy::too_many_arguments)]
fn subdivide(
    py: Python<'_>,
    net: &Net,
    scheme: &str,
    levels: Option<usize>,
    rings: Option<usize>,
    limit: bool,
    fill: bool,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Py<PyAny>> {
    let o = options::options(options)?;
    let source = net.input();
    if let Some(rings) = rings {
        let inner = py
            .detach(|| fairsub::surface(source, scheme, rings, fill, &o))
            .map_err(err)?;
        return Ok(Surface { inner }.into_pyobject(py)?.into_any().unbind());
    }
    let levels = levels.unwrap_or(1);
    let out = py
        .detach(|| fairsub::refine(source, scheme, levels, limit, &o))
        .map_err(err)?;
    Ok(match out {
        fairsub::Refined::Net(m) | fairsub::Refined::FcvNet(m) => {
            Net::refined(m).into_pyobject(py)?.into_any().unbind()
        }
        fairsub::Refined::LimitMesh(m, normals) => {
            let n = points_array(py, &normals);
            (Net::refined(m), n).into_pyobject(py)?.into_any().unbind()
        }
    })
}

/// The stencil table of `--levels N` refinement: refined net and the weights from the
/// control points to its points.
#[pyclass(module = "fairsub._fairsub", frozen)]
pub struct Stencils {
    table: StencilTable,
}

#[pymethods]
impl Stencils {
    /// Number of rows (refined points).
    #[getter]
    fn num_rows(&self) -> usize {
        self.table.num_rows()
    }

    /// Number of sources (control points).
    #[getter]
    fn num_sources(&self) -> usize {
        self.table.num_sources()
    }

    /// The table in CSR form: (indptr, indices, weights).
    fn csr<'py>(&self, py: Python<'py>) -> Csr<'py> {
        csr_arrays(py, &self.table)
    }

    /// Applies the table to control points (num_sources, 3): the refined points (num_rows, 3).
    fn apply<'py>(
        &self,
        py: Python<'py>,
        points: PyReadonlyArray2<'_, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let pts = points_from(&points, "points")?;
        if pts.len() != self.table.num_sources() {
            return Err(PyValueError::new_err(format!(
                "the table takes {} points, not {}",
                self.table.num_sources(),
                pts.len()
            )));
        }
        let out = py.detach(|| self.table.apply(&pts));
        Ok(points_array(py, &out))
    }
}

/// The stencil table of `levels`-fold refinement of `net` by `scheme` (typed options), and
/// the refined net.
#[pyfunction]
#[pyo3(signature = (net, scheme, levels = 1, options = None))]
fn level_stencils(
    py: Python<'_>,
    net: &Net,
    scheme: &str,
    levels: usize,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<(Net, Stencils)> {
    let o = options::options(options)?;
    let source = net.input();
    let (m, table) = py
        .detach(|| fairsub::level_stencils(source, scheme, levels, &o))
        .map_err(err)?;
    Ok((Net::refined(m), Stencils { table }))
}

/// The catalogue as `fairsub schemes --json` prints it.
#[pyfunction]
fn schemes_json() -> String {
    serde_json::to_string_pretty(&fairsub::schemes()).expect("serialisable")
}

/// `fairsub analyze --scheme SCHEME --valence VALENCE --json` with typed options.
#[pyfunction]
#[pyo3(signature = (scheme, valence, replicated_centre = false, options = None))]
fn analyze_json(
    py: Python<'_>,
    scheme: &str,
    valence: usize,
    replicated_centre: bool,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    let o = options::options(options)?;
    let r = py
        .detach(|| fairsub::analyze(scheme, valence, replicated_centre, &o))
        .map_err(err)?;
    Ok(serde_json::to_string_pretty(&r).expect("serialisable"))
}

/// A picture as `fairsub render` draws it, (height, width, 3) uint8, of a Surface or a Net:
/// the keywords are render's options, typed (`mode="highlight"`, `size=(w, h)`,
/// `azimuth=-30.0`, `overlay="net,patches"`, ...: `look.rs`); a bad value is a ValueError
/// naming the keyword.
#[pyfunction]
#[pyo3(signature = (what, **look))]
fn render<'py>(
    py: Python<'py>,
    what: &Bound<'py, PyAny>,
    look: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyArray3<u8>>> {
    let o = look::options(look)?;
    let image = if let Ok(s) = what.cast::<Surface>() {
        let s = &s.get().inner;
        py.detach(|| fairsub::render(s, &o))
    } else if let Ok(n) = what.cast::<Net>() {
        let n = n.get();
        py.detach(|| fairsub::render(&n.mesh, &o))
    } else {
        return Err(PyValueError::new_err("render takes a Net or a Surface"));
    }
    .map_err(err)?;
    Ok(
        Array3::from_shape_vec((image.height, image.width, 3), image.data)
            .expect("image shape")
            .into_pyarray(py),
    )
}

/// The defaults of `render`'s keywords (the library's, which are the command line's).
#[pyfunction]
fn render_defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    look::defaults(py)
}

/// The extension module.
#[pymodule]
fn _fairsub(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // results that do not depend on the machine's number of threads
    fairsub::linalg::deterministic();
    m.add_class::<Net>()?;
    m.add_class::<Surface>()?;
    m.add_class::<Stencils>()?;
    m.add_class::<table::PatchTable>()?;
    m.add_function(wrap_pyfunction!(read, m)?)?;
    m.add_function(wrap_pyfunction!(subdivide, m)?)?;
    m.add_function(wrap_pyfunction!(level_stencils, m)?)?;
    m.add_function(wrap_pyfunction!(schemes_json, m)?)?;
    m.add_function(wrap_pyfunction!(analyze_json, m)?)?;
    m.add_function(wrap_pyfunction!(render, m)?)?;
    m.add_function(wrap_pyfunction!(render_defaults, m)?)?;
    m.add_function(wrap_pyfunction!(shape::scheme_options_json, m)?)?;
    m.add_function(wrap_pyfunction!(shape::curvature_colours, m)?)?;
    batch::register(m)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
