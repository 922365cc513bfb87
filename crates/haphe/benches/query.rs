//! Stage 3 benches, one query at a time on a procedural blob of about 10 000 triangles:
//! the closest point on one triangle (the floor every query is compared with), the
//! watertight segment–triangle test, segment crossing through the map, inside/outside,
//! one coherent step of the surface walk, and the proxy's touching search (the nearest
//! triangle within a quarter micrometre) near and on the surface.
//!
//! The inputs come from the deterministic generators of `haphe::verify` with fixed seeds:
//! coherent trajectories near the surface (steps of 0.05–0.5 mm, a hand at 0.05–0.5 m/s
//! sampled at 1 kHz) and, for the kernels, the triangle the walk is on at each step. Each
//! iteration takes the next input of a cycle, so the figures are means over realistic
//! mixes rather than one repeated case.
//!
//! `cargo bench -p haphe --bench query`; `cargo test --benches` runs each once.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use haphe::DVec3;
use haphe::map::{MapOptions, VoxelMap};
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions, TriId};
use haphe::proxy::ProxyOptions;
use haphe::query::{
    Segment, classify_point, closest_point_triangle, first_crossing, intersect_segment_triangle,
    nearest_within_bounded, walk_to_nearest,
};
use haphe::verify::{bounds, trajectory};

/// Triangles of the benchmark mesh.
const TRIANGLES: usize = 10_000;
/// Trajectories and steps per trajectory of the input cycle.
const TRAJECTORIES: u64 = 16;
const STEPS: usize = 250;
/// Seed of the first trajectory.
const SEED: u64 = 0x00BE_0C40;

/// One coherent step: the triangle the walk stood on, the previous and the new position,
/// and the surface point nearest to the new one.
struct Step {
    triangle: TriId,
    from: DVec3,
    to: DVec3,
    on: DVec3,
}

/// The steps of the input cycle, with the triangle of each step found by walking.
fn steps(surface: &Surface) -> Vec<Step> {
    // 0.05–0.5 mm on a 0.2 m object, scaled with the object.
    let scale = bounds(surface).2 / (0.2 * 3f64.sqrt());
    let mut steps = Vec::new();
    for k in 0..TRAJECTORIES {
        let (mut t, targets) =
            trajectory(surface, STEPS, (0.05e-3 * scale, 0.5e-3 * scale), SEED + k);
        for pair in targets.windows(2) {
            let walked = walk_to_nearest(surface, t, pair[1]).0;
            steps.push(Step {
                triangle: t,
                from: pair[0],
                to: pair[1],
                on: walked.point,
            });
            t = walked.triangle;
        }
    }
    steps
}

/// Calls `f` on the next element of `items` each iteration.
fn cycle<'a, T, R>(items: &'a [T], mut f: impl FnMut(&'a T) -> R) -> impl FnMut() -> R {
    let mut i = 0;
    move || {
        i = if i + 1 < items.len() { i + 1 } else { 0 };
        f(black_box(&items[i]))
    }
}

fn query_stage(c: &mut Criterion) {
    let surface = Surface::new(
        Catalog::Blob.with_triangles(TRIANGLES),
        &SurfaceOptions::default(),
    )
    .expect("the blob is a valid surface");
    let map = VoxelMap::build(&surface, &MapOptions::default()).expect("the map builds");
    let steps = steps(&surface);
    let (surface, map) = (&surface, &map);

    let mut group = c.benchmark_group("query");
    group.bench_function("closest_point_triangle", |b| {
        b.iter(cycle(&steps, |s| {
            closest_point_triangle(s.to, surface.corners(s.triangle))
        }))
    });
    group.bench_function("intersect_segment_triangle", |b| {
        b.iter(cycle(&steps, |s| {
            intersect_segment_triangle(&Segment::new(s.from, s.to), surface.corners(s.triangle))
        }))
    });
    group.bench_function("first_crossing", |b| {
        b.iter(cycle(&steps, |s| {
            first_crossing(surface, map, s.from, s.to)
        }))
    });
    group.bench_function("classify_point", |b| {
        b.iter(cycle(&steps, |s| classify_point(surface, map, s.to)))
    });
    group.bench_function("walk_to_nearest_coherent_step", |b| {
        b.iter(cycle(&steps, |s| {
            walk_to_nearest(surface, s.triangle, s.to)
        }))
    });
    let reach = ProxyOptions::default().probe_reach();
    group.bench_function("nearest_within_reach_near_surface", |b| {
        b.iter(cycle(&steps, |s| {
            nearest_within_bounded(surface, map, s.to, reach)
        }))
    });
    group.bench_function("nearest_within_reach_on_surface", |b| {
        b.iter(cycle(&steps, |s| {
            nearest_within_bounded(surface, map, s.on, reach)
        }))
    });
    group.finish();
}

criterion_group!(benches, query_stage);
criterion_main!(benches);
