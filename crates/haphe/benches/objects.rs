//! The object-count series, one tick at a time: a hand pressing and sliding on one sphere
//! of a cubic grid of spheres sharing one shape (the scene of `haphe bench --objects-only`
//! and of example 08), static, and with a thousand objects moved every tick by key or by
//! name. A tick is what the servo thread runs: `begin_tick`, the moves, the proxy tick.
//!
//! `cargo bench -p haphe --bench objects`; `cargo test --benches` runs it once.

use std::hint::black_box;
use std::sync::Arc;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::scene::{Material, ObjectId, ObjectKey, Pose, Scene, SceneObject, Shape};

/// Distance between neighbouring spheres (0.1 m radius), metres.
const SPACING: f64 = 0.25;
/// Objects moved every tick in the moving configurations.
const MOVING: usize = 1_000;

/// How the moving objects are moved.
#[derive(Clone, Copy)]
enum Moves {
    None,
    ByKey,
    ByName,
}

/// Where object `k` of a grid of `side`³ sits.
fn grid(k: usize, side: usize) -> DVec3 {
    let (x, y, z) = (k % side, (k / side) % side, k / (side * side));
    DVec3::new(x as f64, y as f64, z as f64) * SPACING
}

fn scene(shape: &Arc<Shape>, objects: usize) -> (Scene, Vec<(ObjectKey, DVec3)>) {
    let side = (1..).find(|s: &usize| s.pow(3) >= objects).unwrap_or(1);
    let material = Material::builder()
        .stiffness(1000.0)
        .damping(1.0)
        .build()
        .expect("a valid material");
    let mut scene = Scene::local(objects);
    for k in 0..objects {
        let pose = Pose::from_translation(grid(k, side)).expect("a valid pose");
        let o = SceneObject::new(ObjectId(k as u32), Arc::clone(shape), pose, material);
        scene.insert(o).expect("room");
    }
    // The movers spread over the grid; the touched sphere (0) is not among them.
    let movers = MOVING.min(objects - 1);
    let moving = (0..movers)
        .map(|m| {
            let k = 1 + m * (objects - 1) / movers;
            (ObjectKey::new(ObjectId(k as u32)), grid(k, side))
        })
        .collect();
    (scene, moving)
}

fn object_ticks(c: &mut Criterion) {
    let surface = Surface::new(
        Catalog::Sphere.with_triangles(1_000),
        &SurfaceOptions::default(),
    )
    .expect("a valid surface");
    let shape = Arc::new(Shape::build(surface, &MapOptions::default()).expect("the map builds"));
    shape.prepare_clear_zones();
    let mut group = c.benchmark_group("objects");
    for (objects, moves) in [
        (1, Moves::None),
        (10_000, Moves::None),
        (10_000, Moves::ByKey),
        (10_000, Moves::ByName),
    ] {
        let (mut scene, mut moving) = scene(&shape, objects);
        let mut proxy = Proxy::new(DVec3::new(0.0, 0.0, 0.2), ProxyOptions::default());
        let name = match moves {
            Moves::None => "static",
            Moves::ByKey => "1000 moving by key",
            Moves::ByName => "1000 moving by name",
        };
        let mut t = 0usize;
        group.bench_function(BenchmarkId::new(name, objects), |b| {
            b.iter(|| {
                t += 1;
                scene.begin_tick();
                let wobble = DVec3::new(0.0, 0.0, 1e-3 * (t as f64 * 0.01).sin());
                match moves {
                    Moves::None => {}
                    Moves::ByKey => {
                        for (key, at) in &mut moving {
                            scene.set_pose_keyed(
                                key,
                                Pose::from_translation(*at + wobble).expect("a valid pose"),
                            );
                        }
                    }
                    Moves::ByName => {
                        for (key, at) in &moving {
                            scene.set_pose(
                                key.id(),
                                Pose::from_translation(*at + wobble).expect("a valid pose"),
                            );
                        }
                    }
                }
                // Pressing about 6 mm into the corner sphere, sliding in a 4 cm circle.
                let s = t as f64 * 2e-3;
                let hip = DVec3::new(0.04 * s.cos(), 0.04 * s.sin(), 0.085);
                proxy.tick(&scene, black_box(hip), DVec3::ZERO).force
            })
        });
    }
    group.finish();
}

criterion_group!(benches, object_ticks);
criterion_main!(benches);
