//! Query samples: random and adversarial segments, random points, coherent trajectories.
//!
//! Adversarial segments are built from the mesh's own coordinates, so that they pass
//! through vertices and edges exactly (up to the exactness of adding small powers of two,
//! which holds for the coordinates of usual meshes), lie in face planes or graze edges.

use glam::DVec3;

use crate::mesh::{Surface, TriId};
use crate::rng::SplitMix64;

/// A kind of segment sample.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SegmentKind {
    /// End points uniform in the bounding box grown by a fifth on every side.
    Random,
    /// Through a mesh vertex, along an axis, a diagonal or a random direction.
    ThroughVertex,
    /// Through a point of a mesh edge (its midpoint or a quarter point).
    ThroughEdge,
    /// Lying in the plane of a face, through a point of the face.
    InFacePlane,
    /// Along a mesh edge, beyond both its ends (grazing the two faces of the edge).
    AlongEdge,
    /// Between 1 nm and 10 µm long, through a surface point.
    Short,
    /// Between a thousand and a million object sizes long, passing near the object.
    Long,
}

impl SegmentKind {
    /// Every kind, random first.
    pub const ALL: [SegmentKind; 7] = [
        SegmentKind::Random,
        SegmentKind::ThroughVertex,
        SegmentKind::ThroughEdge,
        SegmentKind::InFacePlane,
        SegmentKind::AlongEdge,
        SegmentKind::Short,
        SegmentKind::Long,
    ];

    /// The adversarial kinds (all but [`SegmentKind::Random`]).
    pub fn is_adversarial(self) -> bool {
        self != SegmentKind::Random
    }
}

/// The bounding box of a surface and its diagonal length (metres).
pub fn bounds(surface: &Surface) -> (DVec3, DVec3, f64) {
    let r = surface.report();
    let (lo, hi) = (
        DVec3::from_array(r.bounds_min),
        DVec3::from_array(r.bounds_max),
    );
    (lo, hi, (hi - lo).length().max(f64::MIN_POSITIVE))
}

/// The largest power of two not above `x` (for offsets that add exactly).
fn power_of_two_below(x: f64) -> f64 {
    if x > 0.0 && x.is_finite() {
        2f64.powi(x.log2().floor() as i32)
    } else {
        1.0
    }
}

/// A direction whose components are 0 or ±1 (an axis, a face diagonal or a space
/// diagonal) — exact offsets — or, one time in four, a random unit vector.
fn direction(random: &mut SplitMix64) -> DVec3 {
    if random.index(4) == 0 {
        return random.unit_vector();
    }
    loop {
        let d = DVec3::new(
            random.index(3) as f64 - 1.0,
            random.index(3) as f64 - 1.0,
            random.index(3) as f64 - 1.0,
        );
        if d != DVec3::ZERO {
            return d;
        }
    }
}

/// A random point of triangle `t` of `surface` (uniform over the triangle).
pub fn point_on(surface: &Surface, t: TriId, random: &mut SplitMix64) -> DVec3 {
    let [a, b, c] = surface.corners(t);
    let (mut u, mut v) = (random.next_unit(), random.next_unit());
    if u + v > 1.0 {
        (u, v) = (1.0 - u, 1.0 - v);
    }
    a + u * (b - a) + v * (c - a)
}

/// `n` segments of `kind` over `surface`, deterministic for a `seed`.
pub fn segments(surface: &Surface, kind: SegmentKind, n: usize, seed: u64) -> Vec<(DVec3, DVec3)> {
    let mut random = SplitMix64::new(seed ^ (kind as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
    let (lo, hi, size) = bounds(surface);
    let margin = DVec3::splat(0.2 * size);
    let reach = power_of_two_below(0.05 * size);
    let triangles = surface.triangle_count();
    (0..n)
        .map(|_| {
            let t = TriId(random.index(triangles) as u32);
            let [a, b, c] = surface.corners(t);
            match kind {
                SegmentKind::Random => (
                    random.point_in(lo - margin, hi + margin),
                    random.point_in(lo - margin, hi + margin),
                ),
                SegmentKind::ThroughVertex => {
                    let v = [a, b, c][random.index(3)];
                    let d = direction(&mut random) * reach;
                    (v + d, v - d)
                }
                SegmentKind::ThroughEdge => {
                    let (p, q) = [(a, b), (b, c), (c, a)][random.index(3)];
                    let s = [0.5, 0.25, 0.75][random.index(3)];
                    let m = p + s * (q - p);
                    let d = direction(&mut random) * reach;
                    (m + d, m - d)
                }
                SegmentKind::InFacePlane => {
                    let q = point_on(surface, t, &mut random);
                    let n = surface.frame(t).normal;
                    let tangent = n.cross(random.unit_vector()).normalize_or(b - a);
                    (q - reach * tangent, q + reach * tangent)
                }
                SegmentKind::AlongEdge => {
                    let (p, q) = [(a, b), (b, c), (c, a)][random.index(3)];
                    let e = q - p;
                    (p - 0.5 * e, q + 0.5 * e)
                }
                SegmentKind::Short => {
                    let q = point_on(surface, t, &mut random);
                    let length = 10f64.powf(random.range(-9.0, -5.0));
                    let d = random.unit_vector() * (0.5 * length);
                    (q + d, q - d)
                }
                SegmentKind::Long => {
                    let q = random.point_in(lo - margin, hi + margin);
                    let length = size * 10f64.powf(random.range(3.0, 6.0));
                    let d = random.unit_vector() * (0.5 * length);
                    (q + d, q - d)
                }
            }
        })
        .collect()
}

/// `n` points uniform in the bounding box grown by a fifth on every side.
pub fn points(surface: &Surface, n: usize, seed: u64) -> Vec<DVec3> {
    let mut random = SplitMix64::new(seed);
    let (lo, hi, size) = bounds(surface);
    let margin = DVec3::splat(0.2 * size);
    (0..n)
        .map(|_| random.point_in(lo - margin, hi + margin))
        .collect()
}

/// A coherent trajectory near the surface: it starts at a random surface point pushed
/// off along the normal, then moves in steps of random length in `[step_min, step_max]`
/// (metres) in slowly turning directions, pulled back towards the start's neighbourhood so
/// it stays near the surface. Returns the start triangle and the targets.
pub fn trajectory(
    surface: &Surface,
    steps: usize,
    (step_min, step_max): (f64, f64),
    seed: u64,
) -> (TriId, Vec<DVec3>) {
    let mut random = SplitMix64::new(seed);
    let (_, _, size) = bounds(surface);
    let t = TriId(random.index(surface.triangle_count()) as u32);
    let start = point_on(surface, t, &mut random);
    let n = surface.frame(t).normal;
    let mut p = start + n * random.range(-0.01, 0.01) * size;
    let mut heading = random.unit_vector();
    let targets = (0..steps)
        .map(|_| {
            heading = (heading + 0.3 * random.unit_vector()).normalize_or(DVec3::X);
            // Pull back towards the start so the path stays on this part of the surface.
            let back = (start - p) / (0.1 * size);
            let d = (heading + back).normalize_or(heading);
            p += d * random.range(step_min, step_max);
            p
        })
        .collect();
    (t, targets)
}
