//! Servo ticks on a grid of many objects sharing one shape, for measuring how a tick grows
//! with the number of objects: the scene of `haphe bench`'s object-count series (spheres
//! of about 1 000 triangles, 0.25 m apart; the hand pressing about 6 mm into the corner
//! sphere and sliding on it), optionally with objects moved every tick.
//!
//! ```sh
//! cargo run --release --example 08_object_ticks -- 10000 0 20000
//! ```
//!
//! Arguments: objects (default 1000), objects moved every tick (default 0), ticks
//! (default 20000), and `linear` to test every object in each search (the path without
//! the broad phase). For an instruction count per tick that does not depend on the
//! machine's load, run it under callgrind, counting inside the tick only (`begin_tick`,
//! the moves and the proxy tick):
//!
//! ```sh
//! valgrind --tool=callgrind --toggle-collect='*tick_once*' \
//!     target/release/examples/08_object_ticks 10000 0 20000
//! ```

use std::sync::Arc;
use std::time::Instant;

use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::{Proxy, ProxyOptions, TickOutput};
use haphe::scene::{Material, ObjectId, ObjectKey, Pose, Scene, SceneObject, Shape};

/// Where object `k` of a grid of `side`³ sits.
fn grid(k: usize, side: usize) -> DVec3 {
    let (x, y, z) = (k % side, (k / side) % side, k / (side * side));
    DVec3::new(x as f64, y as f64, z as f64) * 0.25
}

/// One servo tick: the scene's edits, the moves, the proxy.
#[inline(never)]
fn tick_once(
    scene: &mut Scene,
    proxy: &mut Proxy,
    moving: &mut [(ObjectKey, DVec3)],
    t: usize,
) -> TickOutput {
    scene.begin_tick();
    let wobble = DVec3::new(0.0, 0.0, 1e-3 * (t as f64 * 0.01).sin());
    for (key, at) in moving.iter_mut() {
        scene.set_pose_keyed(
            key,
            Pose::from_translation(*at + wobble).expect("a valid pose"),
        );
    }
    let s = t as f64 * 2e-3;
    let hip = DVec3::new(0.04 * s.cos(), 0.04 * s.sin(), 0.085);
    proxy.tick(scene, hip, DVec3::ZERO)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let objects: usize = args.next().map_or(Ok(1000), |a| a.parse())?;
    let movers: usize = args.next().map_or(Ok(0), |a| a.parse())?;
    let ticks: usize = args.next().map_or(Ok(20_000), |a| a.parse())?;
    let linear = args.next().is_some_and(|a| a == "linear");
    let objects = objects.max(1);

    let surface = Surface::new(
        Catalog::Sphere.with_triangles(1000),
        &SurfaceOptions::default(),
    )?;
    let shape = Arc::new(Shape::build(surface, &MapOptions::default())?);
    shape.prepare_clear_zones();
    let side = (1..).find(|s: &usize| s.pow(3) >= objects).unwrap_or(1);
    let mut scene = Scene::local(objects);
    let material = Material::builder()
        .stiffness(1000.0)
        .damping(1.0)
        .build()
        .expect("a valid material");
    for k in 0..objects {
        let pose = Pose::from_translation(grid(k, side)).expect("a valid pose");
        let _ = scene.insert(SceneObject::new(
            ObjectId(k as u32),
            shape.clone(),
            pose,
            material,
        ));
    }
    let mut moving: Vec<(ObjectKey, DVec3)> = (0..movers.min(objects - 1))
        .map(|m| {
            let k = 1 + m * (objects - 1) / movers;
            (ObjectKey::new(ObjectId(k as u32)), grid(k, side))
        })
        .collect();
    let proxy = Proxy::new(DVec3::new(0.0, 0.0, 0.2), ProxyOptions::default());
    let mut proxy = if linear {
        proxy.with_linear_scan()
    } else {
        proxy
    };
    let mut times = Vec::with_capacity(ticks);
    let mut contacts = 0;
    for t in 0..ticks {
        let start = Instant::now();
        let out = tick_once(&mut scene, &mut proxy, &mut moving, t);
        times.push(start.elapsed().as_nanos() as u64);
        contacts += usize::from(out.contact.is_some());
    }
    times.sort_unstable();
    let at = |q: f64| times[((q * ticks as f64) as usize).min(ticks - 1)];
    println!(
        "{objects} objects, {} moving{}: {ticks} ticks, {contacts} in contact; ns p50 {} p99 {} p99.9 {} max {}",
        moving.len(),
        if linear { ", linear" } else { "" },
        at(0.5),
        at(0.99),
        at(0.999),
        times[ticks - 1]
    );
    Ok(())
}
