//! Stage 2 benches: build a voxel map, encode it with its surface, decode (load and check)
//! the saved bytes, on a procedural blob of about 10 000 triangles.
//!
//! `cargo bench -p haphe --bench map`; `cargo test --benches` runs each once.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use haphe::map::{MapOptions, VoxelMap, decode, encode};
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};

/// Triangles of the benchmark mesh.
const TRIANGLES: usize = 10_000;

fn map_stage(c: &mut Criterion) {
    let surface = Surface::new(
        Catalog::Blob.with_triangles(TRIANGLES),
        &SurfaceOptions::default(),
    )
    .expect("the blob is a valid surface");
    let options = MapOptions::default();
    let map = VoxelMap::build(&surface, &options).expect("the map builds");
    let bytes = encode(&surface, &map);

    let mut group = c.benchmark_group("map");
    group.bench_function("build", |b| {
        b.iter(|| VoxelMap::build(black_box(&surface), &options))
    });
    group.bench_function("encode", |b| {
        b.iter(|| encode(black_box(&surface), black_box(&map)))
    });
    group.bench_function("decode", |b| b.iter(|| decode(black_box(&bytes))));
    group.finish();
}

criterion_group!(benches, map_stage);
criterion_main!(benches);
