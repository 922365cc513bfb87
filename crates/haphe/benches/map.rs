//! Stage 2 benches: build a voxel map, encode it with its surface, decode (load and check)
//! the saved bytes, on a procedural blob of about 10 000 triangles; and refresh a map
//! after a deformation (group `refresh`): a patch of 1 % of the vertices and every vertex
//! moved on a blob of 200 000 triangles (a build, and made locally all the same), and the patch on 20 000 and 1 000 000 beside a
//! build on the same grid (throughput: moved triangles per second).
//!
//! `cargo bench -p haphe --bench map`; `cargo bench -p haphe --bench map -- refresh`;
//! `cargo test --benches` runs each once.

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use haphe::DVec3;
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

/// A blob of `triangles` triangles with its map.
fn blob(triangles: usize) -> (Surface, VoxelMap) {
    let surface = Surface::new(
        Catalog::Blob.with_triangles(triangles),
        &SurfaceOptions::default(),
    )
    .expect("the blob is a valid surface");
    let map = VoxelMap::build(&surface, &MapOptions::default()).expect("the map builds");
    (surface, map)
}

/// The vertices of `surface` with a patch of `share` of them (those nearest the first
/// vertex) pushed a cell of `h` metres toward the centre: a dent.
fn patch(surface: &Surface, share: f64, h: f64) -> Vec<DVec3> {
    let mut vertices = surface.vertices().to_vec();
    let at = vertices[0];
    let mut by_distance: Vec<usize> = (0..vertices.len()).collect();
    by_distance.sort_by(|&a, &b| {
        vertices[a]
            .distance_squared(at)
            .total_cmp(&vertices[b].distance_squared(at))
    });
    let count = (share * vertices.len() as f64).ceil() as usize;
    for &v in &by_distance[..count] {
        let inward = vertices[v].normalize_or_zero() * h;
        vertices[v] -= inward;
    }
    vertices
}

fn refresh(c: &mut Criterion) {
    let mut group = c.benchmark_group("refresh");
    group.sample_size(10);
    for triangles in [20_000, 200_000, 1_000_000] {
        let (surface, map) = blob(triangles);
        let h = map.grid().cell_size();
        let mut cases = vec![("patch 1%", patch(&surface, 0.01, h))];
        if triangles == 200_000 {
            // Breathing: every vertex, scaled about the centre (within the grid).
            let all = surface.vertices().iter().map(|&p| 0.98 * p).collect();
            cases.push(("all", all));
        }
        for (name, vertices) in cases {
            let (moved_surface, moved) = surface.deformed_with_moved(vertices);
            group.throughput(Throughput::Elements(moved.len() as u64));
            group.bench_function(format!("{triangles} {name}"), |b| {
                b.iter(|| {
                    map.refreshed_after(black_box(&surface), black_box(&moved_surface), &moved)
                })
            });
            if name == "all" {
                // Made locally all the same (`refreshed` builds when most triangles moved).
                group.bench_function(format!("{triangles} {name} (local)"), |b| {
                    b.iter(|| {
                        map.refreshed_locally(
                            black_box(&surface),
                            black_box(&moved_surface),
                            &moved,
                        )
                    })
                });
            }
        }
        group.throughput(Throughput::Elements(triangles as u64));
        group.bench_function(format!("{triangles} build on the grid"), |b| {
            b.iter(|| map.built_on_this_grid(black_box(&surface)))
        });
    }
    group.finish();
}

criterion_group!(benches, map_stage, refresh);
criterion_main!(benches);
