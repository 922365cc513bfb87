//! Verification of the accelerated queries against brute-force oracles, on any mesh.
//!
//! The same checks run in the test suite (small samples) and in `haphe verify` (any
//! sample count, on the user's own meshes): segment crossing against every-triangle
//! testing, on random and adversarial segments, with a leak count (segments from outside
//! to inside that report no crossing); inside/outside against winding numbers; the surface
//! walk against the definition of a local minimum and, on convex meshes, against the
//! brute-force nearest point.
//!
//! With the `testing` feature (the command line, the tests, benches and fuzz targets turn
//! it on); an application that only renders does not compile it.

mod cut;
mod deform;
mod fixtures;
mod friction;
mod hold;
mod limits;
mod oracle;
mod paths;
mod proxy;
mod samples;
mod strikes;

pub use cut::{CutCheck, check_cutting};
pub use deform::Deformation;
// The deforming suite's runner, for `haphe verify` and the tests.
#[doc(hidden)]
pub use deform::check_deforming;
pub use fixtures::{HAND_SCALE_M, hand_sized, one_object_scene, sphere_scene};
pub use friction::friction_step;
pub use hold::{HeldContact, hand_deeper_than, saturation_depth_of};
pub use limits::{KEPT_FAILURES, ON_SURFACE_M};
pub use oracle::{BruteCrossing, WindingOracle, distance_to_surface};
pub use paths::{haptic_path, haptic_path_in_contact, lifted_for_tool};
pub use proxy::{BruteProxy, PROXY_TOLERANCE_M, ProxyCheck, check_proxy};
pub use samples::{SegmentKind, bounds, point_on, points, segments, trajectory};
pub use strikes::{
    ENOUGH_DEEP_STRIKES, MAX_STRIKE_ANGLE_DEG, MIN_DEEP_STRIKE_SHARE, STRIKE_FORCE_TOLERANCE_N,
    STRIKE_SPEED_CLASSES, STRIKE_SPEEDS, StrikeCheck, StrikeEntry, StrikeTicks, check_strikes,
    hand_goes_deep, required_deep_strikes, strike_path,
};

use crate::par::*;
use glam::DVec3;
use serde::Serialize;

use crate::map::VoxelMap;
use crate::mesh::{Surface, TriId, VertId};
use crate::query::{
    Feature, Side, WalkStatus, classify_point, closest_point_triangle, first_crossing,
    nearest_point_brute_force, walk_to_nearest,
};

/// Segment crossing against brute force for one kind of segment.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CrossingCheck {
    /// The kind of segments.
    pub kind: SegmentKind,
    /// How many segments.
    pub samples: usize,
    /// How many cross the surface (by brute force).
    pub crossing: usize,
    /// Segments where the accelerated answer differs from brute force (another triangle,
    /// another parameter, or a crossing on one side only).
    pub mismatches: usize,
    /// Segments from a point outside to a point inside a solid (by winding number, end
    /// points off the surface).
    pub outside_to_inside: usize,
    /// Of those, how many report no crossing: users falling through the surface.
    pub leaks: usize,
    /// Some failing segments `[p0, p1]`.
    pub failures: Vec<[[f64; 3]; 2]>,
}

/// Inside/outside against winding numbers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InsideCheck {
    /// How many points.
    pub samples: usize,
    /// How many are inside (by winding number).
    pub inside: usize,
    /// Points classified differently from the oracle, farther than [`ON_SURFACE_M`] from
    /// the surface.
    pub mismatches: usize,
    /// Points classified differently but within [`ON_SURFACE_M`] of the surface (excused).
    pub on_surface: usize,
    /// Points whose winding number is neither 0 nor 1 (where closed parts overlap, or
    /// inside an inside-out part): inside by the non-zero rule and compared like the
    /// others; excused from the peer's comparison only (the peer may use another rule).
    pub overlap: usize,
    /// Some failing points.
    pub failures: Vec<[f64; 3]>,
}

/// The surface walk along coherent trajectories.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WalkCheck {
    /// How many trajectories.
    pub trajectories: usize,
    /// How many walks (steps of all trajectories).
    pub walks: usize,
    /// Walks whose answer has a closer point on a face, edge or vertex adjacent to it.
    pub not_local_minimum: usize,
    /// Whether the mesh is convex (closed, connected, every edge convex).
    pub convex: bool,
    /// On a convex mesh: walks to targets outside it that start on a triangle facing the
    /// target; their answer must be the nearest point. (Every face whose plane the target
    /// projects into holds a local minimum — inside a convex polyhedron, and on its far
    /// side from outside — so only a walk that starts facing the target has one answer.)
    pub outside_walks: usize,
    /// Of those, walks whose answer is not the brute-force nearest point.
    pub not_nearest: usize,
    /// Walks that reached a step cap.
    pub bound_hits: usize,
    /// Some failing targets.
    pub failures: Vec<[f64; 3]>,
}

fn mismatch(a: Option<crate::query::Crossing>, b: Option<crate::query::Crossing>) -> bool {
    match (a, b) {
        (None, None) => false,
        (Some(a), Some(b)) => {
            a.triangle != b.triangle || (a.t - b.t).abs() > 1e-12 * a.t.abs().max(1e-300)
        }
        _ => true,
    }
}

/// Checks [`first_crossing`] against [`crate::query::first_crossing_brute_force`] on `n` segments of
/// `kind`, and counts leaks on solids. Parallel over segments; deterministic.
pub fn check_crossings(
    surface: &Surface,
    map: &VoxelMap,
    kind: SegmentKind,
    n: usize,
    seed: u64,
) -> CrossingCheck {
    check_crossings_with_peer(surface, map, kind, n, seed, None).0
}

/// Whether a peer implementation (another library's ray cast, say) reports a crossing on
/// the segment from `p0` to `p1`.
pub type PeerCrossing<'a> = &'a (dyn Fn(DVec3, DVec3) -> bool + Sync);

/// Whether a peer implementation classifies a point as inside.
pub type PeerInside<'a> = &'a (dyn Fn(DVec3) -> bool + Sync);

/// How a peer implementation fared on the same segments, judged by the same oracles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct PeerCrossings {
    /// Segments that cross the surface (by brute force) where the peer reports nothing.
    pub misses: usize,
    /// Segments from outside to inside a solid (end points off the surface) where the peer
    /// reports nothing: where a renderer built on it lets the user through.
    pub leaks: usize,
}

/// [`check_crossings`], also judging a `peer` on the same segments in the same pass (the
/// oracles run once per segment).
pub fn check_crossings_with_peer(
    surface: &Surface,
    map: &VoxelMap,
    kind: SegmentKind,
    n: usize,
    seed: u64,
    peer: Option<PeerCrossing<'_>>,
) -> (CrossingCheck, Option<PeerCrossings>) {
    let oracle = surface.is_solid().then(|| WindingOracle::new(surface));
    let brute_force = BruteCrossing::new(surface);
    /// What one segment showed.
    struct Outcome {
        crosses: bool,
        mismatch: bool,
        outside_to_inside: bool,
        leak: bool,
        peer_miss: bool,
        peer_leak: bool,
        segment: [[f64; 3]; 2],
    }
    let results: Vec<Outcome> = segments(surface, kind, n, seed)
        .par_iter()
        .map(|&(p0, p1)| {
            let fast = first_crossing(surface, map, p0, p1);
            let brute = brute_force.first_crossing(p0, p1);
            let bad = mismatch(fast, brute);
            let peer_hit = peer.map(|peer| peer(p0, p1));
            let mut candidate = false;
            let mut leak = false;
            let mut peer_leak = false;
            if let Some(oracle) = &oracle {
                let (w0, w1) = (oracle.winding(p0), oracle.winding(p1));
                if (w0 == 0) != (w1 == 0) {
                    // Distances only where they decide (they cost a pass over the mesh),
                    // at most once.
                    let mut off_surface = None;
                    let mut off = || {
                        *off_surface.get_or_insert_with(|| {
                            distance_to_surface(surface, p0) > ON_SURFACE_M
                                && distance_to_surface(surface, p1) > ON_SURFACE_M
                        })
                    };
                    candidate = fast.is_some() || off();
                    leak = candidate && fast.is_none();
                    peer_leak = peer_hit == Some(false) && off();
                }
            }
            Outcome {
                crosses: brute.is_some(),
                mismatch: bad,
                outside_to_inside: candidate,
                leak,
                peer_miss: brute.is_some() && peer_hit == Some(false),
                peer_leak,
                segment: [p0.to_array(), p1.to_array()],
            }
        })
        .collect();
    let check = CrossingCheck {
        kind,
        samples: n,
        crossing: results.iter().filter(|r| r.crosses).count(),
        mismatches: results.iter().filter(|r| r.mismatch).count(),
        outside_to_inside: results.iter().filter(|r| r.outside_to_inside).count(),
        leaks: results.iter().filter(|r| r.leak).count(),
        failures: results
            .iter()
            .filter(|r| r.mismatch || r.leak)
            .take(KEPT_FAILURES)
            .map(|r| r.segment)
            .collect(),
    };
    let peer = peer.map(|_| PeerCrossings {
        misses: results.iter().filter(|r| r.peer_miss).count(),
        leaks: results.iter().filter(|r| r.peer_leak).count(),
    });
    (check, peer)
}

/// Checks [`classify_point`] against winding numbers on `n` random points.
pub fn check_inside(surface: &Surface, map: &VoxelMap, n: usize, seed: u64) -> InsideCheck {
    check_inside_with_peer(surface, map, n, seed, None).0
}

/// [`check_inside`], also counting the points off the surface (farther than
/// [`ON_SURFACE_M`]) where a `peer` disagrees with the winding numbers, in the same pass;
/// the peer is only asked on solids.
pub fn check_inside_with_peer(
    surface: &Surface,
    map: &VoxelMap,
    n: usize,
    seed: u64,
    peer: Option<PeerInside<'_>>,
) -> (InsideCheck, Option<usize>) {
    let oracle = WindingOracle::new(surface);
    let solid = surface.is_solid();
    let peer = peer.filter(|_| solid);
    let results: Vec<(bool, u8, bool, [f64; 3], bool)> = points(surface, n, seed)
        .par_iter()
        .map(|&p| {
            let (side, _) = classify_point(surface, map, p);
            let winding = if solid { oracle.winding(p) } else { 0 };
            let inside = winding != 0;
            let overlap = !(0..=1).contains(&winding);
            let agrees = (side == Side::Inside) == inside;
            let peer_agrees = overlap || peer.is_none_or(|peer| peer(p) == inside);
            let mut near = None;
            let mut on_surface =
                || *near.get_or_insert_with(|| distance_to_surface(surface, p) <= ON_SURFACE_M);
            let verdict = if agrees {
                0
            } else if on_surface() {
                1
            } else {
                2
            };
            let peer_disagrees = !peer_agrees && !on_surface();
            (inside, verdict, peer_disagrees, p.to_array(), overlap)
        })
        .collect();
    let check = InsideCheck {
        samples: n,
        inside: results.iter().filter(|r| r.0).count(),
        mismatches: results.iter().filter(|r| r.1 == 2).count(),
        on_surface: results.iter().filter(|r| r.1 == 1).count(),
        overlap: results.iter().filter(|r| r.4).count(),
        failures: results
            .iter()
            .filter(|r| r.1 == 2)
            .take(KEPT_FAILURES)
            .map(|r| r.3)
            .collect(),
    };
    let peer = peer.map(|_| results.iter().filter(|r| r.2).count());
    (check, peer)
}

/// Whether the surface is convex: closed and connected, with every edge convex (a closed
/// connected surface that is locally convex everywhere bounds a convex body).
pub fn is_convex(surface: &Surface) -> bool {
    let report = surface.report();
    if !surface.is_solid() || report.components != 1 {
        return false;
    }
    let (_, _, size) = bounds(surface);
    let tolerance = 1e-12 * size;
    (0..surface.triangle_count() as u32).all(|t| {
        let t = TriId(t);
        let frame = surface.frame(t);
        (0..3).all(|corner| {
            surface.neighbour(t, corner).is_none_or(|n| {
                surface
                    .corners(n)
                    .iter()
                    .all(|&p| frame.height(p) <= tolerance)
            })
        })
    })
}

/// Checks [`walk_to_nearest`] on `trajectories` coherent trajectories of `steps` targets
/// each (steps of `step_range` metres), each walk starting from the previous answer: every
/// answer is a local minimum of distance, and for targets outside a convex mesh the
/// nearest point.
pub fn check_walk(
    surface: &Surface,
    trajectories: usize,
    steps: usize,
    step_range: (f64, f64),
    seed: u64,
) -> WalkCheck {
    let convex = is_convex(surface);
    let oracle = convex.then(|| WindingOracle::new(surface));
    let (_, _, size) = bounds(surface);
    let tolerance = 1e-12 * size;
    /// What one trajectory showed.
    #[derive(Default)]
    struct Outcome {
        not_local_minimum: usize,
        outside: usize,
        not_nearest: usize,
        bound_hits: usize,
        failures: Vec<[f64; 3]>,
    }
    let per: Vec<Outcome> = (0..trajectories)
        .into_par_iter()
        .map(|k| {
            let (mut t, targets) =
                trajectory(surface, steps, step_range, seed.wrapping_add(k as u64));
            let mut o = Outcome::default();
            for q in targets {
                let facing = surface.frame(t).height(q) >= 0.0;
                let (found, status) = walk_to_nearest(surface, t, q);
                t = found.triangle;
                o.bound_hits += usize::from(status == WalkStatus::BoundHit);
                let closer = |s: u32| {
                    !surface.frame(TriId(s)).is_degenerate()
                        && closest_point_triangle(q, surface.corners(TriId(s)))
                            .point
                            .distance(q)
                            < found.distance - tolerance
                };
                let tri = surface.triangle(found.triangle);
                let local_min = match found.feature {
                    Feature::Face => true,
                    Feature::Edge(i) => surface
                        .neighbour(found.triangle, i as usize)
                        .is_none_or(|n| !closer(n.0)),
                    Feature::Vertex(i) => !surface
                        .fan(VertId(tri[i as usize]))
                        .iter()
                        .any(|&s| closer(s)),
                };
                let mut failed = !local_min;
                o.not_local_minimum += usize::from(!local_min);
                if facing && oracle.as_ref().is_some_and(|o| o.winding(q) == 0) {
                    o.outside += 1;
                    let best = nearest_point_brute_force(surface, q);
                    if found.distance > best.distance + tolerance {
                        o.not_nearest += 1;
                        failed = true;
                    }
                }
                if failed && o.failures.len() < KEPT_FAILURES {
                    o.failures.push(q.to_array());
                }
            }
            o
        })
        .collect();
    WalkCheck {
        trajectories,
        walks: trajectories * steps,
        not_local_minimum: per.iter().map(|o| o.not_local_minimum).sum(),
        convex,
        outside_walks: per.iter().map(|o| o.outside).sum(),
        not_nearest: per.iter().map(|o| o.not_nearest).sum(),
        bound_hits: per.iter().map(|o| o.bound_hits).sum(),
        failures: per
            .into_iter()
            .flat_map(|o| o.failures)
            .take(KEPT_FAILURES)
            .collect(),
    }
}
