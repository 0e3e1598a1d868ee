//! `Surface.evaluate` of many points: the numpy arrays it returns, allocated by numpy and filled
//! in place, in parallel, with the GIL released, from [`eval::Surface::evaluate_into`]'s
//! per-task buffer (no per-point Python object, no second copy of the output).
//!
//! numpy backs large arrays with transparent huge pages where the system allows it (it asks
//! with `madvise`), so filling the ~230 bytes per point of a 10^6-point call costs a few hundred
//! page faults instead of some 56,000; that, not the evaluation, was the Python call's overhead.

use fairsub::surface::eval;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Names of the (n, 3) outputs, in [`Rows::vecs`] order.
const VEC_NAMES: [&str; 7] = ["point", "du", "dv", "duu", "duv", "dvv", "normal"];
/// Names of the (n,) float outputs, in [`Rows::scalars`] order.
const SCALAR_NAMES: [&str; 4] = ["gauss", "mean", "u", "v"];

/// Points per parallel task (its `evaluate_into` buffer: about 60 KB).
const CHUNK: usize = 256;

/// Mutable views of the output arrays' rows `start..start + len` (all of them at first, then
/// one task's share).
struct Rows<'a> {
    start: usize,
    vecs: Vec<&'a mut [f64]>,
    scalars: Vec<&'a mut [f64]>,
    face: &'a mut [u32],
    patch: &'a mut [i64],
    patch_uv: &'a mut [f64],
}

impl<'a> Rows<'a> {
    /// Splits off the first `k` rows.
    fn split(self, k: usize) -> (Rows<'a>, Rows<'a>) {
        let mut vecs = (Vec::new(), Vec::new());
        for b in self.vecs {
            let (x, y) = b.split_at_mut(3 * k);
            vecs.0.push(x);
            vecs.1.push(y);
        }
        let mut scalars = (Vec::new(), Vec::new());
        for b in self.scalars {
            let (x, y) = b.split_at_mut(k);
            scalars.0.push(x);
            scalars.1.push(y);
        }
        let face = self.face.split_at_mut(k);
        let patch = self.patch.split_at_mut(k);
        let patch_uv = self.patch_uv.split_at_mut(2 * k);
        (
            Rows {
                start: self.start,
                vecs: vecs.0,
                scalars: scalars.0,
                face: face.0,
                patch: patch.0,
                patch_uv: patch_uv.0,
            },
            Rows {
                start: self.start + k,
                vecs: vecs.1,
                scalars: scalars.1,
                face: face.1,
                patch: patch.1,
                patch_uv: patch_uv.1,
            },
        )
    }

    /// Evaluates the rows' points; `(index, error)` of the first that fails.
    fn fill(
        mut self,
        ev: &eval::Surface,
        f: &[i64],
        u: &[f64],
        v: &[f64],
    ) -> Result<(), (usize, fairsub::Error)> {
        let n = self.face.len();
        let mut pts = Vec::with_capacity(n);
        for i in self.start..self.start + n {
            let face = u32::try_from(f[i]).map_err(|_| {
                let e = format!("point {i}: face {} does not exist", f[i]);
                (i, fairsub::Error::InvalidArgument(e))
            })?;
            pts.push((face, u[i], v[i]));
        }
        let mut out = vec![eval::Evaluation::default(); n];
        ev.evaluate_into(&pts, &mut out)
            .map_err(|(j, e)| (self.start + j, e))?;
        for (j, e) in out.iter().enumerate() {
            for (b, p) in self
                .vecs
                .iter_mut()
                .zip([e.point, e.du, e.dv, e.duu, e.duv, e.dvv, e.normal])
            {
                b[3 * j..3 * j + 3].copy_from_slice(&p);
            }
            for (b, x) in self.scalars.iter_mut().zip([e.gauss, e.mean, e.u, e.v]) {
                b[j] = x;
            }
            self.face[j] = e.face;
            self.patch[j] = e.patch as i64;
            self.patch_uv[2 * j..2 * j + 2].copy_from_slice(&e.patch_uv);
        }
        Ok(())
    }
}

/// Evaluates `ev` at `(f[i], u[i], v[i])` (slices of one length): the dict of arrays
/// `Surface.evaluate_arrays` returns; a failing point raises ValueError with the message of
/// the first (by index) that fails.
pub fn evaluate_arrays<'py>(
    py: Python<'py>,
    ev: &eval::Surface,
    f: &[i64],
    u: &[f64],
    v: &[f64],
) -> PyResult<Bound<'py, PyDict>> {
    use rayon::prelude::*;
    let n = f.len();
    let vecs: Vec<_> = VEC_NAMES
        .iter()
        .map(|_| PyArray2::<f64>::zeros(py, [n, 3], false))
        .collect();
    let scalars: Vec<_> = SCALAR_NAMES
        .iter()
        .map(|_| PyArray1::<f64>::zeros(py, n, false))
        .collect();
    let face = PyArray1::<u32>::zeros(py, n, false);
    let patch = PyArray1::<i64>::zeros(py, n, false);
    let patch_uv = PyArray2::<f64>::zeros(py, [n, 2], false);
    {
        let mut vec_rw: Vec<_> = vecs.iter().map(|a| a.readwrite()).collect();
        let mut scalar_rw: Vec<_> = scalars.iter().map(|a| a.readwrite()).collect();
        let (mut face_rw, mut patch_rw, mut uv_rw) =
            (face.readwrite(), patch.readwrite(), patch_uv.readwrite());
        let mut all = Rows {
            start: 0,
            vecs: Vec::new(),
            scalars: Vec::new(),
            face: face_rw.as_slice_mut()?,
            patch: patch_rw.as_slice_mut()?,
            patch_uv: uv_rw.as_slice_mut()?,
        };
        for a in &mut vec_rw {
            all.vecs.push(a.as_slice_mut()?);
        }
        for a in &mut scalar_rw {
            all.scalars.push(a.as_slice_mut()?);
        }
        let mut tasks = Vec::with_capacity(n.div_ceil(CHUNK));
        let mut rest = all;
        while rest.face.len() > CHUNK {
            let (task, more) = rest.split(CHUNK);
            tasks.push(task);
            rest = more;
        }
        tasks.push(rest);
        let first = py.detach(|| {
            tasks
                .into_par_iter()
                .filter_map(|t| t.fill(ev, f, u, v).err())
                .min_by_key(|(i, _)| *i)
        });
        if let Some((_, e)) = first {
            return Err(PyValueError::new_err(e.to_string()));
        }
    }
    let d = PyDict::new(py);
    for (name, a) in VEC_NAMES.iter().zip(vecs) {
        d.set_item(*name, a)?;
    }
    for (name, a) in SCALAR_NAMES.iter().zip(scalars) {
        d.set_item(*name, a)?;
    }
    d.set_item("face", face)?;
    d.set_item("patch", patch)?;
    d.set_item("patch_uv", patch_uv)?;
    Ok(d)
}
