use glam::{DAffine3, DVec3};
use rustc_hash::FxHashMap;

use super::{Chunk, Chunks, extract_chunk};
use crate::mesh::{Mesh, Surface, SurfaceOptions, Usability};
use crate::rng::SplitMix64;
use crate::volume::Volume;

/// A volume of `dims` voxels of `h` metres whose values come from `f` (voxel indices).
fn volume_of(dims: [usize; 3], h: f64, f: impl Fn([f64; 3]) -> f32) -> Volume {
    let mut values = Vec::with_capacity(dims.iter().product());
    for k in 0..dims[2] {
        for j in 0..dims[1] {
            for i in 0..dims[0] {
                values.push(f([i as f64, j as f64, k as f64]));
            }
        }
    }
    let to_world = DAffine3::from_scale(DVec3::splat(h));
    Volume::new(dims, values, to_world, 0.0).expect("a valid volume")
}

/// The distance field of a ball of radius `r` voxels about `centre` (voxels): positive
/// inside, in voxels.
fn ball(centre: [f64; 3], r: f64) -> impl Fn([f64; 3]) -> f32 {
    move |p| (r - DVec3::from(p).distance(DVec3::from(centre))) as f32
}

/// The whole grid extracted as one chunk.
fn single_chunk(volume: &Volume) -> Mesh {
    let dims = volume.dims();
    let chunk: Chunk = extract_chunk(volume, [[-1; 3], dims.map(|n| n as i64)]);
    Chunks {
        dims,
        counts: [1, 1, 1],
        chunks: vec![chunk],
    }
    .mesh()
}

/// Asserts that `mesh` is a closed, consistently oriented 2-manifold without degenerate
/// triangles: each directed edge once, and its reverse once; and the crate's report says
/// the same.
fn assert_closed(mesh: &Mesh, context: &str) {
    assert!(!mesh.triangles.is_empty(), "{context}: no triangle");
    let mut directed: FxHashMap<(u32, u32), u32> = FxHashMap::default();
    for t in &mesh.triangles {
        for e in 0..3 {
            *directed.entry((t[e], t[(e + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &directed {
        assert_eq!(n, 1, "{context}: edge {a}→{b} used {n} times");
        assert_eq!(
            directed.get(&(b, a)),
            Some(&1),
            "{context}: {a}→{b} unpaired"
        );
    }
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(t);
        assert!(
            (b - a).cross(c - a).length() > 0.0,
            "{context}: triangle {t} has no area"
        );
    }
    let surface = Surface::new(mesh.clone(), &SurfaceOptions::default()).expect("a surface");
    let report = surface.report();
    assert!(report.closed, "{context}: {:?}", report.problems());
    assert_eq!(
        report.usable_as,
        Usability::Solid,
        "{context}: {:?}",
        report.problems()
    );
    assert_eq!(report.nonmanifold_edges, 0, "{context}");
    assert_eq!(report.nonmanifold_vertices, 0, "{context}");
    assert_eq!(report.orientation_conflicts, 0, "{context}");
    assert_eq!(report.degenerate_triangles, 0, "{context}");
}

/// The volume a closed mesh encloses (divergence theorem), m³.
fn enclosed(mesh: &Mesh) -> f64 {
    (0..mesh.triangles.len())
        .map(|t| {
            let [a, b, c] = mesh.corners(t);
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

/// The triangles as position triples (bits), each rotated to start at its least corner
/// (keeping its orientation), sorted.
fn sorted_triangles(mesh: &Mesh) -> Vec<[[u64; 3]; 3]> {
    let mut all: Vec<[[u64; 3]; 3]> = (0..mesh.triangles.len())
        .map(|t| {
            let mut c = mesh.corners(t).map(|p| p.to_array().map(f64::to_bits));
            let least = (0..3).min_by_key(|&i| c[i]).unwrap_or(0);
            c.rotate_left(least);
            c
        })
        .collect();
    all.sort_unstable();
    all
}

#[test]
fn a_ball_is_closed_round_and_of_its_volume() {
    let (h, r, centre) = (0.001, 20.3, [24.2, 23.9, 24.6]);
    let volume = volume_of([50, 50, 50], h, ball(centre, r));
    let chunks = Chunks::extract(&volume);
    assert_eq!(chunks.chunk_count(), 8);
    let mesh = chunks.mesh();
    assert_eq!(mesh.triangles.len(), chunks.triangle_count());
    assert_closed(&mesh, "ball");
    let c = DVec3::from(centre) * h;
    for p in &mesh.vertices {
        let off = (p.distance(c) - r * h).abs();
        assert!(off < 0.5 * h, "vertex {p} is {off} m off the sphere");
    }
    let exact = 4.0 / 3.0 * std::f64::consts::PI * (r * h).powi(3);
    let error = (enclosed(&mesh) - exact).abs() / exact;
    assert!(error < 0.01, "volume off by {error}");
}

#[test]
fn chunks_meet_without_cracks_and_equal_one_chunk() {
    // A ball crossing the chunk faces at 31, edges and the corner (31, 31, 31), and a
    // second one crossing the faces at 63.
    let a = ball([31.0, 31.0, 31.0], 12.7);
    let b = ball([60.5, 58.0, 40.0], 9.1);
    let volume = volume_of([70, 70, 70], 0.002, |p| a(p).max(b(p)));
    let chunks = Chunks::extract(&volume);
    assert_eq!(chunks.chunks_per_axis(), [3, 3, 3]);
    let mesh = chunks.mesh();
    assert_closed(&mesh, "two balls over chunks");
    assert_eq!(
        sorted_triangles(&mesh),
        sorted_triangles(&single_chunk(&volume))
    );
}

#[test]
fn material_at_the_border_is_closed() {
    let volume = volume_of([5, 6, 40], 0.01, |_| 1.0);
    let mesh = Chunks::extract(&volume).mesh();
    assert_closed(&mesh, "a full grid");
    // Each face lies 1/64 of a voxel beyond the grid's border voxels (the air beyond
    // is -inf), bevelled along the edges.
    let (inner, out) = (4.0 * 5.0 * 39.0 * 1e-6, 2.0 / 64.0);
    let outer = (4.0 + out) * (5.0 + out) * (39.0 + out) * 1e-6;
    let v = enclosed(&mesh);
    assert!(inner < v && v < outer, "{inner} < {v} < {outer}");
}

#[test]
fn a_mirroring_affine_keeps_the_surface_facing_out() {
    let mut volume = volume_of([20, 20, 20], 0.001, ball([9.5, 9.0, 10.2], 6.3));
    volume.to_world = DAffine3::from_scale(DVec3::new(-0.001, 0.001, 0.001));
    let mesh = Chunks::extract(&volume).mesh();
    assert_closed(&mesh, "mirrored ball");
    assert!(enclosed(&mesh) > 0.0);
}

#[test]
fn random_values_are_closed() {
    let mut rng = SplitMix64::new(7);
    let volume = volume_from_draws([41, 37, 35], || rng_value(&mut rng));
    let chunks = Chunks::extract(&volume);
    let mesh = chunks.mesh();
    assert_closed(&mesh, "random values");
    assert_eq!(
        sorted_triangles(&mesh),
        sorted_triangles(&single_chunk(&volume))
    );
}

/// A value in −1..1, a quarter of them rounded to exactly 0 (the iso).
fn rng_value(rng: &mut SplitMix64) -> f32 {
    let v = rng.range(-1.0, 1.0) as f32;
    if rng.index(4) == 0 { 0.0 } else { v }
}

/// A volume of `dims` voxels of a millimetre whose values are drawn in order.
fn volume_from_draws(dims: [usize; 3], mut draw: impl FnMut() -> f32) -> Volume {
    let values = (0..dims.iter().product::<usize>())
        .map(|_| draw())
        .collect();
    Volume::new(dims, values, DAffine3::from_scale(DVec3::splat(0.001)), 0.0)
        .expect("a valid volume")
}

#[test]
fn values_at_iso_and_infinite_are_closed_without_degenerate_triangles() {
    let mut rng = SplitMix64::new(11);
    let choices = [f32::NEG_INFINITY, f32::INFINITY, 0.0, 1.0, -1.0, 0.0];
    let volume = volume_from_draws([36, 34, 33], || choices[rng.index(choices.len())]);
    let mesh = Chunks::extract(&volume).mesh();
    assert_closed(&mesh, "iso and infinite values");
    // Values exactly at iso everywhere: all material, a box.
    let volume = volume_from_draws([4, 4, 4], || 0.0);
    assert_closed(&Chunks::extract(&volume).mesh(), "all at iso");
}

#[test]
fn random_values_over_two_chunks_are_closed() {
    let mut rng = SplitMix64::new(3);
    let volume = volume_from_draws([66, 33, 34], || rng_value(&mut rng));
    assert_closed(&Chunks::extract(&volume).mesh(), "random values, 66 wide");
}

#[test]
fn refresh_equals_a_fresh_extraction_and_touches_only_its_chunks() {
    let mut volume = volume_of([70, 70, 70], 0.001, ball([35.0, 34.0, 36.0], 25.0));
    let mut chunks = Chunks::extract(&volume);
    // Carve a small ball of air about voxel (31, 32, 12): the box 28..=34, 29..=35,
    // 9..=15 meets cells 27..=34 along x (chunks 0 and 1), 28..=35 along y (0 and 1),
    // 8..=15 along z (0).
    let (lo, hi) = ([28, 29, 9], [34, 35, 15]);
    let dims = volume.dims();
    for k in lo[2]..=hi[2] {
        for j in lo[1]..=hi[1] {
            for i in lo[0]..=hi[0] {
                let d = DVec3::new(i as f64 - 31.0, j as f64 - 32.0, k as f64 - 12.0).length();
                let at = (i + dims[0] as i64 * (j + dims[1] as i64 * k)) as usize;
                volume.values[at] = volume.values[at].min((d - 2.5) as f32);
            }
        }
    }
    assert_eq!(chunks.refresh(&volume, lo, hi), 4);
    let fresh = Chunks::extract(&volume).mesh();
    assert_closed(&fresh, "carved ball");
    assert_eq!(sorted_triangles(&chunks.mesh()), sorted_triangles(&fresh));
    assert_eq!(chunks.mesh(), fresh);
    // Inside one chunk, at the grid's corner, beyond the grid.
    assert_eq!(chunks.refresh(&volume, [40, 40, 40], [45, 45, 45]), 1);
    assert_eq!(chunks.refresh(&volume, [0, 0, 0], [0, 0, 0]), 1);
    assert_eq!(chunks.refresh(&volume, [69, 69, 69], [80, 80, 80]), 1);
    assert_eq!(chunks.refresh(&volume, [70, 70, 70], [80, 80, 80]), 0);
    assert_eq!(chunks.refresh(&volume, [-5, -5, -5], [200, 200, 200]), 27);
}

#[test]
fn no_material_no_triangles() {
    let volume = volume_from_draws([10, 10, 10], || -1.0);
    let chunks = Chunks::extract(&volume);
    assert_eq!(chunks.triangle_count(), 0);
    assert!(chunks.mesh().vertices.is_empty());
}

#[test]
fn a_volume_becomes_a_solid_shape() {
    let volume = volume_of([30, 30, 30], 0.001, ball([14.0, 15.0, 14.5], 9.6));
    let options = crate::map::MapOptions::default();
    let shape = volume.shape("ball", &options).expect("a shape");
    assert!(shape.is_solid());
    let empty = volume_from_draws([4, 4, 4], || -1.0);
    let error = empty.shape("air", &options).expect_err("no triangle");
    assert!(error.to_string().starts_with("air: "), "{error}");
}
