//! The arguments several commands share, their parsers and checks, and the command's
//! defaults: units and welding, map options, the objects of a session (a mesh file, a
//! scene file or a built-in shape, and the material of a lone object), the files a
//! session writes, the mapping of a device's workspace, the lengths of runs, and the
//! textures and effects of a session ([`feel`]), and its deformation ([`deform`]).

use std::path::PathBuf;

use anyhow::{anyhow, bail};
use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::{Units, Weld};
use haphe::proxy::ProxyOptions;
use haphe::scene::{Material, Param, Scene};
use haphe::servo::RealtimeOptions;

use self::volume::VolumeArgs;
use crate::input::model::Model;

pub mod cut;
pub mod deform;
pub mod feel;
pub mod volume;

/// Default length of a run, seconds.
pub const DEFAULT_SECONDS: f64 = 5.0;

/// The longest run, seconds (an hour: 3.6 million ticks at 1 kHz, a 400 MB trace).
pub const MAX_SECONDS: f64 = 3600.0;

/// Length of a run until Ctrl-C, for sizing the plot's sampling only, seconds.
pub const PLOT_SECONDS: f64 = 60.0;

/// Default overrun budget: deadlines a run may miss before it stops with zero force.
pub const DEFAULT_OVERRUN_BUDGET: u64 = haphe_devices::DEFAULT_OVERRUN_BUDGET;

/// How a real device's workspace is mapped onto the scene; shared by `haphe run` and
/// `haphe view`. With several devices (`haphe run --device A --device B`), each flag is
/// given once per device, in the devices' order, or not at all.
#[derive(clap::Args, Debug, Clone)]
pub struct MappingArgs {
    /// World metres per device metre (default: the device's workspace covers the scene's
    /// bounds). With several --device, once per device, in their order.
    #[arg(long)]
    pub scale: Vec<f64>,
    /// The world point the centre of the device's workspace maps to, metres, "x,y,z"
    /// (default: the centre of the scene's bounds). With several --device, once per
    /// device, in their order.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_point)]
    pub centre: Vec<DVec3>,
}

/// The mapping flags of one device: `--scale` and `--centre`, each when given.
pub type DeviceMappingFlags = (Option<f64>, Option<DVec3>);

impl MappingArgs {
    /// Checks `--scale` and `--centre` against the library's table of domains.
    ///
    /// # Errors
    /// A value outside its domain, named as its flag.
    pub fn check(&self) -> anyhow::Result<()> {
        for &s in &self.scale {
            Param::Scale
                .check(s)
                .map_err(|e| anyhow!("{}", e.named("--scale")))?;
        }
        for c in &self.centre {
            Param::Centre
                .check_vector(c.to_array())
                .map_err(|e| anyhow!("{}", e.named("--centre")))?;
        }
        Ok(())
    }

    /// The flags of each of `devices` (their specifications, in order), checked: a flag
    /// is given for every device, in their order, or for none (then each device has the
    /// default); given for some devices only, no device would know which is its own
    /// ([`per_device`]).
    ///
    /// # Errors
    /// A value outside its domain, or a flag given a number of times that is neither
    /// zero nor the number of devices, naming the devices left without one.
    pub fn per_device(&self, devices: &[String]) -> anyhow::Result<Vec<DeviceMappingFlags>> {
        self.check()?;
        let scale = per_device("--scale", &self.scale, devices)?;
        let centre = per_device("--centre", &self.centre, devices)?;
        Ok(scale.into_iter().zip(centre).collect())
    }
}

/// The values of a flag given once per device (`--scale`, `--centre`, `--tool-radius` of
/// `haphe run`), paired with `devices` (their specifications) in order: every device's,
/// or none when the flag is not given.
///
/// # Errors
/// The flag given a number of times that is neither zero nor the number of devices,
/// naming the devices left without one: no device would know which value is its own.
pub fn per_device<T: Copy>(
    flag: &str,
    given: &[T],
    devices: &[String],
) -> anyhow::Result<Vec<Option<T>>> {
    let n = devices.len();
    if !given.is_empty() && given.len() != n {
        let without: Vec<String> = devices
            .iter()
            .enumerate()
            .skip(given.len())
            .map(|(i, d)| format!("device {} ({d})", i + 1))
            .collect();
        let what = if without.is_empty() {
            format!("{} more than there are devices", given.len() - n)
        } else {
            format!("none for {}", without.join(", "))
        };
        bail!(
            "{flag} is given {} time(s) for {n} device(s): give it once per --device, in the same order, or not at all ({what})",
            given.len()
        );
    }
    Ok((0..n).map(|i| given.get(i).copied()).collect())
}

pub fn parse_point(s: &str) -> Result<DVec3, String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>().map_err(|e| format!("{x:?}: {e}")))
        .collect::<Result<_, _>>()?;
    match v.as_slice() {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok(DVec3::new(*x, *y, *z)),
        _ => Err(format!("expected three finite numbers x,y,z, not {s:?}")),
    }
}

/// Parses a `--plot` path: plots are PNG images, so the name must end in `.png` (any
/// case); another extension is refused naming the one written, rather than PNG bytes
/// written under a name that says otherwise.
pub fn parse_png_path(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("png") => Ok(path),
        Some(e) => Err(format!(
            "plots are written as PNG only, not .{e}: give a file name ending in .png"
        )),
        None => Err("plots are written as PNG only: give a file name ending in .png".into()),
    }
}

/// Parses a `--units` value.
pub fn parse_units(s: &str) -> Result<Units, String> {
    s.parse()
}

/// The weld mode from the command line's `--weld-tolerance` (metres; 0 means exact).
pub fn weld_mode(tolerance_m: Option<f64>) -> anyhow::Result<Weld> {
    match tolerance_m {
        None => Ok(Weld::Exact),
        Some(0.0) => Ok(Weld::Exact),
        Some(t) if t.is_finite() && t > 0.0 => Ok(Weld::Tolerance(t)),
        Some(t) => {
            bail!("--weld-tolerance must be a non-negative distance in metres, not {t}")
        }
    }
}

/// Map options from the command line.
pub fn map_options(cell_size: Option<f64>, budget_mib: Option<usize>) -> MapOptions {
    let defaults = MapOptions::default();
    MapOptions {
        cell_size_m: cell_size,
        memory_budget_bytes: budget_mib.map_or(defaults.memory_budget_bytes, |mib| {
            mib.saturating_mul(1 << 20)
        }),
        ..defaults
    }
}

/// Where the objects come from (exactly one of `--mesh`, `--scene`, `--shape`,
/// `--volume`), and the material of a `--mesh` or `--shape` object.
#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("model").required(true).args(["mesh", "scene", "shape", "volume"])))]
pub struct ModelArgs {
    /// A mesh file (OBJ, STL, PLY, OFF) placed with the centre of its bounding box at the
    /// origin.
    #[arg(long, value_name = "FILE")]
    pub mesh: Option<PathBuf>,
    /// A scene file (TOML): objects, poses, materials, motions (see docs/guide.md); or a
    /// glTF file (`.glb`, `.gltf`): one object per node with a mesh.
    #[arg(long, value_name = "FILE.toml|FILE.glb")]
    pub scene: Option<PathBuf>,
    /// A built-in shape at the origin: sphere, torus, box, thin-plate, concave-corner, blob.
    #[arg(long, value_name = "NAME")]
    pub shape: Option<String>,
    #[command(flatten)]
    pub volume: VolumeArgs,
    /// Triangles of the built-in shape.
    #[arg(long, default_value_t = 20_000)]
    pub triangles: usize,
    /// Length unit of the mesh file: m, mm, cm, in, or metres per unit.
    #[arg(long, default_value = "m", value_parser = parse_units)]
    pub units: Units,
    /// Stiffness of a --mesh or --shape object, N/m.
    #[arg(long, default_value_t = Material::DEFAULT.stiffness())]
    pub stiffness: f64,
    /// Damping of a --mesh or --shape object, N·s/m.
    #[arg(long, default_value_t = Material::DEFAULT.damping())]
    pub damping: f64,
    /// Static friction coefficient of a --mesh or --shape object.
    #[arg(long, default_value_t = Material::DEFAULT.static_friction())]
    pub static_friction: f64,
    /// Dynamic friction coefficient of a --mesh or --shape object.
    #[arg(long, default_value_t = Material::DEFAULT.dynamic_friction())]
    pub dynamic_friction: f64,
}

impl ModelArgs {
    /// The model to load.
    pub fn model(&self) -> Model<'_> {
        Model {
            scene: self.scene.as_deref(),
            mesh: self.mesh.as_deref(),
            shape: self.shape.as_deref(),
            triangles: self.triangles,
            units: self.units,
            volume: self.volume.file(),
            voxel: self.volume.voxel,
            layers: &self.volume.layers,
        }
    }

    /// The material of a `--mesh` or `--shape` object, checked as a scene file's are.
    ///
    /// # Errors
    /// A value out of its range, named as its option.
    pub fn material(&self) -> anyhow::Result<Material> {
        material_of_flags(
            self.stiffness,
            self.damping,
            self.static_friction,
            self.dynamic_friction,
        )
    }
}

/// The material of the flags `--stiffness`, `--damping`, `--static-friction` and
/// `--dynamic-friction`, checked by the library's table of domains.
///
/// # Errors
/// A value outside its domain, named as its flag.
pub fn material_of_flags(
    stiffness: f64,
    damping: f64,
    static_friction: f64,
    dynamic_friction: f64,
) -> anyhow::Result<Material> {
    Material::builder()
        .stiffness(stiffness)
        .damping(damping)
        .friction(static_friction, dynamic_friction)
        .build()
        .map_err(|e| {
            // Parameter names as flags: `static_friction` also where the message compares.
            let message = e
                .to_string()
                .replace(" static_friction", " --static_friction");
            anyhow!("--{}", message.replace('_', "-"))
        })
}

/// The proxy's options with the maximum force of `--max-force`.
///
/// # Errors
/// A force outside its domain, named as its flag.
pub fn proxy_options(max_force: f64) -> anyhow::Result<ProxyOptions> {
    ProxyOptions::default()
        .with_max_force(max_force)
        .map_err(|e| anyhow!("{}", e.named("--max-force")))
}

/// The tool of a session; shared by `simulate`, `run` and `view`.
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct ToolArgs {
    /// The tool's radius, metres: a sphere centred on the proxy, which keeps it that far
    /// from every surface (0, a point, by default; at most 0.5 m, and at most the diagonal
    /// of the box bounding the scene's objects). Overrides a scene file's `tool_radius`.
    // Negative numbers are values, so that `-0.001` is refused naming the flag.
    #[arg(long, value_name = "METRES", allow_negative_numbers = true)]
    pub tool_radius: Option<f64>,
}

/// A tool radius, metres, and how it was given (`--tool-radius`, or a scene file's line),
/// to name it in errors.
#[derive(Debug, Clone, PartialEq)]
pub struct ToolRadius {
    pub metres: f64,
    pub given_as: String,
}

impl Default for ToolRadius {
    /// A point: no radius given anywhere.
    fn default() -> ToolRadius {
        ToolRadius {
            metres: 0.0,
            given_as: "--tool-radius".into(),
        }
    }
}

impl ToolArgs {
    /// The tool's radius: `--tool-radius`, else the scene file's `tool_radius` (its value
    /// and place), else 0 (a point). The flag is checked against its domain here, before
    /// any shape is built; the scene file checked its own.
    ///
    /// # Errors
    /// A radius outside its domain, named as its flag.
    pub fn radius(&self, from_file: Option<(f64, String)>) -> anyhow::Result<ToolRadius> {
        Ok(match (self.tool_radius, from_file) {
            (Some(r), _) => ToolRadius {
                metres: Param::ToolRadius
                    .check(r)
                    .map_err(|e| anyhow!("{}", e.named("--tool-radius")))?,
                ..ToolRadius::default()
            },
            (None, Some((metres, given_as))) => ToolRadius { metres, given_as },
            (None, None) => ToolRadius::default(),
        })
    }
}

impl ToolRadius {
    /// `options` with this tool radius, checked against `scene`: a radius above the
    /// diagonal of the box bounding its objects is refused ([`Scene::check_tool_radius`]).
    ///
    /// # Errors
    /// A radius outside its domain or larger than the scene, named as it was given.
    pub fn apply(&self, options: ProxyOptions, scene: &Scene) -> anyhow::Result<ProxyOptions> {
        let named = |e: haphe::scene::ParamError| anyhow!("{}", e.named(&self.given_as));
        let r = scene.check_tool_radius(self.metres).map_err(named)?;
        options.with_tool_radius(r).map_err(named)
    }
}

/// The real-time options with the spin of `--spin-us`, microseconds.
///
/// # Errors
/// A spin outside its domain, named as its flag (in microseconds).
pub fn spin(spin_us: Option<f64>) -> anyhow::Result<RealtimeOptions> {
    RealtimeOptions::default()
        .with_spin_seconds(spin_us.map(|us| us * 1e-6))
        .map_err(|_| {
            let domain = Param::SpinSeconds.domain();
            anyhow!(
                "--spin-us must be a finite number from {} to {} µs, not {}",
                domain.low * 1e6,
                domain.high * 1e6,
                spin_us.unwrap_or_default()
            )
        })
}

/// The files a session writes.
#[derive(clap::Args, Debug)]
pub struct OutputArgs {
    /// Write every tick to this CSV file.
    #[arg(long, value_name = "FILE.csv")]
    pub out: Option<PathBuf>,
    /// Draw force, penetration and the side view of the path to this PNG.
    #[arg(long, value_name = "FILE.png", value_parser = parse_png_path)]
    pub plot: Option<PathBuf>,
}

/// The clutch of a session's device; shared by `simulate`, `run` and `view`.
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct ClutchArgs {
    /// While this button of the device is held (0 is the first), the device moves without
    /// moving the tool: a clutch, to re-centre the hand in the workspace. The force fades
    /// out over 50 ms after the press and back in over 50 ms after the release (default:
    /// no clutch).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(0..32))]
    pub clutch_button: Option<u32>,
}
