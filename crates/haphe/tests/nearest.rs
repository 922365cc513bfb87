//! `nearest_within` is exact for any radius, whatever the map's cell size: it equals the
//! brute-force oracle on the real meshes and on a sphere, for points on the surface,
//! within a cell of it and many cells away, and radii from a fraction of a cell to past
//! the whole object.

mod support;

use haphe::DVec3;
use haphe::map::{MapOptions, VoxelMap};
use haphe::mesh::{ReadOptions, Surface, SurfaceOptions, TriId, read_mesh, shapes};
use haphe::query::{nearest_within, nearest_within_bounded, nearest_within_brute_force};
use haphe::rng::SplitMix64;
use proptest::prelude::*;

fn object(mesh: haphe::mesh::Mesh, cell_size_m: Option<f64>) -> (Surface, VoxelMap) {
    let surface = Surface::new(mesh, &SurfaceOptions::default()).expect("valid surface");
    let options = MapOptions {
        cell_size_m,
        ..MapOptions::default()
    };
    let map = VoxelMap::build(&surface, &options).expect("map");
    (surface, map)
}

/// A point of triangle `t` (random barycentric weights), moved by `offset` along a random
/// direction.
fn point_near(surface: &Surface, rng: &mut SplitMix64, offset: f64) -> DVec3 {
    let c = surface.corners(TriId(rng.index(surface.triangle_count()) as u32));
    let w = [rng.next_unit(), rng.next_unit(), rng.next_unit()];
    let s: f64 = w.iter().sum::<f64>().max(1e-12);
    (c[0] * w[0] + c[1] * w[1] + c[2] * w[2]) / s + rng.unit_vector() * offset
}

/// Compares the two on `n` points at distances from a thousandth of a cell to several
/// object sizes, with radii on the same scale; returns how many found a triangle.
fn compare(name: &str, surface: &Surface, map: &VoxelMap, n: usize, seed: u64) -> usize {
    let h = map.grid().cell_size();
    let (lo, hi) = surface.bounds();
    let size = (hi - lo).max_element();
    let mut rng = SplitMix64::new(seed);
    let mut found = 0;
    for _ in 0..n {
        // Log-uniform offsets and radii between 1e-3 cells and twice the object.
        let scale = |rng: &mut SplitMix64| {
            let top = (2.0 * size / h).log10().max(1.0);
            h * 10f64.powf(rng.range(-3.0, top))
        };
        let offset = scale(&mut rng);
        let p = point_near(surface, &mut rng, offset);
        let radius = scale(&mut rng);
        let fast = nearest_within(surface, map, p, radius);
        assert_eq!(
            fast,
            nearest_within_brute_force(surface, p, radius),
            "{name}: p {p:?} radius {radius} (cell {h})"
        );
        found += usize::from(fast.is_some());
    }
    found
}

#[test]
fn equals_brute_force_on_the_real_meshes_at_many_distances() {
    for (name, path) in support::model_files() {
        let bytes = std::fs::read(&path).expect("readable");
        let mesh = read_mesh(&name, &bytes, &ReadOptions::default()).expect("reads");
        let Ok(surface) = Surface::new(mesh, &SurfaceOptions::default()) else {
            continue;
        };
        // Fewer points on the larger meshes: the oracle tests every triangle.
        let n = (2_000_000 / surface.triangle_count()).clamp(40, 400);
        let map = VoxelMap::build(&surface, &MapOptions::default()).expect("map");
        let found = compare(&name, &surface, &map, n, 3);
        assert!(
            found > n / 4,
            "{name}: only {found} of {n} found a triangle"
        );
    }
}

#[test]
fn finds_a_surface_many_cells_away_where_the_servo_variant_does_not() {
    // A fine grid: a point 30 cells off the sphere, with a radius of 100 cells.
    let (surface, map) = object(shapes::sphere(0.1, 3), Some(0.002));
    let p = DVec3::new(0.0, 0.0, 0.16);
    let near = nearest_within(&surface, &map, p, 0.2).expect("the sphere is 0.06 m away");
    let oracle = nearest_within_brute_force(&surface, p, 0.2).expect("within reach");
    assert_eq!(near, oracle);
    // The sphere's top is at 0.1 m, up to its facets' sag.
    assert!((near.distance - 0.06).abs() < 1e-3, "{near:?}");
    assert_eq!(nearest_within_bounded(&surface, &map, p, 0.2), None);
    // Asking less than the distance finds nothing, with either.
    assert_eq!(nearest_within(&surface, &map, p, 0.05), None);
}

#[test]
fn a_fine_grid_and_a_large_radius_fall_back_to_every_triangle_exactly() {
    // Points far outside a fine grid's object, with radii past the whole object: the
    // rings would visit more cells than there are triangles.
    let (surface, map) = object(shapes::sphere(0.1, 2), Some(0.001));
    compare("fine sphere", &surface, &map, 200, 5);
    for p in [DVec3::new(0.3, 0.0, 0.0), DVec3::new(-0.2, 0.25, 0.1)] {
        assert_eq!(
            nearest_within(&surface, &map, p, 1.0),
            nearest_within_brute_force(&surface, p, 1.0)
        );
        assert!(nearest_within(&surface, &map, p, 1.0).is_some());
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn equals_brute_force_anywhere_on_a_coarse_and_a_fine_grid(
        x in -0.4f64..0.4, y in -0.4f64..0.4, z in -0.4f64..0.4,
        log_radius in -6.0f64..0.0,
        fine in any::<bool>(),
    ) {
        let mesh = shapes::cuboid(DVec3::new(0.1, 0.06, 0.03), [4, 3, 2]);
        let (surface, map) = object(mesh, fine.then_some(0.003));
        let p = DVec3::new(x, y, z);
        let radius = 10f64.powf(log_radius);
        prop_assert_eq!(
            nearest_within(&surface, &map, p, radius),
            nearest_within_brute_force(&surface, p, radius)
        );
    }
}
