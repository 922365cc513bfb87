//! `haphe devices`: what is found — each vendor library loaded or not and why, the
//! devices connected, their name, workspace and maximum force.

use haphe::servo::Device;

use crate::{DhdDevice, HdDevice};

/// What was found of one kind of device.
#[derive(Debug, Clone, PartialEq)]
pub struct Found {
    /// The device specification (`dhd`, `openhaptics`).
    pub spec: &'static str,
    /// The vendor's SDK.
    pub sdk: &'static str,
    /// Lines to print: the library, the devices, or why not.
    pub lines: Vec<String>,
    /// Whether a device is ready to run.
    pub ready: bool,
}

fn spec_lines(d: &dyn Device, name: &str) -> String {
    let s = d.spec();
    let (a, b) = (s.workspace_min * 1000.0, s.workspace_max * 1000.0);
    let force = if s.max_force.is_finite() {
        format!("{:.2} N", s.max_force)
    } else {
        "no limit reported".into()
    };
    format!(
        "{name}: workspace x {:.0}..{:.0}, y {:.0}..{:.0}, z {:.0}..{:.0} mm; maximum force {force}",
        a.x, b.x, a.y, b.y, a.z, b.z
    )
}

/// Looks for each vendor library and, where it loads, the devices it sees (opening and
/// closing the first one to read its name and limits).
pub fn list_devices() -> Vec<Found> {
    let mut out = Vec::new();
    let mut dhd = Found {
        spec: "dhd",
        sdk: "Force Dimension",
        lines: Vec::new(),
        ready: false,
    };
    match DhdDevice::load() {
        Err(e) => dhd.lines.push(format!("library not loaded: {e}")),
        Ok(mut d) => {
            dhd.lines
                .push(format!("library loaded: {}", d.api().path()));
            match d.api().device_count() {
                Err(e) => dhd.lines.push(format!("dhdGetDeviceCount failed: {e}")),
                Ok(n) => {
                    dhd.lines.push(format!("{n} device(s) connected"));
                    if n > 0 {
                        match d.open() {
                            Ok(()) => {
                                let name = d.info().map_or("?", |i| i.name.as_str()).to_string();
                                dhd.lines.push(spec_lines(&d, &name));
                                dhd.lines.push(format!(
                                    "(dhdc.h has no workspace query: haphe assumes a {:.0} mm cube)",
                                    2000.0 * crate::DHD_WORKSPACE_HALF_M
                                ));
                                dhd.ready = true;
                                d.close();
                            }
                            Err(e) => dhd.lines.push(e.to_string()),
                        }
                    }
                }
            }
        }
    }
    out.push(dhd);
    let mut hd = Found {
        spec: "openhaptics",
        sdk: "OpenHaptics",
        lines: Vec::new(),
        ready: false,
    };
    match HdDevice::load() {
        Err(e) => hd.lines.push(format!("library not loaded: {e}")),
        Ok(mut d) => {
            hd.lines.push(format!("library loaded: {}", d.api().path()));
            match d.open() {
                Ok(()) => {
                    let name = d.info().map_or("?".into(), |i| {
                        format!("{} at {:.0} Hz", i.model, i.rate_hz)
                    });
                    hd.lines.push(spec_lines(&d, &name));
                    hd.ready = true;
                    d.close();
                }
                Err(e) => hd.lines.push(e.to_string()),
            }
        }
    }
    out.push(hd);
    out
}
