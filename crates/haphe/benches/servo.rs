//! Stage 6 bench: servo ticks of the simulated hand (device, scene, proxy, force and
//! statistics together), as the servo loop runs them but without its clock.
//!
//! `cargo bench -p haphe --bench servo`; `cargo test --benches` runs it once.

use std::sync::Arc;

use criterion::{BatchSize, Criterion, Throughput, criterion_group, criterion_main};
use haphe::mesh::shapes::Catalog;
use haphe::servo::{HandOptions, PathKind, Servo, ServoOptions, SimulatedHand, scripted_path};

mod common;
use common::{RATE_HZ, TICKS, procedural, scene_with};

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
        let options = ServoOptions::new(RATE_HZ).expect("a valid rate");
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

criterion_group!(benches, servo_stage);
criterion_main!(benches);
