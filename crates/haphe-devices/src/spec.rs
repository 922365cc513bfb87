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
    /// `dhd`: a Force Dimension device.
    Dhd,
    /// `openhaptics`: an OpenHaptics device.
    OpenHaptics,
    /// `udp:HOST:PORT`: the network device listening there.
    Udp(String),
    /// `hand`: the simulated hand exploring the scene.
    Hand,
}

/// Why a device could not be named or opened.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SpecError {
    /// The specification names no device.
    #[error(
        "unknown device {0:?}{hint}: expected dhd, openhaptics, udp:HOST:PORT or hand",
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
        match s {
            "dhd" | "forcedimension" => Ok(DeviceKind::Dhd),
            "openhaptics" | "hd" => Ok(DeviceKind::OpenHaptics),
            "hand" => Ok(DeviceKind::Hand),
            _ => match s.strip_prefix("udp:") {
                Some(a)
                    if a.rsplit_once(':')
                        .is_some_and(|(h, p)| !h.is_empty() && p.parse::<u16>().is_ok()) =>
                {
                    Ok(DeviceKind::Udp(a.to_string()))
                }
                _ => Err(SpecError::Unknown(s.to_string())),
            },
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

/// Opens the device `spec` names (`dhd`, `openhaptics`, `udp:HOST:PORT`, `hand`). The
/// simulated hand explores `scene` for `seconds`; the UDP device listens with `udp`.
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
    match spec.parse::<DeviceKind>()? {
        DeviceKind::Dhd => {
            let mut d = DhdDevice::load()?;
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
        DeviceKind::OpenHaptics => {
            let mut d = HdDevice::load()?;
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
        DeviceKind::Hand => {
            let path = scripted_path(PathKind::Explore, scene, seconds, 1)
                .map_err(|e| SpecError::Path(e.to_string()))?;
            let d = SimulatedHand::new(path, HandOptions::default());
            Ok(OpenedDevice {
                description: describe(&d, "the simulated hand exploring the scene".into()),
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
        assert_eq!("dhd".parse::<DeviceKind>().ok(), Some(DeviceKind::Dhd));
        assert_eq!(
            "openhaptics".parse::<DeviceKind>().ok(),
            Some(DeviceKind::OpenHaptics)
        );
        assert_eq!(
            "udp:127.0.0.1:9000".parse::<DeviceKind>().ok(),
            Some(DeviceKind::Udp("127.0.0.1:9000".into()))
        );
        for bad in ["udp:", "udp:host", "udp::9", "udp:h:99999", "phantom", ""] {
            assert!(bad.parse::<DeviceKind>().is_err(), "{bad}");
        }
    }
}
