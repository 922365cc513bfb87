//! `haphe devices`: the haptic devices found, vendor libraries loaded or not, devices
//! connected.

use std::io::Write;
use std::process::ExitCode;

use haphe_devices::list_devices;

/// Arguments of `haphe devices`.
#[derive(clap::Args, Debug)]
pub struct Args {}

/// Runs `haphe devices`.
pub fn run(_args: &Args) -> anyhow::Result<ExitCode> {
    let mut out = std::io::stdout().lock();
    for found in list_devices() {
        writeln!(
            out,
            "{} ({}): {}",
            found.spec,
            found.sdk,
            if found.ready {
                "ready"
            } else {
                "not available"
            }
        )?;
        for line in &found.lines {
            writeln!(out, "  {line}")?;
        }
    }
    writeln!(
        out,
        "udp:HOST:PORT (network device): always available; haphe listens there (docs/devices.md)"
    )?;
    writeln!(out, "hand (the simulated hand): always available")?;
    Ok(ExitCode::SUCCESS)
}
