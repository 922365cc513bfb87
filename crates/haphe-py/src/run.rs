//! `haphe.run`: the servo loop with a device: the simulated hand on the simulated clock,
//! or a real device (src/device.rs) on the wall clock.

use haphe::DVec3;
use haphe::scene::Param;
use haphe::servo::{
    Device, HandOptions, PathKind, Servo, ServoOptions, SimulatedHand, TickRecord, scripted_path,
};
use numpy::IntoPyArray;
use numpy::ndarray::{Array1, Array2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use haphe_devices::{UDP_TIMEOUT_S, UdpOptions};

use crate::device::{DeviceOutcome, DeviceRun, run_devices};
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
/// the scene's objects, else ``HapheError`` naming it. With several devices, one radius
/// for all or a list, one per device.
///
/// The scene's effects (``Scene.add_effect``) are rendered with the surfaces; a vibration
/// above half ``rate_hz`` raises ``HapheError`` naming ``effect`` and its specification.
///
/// Returns a dict of arrays, one row per tick: ``t`` (s), ``hip``, ``proxy`` (N, 3) m,
/// ``velocity`` (N, 3) m/s (the device point's, as the damping and the effects use it),
/// ``force`` (N, 3) N, ``contact`` bool, ``object`` (id, -1 when free), ``triangle``
/// (the file's face index, -1 when free), ``penetration`` m, ``buttons`` (uint32, bit 0
/// the first button), ``clutch`` bool; the ``offset`` (3,) m the clutch moved the device's
/// origin by in the world; and the strings ``device``
/// (what was opened), ``stop`` (``finished``, ``overruns`` or ``fault: ...``) and
/// ``report`` (the device's fault or traffic, or None).
///
/// **Several devices in one scene** (two hands): ``device`` a list, e.g.
/// ``["dhd:0", "dhd:1"]`` (``dhd:N`` the Force Dimension device at index N,
/// ``openhaptics:NAME`` the Touch configured under NAME, network devices on separate
/// ports, ``hand`` or ``hand:SEED``). One servo ticks them all on the same deadlines, each
/// with its own proxy, mapping and safety; a fault of one writes zero force to every
/// device and ``stop`` names it. ``scale`` and ``centre`` are then a list with one value
/// per device, in order (or None for the defaults). With hands only, the run is on the
/// simulated clock and the k-th bare ``"hand"`` (from 0) follows the path of ``seed + k``.
/// Returns a list of dicts, one per device, each as above.
///
/// Raises ``HapheError`` for an unknown device, one given twice or a bad argument, and
/// ``DeviceError`` (an ``OSError``) when a device or its library cannot be opened: the
/// message names the library, the variable that selects it and the SDK.
#[pyfunction]
#[pyo3(signature = (scene, device = OneOrMany::One("hand".to_string()), seconds = 2.0, path = "explore", rate_hz = 1000.0, seed = 1, scale = None, centre = None, udp_timeout = UDP_TIMEOUT_S, udp_workspace = 0.1, clutch_button = None, presses = None, tool_radius = OneOrMany::One(0.0)))]
#[allow(clippy::too_many_arguments)]
pub fn run<'py>(
    py: Python<'py>,
    scene: PyRef<'py, Scene>,
    device: OneOrMany<String>,
    seconds: f64,
    path: &str,
    rate_hz: f64,
    seed: u64,
    scale: Option<OneOrMany<f64>>,
    centre: Option<OneOrMany<[f64; 3]>>,
    udp_timeout: f64,
    udp_workspace: f64,
    clutch_button: Option<u32>,
    presses: Option<Vec<(u32, f64, f64)>>,
    tool_radius: OneOrMany<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let (devices, many) = device.into_vec();
    haphe_devices::parse_devices(&devices).map_err(|e| haphe_error("device", e))?;
    if devices.is_empty() {
        return Err(haphe_error("device", "give at least one device"));
    }
    let scales = per_device("scale", scale, &devices)?;
    let centres = per_device("centre", centre, &devices)?;
    // The library's table of domains checks the rate, the scale and the centre.
    let options = ServoOptions::new(rate_hz).map_err(param_error)?;
    for s in scales.iter().flatten() {
        Param::Scale.check(*s).map_err(param_error)?;
    }
    for c in centres.iter().flatten() {
        Param::Centre.check_vector(*c).map_err(param_error)?;
    }
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
    let hands = devices.iter().all(|d| is_hand(d));
    if !presses.is_empty() && !hands {
        return Err(haphe_error(
            "presses",
            format!("holds buttons of the simulated hand only, not of device {devices:?}"),
        ));
    }
    check_lengths(seconds, rate_hz, udp_timeout, udp_workspace)?;
    let world = scene.snapshot();
    // A vibration above half the rate, refused naming its specification.
    crate::spec::check_rate(&world, scene.effect_specs(), options.rate_hz())?;
    drop(scene);
    // The tool against its domain and the scene's size, as the command checks it.
    let proxies = tools(&world, &options, tool_radius, &devices)?;
    let outcomes = if hands {
        let hands = Hands {
            specs: &devices,
            path,
            seconds,
            seed,
            presses: &presses,
        };
        py.detach(|| run_hands(&hands, world, options, &proxies))
            .map_err(|e| haphe_error(&devices.join(", "), e))?
    } else {
        let h = udp_workspace;
        let request = DeviceRun {
            specs: devices,
            seconds,
            rate_hz,
            scales,
            centres: centres
                .into_iter()
                .map(|c| c.map(DVec3::from_array))
                .collect(),
            udp: UdpOptions {
                timeout_s: udp_timeout,
                workspace: (DVec3::splat(-h), DVec3::splat(h)),
                ..UdpOptions::default()
            },
            clutch_button,
            proxies,
        };
        py.detach(|| run_devices(request, world))?
    };
    let mut dicts = outcomes
        .into_iter()
        .map(|o| arrays(py, o))
        .collect::<PyResult<Vec<_>>>()?;
    if !many
        && dicts.len() == 1
        && let Some(d) = dicts.pop()
    {
        return Ok(d.into_any());
    }
    Ok(PyList::new(py, dicts)?.into_any())
}

/// Each device's proxy options, `options`' with its own tool: `tool_radius` one radius
/// for all, or a list, one per device; checked against its domain and `world`'s size, as
/// the command checks it.
fn tools(
    world: &haphe::scene::Scene,
    options: &ServoOptions,
    tool_radius: OneOrMany<f64>,
    devices: &[String],
) -> PyResult<Vec<haphe::proxy::ProxyOptions>> {
    let radii = match tool_radius {
        OneOrMany::One(r) => vec![Some(r); devices.len()],
        many => per_device("tool_radius", Some(many), devices)?,
    };
    radii
        .into_iter()
        .flatten()
        .map(|r| {
            world
                .check_tool_radius(r)
                .and_then(|r| options.proxy().with_tool_radius(r))
                .map_err(param_error)
        })
        .collect()
}

/// Checks the run's length (positive, at most 1e8 ticks) and the network devices' own
/// settings (positive).
fn check_lengths(seconds: f64, rate_hz: f64, udp_timeout: f64, udp_workspace: f64) -> PyResult<()> {
    if !(seconds.is_finite() && seconds > 0.0 && seconds * rate_hz <= 1e8) {
        return Err(haphe_error(
            "seconds",
            format!("must be positive and give at most 1e8 ticks, not {seconds}"),
        ));
    }
    for (name, value) in [
        ("udp_timeout", udp_timeout),
        ("udp_workspace", udp_workspace),
    ] {
        if !(value.is_finite() && value > 0.0) {
            return Err(haphe_error(name, format!("must be positive, not {value}")));
        }
    }
    Ok(())
}

/// A keyword argument given once (a single device) or as a list (one per device).
#[derive(FromPyObject)]
pub enum OneOrMany<T> {
    /// One value.
    One(T),
    /// A list of values.
    Many(Vec<T>),
}

impl<T> OneOrMany<T> {
    /// The values, and whether a list was given.
    fn into_vec(self) -> (Vec<T>, bool) {
        match self {
            OneOrMany::One(v) => (vec![v], false),
            OneOrMany::Many(v) => (v, true),
        }
    }
}

/// The value of the keyword argument `name` for each of `devices`: none given, one per
/// device as a list, or one value for a single device.
fn per_device<T>(
    name: &str,
    given: Option<OneOrMany<T>>,
    devices: &[String],
) -> PyResult<Vec<Option<T>>> {
    let n = devices.len();
    let Some(given) = given else {
        return Ok((0..n).map(|_| None).collect());
    };
    let (values, many) = given.into_vec();
    if values.len() != n || (!many && n > 1) {
        return Err(haphe_error(
            name,
            format!(
                "give one value per device, as a list in the devices' order ({n} device(s): {devices:?}), or none"
            ),
        ));
    }
    Ok(values.into_iter().map(Some).collect())
}

/// Whether `spec` names the simulated hand (`hand`, `hand:SEED`).
fn is_hand(spec: &str) -> bool {
    spec == "hand" || spec.starts_with("hand:")
}

/// Simulated hands to run on the simulated clock.
struct Hands<'a> {
    specs: &'a [String],
    path: &'a str,
    seconds: f64,
    seed: u64,
    presses: &'a [(u32, f64, f64)],
}

/// Runs the simulated hands of `hands` on one servo over `world`, each with `options` and
/// its own proxy's options of `proxies`,
/// on the simulated clock: the k-th bare `hand` (from 0) along the path of seed
/// `seed + k`, `hand:SEED` along that seed's.
fn run_hands(
    hands: &Hands<'_>,
    world: haphe::scene::Scene,
    options: ServoOptions,
    proxies: &[haphe::proxy::ProxyOptions],
) -> Result<Vec<DeviceOutcome>, String> {
    let mut devices = Vec::with_capacity(hands.specs.len());
    let mut bare = 0;
    for (spec, proxy) in hands.specs.iter().zip(proxies) {
        let seed = match spec.strip_prefix("hand:") {
            Some(s) => s.parse().map_err(|_| format!("not a seed: {s:?}"))?,
            None => {
                bare += 1;
                hands.seed + bare - 1
            }
        };
        let hand = simulated_hand(hands.path, &world, hands.seconds, seed, hands.presses)?;
        devices.push((hand, options.with_proxy(*proxy)));
    }
    let n = devices.len();
    let mut servo = Servo::with_devices(devices, world).map_err(|e| e.to_string())?;
    let ticks = (hands.seconds * options.rate_hz()).round() as u64;
    let mut records: Vec<Vec<TickRecord>> =
        (0..n).map(|_| Vec::with_capacity(ticks as usize)).collect();
    servo.run_simulated(ticks, |r| {
        if let Some(v) = records.get_mut(r.device as usize) {
            v.push(*r);
        }
    });
    servo.close();
    Ok(records
        .into_iter()
        .enumerate()
        .map(|(i, records)| DeviceOutcome {
            records,
            offset: match (servo.mapping_of(i), servo.options_of(i)) {
                (Some(m), Some(o)) => m.offset() - o.mapping().offset(),
                _ => DVec3::ZERO,
            },
            description: format!("the simulated hand ({})", hands.path),
            stop: "finished".into(),
            report: None,
        })
        .collect())
}

/// The dict of arrays of one device's run (see [`run`]).
fn arrays<'py>(py: Python<'py>, outcome: DeviceOutcome) -> PyResult<Bound<'py, PyDict>> {
    let records = outcome.records;
    let n = records.len();
    let mut t = Array1::zeros(n);
    let mut hip = Array2::zeros((n, 3));
    let mut velocity = Array2::zeros((n, 3));
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
            velocity[[i, k]] = r.velocity[k];
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
    d.set_item("velocity", velocity.into_pyarray(py))?;
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
