//! Stage 5 bench, one tick at a time: a moving object pushing the proxy. The object's
//! pose changes every tick and the proxy's motion relative to it is tested in its frame.
//!
//! `cargo bench -p haphe --bench scene`; `cargo test --benches` runs it once.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use haphe::DVec3;
use haphe::mesh::shapes;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::scene::{ObjectId, Pose};

mod common;
use common::scene_of;

/// A 10 cm box moving at 1 m/s along x into a device point that rests 5 mm before its
/// face, and back: every tick sets the pose, and the proxy is carried in the box's frame.
/// The point is off the box's vertices and edges: a device point that moves exactly
/// through a vertex makes every crossing test there decide by exact arithmetic (about
/// six times the cost of this case, counted with callgrind).
fn scene_stage(c: &mut Criterion) {
    let half = DVec3::new(0.05, 0.05, 0.05);
    let surface = Surface::new(shapes::cuboid(half, [8, 8, 8]), &SurfaceOptions::default())
        .expect("a valid surface");
    let mut scene = scene_of(surface);
    let hip = DVec3::new(0.055, 0.0031, -0.0017);
    let mut proxy = Proxy::new(hip, ProxyOptions::default());
    // 1 mm a tick: 20 ticks forward (15 mm into the device point), 20 back.
    let offsets: Vec<f64> = (0..40)
        .map(|k| 1e-3 * f64::from(20 - (k - 20i32).abs()))
        .collect();
    let mut i = 0;
    let mut group = c.benchmark_group("scene");
    group.bench_function("box pushing a resting device point", |b| {
        b.iter(|| {
            i = if i + 1 < offsets.len() { i + 1 } else { 0 };
            let pose =
                Pose::from_translation(DVec3::new(offsets[i], 0.0, 0.0)).expect("a valid pose");
            scene.begin_tick();
            scene.set_pose(ObjectId(0), pose);
            proxy.tick(&scene, black_box(hip), DVec3::ZERO).force
        })
    });
    group.finish();
}

criterion_group!(benches, scene_stage);
criterion_main!(benches);
