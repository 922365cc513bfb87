//! `haphe verify --ticks N`: the proxy against the brute-force proxy on haptic paths over
//! the model.

use std::time::Instant;

use haphe::map::MapOptions;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::ProxyOptions;
use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};
use haphe::verify::{
    ProxyCheck, StrikeCheck, check_proxy, check_strikes, hand_sized, haptic_path,
    haptic_path_in_contact,
};
use rayon::prelude::*;
use serde::Serialize;

/// Ticks per independent path; longer runs use several paths with their own seeds, run
/// in parallel and summed in order.
const TICKS_PER_PATH: usize = 10_000;

/// One kind of path and what the check found on it.
#[derive(Debug, Serialize)]
pub struct ProxyRow {
    /// The kind of path.
    pub path: &'static str,
    /// Device speeds, m/s.
    pub speeds_m_s: (f64, f64),
    /// The check, summed over the paths of this kind.
    #[serde(flatten)]
    pub check: ProxyCheck,
}

/// The proxy check of one model.
#[derive(Debug, Serialize)]
pub struct ProxyReport {
    /// Scale applied to the model (its largest side becomes
    /// [`HAND_SCALE_M`](haphe::verify::HAND_SCALE_M)).
    pub scale: f64,
    /// The tool's radius, metres (0: a point).
    pub tool_radius_m: f64,
    /// One row per kind of path.
    pub rows: Vec<ProxyRow>,
    /// Seconds for the whole check.
    pub seconds: f64,
}

/// The path kinds: exploring (presses and slides, 0.01–2 m/s), strikes (2–10 m/s, up to
/// 1 cm per tick), and steady contact (0.5–3 mm deep, 0.05–0.5 m/s).
const KINDS: [(&str, (f64, f64)); 3] = [
    ("exploring", (0.01, 2.0)),
    ("strikes", (2.0, 10.0)),
    ("contact", (0.05, 0.5)),
];

/// The material of the proxy checks: 800 N/m, 1 N·s/m, friction 0.5 / 0.3.
pub fn verify_material() -> Material {
    Material::builder()
        .stiffness(800.0)
        .damping(1.0)
        .friction(0.5, 0.3)
        .build()
        .expect("800 N/m, 1 N·s/m and 0.5 / 0.3 are in their domains")
}

/// `surface` scaled to a hand's size (its largest side
/// [`HAND_SCALE_M`](haphe::verify::HAND_SCALE_M)) and mapped, and the scale.
pub fn scaled_shape(surface: &Surface) -> anyhow::Result<(std::sync::Arc<Shape>, f64)> {
    let (mesh, scale) = hand_sized(surface);
    let shape = Shape::build(
        Surface::new(mesh, &SurfaceOptions::default())?,
        &MapOptions::default(),
    )?;
    Ok((std::sync::Arc::new(shape), scale))
}

/// A scene of `shape` alone, at the origin.
pub fn scene_of(shape: &std::sync::Arc<Shape>, material: Material) -> anyhow::Result<Scene> {
    let mut scene = Scene::local(1);
    let object = SceneObject::new(ObjectId(0), shape.clone(), Pose::IDENTITY, material);
    scene.insert(object).map_err(|(e, _)| e)?;
    Ok(scene)
}

/// Deep strikes on the model scaled to a hand's size (see [`check_strikes`]).
#[derive(Debug, Serialize)]
pub struct StrikeReport {
    /// Scale applied to the model.
    pub scale: f64,
    /// The saturation depth of the material and device, metres (`max_force / stiffness`).
    pub saturation_depth_m: f64,
    /// The tool's radius, metres (0: a point).
    pub tool_radius_m: f64,
    /// What the strikes found.
    #[serde(flatten)]
    pub check: StrikeCheck,
    /// Seconds for the whole check, and the proxy's mean time per tick, microseconds.
    pub seconds: f64,
    pub us_per_tick: f64,
}

impl StrikeReport {
    /// Whether enough strikes went deeper than the saturation depth (by the hand's path:
    /// half of them, or 50) and no tick from the one a strike went that deep lost contact, pulled
    /// the hand on or faced the far side (see [`StrikeCheck::passed`]). (A grazing strike
    /// that never goes that deep stays in the physical range, where the proxy is the
    /// god-object: it slides over the surface and may be pushed on by it past a crest, as
    /// by a real surface; those strikes are counted apart.)
    pub fn passed(&self) -> bool {
        self.check.passed()
    }
}

/// Runs `strikes` deep strikes (0–70° from the normal, 0.5–10 m/s at 1 kHz, up to 0.25 m
/// past the entry, through the model and out) on a solid `surface` scaled to a hand's
/// size, with the material of the proxy check (without friction) and the proxy's `options`.
pub fn strikes(
    surface: &Surface,
    options: ProxyOptions,
    strikes: usize,
    seed: u64,
) -> anyhow::Result<StrikeReport> {
    let start = Instant::now();
    let (shape, scale) = scaled_shape(surface)?;
    let material = verify_material().to_builder().friction(0.0, 0.0).build()?;
    let scene = scene_of(&shape, material)?;
    let clock = Instant::now();
    let check = check_strikes(&scene, options, strikes, 0.25, 1e3, seed);
    let us_per_tick = clock.elapsed().as_secs_f64() * 1e6 / check.ticks.max(1) as f64;
    Ok(StrikeReport {
        scale,
        saturation_depth_m: options.max_force() / material.stiffness(),
        tool_radius_m: options.tool_radius(),
        check,
        seconds: start.elapsed().as_secs_f64(),
        us_per_tick,
    })
}

/// Runs `ticks` ticks of each kind of path on `surface` scaled to a hand's size, with a
/// material with friction and the proxy's `options`, comparing the proxy with the
/// brute-force proxy at every tick.
pub fn check(
    surface: &Surface,
    options: ProxyOptions,
    ticks: usize,
    seed: u64,
) -> anyhow::Result<ProxyReport> {
    let start = Instant::now();
    let (shape, scale) = scaled_shape(surface)?;
    let material = verify_material();
    // A scene per path (a scene belongs to one servo thread); the shape is shared.
    let scene = || scene_of(&shape, material);
    scene()?;
    let paths = ticks.div_ceil(TICKS_PER_PATH);
    let jobs: Vec<(usize, usize)> = (0..KINDS.len())
        .flat_map(|k| (0..paths).map(move |p| (k, p)))
        .collect();
    let checks: Vec<(usize, ProxyCheck)> = jobs
        .par_iter()
        .filter_map(|&(k, p)| {
            let scene = scene().ok()?;
            let n = TICKS_PER_PATH.min(ticks - p * TICKS_PER_PATH);
            let seed = seed
                .wrapping_mul(7919)
                .wrapping_add((k * 100_003 + p) as u64);
            let (name, speeds) = KINDS[k];
            let path = if name == "contact" {
                haptic_path_in_contact(&scene, n, speeds, (0.5e-3, 3e-3), 1e3, seed)
            } else {
                haptic_path(&scene, n, speeds, 1e3, seed)
            };
            Some((k, check_proxy(&scene, &path, options)))
        })
        .collect();
    let rows = KINDS
        .iter()
        .enumerate()
        .map(|(k, &(path, speeds_m_s))| {
            let check = checks
                .iter()
                .filter(|(kk, _)| *kk == k)
                .map(|(_, c)| c.clone())
                .reduce(|a, b| a.merged(b))
                .unwrap_or_else(ProxyCheck::empty);
            ProxyRow {
                path,
                speeds_m_s,
                check,
            }
        })
        .collect();
    Ok(ProxyReport {
        scale,
        tool_radius_m: options.tool_radius(),
        rows,
        seconds: start.elapsed().as_secs_f64(),
    })
}

impl ProxyReport {
    /// Whether every tick matched the oracle, stayed outside and rendered a bounded force.
    pub fn passed(&self) -> bool {
        self.rows
            .iter()
            .all(|r| r.check.mismatches == 0 && r.check.inside == 0 && r.check.bad_forces == 0)
    }
}
