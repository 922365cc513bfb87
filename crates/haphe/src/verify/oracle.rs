//! Brute-force oracles: every triangle tested, no map, no walk.

use glam::DVec3;

use crate::map::clip_to_box;
use crate::mesh::{Surface, TriId};
use crate::query::{Segment, intersect_segment_triangle, triangle_hit};

/// The direction of the oracle's rays: generic, so that no ray runs along the axis-aligned
/// faces and edges of CAD meshes.
const RAY_DIRECTION: [f64; 3] = [0.573_462_1, 0.623_182_7, 0.531_740_9];

/// Winding numbers by signed crossing counts: for a closed surface the number of crossings
/// of a ray from `p` going out minus those going in is the winding number of `p` (1 inside
/// an outward-oriented part, 2 where two overlap, −1 inside an inside-out part, 0
/// outside), exactly, with the same exact segment test the queries use. Inside is a
/// winding number other than 0 (the non-zero rule), as for
/// [`classify_point`](crate::query::classify_point).
///
/// # Performance
/// Written apart from the voxel map: the triangles are binned once on a 2D grid over the
/// plane across the ray, by their extents there (padded for rounding), so a query tests
/// only the triangles whose extents contain the point's projection — a few dozen on usual
/// meshes instead of all. The tests check it against the generalised winding number.
pub struct WindingOracle<'a> {
    surface: &'a Surface,
    ray: DVec3,
    across: [DVec3; 2],
    /// Per triangle: (min u, max u, min w, max w, max along the ray).
    extents: Vec<[f64; 5]>,
    length: f64,
    /// The bin grid over `(u, w)`: lower corner, bins per unit, bins per side.
    origin: [f64; 2],
    scale: [f64; 2],
    bins: [usize; 2],
    /// Triangles of bin `k` are `members[starts[k]..starts[k + 1]]`.
    starts: Vec<u32>,
    members: Vec<u32>,
    /// Largest `|u|, |w|` of any corner: slack in the bins.
    reach: f64,
}

/// Relative slack of the extent filter, for the rounding of the projections.
const PROJECTION_SLACK: f64 = 1e-9;

impl<'a> WindingOracle<'a> {
    /// Prepares the oracle for `surface`.
    pub fn new(surface: &'a Surface) -> WindingOracle<'a> {
        let ray = DVec3::from_array(RAY_DIRECTION).normalize();
        let u = ray.any_orthonormal_vector();
        let w = ray.cross(u);
        let extents: Vec<[f64; 5]> = (0..surface.triangle_count() as u32)
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
        let reach = extents
            .iter()
            .map(|e| e[0].abs().max(e[1].abs()).max(e[2].abs()).max(e[3].abs()))
            .fold(0.0, f64::max);
        // Twice the largest slack a query near the surface uses.
        let pad = 2.0 * PROJECTION_SLACK * (1.0 + reach);
        let lo = extents
            .iter()
            .fold([f64::INFINITY; 2], |m, e| [m[0].min(e[0]), m[1].min(e[2])]);
        let hi = extents.iter().fold([f64::NEG_INFINITY; 2], |m, e| {
            [m[0].max(e[1]), m[1].max(e[3])]
        });
        let side = ((extents.len() as f64).sqrt().ceil() as usize).clamp(1, 2048);
        let origin = [lo[0] - pad, lo[1] - pad];
        let span = [
            (hi[0] - lo[0] + 2.0 * pad).max(f64::MIN_POSITIVE),
            (hi[1] - lo[1] + 2.0 * pad).max(f64::MIN_POSITIVE),
        ];
        let bins = [side, side];
        let scale = [side as f64 / span[0], side as f64 / span[1]];
        let bin_range = |e: &[f64; 5]| {
            let index = |x: f64, k: usize| {
                (((x - origin[k]) * scale[k]).floor().max(0.0) as usize).min(bins[k] - 1)
            };
            (
                index(e[0] - pad, 0)..=index(e[1] + pad, 0),
                index(e[2] - pad, 1)..=index(e[3] + pad, 1),
            )
        };
        let mut counts = vec![0u32; bins[0] * bins[1] + 1];
        for e in &extents {
            let (iu, iw) = bin_range(e);
            for i in iu {
                for j in iw.clone() {
                    counts[i * bins[1] + j + 1] += 1;
                }
            }
        }
        for k in 1..counts.len() {
            counts[k] += counts[k - 1];
        }
        let starts = counts.clone();
        let mut members = vec![0u32; *counts.last().unwrap_or(&0) as usize];
        for (t, e) in extents.iter().enumerate() {
            let (iu, iw) = bin_range(e);
            for i in iu {
                for j in iw.clone() {
                    let k = i * bins[1] + j;
                    members[counts[k] as usize] = t as u32;
                    counts[k] += 1;
                }
            }
        }
        WindingOracle {
            surface,
            ray,
            across: [u, w],
            extents,
            // From any point of interest (within a few sizes of the object) past the object.
            length: 16.0 * size,
            origin,
            scale,
            bins,
            starts,
            members,
            reach,
        }
    }

    /// The winding number of `p`: leaving crossings minus entering ones along the ray.
    pub fn winding(&self, p: DVec3) -> i64 {
        let (pu, pw, pr) = (
            p.dot(self.across[0]),
            p.dot(self.across[1]),
            p.dot(self.ray),
        );
        let slack = PROJECTION_SLACK * (1.0 + pu.abs().max(pw.abs()));
        // The bins cover every extent padded by twice the slack of any point with
        // |u|, |w| ≤ 1 + 2·reach; a point farther out (whose slack is larger) scans all.
        let mut cell = [0usize; 2];
        let mut binned = true;
        for (k, x) in [pu, pw].into_iter().enumerate() {
            let f = (x - self.origin[k]) * self.scale[k];
            if f >= 0.0 && f < self.bins[k] as f64 {
                cell[k] = f as usize;
            } else {
                binned = false;
            }
        }
        let all: Vec<u32>;
        let members: &[u32] = if binned {
            let k = cell[0] * self.bins[1] + cell[1];
            &self.members[self.starts[k] as usize..self.starts[k + 1] as usize]
        } else if pu.abs().max(pw.abs()) <= 1.0 + 2.0 * self.reach {
            // Outside the padded range of every extent: the ray meets nothing.
            return 0;
        } else {
            all = (0..self.extents.len() as u32).collect();
            &all
        };
        let length = self.length + (p.length() * 2.0);
        let segment = Segment::new(p, p + self.ray * length);
        let mut winding = 0;
        for &t in members {
            let e = &self.extents[t as usize];
            if pu < e[0] - slack
                || pu > e[1] + slack
                || pw < e[2] - slack
                || pw > e[3] + slack
                || e[4] < pr - slack
            {
                continue;
            }
            if let Some(hit) = intersect_segment_triangle(&segment, self.surface.corners(TriId(t)))
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
    boxes: TriangleBounds,
}

impl<'a> BruteCrossing<'a> {
    /// Prepares the boxes of `surface`'s triangles.
    pub fn new(surface: &'a Surface) -> BruteCrossing<'a> {
        BruteCrossing {
            surface,
            boxes: TriangleBounds::new(surface),
        }
    }

    /// The first crossing of the segment from `p0` to `p1`, testing every triangle whose
    /// box the segment meets.
    pub fn first_crossing(&self, p0: DVec3, p1: DVec3) -> Option<crate::query::Crossing> {
        self.boxes
            .first_crossing_where(self.surface, p0, p1, |_| true)
    }
}

/// The bounding box of every triangle of a surface, grown by a relative hair: a slab test
/// against them skips most triangles of a brute-force crossing query without changing its
/// answer.
pub(crate) struct TriangleBounds {
    /// Per triangle: min corner, max corner.
    boxes: Vec<[DVec3; 2]>,
}

impl TriangleBounds {
    /// The boxes of `surface`'s triangles.
    pub(crate) fn new(surface: &Surface) -> TriangleBounds {
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
        TriangleBounds { boxes }
    }

    /// The first crossing of the segment from `p0` to `p1` with `surface` (whose boxes
    /// these are) that `accept` keeps, testing every triangle whose box the segment meets:
    /// the same answer as [`first_crossing_brute_force_where`], lowest `t`, then lowest
    /// triangle index.
    ///
    /// [`first_crossing_brute_force_where`]: crate::query::first_crossing_brute_force_where
    pub(crate) fn first_crossing_where(
        &self,
        surface: &Surface,
        p0: DVec3,
        p1: DVec3,
        accept: impl Fn(&crate::query::SegmentHit) -> bool,
    ) -> Option<crate::query::Crossing> {
        let segment = Segment::new(p0, p1);
        let d = p1 - p0;
        let inv = DVec3::ONE / d;
        let mut best: Option<(crate::query::SegmentHit, u32)> = None;
        for (t, [lo, hi]) in self.boxes.iter().enumerate() {
            let Some((t0, _)) = clip_to_box(p0, d, inv, *lo, *hi) else {
                continue;
            };
            if best.is_some_and(|(b, _)| t0 > b.t) {
                continue;
            }
            let tri = TriId(t as u32);
            if let Some(h) = triangle_hit(surface, tri, (p0, p1), || segment)
                && accept(&h)
                && best.is_none_or(|(b, _)| h.t < b.t)
            {
                best = Some((h, t as u32));
            }
        }
        best.map(|(hit, t)| crate::query::crossing_from_hit(surface, hit, t))
    }

    /// The first contact of the sphere of `radius` swept from `a` to `b` with `surface`
    /// (whose boxes these are), testing every triangle whose box comes within
    /// `radius + reach` of the segment's box: the same answer as
    /// [`first_sphere_contact_brute_force`](crate::query::first_sphere_contact_brute_force).
    pub(crate) fn first_sphere_contact(
        &self,
        surface: &Surface,
        (a, b): (DVec3, DVec3),
        (radius, reach): (f64, f64),
        one_sided: bool,
    ) -> Option<crate::query::SphereContact> {
        let g = DVec3::splat(radius + reach);
        let (lo, hi) = (a.min(b) - g, a.max(b) + g);
        let mut best = None;
        for (t, [tlo, thi]) in self.boxes.iter().enumerate() {
            if (tlo.cmpgt(hi) | thi.cmplt(lo)).any() {
                continue;
            }
            crate::query::consider_sphere(
                surface,
                TriId(t as u32),
                (a, b),
                (radius, reach),
                one_sided,
                &mut best,
            );
        }
        best
    }
}
