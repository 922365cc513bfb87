//! Device paths for the proxy checks: exploring strides, strikes and steady contact over
//! a scene's objects, drawn from a seed.

use glam::DVec3;

use super::{bounds, point_on};
use crate::mesh::TriId;
use crate::query::{Side, classify_point, walk_to_nearest};
use crate::rng::SplitMix64;
use crate::scene::Scene;

/// `path` for a tool of `radius` metres: each point moved out along the surface's normal
/// of the scene's first object by the radius, so that the tool's centre lies as deep past
/// the tool's offset as the point lies past the surface (points inside deeper than
/// `deepest` metres, or outside farther than the radius, stay). How the benches turn the
/// point's contact path into the tool's.
pub fn lifted_for_tool(scene: &Scene, path: &[DVec3], radius: f64, deepest: f64) -> Vec<DVec3> {
    let Some(o) = scene.objects().first() else {
        return path.to_vec();
    };
    let (surface, map) = (o.shape.surface(), o.shape.map());
    path.iter()
        .map(|&p| {
            let q = o.pose.to_object(p);
            let inside = classify_point(surface, map, q).0 == Side::Inside;
            let reach = if inside { deepest } else { radius };
            match crate::query::nearest_within(surface, map, q, reach) {
                Some(near) => {
                    let away = o
                        .pose
                        .vector_to_world((q - near.closest.point).normalize_or_zero());
                    p + radius * if inside { -away } else { away }
                }
                None => p,
            }
        })
        .collect()
}

/// A haptic trajectory for the proxy check: device points at `rate_hz`, moving in straight
/// legs between waypoints near the surface of `scene`'s objects (from a few millimetres
/// outside to well inside, scaled to the object's size), at speeds drawn log-uniformly
/// in `speeds` (m/s). Most legs stay close to the previous waypoint (sliding); some cross
/// the object (strikes through thin parts).
pub fn haptic_path(
    scene: &Scene,
    ticks: usize,
    speeds: (f64, f64),
    rate_hz: f64,
    seed: u64,
) -> Vec<DVec3> {
    path(scene, ticks, speeds, rate_hz, Style::Exploring, seed)
}

/// A haptic trajectory in steady contact, as a hand feels a surface: it starts outside,
/// then slides from waypoint to nearby waypoint (a few percent of the object's size apart)
/// at depths drawn uniformly in `depths` (metres below the surface; a negative depth is
/// above it), at speeds drawn log-uniformly in `speeds` (m/s).
pub fn haptic_path_in_contact(
    scene: &Scene,
    ticks: usize,
    speeds: (f64, f64),
    depths: (f64, f64),
    rate_hz: f64,
    seed: u64,
) -> Vec<DVec3> {
    path(scene, ticks, speeds, rate_hz, Style::Touching(depths), seed)
}

/// How a path moves over the surface.
#[derive(Clone, Copy)]
enum Style {
    /// Deep presses, long strides, strikes across the object.
    Exploring,
    /// Shallow presses at these depths (metres), short strides.
    Touching((f64, f64)),
}

fn path(
    scene: &Scene,
    ticks: usize,
    speeds: (f64, f64),
    rate_hz: f64,
    style: Style,
    seed: u64,
) -> Vec<DVec3> {
    let mut random = SplitMix64::new(seed);
    let mut out = Vec::with_capacity(ticks);
    let dt = 1.0 / rate_hz;
    let (near_share, stride) = match style {
        Style::Exploring => (0.8, 0.1),
        Style::Touching(_) => (1.0, 0.03),
    };
    let waypoint = |random: &mut SplitMix64, near: Option<(usize, TriId, DVec3)>| {
        let i = near.map_or_else(|| random.index(scene.objects().len()), |n| n.0);
        let o = &scene.objects()[i];
        let surface = o.shape.surface();
        let (_, _, size) = bounds(surface);
        let (t, p_object) = match near {
            Some((_, t, p)) if random.next_unit() < near_share => {
                let goal =
                    o.pose.to_object(p) + random.unit_vector() * random.range(0.0, stride) * size;
                let (s, _) = walk_to_nearest(surface, t, goal);
                (s.triangle, s.point)
            }
            _ => {
                let t = TriId(random.index(surface.triangle_count()) as u32);
                (t, point_on(surface, t, random))
            }
        };
        let n = surface.frame(t).normal;
        let offset = match (near, style) {
            // The first waypoint, where the device starts: outside.
            (None, _) => random.range(0.01, 0.03) * size,
            (Some(_), Style::Exploring) => random.range(-0.08, 0.03) * size,
            (Some(_), Style::Touching((lo, hi))) => -random.range(lo, hi),
        };
        (i, t, o.pose.to_world(p_object + offset * n))
    };
    // The device starts outside every solid: a start that lands inside one (off a thin
    // part, or across a hole) is drawn again.
    let mut at = waypoint(&mut random, None);
    for _ in 0..MAX_START_DRAWS {
        if !inside_a_solid(scene, at.2) {
            break;
        }
        at = waypoint(&mut random, None);
    }
    let mut p = at.2;
    if ticks > 0 {
        out.push(p);
    }
    while out.len() < ticks {
        let next = waypoint(&mut random, Some(at));
        let speed = (speeds.0.ln() + random.next_unit() * (speeds.1 / speeds.0).ln()).exp();
        let step = speed * dt;
        let leg = next.2 - p;
        let n = ((leg.length() / step).ceil() as usize).clamp(1, 10_000);
        for k in 1..=n {
            if out.len() == ticks {
                break;
            }
            out.push(p + leg * (k as f64 / n as f64));
        }
        p = next.2;
        at = next;
    }
    out
}

/// Most draws of a path's starting point before the last one is kept.
const MAX_START_DRAWS: usize = 100;

/// Whether `p` (world frame) is inside one of the scene's solid objects.
fn inside_a_solid(scene: &Scene, p: DVec3) -> bool {
    scene.objects().iter().any(|o| {
        o.shape.is_solid()
            && classify_point(o.shape.surface(), o.shape.map(), o.pose.to_object(p)).0
                == Side::Inside
    })
}
