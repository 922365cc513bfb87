//! Stage 4–6 benches, one tick at a time: the proxy in steady contact with a procedural
//! blob and a 0.1 mm thin plate of about 10 000 triangles each, the proxy on an exploring
//! path (free space, touch-downs, strikes through the plate), a box pushing a resting
//! device point (a moving object, tested in its own frame), and a servo tick of the
//! simulated hand (device, scene, proxy and statistics together).
//!
//! The device paths come from the deterministic generators of `haphe::verify` and
//! `haphe::servo` with fixed seeds (1 kHz; 0.05–0.5 m/s and 0.5–3 mm deep in contact, as
//! the contact rows of `haphe bench`). Each iteration ticks the next device point of a
//! cycle with the proxy carried from tick to tick, so the figures are means over realistic
//! mixes rather than one repeated case.
//!
//! `cargo bench -p haphe --bench proxy`; `cargo test --benches` runs each once.

use std::hint::black_box;
use std::sync::Arc;

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::{self, Shape as Catalog};
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};
use haphe::servo::{HandOptions, PathKind, Servo, ServoOptions, SimulatedHand, scripted_path};
use haphe::verify::{haptic_path, haptic_path_in_contact};

/// Triangles of each benchmark mesh.
const TRIANGLES: usize = 10_000;
/// Device points of each path's cycle (ten seconds at 1 kHz).
const TICKS: usize = 10_000;
/// The servo rate, Hz.
const RATE_HZ: f64 = 1000.0;

/// A scene of one shape at the origin, its clear zones computed as a servo application
/// does when it loads a shape.
fn scene_of(surface: Surface) -> Scene {
    let shape = Shape::build(surface, &MapOptions::default()).expect("the map builds");
    shape.prepare_clear_zones();
    scene_with(Arc::new(shape))
}

/// A scene of the shared `shape` at the origin.
fn scene_with(shape: Arc<Shape>) -> Scene {
    let mut scene = Scene::local(4);
    let object = SceneObject::new(ObjectId(0), shape, Pose::IDENTITY, Material::default());
    scene
        .insert(object)
        .map_err(|(e, _)| e)
        .expect("room for it");
    scene
}

fn procedural(which: Catalog) -> Scene {
    let surface = Surface::new(which.with_triangles(TRIANGLES), &SurfaceOptions::default())
        .expect("a valid surface");
    scene_of(surface)
}

/// Ticks the proxy at the next point of `path` each iteration.
fn ticking<'a>(scene: &'a Scene, path: &'a [DVec3]) -> impl FnMut() -> DVec3 + 'a {
    let mut proxy = Proxy::new(path[0], ProxyOptions::default());
    let mut i = 0;
    move || {
        i = if i + 1 < path.len() { i + 1 } else { 0 };
        proxy.tick(scene, black_box(path[i]), DVec3::ZERO).force
    }
}

fn proxy_stage(c: &mut Criterion) {
    let blob = procedural(Catalog::Blob);
    let plate = procedural(Catalog::ThinPlate);
    let in_contact = |scene: &Scene| {
        haptic_path_in_contact(scene, TICKS, (0.05, 0.5), (0.0005, 0.003), RATE_HZ, 1)
    };
    let (blob_contact, plate_contact) = (in_contact(&blob), in_contact(&plate));
    let plate_exploring = haptic_path(&plate, TICKS, (0.01, 2.0), RATE_HZ, 2);

    let mut group = c.benchmark_group("proxy");
    group.bench_function("contact tick, blob", |b| {
        b.iter(ticking(&blob, &blob_contact))
    });
    group.bench_function("contact tick, thin plate", |b| {
        b.iter(ticking(&plate, &plate_contact))
    });
    group.bench_function("exploring tick, thin plate", |b| {
        b.iter(ticking(&plate, &plate_exploring))
    });
    group.finish();
}

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
            let pose = Pose::from_translation(DVec3::new(offsets[i], 0.0, 0.0));
            scene.begin_tick();
            scene.set_pose(ObjectId(0), pose);
            proxy.tick(&scene, black_box(hip), DVec3::ZERO).force
        })
    });
    group.finish();
}

/// The simulated hand exploring the blob for ten seconds at 1 kHz, from a fresh servo
/// each time (its clock only moves forward): device, proxy, force and statistics in each
/// tick. Criterion reports the time of the whole run and, as throughput, ticks per second.
fn servo_stage(c: &mut Criterion) {
    let blob = procedural(Catalog::Blob);
    let shape = Arc::clone(&blob.objects()[0].shape);
    let seconds = TICKS as f64 / RATE_HZ;
    let path = scripted_path(PathKind::Explore, &blob, seconds, 3).expect("a path");
    let fresh = || {
        let scene = scene_with(Arc::clone(&shape));
        let hand = SimulatedHand::new(path.clone(), HandOptions::default());
        let options = ServoOptions {
            rate_hz: RATE_HZ,
            ..ServoOptions::default()
        };
        Servo::new(hand, scene, options).expect("the servo starts")
    };
    let mut group = c.benchmark_group("servo");
    group.throughput(Throughput::Elements(TICKS as u64));
    group.sample_size(10);
    group.bench_function("simulated hand exploring the blob, 10 s at 1 kHz", |b| {
        b.iter_batched_ref(
            fresh,
            |servo| {
                (0..TICKS)
                    .map(|k| servo.tick_at(k as f64 / RATE_HZ).force.length())
                    .sum::<f64>()
            },
            BatchSize::PerIteration,
        )
    });
    group.finish();
}

criterion_group!(benches, proxy_stage, scene_stage, servo_stage);
criterion_main!(benches);
