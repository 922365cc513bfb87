//! Cutting suites: a tool drilling into a volume while the proxy and its brute-force
//! oracle touch the surface of every version the cutter makes, checked as
//! [`check_proxy`](super::check_proxy) checks a scene at rest.

use std::sync::Arc;

use glam::DVec3;

use super::proxy::{ProxyCheck, ProxyPair};
use crate::proxy::ProxyOptions;
use crate::scene::{Material, ObjectId, Pose, Scene, SceneObject};
use crate::volume::{CutError, Cutter};

/// What a cutting suite did besides the proxy's checks.
#[derive(Debug, Clone)]
pub struct CutCheck {
    /// The proxy against its oracle, at every tick.
    pub proxy: ProxyCheck,
    /// Ticks where the tool was inside the material left, or closer than its radius less
    /// the skin to the surface (by brute force over the current surface).
    pub too_close: usize,
    /// Versions of the shape handed to the scene.
    pub versions: u64,
    /// Of those, versions whose surface is not a closed solid (a crack).
    pub open_versions: u64,
    /// Voxels removed.
    pub removed: u64,
    /// Where the proxy ended, world frame.
    pub end: DVec3,
    /// Where the proxy was at each tick (the tool's path), world frame.
    pub tool_path: Vec<DVec3>,
}

/// Runs the device points `path` (one a tick, at `rate_hz`) against the volume of
/// `cutter`, placed at `pose` with `material`, the tool cutting when `cut` is on: each
/// tick the cutter is told where the tool pressed and how hard, and every `refresh_every`
/// ticks the shape of the cut volume is made and given to the scene (as a servo would
/// take it from another thread, in lockstep here so that runs repeat). The proxy and its
/// oracle see every version.
///
/// # Errors
/// A version that cannot be made (all material cut away).
pub fn check_cutting(
    cutter: &mut Cutter,
    (pose, material): (Pose, Material),
    path: &[DVec3],
    (options, rate_hz): (ProxyOptions, f64),
    (cut, refresh_every): (bool, usize),
) -> Result<CutCheck, CutError> {
    let mut scene = Scene::local(1);
    let object = SceneObject::new(ObjectId(0), Arc::clone(cutter.shape()), pose, material);
    if scene.insert(object).is_err() {
        unreachable!("an empty scene of one place takes an object");
    }
    let start = path.first().copied().unwrap_or(DVec3::ZERO);
    let mut pair = ProxyPair::new(&scene, start, options);
    let mut check = ProxyCheck {
        ticks: path.len(),
        ..ProxyCheck::empty()
    };
    let (mut too_close, mut versions, mut open_versions, mut end) = (0, 0, 0, start);
    let dt = 1.0 / rate_hz;
    let mut tool_path = Vec::with_capacity(path.len());
    for (tick, &hip) in path.iter().enumerate() {
        if cut
            && tick % refresh_every.max(1) == 0
            && let Some(shape) = cutter.refresh()?
        {
            open_versions += u64::from(!shape.is_solid());
            if scene.replace(ObjectId(0), shape).is_err() {
                unreachable!("the cutter's versions replace the object's");
            }
            versions += 1;
        }
        scene.begin_tick();
        pair.brute().sync(&scene);
        let out = pair.tick(&scene, tick, hip, &mut check);
        end = out.proxy;
        tool_path.push(out.proxy);
        too_close += usize::from(closer_than_the_tool(&scene, out.proxy, &options));
        if cut && out.contact.is_some() {
            cutter.press(pose.to_object(out.proxy), out.force.length(), dt);
        }
    }
    Ok(CutCheck {
        proxy: check,
        too_close,
        versions,
        open_versions,
        removed: cutter.removed(),
        end,
        tool_path,
    })
}

/// Whether the tool centred at `p` lies inside the material of the scene's object, or
/// closer than its radius less the skin to its surface (every triangle tested).
fn closer_than_the_tool(scene: &Scene, p: DVec3, options: &ProxyOptions) -> bool {
    let o = &scene.objects()[0];
    let q = o.pose.to_object(p);
    let surface = o.shape.surface();
    let inside = super::WindingOracle::new(surface).winding(q) != 0;
    let near = crate::query::nearest_within_brute_force(surface, q, f64::MAX);
    let close = near.is_some_and(|n| n.distance < options.tool_radius() - options.skin());
    inside || close
}
