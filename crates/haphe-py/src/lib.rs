//! Python bindings of haphe: the module `haphe` (its native part, `haphe._haphe`).
//!
//! A thin layer: every function here converts arrays and arguments, calls the library and
//! converts the answer back. Batch queries take and give numpy arrays, run without the GIL
//! and loop in Rust; errors become Python exceptions carrying the library's messages, which
//! name the file and the place.

mod arrays;
mod deform;
mod device;
mod errors;
mod files;
mod run;
mod scene;
mod shape;
mod spec;
mod volume;

#[cfg(feature = "count-allocations")]
mod alloc;

use pyo3::prelude::*;

/// The native module, re-exported by the Python package `haphe`.
#[pymodule]
#[pyo3(name = "_haphe")]
fn haphe_native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("HapheError", m.py().get_type::<errors::HapheError>())?;
    m.add("DeviceError", m.py().get_type::<device::DeviceError>())?;
    m.add_function(wrap_pyfunction!(files::validate, m)?)?;
    m.add_function(wrap_pyfunction!(run::run, m)?)?;
    m.add_function(wrap_pyfunction!(deform::check_deforming, m)?)?;
    m.add_function(wrap_pyfunction!(allocations, m)?)?;
    m.add_class::<shape::Shape>()?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<scene::Proxy>()?;
    m.add_class::<scene::Contact>()?;
    m.add_class::<volume::Volume>()?;
    m.add_class::<volume::Cutter>()?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("DEFAULT_MAX_FORCE", haphe::scene::DEFAULT_MAX_FORCE_N)?;
    Ok(())
}

/// Allocation calls made by the Rust side of the module since it was loaded, or `None`
/// when the module was built without the `count-allocations` feature.
#[pyfunction]
fn allocations() -> Option<u64> {
    #[cfg(feature = "count-allocations")]
    {
        Some(alloc::allocations())
    }
    #[cfg(not(feature = "count-allocations"))]
    {
        None
    }
}
