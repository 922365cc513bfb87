//! Stage 7 benches: the iso-surface of a volume and the volume of a mesh, on a ball of
//! radius 50 voxels in a 128³ grid (a distance field): one 32³ chunk re-extracted where
//! the surface crosses it (`Chunks::refresh` of one voxel), every chunk extracted, and a
//! 20 000-triangle sphere voxelised at 128 voxels across (`Volume::from_shape`).
//!
//! `cargo bench -p haphe --bench volume` (`-- --quick` for a first look); `cargo test
//! --benches` runs each once.

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use haphe::DVec3;
use haphe::glam::DAffine3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::scene::Shape;
use haphe::volume::{Chunks, Volume};

/// Voxels along each axis of the benchmark volume.
const N: usize = 128;
/// Voxels across the voxelised sphere.
const ACROSS: f64 = 128.0;
/// Triangles of the voxelised sphere.
const TRIANGLES: usize = 20_000;

/// A ball of radius 50 voxels (of a millimetre) centred in an `N`³ grid: its distance
/// field, positive inside.
fn ball() -> Volume {
    let centre = DVec3::splat(0.5 * (N - 1) as f64);
    let mut values = Vec::with_capacity(N * N * N);
    for k in 0..N {
        for j in 0..N {
            for i in 0..N {
                let p = DVec3::new(i as f64, j as f64, k as f64);
                values.push((50.0 - p.distance(centre)) as f32);
            }
        }
    }
    let to_world = DAffine3::from_scale(DVec3::splat(0.001));
    Volume::new([N; 3], values, to_world, 0.0).expect("a valid volume")
}

fn extract(c: &mut Criterion) {
    let volume = ball();
    let mut chunks = Chunks::extract(&volume);
    let mut group = c.benchmark_group("volume");
    group.sample_size(10);
    // Voxel (112, 72, 72) is on the sphere and a corner of cells in chunk (3, 2, 2) only.
    let voxel = [112, 72, 72];
    assert_eq!(chunks.refresh(&volume, voxel, voxel), 1);
    group.bench_function("refresh one chunk", |b| {
        b.iter(|| chunks.refresh(black_box(&volume), voxel, voxel))
    });
    group.throughput(Throughput::Elements((N * N * N) as u64));
    group.bench_function("extract 128^3", |b| {
        b.iter(|| Chunks::extract(black_box(&volume)))
    });
    group.finish();
}

fn voxelise(c: &mut Criterion) {
    let mesh = Catalog::Sphere.with_triangles(TRIANGLES);
    let shape = Shape::from_mesh("sphere", mesh, &MapOptions::default()).expect("a shape");
    let voxel = 2.0 * shape.bound_radius() / ACROSS;
    let mut group = c.benchmark_group("volume");
    group.sample_size(10);
    group.bench_function("voxelise 20k-triangle sphere at 128 across", |b| {
        b.iter(|| Volume::from_shape(black_box(&shape), voxel))
    });
    group.finish();
}

criterion_group!(benches, extract, voxelise);
criterion_main!(benches);
