//! The triangles near a tool, kept from one tick to the next: every triangle of a shape
//! within a distance of a centre, nearest first. While the tool's moves stay near that
//! centre, its sweeps and its touching search test only the first few of them (those that
//! can come within the tool's reach) instead of every triangle of the map's cells around
//! it, with the same answers. The coherence between ticks of König & Strothotte, for a
//! tool with a size.

use glam::DVec3;

use super::bounds::beyond_bounds;
use super::closest::closest_point_triangle;
use super::sweep::{Seen, SphereContact, consider as consider_sphere};
use crate::map::{CellBox, VoxelMap};
use crate::mesh::{Surface, TriId};

/// Most triangles kept: where more lie within the distance asked, the nearest are kept
/// and the distance shrinks to what they cover.
pub(crate) const NEAR_TOOL_TRIANGLES: usize = 96;

/// The triangles of one shape near a centre (object frame), nearest first.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ToolNear {
    /// The surface they belong to ([`Surface::uid`]), `None` when empty.
    shape: Option<u64>,
    centre: DVec3,
    /// Every triangle nearer than this to the centre is listed, metres.
    complete_to: f64,
    /// More triangles lay within the distance asked than are kept.
    capped: bool,
    len: usize,
    /// Distance from the centre and triangle, by distance then index.
    items: [(f64, u32); NEAR_TOOL_TRIANGLES],
}

impl ToolNear {
    /// Nothing kept.
    pub(crate) const EMPTY: ToolNear = ToolNear {
        shape: None,
        centre: DVec3::ZERO,
        complete_to: 0.0,
        capped: false,
        len: 0,
        items: [(0.0, 0); NEAR_TOOL_TRIANGLES],
    };

    /// Whether the kept triangles are those of `surface`.
    #[inline]
    pub(crate) fn is_of(&self, surface: &Surface) -> bool {
        self.shape == Some(surface.uid())
    }

    /// Whether gathering around `at` for `surface` may help: not when the triangles kept
    /// there were too many to keep all within the distance asked and were gathered less
    /// than `radius` away (gathering again would find as many).
    #[inline]
    pub(crate) fn worth_gathering(&self, surface: &Surface, at: DVec3, radius: f64) -> bool {
        !(self.is_of(surface) && self.capped && self.centre.distance(at) < radius)
    }

    /// Keeps the triangles of `surface` within `distance` of `centre` (object frame),
    /// found in the map's cells of the cube around it (or, when those would cost more,
    /// in every triangle), at most [`NEAR_TOOL_TRIANGLES`] of them, the nearest.
    ///
    /// # Real-time
    /// No allocation, no panic: one closest-point kernel per triangle listed near the
    /// centre that the plane and the sphere round its corners do not rule out.
    pub(crate) fn gather(
        &mut self,
        surface: &Surface,
        map: &VoxelMap,
        centre: DVec3,
        distance: f64,
    ) {
        *self = ToolNear::EMPTY;
        if !(centre.is_finite() && distance.is_finite() && distance > 0.0) {
            return;
        }
        self.shape = Some(surface.uid());
        self.centre = centre;
        self.complete_to = distance;
        if beyond_bounds(surface, centre, centre, distance) {
            return;
        }
        let g = DVec3::splat(distance);
        let cells = CellBox::around(map.grid(), centre - g, centre + g);
        let budget = 4u64.saturating_mul(surface.triangle_count() as u64);
        match map.clip_cells(cells) {
            None => {}
            Some(c) if c.count() > budget => {
                for t in 0..surface.triangle_count() as u32 {
                    self.offer(surface, t);
                }
            }
            Some(_) => {
                let mut seen = Seen::new();
                map.visit_cells(cells, |c, triangles| {
                    if super::sweep::cell_beyond(map.grid(), c, centre, self.complete_to) {
                        return;
                    }
                    for &t in triangles.iter().filter(|&&t| seen.first_time(t)) {
                        self.offer(surface, t);
                    }
                });
            }
        }
        self.items[..self.len].sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        // A triangle listed in several cells was offered as often: once is enough.
        let mut kept = 0;
        for k in 0..self.len {
            if kept == 0 || self.items[kept - 1].1 != self.items[k].1 {
                self.items[kept] = self.items[k];
                kept += 1;
            }
        }
        self.len = kept;
    }

    /// Lists triangle `t` when it lies nearer than `complete_to`; when the list is full,
    /// keeps the nearer half and shrinks `complete_to` to what they cover.
    #[inline]
    fn offer(&mut self, surface: &Surface, t: u32) {
        let corners = surface.corners(TriId(t));
        let face = surface.frame(TriId(t)).normal;
        if face.dot(self.centre - corners[0]).abs() >= self.complete_to
            || super::sweep::beyond_sphere(corners, (self.centre, DVec3::ZERO), self.complete_to)
        {
            return;
        }
        let d = self
            .centre
            .distance(closest_point_triangle(self.centre, corners).point);
        if d >= self.complete_to {
            return;
        }
        if self.len == NEAR_TOOL_TRIANGLES {
            // Full (duplicates included): keep those nearer than the median.
            let items = &mut self.items[..];
            items.select_nth_unstable_by(NEAR_TOOL_TRIANGLES / 2, |a, b| a.0.total_cmp(&b.0));
            let median = items[NEAR_TOOL_TRIANGLES / 2].0;
            let mut kept = 0;
            for k in 0..NEAR_TOOL_TRIANGLES {
                if items[k].0 < median {
                    items[kept] = items[k];
                    kept += 1;
                }
            }
            self.len = kept;
            self.complete_to = median;
            self.capped = true;
            if d >= self.complete_to {
                return;
            }
        }
        self.items[self.len] = (d, t);
        self.len += 1;
    }

    /// How far from the centre a triangle may lie and still come within `grow` of a point
    /// of the segment `a → b`; `None` when that reaches beyond what is kept.
    #[inline]
    fn limit(&self, (a, b): (DVec3, DVec3), grow: f64) -> Option<f64> {
        let e = self.centre.distance(a).max(self.centre.distance(b));
        // A margin far above the rounding of the distances compared.
        let limit = (grow + e) * (1.0 + 1e-9) + 1e-15;
        (limit < self.complete_to).then_some(limit)
    }

    /// [`first_sphere_contact`](super::first_sphere_contact) of `surface` (whose
    /// triangles these are) from the kept triangles, when they hold every triangle the
    /// sweep could touch; `None` when they do not (the caller searches the map).
    #[inline]
    pub(crate) fn first_contact(
        &self,
        surface: &Surface,
        (a, b): (DVec3, DVec3),
        (radius, reach, one_sided): (f64, f64, bool),
    ) -> Option<Option<SphereContact>> {
        let limit = self.limit((a, b), radius + reach)?;
        let mut best = None;
        for &(d, t) in &self.items[..self.len] {
            if d > limit {
                break;
            }
            consider_sphere(
                surface,
                TriId(t),
                (a, b),
                (radius, reach),
                one_sided,
                &mut best,
            );
        }
        Some(best)
    }

    /// The nearest triangle within `grow` of `p` (the touching search of a tool, the
    /// answer of [`nearest_within`](super::nearest_within)) from the kept triangles, when
    /// they hold every triangle that near; `None` when they do not.
    #[inline]
    pub(crate) fn nearest(
        &self,
        surface: &Surface,
        p: DVec3,
        grow: f64,
    ) -> Option<Option<super::NearTriangle>> {
        let limit = self.limit((p, p), grow)?;
        let mut best = None;
        for &(d, t) in &self.items[..self.len] {
            if d > limit {
                break;
            }
            super::near::consider(surface, TriId(t), p, grow, &mut best);
        }
        Some(best)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::MapOptions;
    use crate::mesh::{SurfaceOptions, shapes};
    use crate::query::{first_sphere_contact_brute_force, nearest_within_brute_force};
    use crate::rng::SplitMix64;

    /// Kept near a centre, the answers for moves and points near it equal brute force;
    /// farther away there is no answer from the list.
    #[test]
    fn answers_equal_brute_force_near_the_centre() {
        for triangles in [3, 6] {
            let mesh = shapes::sphere(0.05, triangles);
            let surface = Surface::new(mesh, &SurfaceOptions::default()).unwrap();
            let map = VoxelMap::build(&surface, &MapOptions::default()).unwrap();
            let mut rng = SplitMix64::new(2);
            let (mut answered, mut declined) = (0, 0);
            for i in 0..600 {
                let radius = [0.001, 0.004, 0.01][i % 3];
                let centre = rng.unit_vector() * (0.05 + radius * rng.range(0.8, 1.5));
                let mut near = ToolNear::EMPTY;
                near.gather(&surface, &map, centre, radius * 2.0);
                for _ in 0..10 {
                    let a = centre + rng.unit_vector() * radius * rng.range(0.0, 0.8);
                    let b = a + rng.unit_vector() * radius * rng.range(0.0, 0.8);
                    let sphere = (radius, 1e-7, false);
                    match near.first_contact(&surface, (a, b), sphere) {
                        Some(c) => {
                            let brute = first_sphere_contact_brute_force(
                                &surface,
                                (a, b),
                                radius,
                                1e-7,
                                false,
                            );
                            assert_eq!(c, brute, "{a:?} {b:?} {radius}");
                            answered += 1;
                        }
                        None => declined += 1,
                    }
                    if let Some(n) = near.nearest(&surface, b, radius) {
                        assert_eq!(n, nearest_within_brute_force(&surface, b, radius));
                    }
                }
            }
            assert!(answered > 1000 && declined > 10, "{answered} {declined}");
        }
    }
}
