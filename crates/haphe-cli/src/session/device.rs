//! The device of a session named by a specification (`haphe run`, `haphe view`): how it
//! was chosen, opened and mapped onto the scene.

use std::io::Write;

use haphe::DVec3;
use haphe::scene::{Param, Scene};
use haphe::servo::{DeviceMapping, DeviceSpec};
use haphe_devices::{UdpOptions, workspace_mapping};

/// How `haphe run` chose its device.
#[derive(Debug, Clone)]
pub struct VendorChoice {
    /// The specification.
    pub spec: String,
    /// Settings of the network device.
    pub udp: UdpOptions,
    /// `--scale`.
    pub scale: Option<f64>,
    /// `--centre`.
    pub centre: Option<DVec3>,
    /// `--overrun-budget`.
    pub overrun_budget: Option<u64>,
    /// The tool's radius of this device (`--tool-radius`, once per device).
    pub tool_radius: crate::args::ToolRadius,
}

impl VendorChoice {
    /// Whether it names the simulated hand (`hand`, `hand:SEED`), which moves in the
    /// world already: no mapping.
    pub fn is_hand(&self) -> bool {
        self.spec == "hand" || self.spec.starts_with("hand:")
    }
}

/// The device choice of `haphe view`: `mapping`, and `haphe run`'s default network
/// settings and overrun budget.
#[cfg(feature = "view")]
pub fn view_choice(spec: &str, mapping: crate::args::DeviceMappingFlags) -> VendorChoice {
    VendorChoice {
        spec: spec.to_string(),
        udp: UdpOptions::default(),
        scale: mapping.0,
        centre: mapping.1,
        overrun_budget: Some(crate::args::DEFAULT_OVERRUN_BUDGET),
        // The view applies its own tool to the servo's options.
        tool_radius: crate::args::ToolRadius::default(),
    }
}

/// The mapping of the run: the device's workspace centred on the scene and scaled to
/// cover its bounds, unless `--scale` / `--centre` say otherwise. The simulated hand
/// moves in the world already.
///
/// # Errors
/// A scale or centre outside its domain, named as its flag.
pub fn mapping(
    choice: &VendorChoice,
    spec: &DeviceSpec,
    scene: &Scene,
) -> anyhow::Result<DeviceMapping> {
    if choice.is_hand() {
        return Ok(DeviceMapping::IDENTITY);
    }
    workspace_mapping(spec, scene, choice.scale, choice.centre).map_err(|e| {
        let flag = if e.param() == Param::Scale {
            "--scale"
        } else {
            "--centre"
        };
        anyhow::anyhow!("{}", e.named(flag))
    })
}

/// Prints the mapping and what it does to stiffness.
pub fn print_mapping(
    out: &mut impl Write,
    choice: &VendorChoice,
    m: &DeviceMapping,
    stiffness: f64,
) -> std::io::Result<()> {
    if choice.is_hand() {
        return Ok(());
    }
    let c = m.offset();
    writeln!(
        out,
        "mapping: {:.3} world m per device m, device origin at world ({:.4}, {:.4}, {:.4}) m \
         (set with --scale, --centre); {stiffness:.0} N/m is felt as {:.0} N/m at the device",
        m.scale(),
        c.x,
        c.y,
        c.z,
        m.stiffness_at_device(stiffness)
    )
}
