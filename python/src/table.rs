//! `Surface.stencils()`: the patch stencil table of a surface (the table `subdivide --rings K
//! --stencils FILE` writes, built by the same code path), applied to moved control points or
//! to any per-point data.

use super::{Csr, csr_arrays, err};
use fairsub::surface::table::PatchTable as Table;
use numpy::ndarray::Array3;
use numpy::{IntoPyArray, PyArray1, PyArray3, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::path::Path;

/// The patch stencil table of a surface: the weights from the net's control points to every
/// Bezier coefficient of its patches (see `fairsub::surface::table`).
#[pyclass(module = "fairsub._fairsub", frozen)]
pub struct PatchTable {
    pub(crate) table: Table,
}

/// Patches as float64 arrays of shape (deg_u + 1, deg_v + 1, d) from flat coefficient rows.
fn patch_arrays<'py>(
    py: Python<'py>,
    shapes: &[(u32, u32)],
    flat: Vec<Vec<f64>>,
    d: usize,
) -> Vec<Bound<'py, PyArray3<f64>>> {
    shapes
        .iter()
        .zip(flat)
        .map(|(&(du, dv), v)| {
            Array3::from_shape_vec((du as usize + 1, dv as usize + 1, d), v)
                .expect("patch shape")
                .into_pyarray(py)
        })
        .collect()
}

#[pymethods]
impl PatchTable {
    /// Number of control points the table reads.
    #[getter]
    fn num_sources(&self) -> usize {
        self.table.num_sources()
    }

    /// Number of patches.
    fn __len__(&self) -> usize {
        self.table.num_patches()
    }

    /// Number of rows (every coefficient of every patch, then the G^1 caps' data rows).
    #[getter]
    fn num_rows(&self) -> usize {
        self.table.rows().num_rows()
    }

    /// (deg_u, deg_v) of every patch.
    #[getter]
    fn shapes(&self) -> Vec<(u32, u32)> {
        self.table.shapes().to_vec()
    }

    /// The first row of every patch's coefficients (b[i, j] at first + i (deg_v + 1) + j).
    #[getter]
    fn first_rows<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u64>> {
        (0..self.table.num_patches())
            .map(|p| self.table.first_row(p) as u64)
            .collect::<Vec<_>>()
            .into_pyarray(py)
    }

    /// Whether each patch is computed by a G^1 cap step (its rows are empty).
    #[getter]
    fn cap_patches(&self) -> Vec<bool> {
        (0..self.table.num_patches())
            .map(|p| self.table.is_cap_patch(p))
            .collect()
    }

    /// The rows in CSR form: (indptr, indices, weights).
    fn csr<'py>(&self, py: Python<'py>) -> Csr<'py> {
        csr_arrays(py, self.table.rows())
    }

    /// The patches of moved control points, (num_sources, 3) float64 positions: the complex
    /// the construction computes from them (G^1 caps rebuilt in their tangent plane). Other
    /// widths (num_sources, d) are per-point data, as apply_data.
    fn apply<'py>(
        &self,
        py: Python<'py>,
        points: PyReadonlyArray2<'_, f64>,
    ) -> PyResult<Vec<Bound<'py, PyArray3<f64>>>> {
        let shape = points.shape().to_vec();
        if shape.len() == 2 && shape[1] != 3 {
            return self.apply_data(py, points);
        }
        let pts = super::points_from(&points, "points")?;
        let c = py.detach(|| self.table.apply(&pts)).map_err(err)?;
        let flat: Vec<Vec<f64>> = c
            .patches
            .into_iter()
            .map(|p| p.cps.into_iter().flatten().collect())
            .collect();
        Ok(patch_arrays(py, self.table.shapes(), flat, 3))
    }

    /// Per-point data (num_sources, d) float64 (colours, texture coordinates, ...) through the
    /// same rows: per patch a (deg_u + 1, deg_v + 1, d) array. G^1 caps fit their spoke tangents
    /// in the data's own space (no tangent plane).
    fn apply_data<'py>(
        &self,
        py: Python<'py>,
        values: PyReadonlyArray2<'_, f64>,
    ) -> PyResult<Vec<Bound<'py, PyArray3<f64>>>> {
        let shape = values.shape().to_vec();
        if shape.len() != 2 || shape[0] != self.table.num_sources() {
            return Err(PyValueError::new_err(format!(
                "values must have shape ({}, d), not {shape:?}",
                self.table.num_sources()
            )));
        }
        let d = shape[1];
        let flat: Vec<f64> = values.as_array().iter().copied().collect();
        let out = py.detach(|| self.table.apply_data(&flat, d)).map_err(err)?;
        Ok(patch_arrays(py, self.table.shapes(), out, d))
    }

    /// Writes the table as `subdivide --stencils FILE` does (the README's format).
    fn write(&self, py: Python<'_>, path: &str) -> PyResult<()> {
        py.detach(|| fairsub::cli::api::write_patch_table(&self.table, Path::new(path)))
            .map_err(err)
    }

    fn __repr__(&self) -> String {
        format!(
            "PatchTable({} patches, {} rows, {} weights over {} points, {} G^1 caps)",
            self.table.num_patches(),
            self.table.rows().num_rows(),
            self.table.rows().num_entries(),
            self.table.num_sources(),
            self.table.caps().len()
        )
    }
}
