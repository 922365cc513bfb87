//! `haphe verify --deform KIND`: the proxy against the brute-force proxy while the model,
//! scaled to a hand's size, deforms at every tick (breathing, a travelling dent,
//! twisting), on pressing paths that the moving surface meets and leaves.

use std::time::Instant;

use haphe::mesh::Surface;
use haphe::proxy::ProxyOptions;
use haphe::verify::{Deformation, ProxyCheck, check_deforming, haptic_path_in_contact};
use rayon::prelude::*;
use serde::Serialize;

use super::proxy::{scaled_shape, scene_of, verify_material};

/// The servo rate of the deforming suites, Hz: one deformation a tick.
const RATE_HZ: f64 = 1e3;

/// Device speeds of the pressing paths, m/s.
const SPEEDS_M_S: (f64, f64) = (0.02, 0.3);

/// Depths of the pressing paths below the surface at rest, metres (a negative depth is
/// above it): the surface moving by centimetres meets the hand and leaves it.
const DEPTHS_M: (f64, f64) = (-2e-3, 10e-3);

/// The deformations `--deform all` checks.
pub const ALL: [Deformation; 3] = [Deformation::Breathe, Deformation::Dent, Deformation::Twist];

/// The deformations named by `--deform`.
#[derive(Debug, Clone)]
pub struct Kinds(pub Vec<Deformation>);

/// The deformations named by `--deform`: one kind, or `all`.
///
/// # Errors
/// A name that is neither a kind nor `all`.
pub fn parse_kinds(s: &str) -> Result<Kinds, String> {
    if s == "all" {
        return Ok(Kinds(ALL.to_vec()));
    }
    s.parse::<Deformation>()
        .map(|d| Kinds(vec![d]))
        .map_err(|e| format!("{e}, or all"))
}

/// One deformation and what the check found.
#[derive(Debug, Serialize)]
pub struct DeformRow {
    pub deformation: &'static str,
    #[serde(flatten)]
    pub check: ProxyCheck,
}

/// The deforming suites of one model.
#[derive(Debug, Serialize)]
pub struct DeformReport {
    /// Scale applied to the model.
    pub scale: f64,
    /// The tool's radius, metres (0: a point).
    pub tool_radius_m: f64,
    pub rows: Vec<DeformRow>,
    pub seconds: f64,
}

impl DeformReport {
    /// Whether every tick matched the oracle, stayed outside the current surface and
    /// rendered a bounded force, and every suite touched the surface (a suite that never
    /// met it checked nothing of the deformation).
    pub fn passed(&self) -> bool {
        self.rows.iter().all(|r| {
            let c = &r.check;
            c.mismatches == 0 && c.inside == 0 && c.bad_forces == 0 && c.contact_ticks > 0
        })
    }
}

/// Runs `ticks` ticks of each of `kinds` on `surface` scaled to a hand's size, deformed
/// before every tick, comparing the proxy (with `options`) with the brute-force proxy on
/// the current vertices at every tick.
///
/// # Errors
/// A surface that cannot be mapped, or a deformation the map cannot hold.
pub fn check(
    surface: &Surface,
    kinds: &[Deformation],
    options: ProxyOptions,
    ticks: usize,
    seed: u64,
) -> anyhow::Result<DeformReport> {
    let start = Instant::now();
    let (shape, scale) = scaled_shape(surface)?;
    let material = verify_material();
    let rows = kinds
        .par_iter()
        .enumerate()
        .map(|(k, &kind)| {
            // Each deformation deforms a scene of its own, from the same rest shape.
            let mut scene = scene_of(&shape, material)?;
            let seed = seed.wrapping_mul(7919).wrapping_add(k as u64 + 1);
            let path = haptic_path_in_contact(&scene, ticks, SPEEDS_M_S, DEPTHS_M, RATE_HZ, seed);
            let check = check_deforming(&mut scene, kind, &path, options, RATE_HZ)?;
            Ok(DeformRow {
                deformation: kind.name(),
                check,
            })
        })
        .collect::<anyhow::Result<Vec<DeformRow>>>()?;
    Ok(DeformReport {
        scale,
        tool_radius_m: options.tool_radius(),
        rows,
        seconds: start.elapsed().as_secs_f64(),
    })
}
