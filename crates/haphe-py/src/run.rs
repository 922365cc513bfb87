//! `haphe.run`: the servo loop with a device, on the simulated clock.

use haphe::servo::{
    Device, HandOptions, PathKind, Servo, ServoOptions, SimulatedHand, TickRecord, scripted_path,
};
use numpy::IntoPyArray;
use numpy::ndarray::{Array1, Array2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::haphe_error;
use crate::scene::Scene;

/// Opens the device named `device` for `scene` and a run of `seconds`.
///
/// `hand` is the simulated hand following the scripted path `path`. Hardware devices
/// (`dhd`, `udp:...`) are opened here once the device crate provides them.
fn open_device(
    device: &str,
    path: &str,
    scene: &haphe::scene::Scene,
    seconds: f64,
    seed: u64,
) -> Result<Box<dyn Device + Send>, String> {
    match device {
        "hand" => {
            let kind: PathKind = path.parse()?;
            let path = scripted_path(kind, scene, seconds, seed).map_err(|e| e.to_string())?;
            Ok(Box::new(SimulatedHand::new(path, HandOptions::default())))
        }
        other => Err(format!(
            "device {other:?} is not available in this build: the devices are \"hand\" (the simulated hand)"
        )),
    }
}

/// run(scene, device="hand", seconds=2.0, path="explore", rate_hz=1000.0, seed=1)
/// --
///
/// Runs the servo loop over ``scene`` with a device for ``seconds``: each tick reads the
/// device, ticks the proxy (after the safe start: no force until the device point is
/// outside every solid, then a 50 ms ramp) and writes the force. ``device="hand"`` is the
/// simulated hand (a mass–spring–damper arm pushed back by the force) following the
/// scripted ``path`` (``press``, ``slide``, ``circle``, ``explore`` or ``strike``) on a
/// simulated clock, as fast as the machine goes. Runs without the GIL.
///
/// Returns a dict of arrays, one row per tick: ``t`` (s), ``hip``, ``proxy`` (N, 3) m,
/// ``force`` (N, 3) N, ``contact`` bool, ``object`` (id, -1 when free), ``triangle``
/// (the file's face index, -1 when free), ``penetration`` m.
#[pyfunction]
#[pyo3(signature = (scene, device = "hand", seconds = 2.0, path = "explore", rate_hz = 1000.0, seed = 1))]
pub fn run<'py>(
    py: Python<'py>,
    scene: PyRef<'py, Scene>,
    device: &str,
    seconds: f64,
    path: &str,
    rate_hz: f64,
    seed: u64,
) -> PyResult<Bound<'py, PyDict>> {
    if !(seconds.is_finite() && seconds > 0.0 && seconds * rate_hz <= 1e8) {
        return Err(haphe_error(
            "seconds",
            format!("must be positive and give at most 1e8 ticks, not {seconds}"),
        ));
    }
    let world = scene.snapshot();
    drop(scene);
    let records = py
        .detach(|| -> Result<Vec<TickRecord>, String> {
            let device = open_device(device, path, &world, seconds, seed)?;
            let options = ServoOptions {
                rate_hz,
                ..ServoOptions::default()
            };
            let mut servo = Servo::new(device, world, options).map_err(|e| e.to_string())?;
            let ticks = (seconds * rate_hz).round() as u64;
            let mut records = Vec::with_capacity(ticks as usize);
            servo.run_simulated(ticks, |r| records.push(*r));
            servo.close();
            Ok(records)
        })
        .map_err(|e| haphe_error(device, e))?;
    let n = records.len();
    let mut t = Array1::zeros(n);
    let mut hip = Array2::zeros((n, 3));
    let mut proxy = Array2::zeros((n, 3));
    let mut force = Array2::zeros((n, 3));
    let mut contact = Array1::from_elem(n, false);
    let mut object = Array1::from_elem(n, -1i64);
    let mut triangle = Array1::from_elem(n, -1i64);
    let mut penetration = Array1::zeros(n);
    for (i, r) in records.iter().enumerate() {
        t[i] = r.t;
        for k in 0..3 {
            hip[[i, k]] = r.hip[k];
            proxy[[i, k]] = r.proxy[k];
            force[[i, k]] = r.force[k];
        }
        contact[i] = r.in_contact();
        object[i] = r.object.map_or(-1, |o| i64::from(o.0));
        triangle[i] = r.triangle.map_or(-1, i64::from);
        penetration[i] = r.penetration;
    }
    let d = PyDict::new(py);
    d.set_item("t", t.into_pyarray(py))?;
    d.set_item("hip", hip.into_pyarray(py))?;
    d.set_item("proxy", proxy.into_pyarray(py))?;
    d.set_item("force", force.into_pyarray(py))?;
    d.set_item("contact", contact.into_pyarray(py))?;
    d.set_item("object", object.into_pyarray(py))?;
    d.set_item("triangle", triangle.into_pyarray(py))?;
    d.set_item("penetration", penetration.into_pyarray(py))?;
    Ok(d)
}
