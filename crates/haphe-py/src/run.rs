//! `haphe.run`: the servo loop with a device: the simulated hand on the simulated clock,
//! or a real device (src/device.rs) on the wall clock.

use haphe::DVec3;
use haphe::scene::Param;
use haphe::servo::{
    Device, HandOptions, PathKind, Servo, ServoOptions, SimulatedHand, scripted_path,
};
use numpy::IntoPyArray;
use numpy::ndarray::{Array1, Array2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use haphe_devices::{UDP_TIMEOUT_S, UdpOptions};

use crate::device::{DeviceOutcome, DeviceRun, run_device};
use crate::errors::{haphe_error, param_error};
use crate::scene::Scene;

/// The simulated hand following the scripted path `path` over `scene` for `seconds`,
/// holding the buttons of `presses` (button, from, until).
fn simulated_hand(
    path: &str,
    scene: &haphe::scene::Scene,
    seconds: f64,
    seed: u64,
    presses: &[(u32, f64, f64)],
) -> Result<Box<dyn Device + Send>, String> {
    let kind: PathKind = path.parse()?;
    let path = scripted_path(kind, scene, seconds, seed).map_err(|e| e.to_string())?;
    let mut hand = SimulatedHand::new(path, HandOptions::default());
    for &(button, from, until) in presses {
        hand = hand
            .press(button, from, until)
            .map_err(|e| format!("presses: {e}"))?;
    }
    Ok(Box::new(hand))
}

/// run(scene, device="hand", seconds=2.0, path="explore", rate_hz=1000.0, seed=1, scale=None, centre=None, udp_timeout=0.05, udp_workspace=0.1, clutch_button=None, presses=None, tool_radius=0.0)
/// --
///
/// Runs the servo loop over ``scene`` with a device for ``seconds``: each tick reads the
/// device, ticks the proxy (after the safe start: no force until the device point is
/// outside every solid, then a 50 ms ramp) and writes the force. Runs without the GIL.
///
/// ``device`` is one of
///
/// - ``"hand"``: the simulated hand (a mass–spring–damper arm pushed back by the force)
///   following the scripted ``path`` (``press``, ``slide``, ``circle``, ``explore`` or
///   ``strike``) on a simulated clock, as fast as the machine goes;
/// - ``"dhd"``: a Force Dimension device (``libdhd.so``, or the file named by
///   ``HAPHE_DHD_LIBRARY``);
/// - ``"openhaptics"``: a 3D Systems Touch through OpenHaptics (``libHD.so``, or
///   ``HAPHE_HD_LIBRARY``), ticked by its scheduler (``rate_hz`` must be its rate);
/// - ``"udp:HOST:PORT"``: a device driven by another process over UDP (haphe listens
///   there; the datagrams are in docs/devices.md); ``udp_timeout`` seconds without a
///   position stop the run with zero force, ``udp_workspace`` is the half size of the
///   peer's workspace cube, metres.
///
/// ``clutch_button`` (0 to 31) makes that button of the device a clutch: while it is held
/// the device moves without moving the tool (to re-centre the hand in the workspace), the
/// tool stays where it was and the force fades out over 50 ms, then back in after the
/// release; the tool then continues from where it stayed. ``presses``, a list of
/// ``(button, from, until)`` (seconds), holds buttons of the simulated hand.
///
/// A real device runs on the wall clock on a real-time thread. Its workspace is mapped
/// onto the scene as ``haphe run`` maps it: ``scale`` world metres per device metre
/// (default: the workspace covers the scene's bounds) and its centre at the world point
/// ``centre`` (default: the centre of the scene's bounds). Ctrl-C stops it: zero force is
/// written, then ``KeyboardInterrupt`` is raised.
///
/// ``tool_radius`` (metres) makes the tool a sphere of that radius centred on the proxy
/// (0, a point, by default): from 0 to 0.5 m and at most the diagonal of the box bounding
/// the scene's objects, else ``HapheError`` naming it.
///
/// Returns a dict of arrays, one row per tick: ``t`` (s), ``hip``, ``proxy`` (N, 3) m,
/// ``force`` (N, 3) N, ``contact`` bool, ``object`` (id, -1 when free), ``triangle``
/// (the file's face index, -1 when free), ``penetration`` m, ``buttons`` (uint32, bit 0
/// the first button), ``clutch`` bool; the ``offset`` (3,) m the clutch moved the device's
/// origin by in the world; and the strings ``device``
/// (what was opened), ``stop`` (``finished``, ``overruns`` or ``fault: ...``) and
/// ``report`` (the device's fault or traffic, or None).
///
/// Raises ``HapheError`` for an unknown device or a bad argument, and ``DeviceError`` (an
/// ``OSError``) when the device or its library cannot be opened: the message names the
/// library, the variable that selects it and the SDK.
#[pyfunction]
#[pyo3(signature = (scene, device = "hand", seconds = 2.0, path = "explore", rate_hz = 1000.0, seed = 1, scale = None, centre = None, udp_timeout = UDP_TIMEOUT_S, udp_workspace = 0.1, clutch_button = None, presses = None, tool_radius = 0.0))]
#[allow(clippy::too_many_arguments)]
pub fn run<'py>(
    py: Python<'py>,
    scene: PyRef<'py, Scene>,
    device: &str,
    seconds: f64,
    path: &str,
    rate_hz: f64,
    seed: u64,
    scale: Option<f64>,
    centre: Option<[f64; 3]>,
    udp_timeout: f64,
    udp_workspace: f64,
    clutch_button: Option<u32>,
    presses: Option<Vec<(u32, f64, f64)>>,
    tool_radius: f64,
) -> PyResult<Bound<'py, PyDict>> {
    // The library's table of domains checks the rate, the scale and the centre.
    let options = ServoOptions::new(rate_hz).map_err(param_error)?;
    if let Some(b) = clutch_button
        && b >= 32
    {
        return Err(haphe_error(
            "clutch_button",
            format!("must be a button from 0 to 31, not {b}"),
        ));
    }
    let options = options.with_clutch_button(clutch_button);
    let presses = presses.unwrap_or_default();
    if !presses.is_empty() && device != "hand" {
        return Err(haphe_error(
            "presses",
            format!("holds buttons of the simulated hand only, not of device {device:?}"),
        ));
    }
    if !(seconds.is_finite() && seconds > 0.0 && seconds * rate_hz <= 1e8) {
        return Err(haphe_error(
            "seconds",
            format!("must be positive and give at most 1e8 ticks, not {seconds}"),
        ));
    }
    if let Some(s) = scale {
        Param::Scale.check(s).map_err(param_error)?;
    }
    if let Some(c) = centre {
        Param::Centre.check_vector(c).map_err(param_error)?;
    }
    // The network device's own settings, not servo parameters.
    for (name, value) in [
        ("udp_timeout", udp_timeout),
        ("udp_workspace", udp_workspace),
    ] {
        if !(value.is_finite() && value > 0.0) {
            return Err(haphe_error(name, format!("must be positive, not {value}")));
        }
    }
    let world = scene.snapshot();
    drop(scene);
    // The tool against its domain and the scene's size, as the command checks it.
    let proxy = world
        .check_tool_radius(tool_radius)
        .and_then(|r| options.proxy().with_tool_radius(r))
        .map_err(param_error)?;
    let options = options.with_proxy(proxy);
    let outcome = if device == "hand" {
        py.detach(|| -> Result<DeviceOutcome, String> {
            let hand = simulated_hand(path, &world, seconds, seed, &presses)?;
            let mut servo = Servo::new(hand, world, options).map_err(|e| e.to_string())?;
            let ticks = (seconds * rate_hz).round() as u64;
            let mut records = Vec::with_capacity(ticks as usize);
            servo.run_simulated(ticks, |r| records.push(*r));
            servo.close();
            Ok(DeviceOutcome {
                records,
                offset: servo.mapping().offset() - servo.options().mapping().offset(),
                description: format!("the simulated hand ({path})"),
                stop: "finished".into(),
                report: None,
            })
        })
        .map_err(|e| haphe_error(device, e))?
    } else {
        let h = udp_workspace;
        let request = DeviceRun {
            spec: device.to_string(),
            seconds,
            rate_hz,
            scale,
            centre: centre.map(DVec3::from_array),
            udp: UdpOptions {
                timeout_s: udp_timeout,
                workspace: (DVec3::splat(-h), DVec3::splat(h)),
                ..UdpOptions::default()
            },
            clutch_button,
            proxy,
        };
        py.detach(|| run_device(request, world))?
    };
    let records = outcome.records;
    let n = records.len();
    let mut t = Array1::zeros(n);
    let mut hip = Array2::zeros((n, 3));
    let mut proxy = Array2::zeros((n, 3));
    let mut force = Array2::zeros((n, 3));
    let mut contact = Array1::from_elem(n, false);
    let mut object = Array1::from_elem(n, -1i64);
    let mut triangle = Array1::from_elem(n, -1i64);
    let mut penetration = Array1::zeros(n);
    let mut buttons = Array1::zeros(n);
    let mut clutch = Array1::from_elem(n, false);
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
        buttons[i] = r.buttons.0;
        clutch[i] = r.clutch;
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
    d.set_item("buttons", buttons.into_pyarray(py))?;
    d.set_item("clutch", clutch.into_pyarray(py))?;
    d.set_item(
        "offset",
        Array1::from(outcome.offset.to_array().to_vec()).into_pyarray(py),
    )?;
    d.set_item("device", outcome.description)?;
    d.set_item("stop", outcome.stop)?;
    d.set_item("report", outcome.report)?;
    Ok(d)
}
