//! What the clear zones decide without a search: a proxy move that meets nothing
//! ([`Scene::clear_move`]) and the first hit of a move into the convex surface under the
//! proxy ([`Scene::first_hit_shown`]). Both give exactly what the searches would.

use glam::DVec3;

use super::broad::Near;
use super::hit::{Hit, SurfaceRef};
use super::object::{BOUND_SLACK, SceneObject, Sides};
use super::world::Scene;
use crate::mesh::TriId;
use crate::query::{
    ClearZone, Probe, Segment, crossing_from_hit, distance_to_segment, triangle_hit,
};

/// Smallest barycentric weight of a crossing that [`Scene::first_hit_shown`] takes as
/// strictly inside its triangle: far above the rounding of the weights, so that no
/// neighbour shares the point.
const INSIDE_WEIGHT: f64 = 1e-6;

impl Scene {
    /// Whether the proxy move `from → to` (world frame) provably meets no surface of any
    /// object, with every probe of it reaching `reach` metres: both ends lie in the
    /// [`ClearZone`] of the triangle `on` (the surface the proxy slides on), and every
    /// other object's bounding sphere is farther than `reach` from the move (the others
    /// taken from `near`, a superset of those whose bounding sphere comes within
    /// [`others_box`] of the move). Then [`Scene::first_hit`] finds nothing for any object
    /// and [`Scene::touching`] finds nothing at `to`, so a tick may skip both searches.
    /// `false` whenever that is not shown (including `on` out of range).
    ///
    /// # Real-time
    /// One zone (computed on the triangle's first use, see
    /// [`Shape::clear_zone`](super::Shape::clear_zone)), two frame changes, one sphere test
    /// per other object; no allocation, no panic.
    pub(crate) fn clear_move(
        &self,
        near: &Near,
        on: SurfaceRef,
        from: DVec3,
        to: DVec3,
        reach: f64,
    ) -> bool {
        let SurfaceRef {
            object: i,
            triangle,
        } = on;
        let Some((o, zone)) = self.zone_of(i, triangle) else {
            return false;
        };
        if !zone.clears(
            o.shape.surface().frame(triangle),
            o.pose.to_object(from),
            o.pose.to_object(to),
            reach,
        ) {
            return false;
        }
        self.others_beyond(near, i, from, to, reach)
    }

    /// [`first_hit`](Scene::first_hit) over every object, when it can be shown without a
    /// search to be a crossing of triangle `triangle` of object `i` (the triangle under
    /// the proxy at `from`): the move's probe starts in front of that triangle, in its
    /// [`ClearZone`], whose neighbourhood lies on or behind its plane and outside the
    /// triangle (`below`), and enters it strictly inside; every other object's bounding
    /// sphere is farther from the move than the reach. Then nothing else is crossed
    /// before, and the hit is the one the search would return, bit for bit. `None` when
    /// that is not shown.
    ///
    /// # Real-time
    /// One zone, one triangle test, a bounding-sphere test per other object.
    pub(crate) fn first_hit_shown(
        &self,
        near: &Near,
        under: SurfaceRef,
        from: DVec3,
        to: DVec3,
        reach: f64,
    ) -> Option<Hit> {
        let SurfaceRef {
            object: i,
            triangle,
        } = under;
        let (o, zone) = self.zone_of(i, triangle)?;
        let surface = o.shape.surface();
        if !zone.below || !self.others_beyond(near, i, from, to, reach) {
            return None;
        }
        let one_sided = o.sides == Sides::Front;
        let probe = Probe::new(from, to, reach, one_sided);
        let (a, b) = (o.pose.to_object(probe.p0), o.pose.to_object(probe.p1));
        // The probe from its start to the crossing lies in the zone: its start is in the
        // zone in front of the plane, and the crossing inside the triangle.
        if !zone.holds_in_front(surface.frame(triangle), a) {
            return None;
        }
        let hit = triangle_hit(surface, triangle, (a, b), || Segment::new(a, b))?;
        // Entering (decided exactly: the probe lies in front of the plane up to the
        // crossing, where no other triangle of the zone reaches) and strictly inside (no
        // neighbour shares the point).
        if !(hit.entering && hit.weights.iter().all(|&w| w > INSIDE_WEIGHT)) {
            return None;
        }
        let c = crossing_from_hit(surface, hit, triangle.0);
        Some(Hit::of_crossing(i, &o.pose, &probe, &c))
    }

    /// Object `i` and the clear zone of its triangle `triangle`; `None` when either is
    /// out of range.
    #[inline]
    fn zone_of(&self, i: usize, triangle: TriId) -> Option<(&SceneObject, ClearZone)> {
        let o = self.objects.get(i)?;
        (triangle.index() < o.shape.surface().triangle_count())
            .then(|| (o, o.shape.clear_zone(triangle)))
    }

    /// Whether every object but `i` keeps its bounding sphere farther than `reach` (and
    /// the rounding of coordinates) from the move `from → to` (world frame); the others
    /// are taken from `near`, a superset of those near [`others_box`].
    fn others_beyond(&self, near: &Near, i: usize, from: DVec3, to: DVec3, reach: f64) -> bool {
        // A scene of one object (`i`, in range in every caller): no other.
        if self.objects.len() == 1 {
            return true;
        }
        near.indices(self.objects.len()).all(|j| {
            let other = &self.objects[j];
            j == i || {
                let shape = &*other.shape;
                let centre = other.pose.to_world(shape.bound_centre());
                // Twice the reach, and the rounding of coordinates far from the origin.
                let slack = 2.0 * reach + 1e-12 * centre.abs().max_element().max(1.0);
                distance_to_segment(centre, [from, to]) > shape.bound_radius() * BOUND_SLACK + slack
            }
        })
    }
}

/// The box around the move `from → to` within which an object's bounding sphere must come
/// to count in [`Scene::clear_move`]: the move's box grown by three reaches (the test uses
/// two; the broad phase adds the rounding of coordinates).
pub(crate) fn others_box(from: DVec3, to: DVec3, reach: f64) -> (DVec3, DVec3) {
    let m = DVec3::splat(3.0 * reach.max(0.0));
    (from.min(to) - m, from.max(to) + m)
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::map::MapOptions;
    use crate::mesh::shapes::Catalog;
    use crate::mesh::{Surface, SurfaceOptions};
    use crate::rng::SplitMix64;
    use crate::scene::{Material, ObjectId, Pose, SceneObject, Shape};

    fn scene_of(which: Catalog, triangles: usize, pose: Pose) -> Scene {
        let surface = Surface::new(which.with_triangles(triangles), &SurfaceOptions::default())
            .expect("a usable surface");
        let shape = Arc::new(Shape::build(surface, &MapOptions::default()).expect("a map"));
        let mut scene = Scene::local(2);
        add(&mut scene, 0, shape, pose);
        scene
    }

    fn add(scene: &mut Scene, id: u32, shape: Arc<Shape>, pose: Pose) {
        scene
            .insert(SceneObject::new(
                ObjectId(id),
                shape,
                pose,
                Material::default(),
            ))
            .map_err(|(e, _)| e)
            .expect("room");
    }

    /// Legs as a proxy's first leg of a tick: from about a skin over a triangle (over its
    /// neighbourhood, some of them) into the surface, millimetres deep and askew. Wherever
    /// the shortcut answers, its hit is the search's, bit for bit. It answers on most legs
    /// over the sphere, the blob, the plate and the flat parts of the concave corner (axis
    /// planes: a neighbour in the plane is shown beside the face exactly), never on the
    /// torus (its planar quads are tilted: a neighbour in the plane is within rounding).
    #[test]
    fn a_shown_hit_is_the_searched_hit() {
        let mut rng = SplitMix64::new(11);
        let pose = Pose::from_translation(DVec3::new(0.3, -0.2, 0.1)).unwrap();
        for (which, least_share) in [
            (Catalog::Sphere, 0.5),
            (Catalog::Blob, 0.5),
            (Catalog::Torus, 0.0),
            (Catalog::ConcaveCorner, 0.4),
            (Catalog::ThinPlate, 0.5),
        ] {
            let scene = scene_of(which, 3000, pose);
            let surface = scene.objects()[0].shape.surface();
            let n = surface.triangle_count();
            let (mut shown, mut legs) = (0, 0);
            for _ in 0..4000 {
                let t = TriId(rng.index(n) as u32);
                let [a, b, c] = surface.corners(t);
                let normal = surface.frame(t).normal;
                let (u, v) = (rng.range(-0.2, 1.0), rng.range(-0.2, 1.0));
                let (u, v) = if u + v > 1.0 {
                    (1.0 - u, 1.0 - v)
                } else {
                    (u, v)
                };
                let skin = 1e-6;
                let on = a + u * (b - a) + v * (c - a);
                let from = on + normal * skin * rng.range(0.5, 1.5);
                let aside = rng.unit_vector() * rng.range(0.0, 2e-3);
                let to = on - normal * rng.range(5e-4, 3e-3) + aside;
                let (from, to) = (pose.to_world(from), pose.to_world(to));
                let reach = 0.25 * skin;
                legs += 1;
                if let Some(hit) = scene.first_hit_shown(
                    &Near::ALL,
                    SurfaceRef {
                        object: 0,
                        triangle: t,
                    },
                    from,
                    to,
                    reach,
                ) {
                    shown += 1;
                    assert_eq!(
                        Some(hit),
                        scene.first_hit(0, from, to, reach),
                        "{which:?} triangle {t:?}"
                    );
                }
            }
            let share = f64::from(shown) / f64::from(legs);
            println!("{which:?}: {shown} of {legs} legs shown");
            assert!(share >= least_share, "{which:?}: {share}");
            if which == Catalog::Torus {
                // Tilted planar quads: a neighbour lies in the plane, within rounding.
                assert_eq!(shown, 0);
            }
        }
    }

    /// Another object near the move, a triangle out of range, or a start behind the
    /// triangle: no shortcut.
    #[test]
    fn no_shortcut_when_not_shown() {
        let mut scene = scene_of(Catalog::Sphere, 2000, Pose::IDENTITY);
        let surface = scene.objects()[0].shape.surface();
        let t = TriId(7);
        let [a, b, c] = surface.corners(t);
        let normal = surface.frame(t).normal;
        let on = (a + b + c) / 3.0;
        let (from, to) = (on + normal * 1e-6, on - normal * 2e-3);
        assert!(
            scene
                .first_hit_shown(
                    &Near::ALL,
                    SurfaceRef {
                        object: 0,
                        triangle: t
                    },
                    from,
                    to,
                    2.5e-7
                )
                .is_some()
        );
        assert!(
            scene
                .first_hit_shown(
                    &Near::ALL,
                    SurfaceRef {
                        object: 0,
                        triangle: TriId(1 << 30)
                    },
                    from,
                    to,
                    2.5e-7
                )
                .is_none()
        );
        assert!(
            scene
                .first_hit_shown(
                    &Near::ALL,
                    SurfaceRef {
                        object: 3,
                        triangle: t
                    },
                    from,
                    to,
                    2.5e-7
                )
                .is_none()
        );
        assert!(
            scene
                .first_hit_shown(
                    &Near::ALL,
                    SurfaceRef {
                        object: 0,
                        triangle: t
                    },
                    to,
                    from,
                    2.5e-7
                )
                .is_none()
        );
        let shape = Arc::clone(&scene.objects()[0].shape);
        add(
            &mut scene,
            1,
            shape,
            Pose::from_translation(on + normal * 0.05).unwrap(),
        );
        assert!(
            scene
                .first_hit_shown(
                    &Near::ALL,
                    SurfaceRef {
                        object: 0,
                        triangle: t
                    },
                    from,
                    to,
                    2.5e-7
                )
                .is_none()
        );
    }
}
