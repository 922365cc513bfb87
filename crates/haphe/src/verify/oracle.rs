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
