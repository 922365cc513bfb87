//! Stage 4 benches, one tick at a time: the proxy in steady contact with a procedural
//! blob and a 0.1 mm thin plate of about 10 000 triangles each, and the proxy on an
//! exploring path (free space, touch-downs, strikes through the plate).
//!
//! The device paths come from the deterministic generators of `haphe::verify` with fixed
//! seeds (1 kHz; 0.05–0.5 m/s and 0.5–3 mm deep in contact, as the contact rows of `haphe
//! bench`). Each iteration ticks the next device point of a cycle with the proxy carried
//! from tick to tick, so the figures are means over realistic mixes rather than one
//! repeated case.
//!
//! `cargo bench -p haphe --bench proxy`; `cargo test --benches` runs each once.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use haphe::DVec3;
use haphe::mesh::shapes::Catalog;
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::scene::Scene;
use haphe::verify::{haptic_path, haptic_path_in_contact, lifted_for_tool};

mod common;
use common::{RATE_HZ, TICKS, procedural};

/// Ticks the proxy at the next point of `path` each iteration.
fn ticking<'a>(scene: &'a Scene, path: &'a [DVec3]) -> impl FnMut() -> DVec3 + 'a {
    tool_ticking(scene, path, 0.0)
}

/// Ticks a tool of `radius` metres at the next point of `path` each iteration.
fn tool_ticking<'a>(
    scene: &'a Scene,
    path: &'a [DVec3],
    radius: f64,
) -> impl FnMut() -> DVec3 + 'a {
    let options = ProxyOptions::default()
        .with_tool_radius(radius)
        .expect("in its domain");
    let mut proxy = Proxy::new(path[0], options);
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
    // The tool (a sphere proxy) on the same blob path, its centre moved out by the radius
    // so that it is as deep past the tool's offset as the point is past the surface.
    for (name, radius) in [("1 mm", 1e-3), ("2 % of the blob", 0.004)] {
        let path = lifted_for_tool(&blob, &blob_contact, radius, 0.004);
        group.bench_function(format!("tool contact tick, blob, r {name}"), |b| {
            b.iter(tool_ticking(&blob, &path, radius))
        });
    }
    group.finish();
}

criterion_group!(benches, proxy_stage);
criterion_main!(benches);
