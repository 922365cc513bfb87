//! Brute-force oracles: every triangle tested, no map, no walk.

use glam::DVec3;

use crate::mesh::{Surface, TriId};
use crate::query::{Segment, intersect_segment_triangle};

/// The direction of the oracle's rays: generic, so that no ray runs along the axis-aligned
/// faces and edges of CAD meshes.
const RAY_DIRECTION: [f64; 3] = [0.573_462_1, 0.623_182_7, 0.531_740_9];

/// Winding numbers by signed crossing counts: for a closed, outward-oriented surface the
/// number of crossings of a ray from `p` going out minus those going in is the winding
/// number of `p` (1 inside, 0 outside), exactly, with the same watertight test the
/// queries use. A prefilter on the triangles' extents across the ray keeps each query at a
/// few nanoseconds per triangle; every triangle is still considered.
pub struct WindingOracle<'a> {
    surface: &'a Surface,
    ray: DVec3,
    across: [DVec3; 2],
    /// Per triangle: (min u, max u, min w, max w, max along the ray).
    extents: Vec<[f64; 5]>,
    length: f64,
}

impl<'a> WindingOracle<'a> {
    /// Prepares the oracle for `surface`.
    pub fn new(surface: &'a Surface) -> WindingOracle<'a> {
        let ray = DVec3::from_array(RAY_DIRECTION).normalize();
        let u = ray.any_orthonormal_vector();
        let w = ray.cross(u);
        let extents = (0..surface.triangle_count() as u32)
            .map(|t| {
                let c = surface.corners(TriId(t));
                let pu = c.map(|p| p.dot(u));
                let pw = c.map(|p| p.dot(w));
                let pr = c.map(|p| p.dot(ray));
                [
                    pu[0].min(pu[1]).min(pu[2]),
                    pu[0].max(pu[1]).max(pu[2]),
                    pw[0].min(pw[1]).min(pw[2]),
                    pw[0].max(pw[1]).max(pw[2]),
                    pr[0].max(pr[1]).max(pr[2]),
                ]
            })
            .collect();
        let (_, _, size) = super::samples::bounds(surface);
        WindingOracle {
            surface,
            ray,
            across: [u, w],
            extents,
            // From any point of interest (within a few sizes of the object) past the object.
            length: 16.0 * size,
        }
    }

    /// The winding number of `p`: leaving crossings minus entering ones along the ray.
    pub fn winding(&self, p: DVec3) -> i64 {
        let (pu, pw, pr) = (
            p.dot(self.across[0]),
            p.dot(self.across[1]),
            p.dot(self.ray),
        );
        // Relative slack in the prefilter, for the rounding of the projections.
        let slack = 1e-9 * (1.0 + pu.abs().max(pw.abs()));
        let length = self.length + (p.length() * 2.0);
        let segment = Segment::new(p, p + self.ray * length);
        let mut winding = 0;
        for (t, e) in self.extents.iter().enumerate() {
            if pu < e[0] - slack
                || pu > e[1] + slack
                || pw < e[2] - slack
                || pw > e[3] + slack
                || e[4] < pr - slack
            {
                continue;
            }
            if let Some(hit) =
                intersect_segment_triangle(&segment, self.surface.corners(TriId(t as u32)))
            {
                winding += if hit.entering { -1 } else { 1 };
            }
        }
        winding
    }
}

/// The distance from `p` to the surface (metres), by testing every triangle.
pub fn distance_to_surface(surface: &Surface, p: DVec3) -> f64 {
    crate::query::nearest_point_brute_force(surface, p).distance
}

/// First crossings by testing every triangle, with each triangle's bounding box tested
/// first (a slab test), so that a million segments against a hundred thousand triangles
/// stay affordable. Same answers as [`first_crossing_brute_force`]: the lowest `t`, then
/// the lowest triangle index.
///
/// [`first_crossing_brute_force`]: crate::query::first_crossing_brute_force
pub struct BruteCrossing<'a> {
    surface: &'a Surface,
    /// Per triangle: min corner, max corner.
    boxes: Vec<[DVec3; 2]>,
}

impl<'a> BruteCrossing<'a> {
    /// Prepares the boxes of `surface`'s triangles.
    pub fn new(surface: &'a Surface) -> BruteCrossing<'a> {
        let boxes = (0..surface.triangle_count() as u32)
            .map(|t| {
                let [a, b, c] = surface.corners(TriId(t));
                // Grown by a relative hair so rounding in the slab test never drops a hit.
                let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
                let pad = (hi - lo)
                    .max_element()
                    .max(hi.abs().max(lo.abs()).max_element())
                    * 1e-9;
                [lo - DVec3::splat(pad), hi + DVec3::splat(pad)]
            })
            .collect();
        BruteCrossing { surface, boxes }
    }

    /// The first crossing of the segment from `p0` to `p1`, testing every triangle whose
    /// box the segment meets.
    pub fn first_crossing(&self, p0: DVec3, p1: DVec3) -> Option<crate::query::Crossing> {
        let segment = Segment::new(p0, p1);
        let d = p1 - p0;
        let inv = DVec3::ONE / d;
        let mut best: Option<(crate::query::SegmentHit, u32)> = None;
        for (t, [lo, hi]) in self.boxes.iter().enumerate() {
            // Slab test on [0, 1] (infinities from zero components compare correctly;
            // NaN from 0 · ∞ is avoided by testing the degenerate axes separately).
            let mut t0 = 0.0f64;
            let mut t1 = 1.0f64;
            let mut hit = true;
            for k in 0..3 {
                if d[k] == 0.0 {
                    if p0[k] < lo[k] || p0[k] > hi[k] {
                        hit = false;
                        break;
                    }
                } else {
                    let (a, b) = ((lo[k] - p0[k]) * inv[k], (hi[k] - p0[k]) * inv[k]);
                    t0 = t0.max(a.min(b));
                    t1 = t1.min(a.max(b));
                    if t0 > t1 {
                        hit = false;
                        break;
                    }
                }
            }
            if !hit || best.is_some_and(|(b, _)| t0 > b.t) {
                continue;
            }
            if let Some(h) =
                intersect_segment_triangle(&segment, self.surface.corners(TriId(t as u32)))
                && best.is_none_or(|(b, _)| h.t < b.t)
            {
                best = Some((h, t as u32));
            }
        }
        best.map(|(hit, t)| crate::query::crossing_from_hit(self.surface, hit, t))
    }
}
