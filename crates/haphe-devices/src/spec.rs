//! Device specifications (`dhd`, `openhaptics`, `udp:HOST:PORT`, `hand`) and
//! [`open_device`], shared by every front end.

use std::str::FromStr;

use haphe::scene::Scene;
use haphe::servo::{
    Device, DeviceClock, DeviceError, HandOptions, PathKind, SimulatedHand, scripted_path,
};

use crate::library::LoadError;
use crate::udp::{UdpDevice, UdpOptions};
use crate::{DhdDevice, HdDevice};

/// Default overrun budget of a run with a real device: deadlines it may miss before it
/// stops with zero force (0.1 s of deadlines at 1 kHz, over the whole run; a policy, not a
/// measured value).
pub const DEFAULT_OVERRUN_BUDGET: u64 = 100;

/// Which device a specification names.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum DeviceKind {
    /// `dhd`: the first available Force Dimension device (`dhdOpen`); `dhd:N`: the one at
    /// index `N` (`dhdOpenID`, 0 the first).
    Dhd(Option<u8>),
    /// `openhaptics`: the default OpenHaptics device; `openhaptics:NAME`: the device
    /// configured under `NAME` (Touch Setup's name, given to `hdInitDevice`).
    OpenHaptics(Option<String>),
    /// `udp:HOST:PORT`: the network device listening there.
    Udp(String),
    /// `hand`: the simulated hand exploring the scene; `hand:SEED`: along the explore
    /// path of that seed (`hand` is `hand:1`).
    Hand(Option<u64>),
}

/// The largest Force Dimension index, `dhd:127` (`dhdOpenID` takes a C `char`).
pub const MAX_DHD_INDEX: u8 = 127;

impl DeviceKind {
    /// Whether `self` and `other` name the same device, which a run may not open twice:
    /// `dhd` is `dhd:0`'s device, `openhaptics` the default one, network devices on one
    /// port clash whatever the host, and a simulated hand is the same hand with the same
    /// seed (`hand` is `hand:1`).
    pub fn same_device(&self, other: &DeviceKind) -> bool {
        match (self, other) {
            (DeviceKind::Dhd(a), DeviceKind::Dhd(b)) => a.unwrap_or(0) == b.unwrap_or(0),
            (DeviceKind::OpenHaptics(a), DeviceKind::OpenHaptics(b)) => a == b,
            (DeviceKind::Udp(a), DeviceKind::Udp(b)) => {
                let port = |s: &str| s.rsplit_once(':').map(|(_, p)| p.to_string());
                port(a) == port(b) && port(a).is_some_and(|p| p != "0")
            }
            (DeviceKind::Hand(a), DeviceKind::Hand(b)) => a.unwrap_or(1) == b.unwrap_or(1),
            _ => false,
        }
    }
}

/// Why a device could not be named or opened.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SpecError {
    /// The specification names no device.
    #[error(
        "unknown device {0:?}{hint}: expected dhd or dhd:N (N from 0 to 127), openhaptics or openhaptics:NAME, udp:HOST:PORT, or hand or hand:SEED",
        hint = did_you_mean_device(.0)
    )]
    Unknown(String),
    /// The vendor library could not be loaded.
    #[error(transparent)]
    Load(#[from] LoadError),
    /// The device could not be opened.
    #[error(transparent)]
    Open(#[from] DeviceError),
    /// The simulated hand's path could not be made.
    #[error("cannot make the simulated hand's path: {0}")]
    Path(String),
    /// A device of a run named twice (by the position of each among the devices, from 1).
    #[error(
        "device {second} ({second_spec}) is device {first} ({first_spec}) again: each device may be given once"
    )]
    Twice {
        /// The first mention, from 1.
        first: usize,
        /// Its specification.
        first_spec: String,
        /// The second mention, from 1.
        second: usize,
        /// Its specification.
        second_spec: String,
    },
    /// A device of several could not be opened: its position (from 1), its
    /// specification and why (the devices opened before it were closed again).
    #[error("device {position} ({spec}): {error}")]
    At {
        /// Its position among the devices, from 1.
        position: usize,
        /// Its specification.
        spec: String,
        /// Why.
        #[source]
        error: Box<SpecError>,
    },
}

/// Product and vendor names people type for a device, and the specification that drives
/// it (the SDK that each product uses).
const PRODUCT_NAMES: [(&str, &str); 12] = [
    ("phantom", "openhaptics"),
    ("touch", "openhaptics"),
    ("geomagic", "openhaptics"),
    ("3dsystems", "openhaptics"),
    ("sensable", "openhaptics"),
    ("falcon", "dhd"),
    ("novint", "dhd"),
    ("omega", "dhd"),
    ("delta", "dhd"),
    ("sigma", "dhd"),
    ("lambda", "dhd"),
    ("simulated", "hand"),
];

/// `" (did you mean 'X'?)"` for an unknown device: the specification of a product named
/// in it (`phantom` → `openhaptics`), else the closest specification's spelling.
fn did_you_mean_device(given: &str) -> String {
    let lower = given.to_lowercase();
    let product = PRODUCT_NAMES
        .iter()
        .find(|(product, _)| lower.contains(product))
        .map(|(_, spec)| *spec)
        .or_else(|| lower.starts_with("udp").then_some("udp:127.0.0.1:7700"));
    let meant = product.or_else(|| {
        haphe::names::closest(
            &lower,
            &["dhd", "forcedimension", "openhaptics", "hand", "udp"],
        )
        .map(|name| match name {
            "udp" => "udp:127.0.0.1:7700",
            other => other,
        })
    });
    meant.map_or_else(String::new, |spec| format!(" (did you mean '{spec}'?)"))
}

impl FromStr for DeviceKind {
    type Err = SpecError;

    fn from_str(s: &str) -> Result<DeviceKind, SpecError> {
        let unknown = || SpecError::Unknown(s.to_string());
        let (kind, rest) = match s.split_once(':') {
            Some((k, r)) => (k, Some(r)),
            None => (s, None),
        };
        match (kind, rest) {
            ("dhd" | "forcedimension", None) => Ok(DeviceKind::Dhd(None)),
            ("dhd" | "forcedimension", Some(i)) => match i.parse::<u8>() {
                Ok(i) if i <= MAX_DHD_INDEX => Ok(DeviceKind::Dhd(Some(i))),
                _ => Err(unknown()),
            },
            ("openhaptics" | "hd", None) => Ok(DeviceKind::OpenHaptics(None)),
            ("openhaptics" | "hd", Some(name)) if !name.is_empty() && !name.contains('\0') => {
                Ok(DeviceKind::OpenHaptics(Some(name.to_string())))
            }
            ("hand", None) => Ok(DeviceKind::Hand(None)),
            ("hand", Some(seed)) => seed
                .parse()
                .map(|s| DeviceKind::Hand(Some(s)))
                .map_err(|_| unknown()),
            ("udp", Some(a))
                if a.rsplit_once(':')
                    .is_some_and(|(h, p)| !h.is_empty() && p.parse::<u16>().is_ok()) =>
            {
                Ok(DeviceKind::Udp(a.to_string()))
            }
            _ => Err(unknown()),
        }
    }
}

/// An opened device, ready for [`haphe::servo::Servo::new`] (whose `open` finds it open).
pub struct OpenedDevice {
    /// The device.
    pub device: Box<dyn Device>,
    /// What it is, for reports: name, workspace, maximum force, where the library came
    /// from.
    pub description: String,
    /// The device's own servo clock, when it has one (OpenHaptics): run the servo with
    /// [`ServoLoop::spawn_clocked`](haphe::servo::ServoLoop::spawn_clocked).
    pub clock: Option<Box<dyn DeviceClock>>,
    /// After a run, what the device reported of its last fault or its traffic.
    pub report: Box<dyn Fn() -> Option<String> + Send + Sync>,
}

/// Opens the device `spec` names (`dhd`, `dhd:N`, `openhaptics`, `openhaptics:NAME`,
/// `udp:HOST:PORT`, `hand`, `hand:SEED`). The simulated hand explores `scene` for
/// `seconds`; the UDP device listens with `udp`.
///
/// # Errors
/// An unknown specification, a library that does not load (the error names the library,
/// the variable to set and the SDK), a device that does not open.
pub fn open_device(
    spec: &str,
    scene: &Scene,
    seconds: f64,
    udp: UdpOptions,
) -> Result<OpenedDevice, SpecError> {
    open_kind(spec.parse()?, scene, seconds, udp)
}

/// The devices of a run of several, parsed and checked before any is opened: the
/// `k`-th bare `hand` explores along the path of seed `k` (so two hands do not follow
/// one path), and no device may be named twice ([`DeviceKind::same_device`]).
///
/// # Errors
/// The first specification that names no device, or [`SpecError::Twice`].
pub fn parse_devices(specs: &[String]) -> Result<Vec<DeviceKind>, SpecError> {
    let mut kinds: Vec<DeviceKind> = Vec::with_capacity(specs.len());
    let mut hands = 0;
    for (second, spec) in specs.iter().enumerate() {
        let mut kind: DeviceKind = spec.parse()?;
        if kind == DeviceKind::Hand(None) {
            hands += 1;
            kind = DeviceKind::Hand(Some(hands));
        }
        if let Some(first) = kinds.iter().position(|k| k.same_device(&kind)) {
            return Err(SpecError::Twice {
                first: first + 1,
                first_spec: specs[first].clone(),
                second: second + 1,
                second_spec: spec.clone(),
            });
        }
        kinds.push(kind);
    }
    Ok(kinds)
}

/// Opens every device of `specs` ([`parse_devices`] first: nothing is opened when one
/// is wrong or given twice), in order, each as [`open_device`] does; when one does not
/// open, those opened before it are closed (zero force) and the error names it.
///
/// # Errors
/// Those of [`parse_devices`], and [`SpecError::At`] naming the device that did not open.
pub fn open_devices(
    specs: &[String],
    scene: &Scene,
    seconds: f64,
    udp: UdpOptions,
) -> Result<Vec<OpenedDevice>, SpecError> {
    let kinds = parse_devices(specs)?;
    let mut opened: Vec<OpenedDevice> = Vec::with_capacity(kinds.len());
    for (i, kind) in kinds.into_iter().enumerate() {
        match open_kind(kind, scene, seconds, udp) {
            Ok(d) => opened.push(d),
            Err(error) => {
                for o in &mut opened {
                    let _ = o.device.write_force(haphe::DVec3::ZERO);
                    o.device.close();
                }
                return Err(SpecError::At {
                    position: i + 1,
                    spec: specs[i].clone(),
                    error: Box::new(error),
                });
            }
        }
    }
    Ok(opened)
}

/// Opens the device of `kind` (see [`open_device`]).
fn open_kind(
    kind: DeviceKind,
    scene: &Scene,
    seconds: f64,
    udp: UdpOptions,
) -> Result<OpenedDevice, SpecError> {
    let describe = |d: &dyn Device, what: String| {
        let s = d.spec();
        let w = s.workspace_size() * 1000.0;
        let force = if s.max_force.is_finite() {
            format!("{:.2} N", s.max_force)
        } else {
            "no limit reported".into()
        };
        format!(
            "{what}; workspace {:.0} × {:.0} × {:.0} mm; maximum force {force}",
            w.x, w.y, w.z
        )
    };
    match kind {
        DeviceKind::Dhd(index) => {
            let mut d = DhdDevice::load_at(index)?;
            d.open()?;
            let name = d.info().map_or("?", |i| i.name.as_str()).to_string();
            let what = format!("Force Dimension {name} (SDK {})", d.api().path());
            let report = Box::new(d.fault_report());
            Ok(OpenedDevice {
                description: describe(&d, what),
                device: Box::new(d),
                clock: None,
                report,
            })
        }
        DeviceKind::OpenHaptics(name) => {
            let mut d = HdDevice::load_named(name.as_deref())?;
            d.open()?;
            let (model, rate) = d
                .info()
                .map_or(("?".into(), 1000.0), |i| (i.model.clone(), i.rate_hz));
            let what = format!(
                "OpenHaptics {model} at {rate:.0} Hz (HD API {})",
                d.api().path()
            );
            let report = Box::new(d.fault_report());
            let clock: Box<dyn DeviceClock> = Box::new(d.clock());
            Ok(OpenedDevice {
                description: describe(&d, what),
                device: Box::new(d),
                clock: Some(clock),
                report,
            })
        }
        DeviceKind::Udp(address) => {
            let mut d = UdpDevice::new(&address, udp)?;
            d.open()?;
            let counters = d.counters();
            let what = format!(
                "the network device on udp:{} (peer timeout {:.0} ms)",
                d.local_addr(),
                udp.timeout_s * 1e3
            );
            Ok(OpenedDevice {
                description: describe(&d, what),
                device: Box::new(d),
                clock: None,
                report: Box::new(move || Some(counters.summary())),
            })
        }
        DeviceKind::Hand(seed) => {
            let seed = seed.unwrap_or(1);
            let path = scripted_path(PathKind::Explore, scene, seconds, seed)
                .map_err(|e| SpecError::Path(e.to_string()))?;
            let d = SimulatedHand::new(path, HandOptions::default());
            let what = if seed == 1 {
                "the simulated hand exploring the scene".to_string()
            } else {
                format!("the simulated hand exploring the scene (path seed {seed})")
            };
            Ok(OpenedDevice {
                description: describe(&d, what),
                device: Box::new(d),
                clock: None,
                report: Box::new(|| None),
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specifications_parse() {
        assert_eq!(
            "dhd".parse::<DeviceKind>().ok(),
            Some(DeviceKind::Dhd(None))
        );
        assert_eq!(
            "dhd:1".parse::<DeviceKind>().ok(),
            Some(DeviceKind::Dhd(Some(1)))
        );
        assert_eq!(
            "openhaptics".parse::<DeviceKind>().ok(),
            Some(DeviceKind::OpenHaptics(None))
        );
        assert_eq!(
            "openhaptics:Left Touch".parse::<DeviceKind>().ok(),
            Some(DeviceKind::OpenHaptics(Some("Left Touch".into())))
        );
        assert_eq!(
            "hand:3".parse::<DeviceKind>().ok(),
            Some(DeviceKind::Hand(Some(3)))
        );
        assert_eq!(
            "udp:127.0.0.1:9000".parse::<DeviceKind>().ok(),
            Some(DeviceKind::Udp("127.0.0.1:9000".into()))
        );
        for bad in [
            "udp:",
            "udp:host",
            "udp::9",
            "udp:h:99999",
            "phantom",
            "",
            "dhd:",
            "dhd:-1",
            "dhd:128",
            "dhd:x",
            "openhaptics:",
            "hand:",
            "hand:-2",
        ] {
            assert!(bad.parse::<DeviceKind>().is_err(), "{bad}");
        }
    }

    #[test]
    fn the_same_device_twice_is_refused_before_any_opens() {
        let specs = |s: &[&str]| s.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        let twice = [
            (&["dhd:0", "dhd:0"][..], (1, 2)),
            (&["dhd", "dhd:0"][..], (1, 2)),
            (
                &["openhaptics:Left", "dhd:1", "openhaptics:Left"][..],
                (1, 3),
            ),
            (&["openhaptics", "openhaptics"][..], (1, 2)),
            (&["udp:127.0.0.1:7700", "udp:0.0.0.0:7700"][..], (1, 2)),
            (&["hand", "hand:1"][..], (1, 2)),
            (&["hand", "hand", "hand:2"][..], (2, 3)),
        ];
        for (given, (a, b)) in twice {
            match parse_devices(&specs(given)) {
                Err(SpecError::Twice { first, second, .. }) => {
                    assert_eq!((first, second), (a, b), "{given:?}");
                }
                other => panic!("{given:?}: {other:?}"),
            }
        }
        let e = parse_devices(&specs(&["dhd:1", "dhd:1"])).expect_err("twice");
        assert_eq!(
            e.to_string(),
            "device 2 (dhd:1) is device 1 (dhd:1) again: each device may be given once"
        );
        let kinds = parse_devices(&specs(&[
            "dhd:0",
            "dhd:1",
            "openhaptics",
            "openhaptics:Right",
            "udp:127.0.0.1:7700",
            "udp:127.0.0.1:7701",
            "hand",
            "hand",
        ]))
        .expect("all different");
        assert_eq!(kinds[6], DeviceKind::Hand(Some(1)));
        assert_eq!(kinds[7], DeviceKind::Hand(Some(2)));
    }
}
