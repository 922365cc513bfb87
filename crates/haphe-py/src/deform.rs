//! Deformation from Python: the arguments of `Scene.deform` (vertex positions, and the
//! indices of a subset) read as numpy reads them, the library's refusals as exceptions,
//! and `check_deforming`, the library's comparison of the proxy with brute force while a
//! shape deforms.

use haphe::DVec3;
use haphe::proxy::ProxyOptions;
use haphe::scene::{self as hs, DeformError, ObjectId};
use haphe::verify::{Deformation, check_deforming as check};
use numpy::{PyArrayDyn, PyArrayMethods};
use pyo3::exceptions::PyKeyError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{rows, rows_argument};
use crate::errors::{haphe_error, param_error};

/// An `(N, 3)` array-like argument named `what` (the positions of a deformation, a path)
/// as points, read as the batch queries read theirs.
pub fn points(what: &str, x: &Bound<'_, PyAny>) -> PyResult<Vec<DVec3>> {
    let array = rows_argument(what, x)?;
    Ok(rows(&array).iter().map(|&p| DVec3::from_array(p)).collect())
}

/// The vertex indices of a subset: a 1-D array-like of integers (any integer dtype; an
/// empty list too), each one a `u32` below `count`, else `HapheError` naming the first
/// row that is not.
pub fn indices(x: &Bound<'_, PyAny>, count: usize) -> PyResult<Vec<u32>> {
    let numpy = x.py().import("numpy")?;
    let array = numpy.getattr("asarray")?.call1((x,)).map_err(|e| {
        haphe_error(
            "indices",
            format!("cannot be read as a 1-D array of integers: {e}"),
        )
    })?;
    let shape: Vec<usize> = array.getattr("shape")?.extract()?;
    let kind: String = array.getattr("dtype")?.getattr("kind")?.extract()?;
    let empty = shape.iter().product::<usize>() == 0;
    if shape.len() != 1 || !(matches!(kind.as_str(), "i" | "u") || empty) {
        let dtype = array.getattr("dtype")?.str()?;
        return Err(haphe_error(
            "indices",
            format!("expected a 1-D array of integers, got shape {shape:?} of {dtype}"),
        ));
    }
    // Unsigned indices as u64, signed as i64: every value is then read as given.
    let wide: Vec<i128> = if kind == "u" {
        let a = array.call_method1("astype", (numpy.getattr("uint64")?,))?;
        let a = a.cast_into::<PyArrayDyn<u64>>()?;
        let a = a.readonly();
        a.as_array().iter().map(|&i| i128::from(i)).collect()
    } else {
        let a = array.call_method1("astype", (numpy.getattr("int64")?,))?;
        let a = a.cast_into::<PyArrayDyn<i64>>()?;
        let a = a.readonly();
        a.as_array().iter().map(|&i| i128::from(i)).collect()
    };
    wide.iter()
        .enumerate()
        .map(|(row, &i)| {
            u32::try_from(i)
                .ok()
                .filter(|&v| (v as usize) < count)
                .ok_or_else(|| {
                    haphe_error(
                        "indices",
                        format!(
                            "row {row}: vertex index {i} is out of range (the shape has {count} vertices)"
                        ),
                    )
                })
        })
        .collect()
}

/// A refused deformation as Python sees it: `KeyError` for an unknown object (as
/// `Scene.move` raises), else `HapheError` naming the argument at fault and its row.
pub fn deform_error(e: DeformError) -> PyErr {
    match e {
        DeformError::UnknownObject(id) => PyKeyError::new_err(id),
        e @ (DeformError::Index { .. } | DeformError::IndicesCount { .. }) => {
            haphe_error("indices", e)
        }
        e @ (DeformError::Count { .. } | DeformError::NotFinite { .. }) => {
            haphe_error("vertices", e)
        }
        e => haphe_error("deform", e),
    }
}

/// The vertex count of object `id`'s shape, `KeyError` when there is no such object.
pub fn vertex_count(scene: &hs::Scene, id: u32) -> PyResult<usize> {
    scene
        .index_of(ObjectId(id))
        .map(|i| scene.objects()[i].shape.surface().vertex_count())
        .ok_or_else(|| PyKeyError::new_err(id))
}

/// check_deforming(scene, deformation, path, rate_hz=1000.0, tool_radius=0.0)
/// --
///
/// The library's check of the proxy while a shape deforms (``haphe verify``'s deforming
/// suites): the first object of ``scene`` is deformed before every tick by
/// ``deformation`` (``"breathe"``, ``"dent"``, ``"breathe-dent"`` or ``"twist"``, its
/// vertices now being the rest shape) while the proxy and a brute-force proxy (every
/// triangle, no map) follow ``path``, an ``(N, 3)`` array of device points (metres, one
/// per tick at ``rate_hz``). Returns a dict of counts: ``ticks``, ``contact_ticks``,
/// ``mismatches`` (ticks where the two proxies differ), ``max_deviation`` (metres),
/// ``inside`` (ticks where the proxy is inside the current surface deeper than its skin)
/// and ``bad_forces`` (non-finite or above the maximum). The scene is left deformed as at
/// the last tick. Runs without the GIL.
#[pyfunction]
#[pyo3(signature = (scene, deformation, path, rate_hz = 1000.0, tool_radius = 0.0))]
pub fn check_deforming<'py>(
    py: Python<'py>,
    mut scene: PyRefMut<'py, crate::scene::Scene>,
    deformation: &str,
    path: &Bound<'py, PyAny>,
    rate_hz: f64,
    tool_radius: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let deformation: Deformation = deformation
        .parse()
        .map_err(|e: String| haphe_error("deformation", e))?;
    if !(rate_hz.is_finite() && rate_hz > 0.0) {
        return Err(haphe_error(
            "rate_hz",
            format!("must be a positive rate in Hz, not {rate_hz}"),
        ));
    }
    let options = ProxyOptions::default()
        .with_tool_radius(tool_radius)
        .map_err(param_error)?;
    let path = points("path", path)?;
    let scene = scene.scene();
    let c = py
        .detach(|| check(scene, deformation, &path, options, rate_hz))
        .map_err(deform_error)?;
    let d = PyDict::new(py);
    d.set_item("ticks", c.ticks)?;
    d.set_item("contact_ticks", c.contact_ticks)?;
    d.set_item("mismatches", c.mismatches)?;
    d.set_item("max_deviation", c.max_deviation_m)?;
    d.set_item("inside", c.inside)?;
    d.set_item("bad_forces", c.bad_forces)?;
    Ok(d)
}
