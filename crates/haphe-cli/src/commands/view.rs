//! `haphe view`: the live 3D view in the browser — a mesh, a built-in shape, a scene file
//! or a volume touched with the mouse (or the simulated hand), deformed or cut as the
//! session's are, or a recorded trace replayed.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;

use anyhow::{anyhow, bail};
use haphe::map::MapOptions;
use haphe::mesh::Units;
use haphe::mesh::shapes::Catalog;
use haphe::proxy::ProxyOptions;
use haphe::scene::{Material, ObjectId, Pose, SceneObject};
use haphe_view::{Model, Source, Trace};

use crate::args::cut::CutArgs;
use crate::args::deform::DeformArgs;
use crate::args::feel::FeelArgs;
use crate::args::volume::VolumeArgs;
use crate::args::{ClutchArgs, MappingArgs, ToolArgs, parse_units};
use crate::input::files::{self, read_input};
use crate::input::mesh::UnitsGiven;
use crate::input::model::{self, load_volume};
use crate::input::scene::{LoadedObject, LoadedScene, load_scene, mesh_shape, shape_of};
use crate::output::check_outputs;
use crate::session::device::view_choice;
use crate::session::live::{HAND_SECONDS, Serve, ViewDevice, live, scene_of, serve};

/// Arguments of `haphe view`.
#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("model").args(["mesh", "scene", "shape", "volume"])))]
pub struct Args {
    /// A mesh file (OBJ, STL, PLY, OFF) placed at the origin.
    #[arg(long, value_name = "FILE")]
    mesh: Option<PathBuf>,
    /// A scene file (TOML): objects, poses, materials, motions.
    #[arg(long, value_name = "FILE.toml")]
    scene: Option<PathBuf>,
    /// A built-in shape at the origin: sphere, torus, box, thin-plate, concave-corner, blob.
    #[arg(long, value_name = "NAME")]
    shape: Option<String>,
    #[command(flatten)]
    volume: VolumeArgs,
    /// Replay a trace written by `haphe simulate --out` (with --mesh, --shape or --scene
    /// the objects are drawn too).
    #[arg(long, value_name = "RUN.csv")]
    replay: Option<PathBuf>,
    /// Triangles of the built-in shape.
    #[arg(long, default_value_t = 20_000)]
    triangles: usize,
    /// Length unit of the mesh file: m, mm, cm, in, or metres per unit.
    #[arg(long, default_value = "m", value_parser = parse_units)]
    units: Units,
    /// The device: `mouse` (the pointer moves the device point), `hand` (the simulated
    /// hand explores the scene), dhd (Force Dimension), openhaptics (3D Systems Touch) or
    /// udp:HOST:PORT (listen there for a network device), mapped as `haphe run` maps it.
    /// Repeat it for several devices in one scene, as `haphe run` takes them (each tool is
    /// drawn).
    #[arg(long, default_value = "mouse", value_name = "SPEC")]
    device: Vec<String>,
    /// Servo rate, Hz.
    #[arg(long, default_value_t = 1000.0)]
    rate: f64,
    /// Length of the run, seconds (default: 60 for `--device hand`, until Ctrl-C for a
    /// real device).
    #[arg(long)]
    seconds: Option<f64>,
    #[command(flatten)]
    mapping: MappingArgs,
    #[command(flatten)]
    clutch: ClutchArgs,
    /// Stiffness of a --mesh or --shape object, N/m.
    #[arg(long, default_value_t = Material::DEFAULT.stiffness())]
    stiffness: f64,
    /// Static friction coefficient of a --mesh or --shape object.
    #[arg(long, default_value_t = Material::DEFAULT.static_friction())]
    static_friction: f64,
    /// Dynamic friction coefficient of a --mesh or --shape object.
    #[arg(long, default_value_t = Material::DEFAULT.dynamic_friction())]
    dynamic_friction: f64,
    #[command(flatten)]
    tool: ToolArgs,
    #[command(flatten)]
    feel: FeelArgs,
    #[command(flatten)]
    deform: DeformArgs,
    #[command(flatten)]
    cut: CutArgs,
    #[command(flatten)]
    serve: Serve,
}

/// Runs `haphe view`.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    // The flag's domain first; its fit to the scene once the scene is built.
    args.tool.radius(None)?;
    let feel = args.feel.check(args.rate)?;
    let deform = args.deform.check(args.rate)?;
    check_cut(args)?;
    let (mut loaded, what) = load(args)?;
    feel.apply(&mut loaded, args.rate)?;
    let cut = args
        .cut
        .setup(loaded.cutter.take(), args.rate, deform.is_some())?;
    let tool = args.tool.radius(loaded.tool_radius.clone())?;
    if let Some(file) = &args.replay {
        if deform.is_some() {
            bail!(
                "--deform deforms the object of a live view; a replay (--replay) shows its trace's objects as they were"
            );
        }
        let name = file.display().to_string();
        // Through the input module, like every command: a size limit, devices refused.
        let bytes = read_input(file, files::TRACE)?;
        let trace = Trace::read(&name, bytes.as_slice())?;
        let (scene, names, motions) = scene_of(loaded)?;
        let proxy = tool.apply(ProxyOptions::default(), &scene)?;
        let model = Model::from_scene(&scene, &names)
            .with_motions(motions)
            .with_tool_radius(proxy.tool_radius());
        let title = format!("haphe view: replay of {name} ({} ticks)", trace.rows.len());
        return serve(model, Source::Replay(trace), &title, &args.serve);
    }
    let device = match args.device.as_slice() {
        [one] if one == "mouse" => ViewDevice::Mouse,
        [one] if one == "hand" => ViewDevice::Hand(args.seconds.unwrap_or(HAND_SECONDS)),
        specs => {
            haphe_devices::parse_devices(specs).map_err(|e| match specs {
                [one] => anyhow!("--device {one:?}: {e} (or mouse, the default, for the view)"),
                _ => anyhow!("--device: {e} (or mouse, the default, alone, for the view)"),
            })?;
            let flags = args.mapping.per_device(specs)?;
            let choices = specs
                .iter()
                .zip(flags)
                .map(|(spec, f)| view_choice(spec, f))
                .collect();
            ViewDevice::Vendor(choices, args.seconds, args.clutch.clutch_button)
        }
    };
    live(
        loaded,
        device,
        args.rate,
        &tool,
        &what,
        (&args.serve, deform, cut),
    )
}

/// Checks the cutting's flags against the others before anything is loaded: `--cut` and
/// `--save-volume` act on a live view (not a replay), with one device; the volume is
/// written to a path that can take it, none of the inputs.
fn check_cut(args: &Args) -> anyhow::Result<()> {
    if args.replay.is_some() {
        let flag = if args.cut.cut {
            Some("--cut")
        } else if args.cut.save_volume.is_some() {
            Some("--save-volume")
        } else {
            None
        };
        if let Some(flag) = flag {
            bail!(
                "{flag} cuts or saves the volume of a live view; a replay (--replay) shows its trace's objects as they were"
            );
        }
    }
    args.cut.one_device(args.device.len())?;
    if let Some(out) = &args.cut.save_volume {
        let inputs: Vec<&Path> = [&args.mesh, &args.scene, &args.volume.volume, &args.replay]
            .into_iter()
            .flatten()
            .map(PathBuf::as_path)
            .collect();
        check_outputs(&[out.as_path()], &inputs)?;
    }
    Ok(())
}

/// The objects to show and what they are called in the title: a volume (a file, or the
/// mesh voxelised), a scene file, a mesh, a built-in shape, or none for a replay alone.
fn load(args: &Args) -> anyhow::Result<(LoadedScene, String)> {
    let map = MapOptions::default();
    let material = crate::args::material_of_flags(
        args.stiffness,
        Material::DEFAULT.damping(),
        args.static_friction,
        args.dynamic_friction,
    )?;
    let volume = model::Model {
        scene: None,
        mesh: args.mesh.as_deref(),
        shape: None,
        triangles: args.triangles,
        units: args.units,
        volume: args.volume.file(),
        voxel: args.volume.voxel,
        layers: &args.volume.layers,
    };
    if let Some(loaded) = load_volume(&volume, material)? {
        return Ok(loaded);
    }
    let single = |name: String, shape| {
        vec![LoadedObject {
            name,
            object: SceneObject::new(ObjectId(0), Arc::new(shape), Pose::IDENTITY, material),
            motion: None,
        }]
    };
    Ok(if let Some(file) = &args.scene {
        (load_scene(file, &map)?, file.display().to_string())
    } else if let Some(file) = &args.mesh {
        let shape = mesh_shape(file, args.units, &map, UnitsGiven::Flag)?;
        let name = file.display().to_string();
        (single(name.clone(), shape).into(), name)
    } else if let Some(name) = &args.shape {
        let which: Catalog = name.parse().map_err(|e| anyhow!("--shape {name:?}: {e}"))?;
        let shape = shape_of(which, args.triangles, &map)?;
        (single(name.clone(), shape).into(), name.clone())
    } else if args.replay.is_some() {
        (LoadedScene::from(Vec::new()), String::new())
    } else {
        bail!(
            "say what to show: --mesh FILE, --shape NAME, --scene FILE, --volume FILE.nii or --replay RUN.csv"
        );
    })
}
