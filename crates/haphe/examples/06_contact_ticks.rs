//! Proxy ticks in steady contact with a procedural shape, for measuring what a tick costs:
//! a path 0.5–3 mm inside the surface at 0.05–0.5 m/s and 1 kHz (the one `haphe bench`
//! uses for its contact rows), ticked once, with the tick times of the contact ticks.
//!
//! ```sh
//! cargo run --release --example 06_contact_ticks -- 1000 blob 20000
//! ```
//!
//! Arguments: triangles (default 1000), shape (default `blob`), ticks (default 20000), then
//! `loaded` to tick on the shape saved to map bytes and loaded in place
//! ([`haphe::map::decode_in_place`], as an application that loads a built map does), and
//! `tool=R` to tick a tool of radius `R` metres on the same path moved out by `R`
//! ([`haphe::verify::lifted_for_tool`]), and `texture=SPEC` to give the shape a texture
//! (`texture=sine:0.0001:0.002`). For
//! an instruction count that does not depend on the machine's load, run it under
//! callgrind, counting inside the tick only:
//!
//! ```sh
//! valgrind --tool=callgrind --toggle-collect='*tick_once*' \
//!     target/release/examples/06_contact_ticks 1000 blob 20000
//! ```

use std::sync::Arc;
use std::time::Instant;

use haphe::DVec3;
use haphe::map::{MapBytes, MapOptions, decode_in_place, encode};
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::{Proxy, ProxyOptions, TickOutput};
use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};
use haphe::verify::{haptic_path_in_contact, lifted_for_tool};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let triangles: usize = args.next().map_or(Ok(1000), |a| a.parse())?;
    let which: Catalog = args.next().map_or(Ok(Catalog::Blob), |a| a.parse())?;
    let ticks: usize = args.next().map_or(Ok(20_000), |a| a.parse())?;
    let rest: Vec<String> = args.collect();
    let loaded = rest.iter().any(|a| a == "loaded");
    let radius: f64 = match rest.iter().find_map(|a| a.strip_prefix("tool=")) {
        Some(r) => r.parse()?,
        None => 0.0,
    };
    let texture = match rest.iter().find_map(|a| a.strip_prefix("texture=")) {
        Some(spec) => Some(spec.parse::<haphe::scene::Texture>()?),
        None => None,
    };

    let surface = Surface::new(which.with_triangles(triangles), &SurfaceOptions::default())?;
    let mut shape = Shape::build(surface, &MapOptions::default())?;
    if loaded {
        let bytes = MapBytes::copy_from_slice(&encode(shape.surface(), shape.map()));
        let (surface, map) = decode_in_place(&bytes)?;
        shape = Shape::new(surface, map);
    }
    let shape = Arc::new(shape);
    // Every triangle's clear zone now, as a servo loop does before it starts: no tick
    // below computes one.
    shape.prepare_clear_zones();
    let mut scene = Scene::local(1);
    let mut object = SceneObject::new(ObjectId(0), shape, Pose::IDENTITY, Material::default());
    object.texture = texture;
    scene.insert(object).map_err(|(e, _)| e)?;
    let mut path = haptic_path_in_contact(&scene, ticks, (0.05, 0.5), (0.0005, 0.003), 1e3, 1);
    if radius > 0.0 {
        path = lifted_for_tool(&scene, &path, radius, 0.004);
    }

    let mut proxy = Proxy::new(path[0], ProxyOptions::default().with_tool_radius(radius)?);
    let mut contact_ns = Vec::with_capacity(path.len());
    let mut cleared = 0;
    for &hip in &path {
        let started = Instant::now();
        let out = tick_once(&mut proxy, &scene, hip);
        let ns = started.elapsed().as_nanos() as u64;
        if out.contact.is_some() {
            contact_ns.push(ns);
            cleared += usize::from(out.status.cleared);
        }
    }
    contact_ns.sort_unstable();
    let triangles = scene.objects()[0].shape.surface().triangle_count();
    if contact_ns.is_empty() {
        println!("{which} ({triangles} triangles): no tick in contact");
        return Ok(());
    }
    let at = |q: f64| contact_ns[((contact_ns.len() - 1) as f64 * q) as usize];
    println!(
        "{which} ({triangles} triangles): {} of {} ticks in contact ({cleared} of them moved in a clear zone, without searches); tick time p50 {} ns, p99 {} ns, p99.9 {} ns, max {} ns (clock included)",
        contact_ns.len(),
        path.len(),
        at(0.5),
        at(0.99),
        at(0.999),
        at(1.0)
    );
    Ok(())
}

/// One tick, never inlined, so that callgrind can count inside it whatever the compiler
/// inlined into it.
#[inline(never)]
fn tick_once(proxy: &mut Proxy, scene: &Scene, hip: DVec3) -> TickOutput {
    proxy.tick(scene, hip, DVec3::ZERO)
}
