//! What front ends that show a surface need beside its patches (the Blender add-on in
//! `blender/`): the watertight tessellation with its exact normals and curvatures per vertex,
//! the renderer's curvature colour map, and the options a scheme takes, described from the
//! command line's own definitions.

use super::err;
use fairsub::cli::api;
use fairsub::schemes::registry;
use fairsub::surface::PatchComplex;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Rows of `K` values as a C-contiguous (n, K) array.
fn array<T: numpy::Element, const K: usize>(
    py: Python<'_>,
    rows: Vec<[T; K]>,
) -> Bound<'_, numpy::PyArray2<T>> {
    let n = rows.len();
    let flat: Vec<T> = rows.into_iter().flatten().collect();
    Array2::from_shape_vec((n, K), flat)
        .expect("n x K")
        .into_pyarray(py)
}

/// The watertight tessellation of a complex with `n` samples per patch edge (the one
/// `subdivide --rings K --tess n -o X.obj` writes, validated the same way) and, per vertex, the
/// exact patch normal, the patch and its domain point, and the exact Gauss and mean curvature
/// there (signs relative to the patch normal; NaN where undefined).
pub fn tessellation<'py>(
    py: Python<'py>,
    complex: &PatchComplex,
    n: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let (t, curv) = py
        .detach(|| {
            fairsub::cli::limits::check_tessellation(complex, n)?;
            let t = fairsub::surface::tessellate::tessellate(complex, n);
            // the mesh a writer would write: an error names the patch when it is not valid
            let mesh = t.to_mesh(complex)?;
            if mesh.num_vertices() != t.num_vertices() {
                return Err(fairsub::Error::InvalidArgument(format!(
                    "the tessellation has {} vertices but its mesh {}",
                    t.num_vertices(),
                    mesh.num_vertices()
                )));
            }
            use rayon::prelude::*;
            let curv: Vec<[f64; 2]> = (0..t.num_vertices())
                .into_par_iter()
                .map(|v| {
                    let p = &complex.patches[t.patch_of_vertex[v] as usize];
                    let c = p.curvatures(t.uv[v][0], t.uv[v][1]);
                    [c.gauss, c.mean]
                })
                .collect();
            Ok((t, curv))
        })
        .map_err(err)?;
    let d = PyDict::new(py);
    d.set_item("vertices", array(py, t.positions))?;
    d.set_item("triangles", array(py, t.triangles))?;
    d.set_item("normals", array(py, t.normals))?;
    d.set_item("patch", t.patch_of_vertex.into_pyarray(py))?;
    d.set_item("patch_uv", array(py, t.uv))?;
    d.set_item("triangle_patch", t.triangle_patch.into_pyarray(py))?;
    let (gauss, mean): (Vec<f64>, Vec<f64>) = curv.into_iter().map(|c| (c[0], c[1])).unzip();
    d.set_item("gauss", gauss.into_pyarray(py))?;
    d.set_item("mean", mean.into_pyarray(py))?;
    Ok(d)
}

/// The options of `subdivide` that set the parameters of `scheme` (a name or alias), as JSON:
/// name, help, choices, and whether it names a file, is a flag or may repeat.
#[pyfunction]
pub fn scheme_options_json(scheme: &str) -> PyResult<String> {
    let spec = registry().lookup(scheme).map_err(err)?;
    let kinds = registry().descriptor(spec.id).params();
    Ok(serde_json::to_string(&api::option_words(kinds)).expect("serialisable"))
}

/// Curvature values as the renderer's diverging colours (blue negative, white 0, red
/// positive; NaN white) over the symmetric range `[-range, range]`: `range` as given, or
/// the `percentile` of `|value|` over the finite values rounded up to two significant digits
/// (as `render --mode mean|gauss` chooses it over pixels). Returns (colours (n, 3) in 0..1,
/// the range).
#[pyfunction]
#[pyo3(signature = (values, range = None, percentile = 0.98))]
pub fn curvature_colours<'py>(
    py: Python<'py>,
    values: PyReadonlyArray1<'_, f64>,
    range: Option<f64>,
    percentile: f64,
) -> PyResult<(Bound<'py, numpy::PyArray2<f64>>, f64)> {
    let v = values.as_slice()?;
    let r = match range {
        Some(r) if r.is_finite() && r > 0.0 => r,
        Some(r) => {
            return Err(PyValueError::new_err(format!(
                "the range must be a positive number, not {r}"
            )));
        }
        None => auto_range(v, percentile),
    };
    let colours: Vec<[f64; 3]> = v
        .iter()
        .map(|&x| fairsub::render::shade::diverging(x / r))
        .collect();
    Ok((array(py, colours), r))
}

/// The `percentile` of `|v|` over the finite values, rounded up to two significant digits;
/// `1e-12` when there is none (a flat surface stays white).
fn auto_range(v: &[f64], percentile: f64) -> f64 {
    let mut a: Vec<f64> = v
        .iter()
        .filter(|x| x.is_finite())
        .map(|x| x.abs())
        .collect();
    if a.is_empty() {
        return 1e-12;
    }
    let k = ((a.len() - 1) as f64 * percentile.clamp(0.0, 1.0)).round() as usize;
    let (_, x, _) = a.select_nth_unstable_by(k, f64::total_cmp);
    fairsub::render::nice_ceil(x.max(1e-12))
}
