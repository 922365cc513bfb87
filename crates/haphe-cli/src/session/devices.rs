//! The devices of a session, opened and mapped: one simulated device, or one or several
//! named by specifications (`haphe run --device A --device B`), each with its own mapping
//! and options, on one servo.

use std::io::Write;

use anyhow::anyhow;
use haphe::scene::Scene;
use haphe::servo::{
    Device, DeviceClock, DeviceMapping, DeviceSpec, STIFFNESS_RATED_AT_HZ, Servo, ServoError,
    ServoOptions,
};

use haphe_devices::SpecError;

use super::device::{self, VendorChoice};

/// What a device reports after a run.
pub type Report = Box<dyn Fn() -> Option<String> + Send + Sync>;

/// A device named by a specification, opened for the session.
pub struct Vendor {
    pub choice: VendorChoice,
    pub description: String,
    pub clock: Option<Box<dyn DeviceClock>>,
    pub report: Report,
}

/// A device of the session, opened: with what its specification opened, when it was
/// named by one.
pub struct Opened {
    pub device: Box<dyn Device>,
    pub vendor: Option<Vendor>,
}

/// The devices named by `choices`, opened in order ([`haphe_devices::open_devices`]: a
/// device given twice is refused before any opens, and those opened are closed again
/// when a later one fails).
pub fn open_vendors(
    choices: Vec<VendorChoice>,
    scene: &Scene,
    seconds: f64,
) -> anyhow::Result<Vec<Opened>> {
    let specs: Vec<String> = choices.iter().map(|c| c.spec.clone()).collect();
    let udp = choices.first().map(|c| c.udp).unwrap_or_default();
    let opened = haphe_devices::open_devices(&specs, scene, seconds, udp).map_err(|e| match e {
        // The only device: its error as it is (the command names the device already).
        SpecError::At { error, .. } if specs.len() == 1 => *error,
        other => other,
    })?;
    Ok(choices
        .into_iter()
        .zip(opened)
        .map(|(choice, o)| Opened {
            device: o.device,
            vendor: Some(Vendor {
                choice,
                description: o.description,
                clock: o.clock,
                report: o.report,
            }),
        })
        .collect())
}

/// How device `i` of `n` is named in messages: `device 2 (dhd:1)`, or `the device` for
/// the only one.
pub fn name(i: usize, n: usize, vendor: Option<&Vendor>) -> String {
    match vendor {
        _ if n == 1 => "the device".to_string(),
        Some(v) => format!("device {} ({})", i + 1, v.choice.spec),
        None => format!("device {}", i + 1),
    }
}

/// A session's servo and, for each of its devices, what its specification opened.
pub type MappedServo = (Servo<Box<dyn Device>>, Vec<Option<Vendor>>);

/// The servo of the session over `opened`, each device with `options` and its own
/// mapping (named by a specification: `--scale`/`--centre` of its own, else its
/// workspace over the scene), with a warning for each device that would render the
/// stiffest object unstably; the mappings, in the devices' order.
pub fn servo_of(
    opened: Vec<Opened>,
    scene: Scene,
    options: ServoOptions,
    stiffness: f64,
) -> anyhow::Result<MappedServo> {
    let n = opened.len();
    let mut devices = Vec::with_capacity(n);
    let mut vendors = Vec::with_capacity(n);
    for (i, o) in opened.into_iter().enumerate() {
        let spec = o.device.spec();
        let named = |e: anyhow::Error| match &o.vendor {
            Some(v) if n > 1 => anyhow!("{}: {e}", name(i, n, Some(v))),
            _ => e,
        };
        let (mapping, proxy) = match &o.vendor {
            Some(v) => (
                device::mapping(&v.choice, &spec, &scene).map_err(named)?,
                // Its own tool.
                v.choice
                    .tool_radius
                    .apply(*options.proxy(), &scene)
                    .map_err(named)?,
            ),
            None => (DeviceMapping::IDENTITY, *options.proxy()),
        };
        warn_stiffness(stiffness, &mapping, &spec, options.rate_hz());
        devices.push((o.device, options.with_mapping(mapping).with_proxy(proxy)));
        vendors.push(o.vendor);
    }
    let servo = if n == 1 {
        let (device, options) = devices.pop().ok_or_else(|| anyhow!("no device"))?;
        Servo::new(device, scene, options)?
    } else {
        Servo::with_devices(devices, scene).map_err(|e| match e {
            ServoError::DeviceAt { device, error } => {
                anyhow!("{}: {error}", name(device, n, vendors[device].as_ref()))
            }
            other => other.into(),
        })?
    };
    Ok((servo, vendors))
}

/// Prints each named device and its mapping (a line each; with several devices, each
/// device's lines start with its name).
pub fn print(
    out: &mut impl Write,
    servo: &Servo<Box<dyn Device>>,
    vendors: &[Option<Vendor>],
    stiffness: f64,
) -> std::io::Result<()> {
    let n = vendors.len();
    for (i, v) in vendors.iter().enumerate() {
        let (Some(v), Some(mapping)) = (v, servo.mapping_of(i)) else {
            continue;
        };
        if n == 1 {
            writeln!(out, "device: {}", v.description)?;
        } else {
            writeln!(
                out,
                "device {} ({}): {}",
                i + 1,
                v.choice.spec,
                v.description
            )?;
            let tool = servo.options_of(i).map_or(0.0, |o| o.proxy().tool_radius());
            if tool > 0.0 {
                writeln!(out, "  tool: a sphere of radius {:.3} mm", tool * 1e3)?;
            }
            if !v.choice.is_hand() {
                write!(out, "  ")?;
            }
        }
        device::print_mapping(out, &v.choice, mapping, stiffness)?;
    }
    Ok(())
}

/// Warns on standard error when the stiffest object, felt at the device through
/// `mapping`, is above what the device renders stably at `rate_hz`
/// ([`DeviceSpec::stable_stiffness`], the passivity rule of a sampled wall).
pub fn warn_stiffness(stiffness: f64, mapping: &DeviceMapping, spec: &DeviceSpec, rate_hz: f64) {
    let at_device = mapping.stiffness_at_device(stiffness);
    let stable = spec.stable_stiffness(rate_hz);
    if at_device > stable {
        let felt = if mapping.scale() == 1.0 {
            String::new()
        } else {
            format!(", felt as {at_device:.0} N/m at the device")
        };
        eprintln!(
            "haphe: warning: stiffness {stiffness} N/m{felt} is above the {stable:.0} N/m the device ({}, rated {:.0} N/m at {STIFFNESS_RATED_AT_HZ:.0} Hz) renders stably at {rate_hz} Hz \
             (passivity of a sampled wall, K < K_rated · rate / {STIFFNESS_RATED_AT_HZ:.0} Hz): \
             expect a buzzing wall; lower --stiffness or --scale, or raise --rate",
            spec.name, spec.max_stiffness
        );
    }
}
