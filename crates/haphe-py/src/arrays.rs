//! Array arguments of the batch queries: anything numpy takes as an `(N, 3)` float array,
//! converted as `numpy.asarray(x, dtype=numpy.float64)` does, and the `nonfinite` option.

use std::borrow::Cow;

use haphe::query::{BatchError, NonFinite};
use numpy::{PyArrayDyn, PyArrayMethods, PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::errors::haphe_error;

/// An `(N, 3)` float64 array argument named `what`: a float64 ndarray as it is (any
/// strides), anything else through `numpy.asarray(x, dtype=numpy.float64)` (lists, other
/// dtypes, objects with `__array__`). Raises `HapheError` naming the argument when numpy
/// cannot convert it or its shape is not `(N, 3)`.
pub fn rows_argument<'py>(
    what: &str,
    x: &Bound<'py, PyAny>,
) -> PyResult<PyReadonlyArrayDyn<'py, f64>> {
    let array = match x.cast::<PyArrayDyn<f64>>() {
        Ok(a) => a.clone(),
        Err(_) => {
            let py = x.py();
            let numpy = py.import("numpy")?;
            let converted = numpy
                .getattr("asarray")?
                .call((x, numpy.getattr("float64")?), None)
                .map_err(|e| {
                    let error = haphe_error(
                        what,
                        format!("cannot be read as an array of floats of shape (N, 3): {e}"),
                    );
                    error.set_cause(py, Some(e));
                    error
                })?;
            converted.cast_into::<PyArrayDyn<f64>>()?
        }
    };
    let shape = array.shape();
    if shape.len() != 2 || shape[1] != 3 {
        return Err(haphe_error(
            what,
            format!("expected an array of shape (N, 3), got shape {shape:?}"),
        ));
    }
    Ok(array.readonly())
}

/// The rows of an `(N, 3)` array checked by [`rows_argument`]: borrowed when it is
/// C-contiguous, else copied.
pub fn rows<'a>(array: &'a PyReadonlyArrayDyn<'_, f64>) -> Cow<'a, [[f64; 3]]> {
    // Only a C-ordered array holds its rows one after the other (`as_slice` also takes a
    // Fortran-ordered one, whose memory holds the columns).
    let c_ordered = array
        .is_c_contiguous()
        .then(|| array.as_slice().ok())
        .flatten();
    match c_ordered {
        Some(flat) => Cow::Borrowed(flat.as_chunks::<3>().0),
        None => Cow::Owned(
            array
                .as_array()
                .rows()
                .into_iter()
                .map(|r| [r[0], r[1], r[2]])
                .collect(),
        ),
    }
}

/// The `nonfinite` option: `"error"` (a NaN or infinite coordinate raises, naming the first
/// such row) or `"skip"` (such a row answers "nothing found").
pub fn nonfinite(option: &str) -> PyResult<NonFinite> {
    match option {
        "error" => Ok(NonFinite::Error),
        "skip" => Ok(NonFinite::Skip),
        other => Err(haphe_error(
            "nonfinite",
            format!("must be \"error\" or \"skip\", not {other:?}"),
        )),
    }
}

/// A refused batch as a `HapheError`.
pub fn batch_error(e: BatchError) -> PyErr {
    haphe_error("", e)
}
