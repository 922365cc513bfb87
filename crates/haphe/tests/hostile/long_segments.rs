//! Segments far longer than the object: the same first crossing as the brute force at
//! every length (they used to report an exit for an entry from about 3e11 m, and nothing
//! from 3e12 m).

use haphe::map::{MapOptions, VoxelMap};
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::query::{first_crossing, first_crossing_brute_force};
use haphe::rng::SplitMix64;

#[test]
fn far_segments_agree_with_the_brute_force() {
    let surface = Surface::new(
        Catalog::Blob.with_triangles(2_000),
        &SurfaceOptions::default(),
    )
    .expect("surface");
    let map = VoxelMap::build(&surface, &MapOptions::default()).expect("map");
    let mut rng = SplitMix64::new(7);
    let mut unit = || rng.unit_vector();
    let mut checked = 0;
    for exponent in 0..=15 {
        let far = 10f64.powi(exponent);
        for _ in 0..40 {
            // From far away, through a point near the object, to far beyond it.
            let through = unit() * 0.05;
            let direction = unit();
            let (p0, p1) = (through - direction * far, through + direction * 0.5);
            let fast = first_crossing(&surface, &map, p0, p1);
            let slow = first_crossing_brute_force(&surface, p0, p1);
            assert_eq!(
                fast.map(|c| (c.triangle, c.entering)),
                slow.map(|c| (c.triangle, c.entering)),
                "from {far:e} m: {p0} -> {p1}"
            );
            checked += usize::from(slow.is_some());
        }
    }
    assert!(checked > 300, "only {checked} segments crossed");
}
