//! Clear zones: a move they clear keeps farther than the probe's reach from every triangle
//! (checked by brute force), concave places are never cleared, the shape's cache holds
//! what a fresh computation gives, and a proxy sliding in contact uses them.

use std::sync::Arc;

use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions, TriId};
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::query::{
    ClearZone, ZONE_SPREAD, first_crossing_brute_force, nearest_within_brute_force,
};
use haphe::rng::SplitMix64;
use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};
use haphe::verify::haptic_path_in_contact;

fn shape(which: Catalog, triangles: usize) -> Shape {
    let surface = Surface::new(which.with_triangles(triangles), &SurfaceOptions::default())
        .expect("a usable surface");
    Shape::build(surface, &MapOptions::default()).expect("a map")
}

/// A point over triangle `t` at barycentric weights drawn in `[-spread, 1 + spread]` and
/// `height` metres over its plane.
fn point_over(shape: &Shape, t: TriId, rng: &mut SplitMix64, spread: f64, height: f64) -> DVec3 {
    let [a, b, c] = shape.surface().corners(t);
    let u = rng.range(-spread, 1.0 + spread);
    let v = rng.range(-spread, 1.0 + spread);
    a + u * (b - a) + v * (c - a) + height * shape.surface().frame(t).normal
}

/// Every move a zone clears, with its probe lengthened by `reach` at both ends, crosses no
/// triangle and ends farther than `reach` from every triangle (brute force over all of
/// them; the move is also sampled along its length). Moves are drawn over each triangle's
/// neighbourhood, at heights from the surface to a few skins, on both sides, and some
/// long enough to leave the zone.
#[test]
fn cleared_moves_keep_clear_of_every_triangle() {
    let mut rng = SplitMix64::new(7);
    for which in Catalog::ALL {
        let shape = shape(which, 2000);
        let n = shape.surface().triangle_count();
        let (mut cleared, mut tried) = (0, 0);
        for _ in 0..3000 {
            let t = TriId(rng.index(n) as u32);
            let skin = 10f64.powf(rng.range(-7.0, -5.0));
            let reach = 0.25 * skin;
            let side = if rng.next_unit() < 0.2 { -1.0 } else { 1.0 };
            let h0 = side * skin * rng.range(0.0, 2.0);
            let h1 = side * skin * rng.range(0.0, 2.0);
            let from = point_over(&shape, t, &mut rng, 0.6 * ZONE_SPREAD, h0);
            let to = point_over(&shape, t, &mut rng, 0.6 * ZONE_SPREAD, h1);
            tried += 1;
            if !shape
                .clear_zone(t)
                .clears(shape.surface().frame(t), from, to, reach)
            {
                continue;
            }
            cleared += 1;
            let u = (to - from).normalize_or_zero();
            let surface = shape.surface();
            assert!(
                first_crossing_brute_force(surface, from - reach * u, to + reach * u).is_none(),
                "{which}: a cleared move of triangle {t:?} crosses the surface"
            );
            for k in 0..=8 {
                let x = from.lerp(to, f64::from(k) / 8.0);
                assert!(
                    nearest_within_brute_force(surface, x, reach).is_none(),
                    "{which}: a cleared move of triangle {t:?} passes within reach of a triangle"
                );
            }
        }
        // Not vacuous: many of these moves lie over convex or flat parts.
        println!("{which}: {cleared} of {tried} moves cleared");
        assert!(
            cleared * 8 > tried,
            "{which}: only {cleared} of {tried} moves cleared"
        );
    }
}

/// In the concave corner some zones see a face rising over their plane: no move there is
/// cleared at the heights a proxy keeps, so the searches run where they are needed.
#[test]
fn zones_see_concave_corners() {
    let shape = shape(Catalog::ConcaveCorner, 2000);
    let n = shape.surface().triangle_count();
    let risen = (0..n)
        .map(|t| shape.clear_zone(TriId(t as u32)))
        .filter(|z| z.front > 1e-4)
        .count();
    assert!(
        risen > 0,
        "no zone of the concave corner sees a face over it"
    );
    // A flat-faced box has no such zone (its faces meet at convex edges only).
    let cube = self::shape(Catalog::Box, 2000);
    let largest = (0..cube.surface().triangle_count())
        .map(|t| cube.clear_zone(TriId(t as u32)).front)
        .fold(0.0f32, f32::max);
    assert!(
        largest < 1e-9,
        "a box face sees something over it: {largest}"
    );
}

/// The cache gives what a fresh computation gives; preparing computes each zone once.
#[test]
fn the_cache_holds_fresh_zones() {
    let shape = shape(Catalog::Torus, 3000);
    let n = shape.surface().triangle_count();
    assert_eq!(
        shape.clear_zone(TriId(5)),
        ClearZone::of(shape.surface(), shape.map(), TriId(5))
    );
    assert_eq!(shape.prepare_clear_zones(), n - 1);
    assert_eq!(shape.prepare_clear_zones(), 0);
    for t in (0..n).step_by(7) {
        let t = TriId(t as u32);
        assert_eq!(
            shape.clear_zone(t),
            ClearZone::of(shape.surface(), shape.map(), t)
        );
    }
    assert_eq!(shape.clear_zone(TriId(n as u32)), ClearZone::NONE);
}

/// A proxy sliding in steady contact over the blob moves through clear zones in most
/// ticks (the status says so), without a search.
#[test]
fn a_sliding_proxy_moves_through_clear_zones() {
    let shape = Arc::new(shape(Catalog::Blob, 5000));
    let mut scene = Scene::local(1);
    let object = SceneObject::new(ObjectId(0), shape, Pose::IDENTITY, Material::default());
    scene.insert(object).map_err(|(e, _)| e).expect("room");
    let path = haptic_path_in_contact(&scene, 3000, (0.05, 0.5), (0.0005, 0.003), 1e3, 3);
    let mut proxy = Proxy::new(path[0], ProxyOptions::default());
    let (mut contact, mut cleared) = (0, 0);
    for &hip in &path {
        let out = proxy.tick(&scene, hip, DVec3::ZERO);
        contact += usize::from(out.contact.is_some());
        cleared += usize::from(out.contact.is_some() && out.status.cleared);
    }
    assert!(contact > 2500, "only {contact} ticks in contact");
    assert!(
        cleared * 2 > contact,
        "only {cleared} of {contact} contact ticks cleared"
    );
}
