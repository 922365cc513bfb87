//! A checksum of every tick's output on fixed traces, for checking that a change meant to
//! make the tick cheaper leaves its answers bit for bit as they were: the proxy, the force,
//! the contact (triangle, weights, point, normals, penetration, planes) and the status of
//! every tick, hashed per trace.
//!
//! ```sh
//! cargo run --release --example 10_tick_checksums
//! ```
//!
//! Prints one line per trace (its name, ticks in contact and held deep, the hash); two builds that print
//! the same lines gave the same outputs. The traces: the contact path of `haphe bench` on
//! the 1k and 10k blob and thin plate (as example 06), the 1k blob with friction and
//! damping, pressed deep (holds), with a tool radius, with a texture, an exploring path
//! (strikes, free space) on the 10k plate, and a grid of 27 spheres with objects moved
//! every tick (carry, broad phase). Argument: ticks per trace (default 5000).

use std::sync::Arc;

use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::{Proxy, ProxyOptions, TickOutput};
use haphe::scene::{Material, ObjectId, ObjectKey, Pose, Scene, SceneObject, Shape, Texture};
use haphe::verify::{haptic_path, haptic_path_in_contact, lifted_for_tool};

/// FNV-1a over the bytes of each tick's output as `Debug` prints it (every `f64` printed
/// exactly: the shortest text that reads back to the same bits).
struct Hash(u64);

impl Hash {
    fn add(&mut self, out: &TickOutput) {
        for b in format!("{out:?}").bytes() {
            self.0 = (self.0 ^ u64::from(b)).wrapping_mul(0x100_0000_01b3);
        }
    }
}

/// A scene of one shape from the catalogue, with `material` and `texture`.
fn one(
    which: Catalog,
    triangles: usize,
    material: Material,
    texture: Option<Texture>,
) -> Result<Scene, Box<dyn std::error::Error>> {
    let surface = Surface::new(which.with_triangles(triangles), &SurfaceOptions::default())?;
    let shape = Arc::new(Shape::build(surface, &MapOptions::default())?);
    shape.prepare_clear_zones();
    let mut scene = Scene::local(1);
    let mut object = SceneObject::new(ObjectId(0), shape, Pose::IDENTITY, material);
    object.texture = texture;
    scene.insert(object).map_err(|(e, _)| e)?;
    Ok(scene)
}

/// The hash of `path` ticked by a proxy with `options` on `scene` (velocity from the
/// path's steps), and the ticks in contact.
fn run(scene: &Scene, path: &[DVec3], options: ProxyOptions) -> (u64, usize, usize) {
    let mut proxy = Proxy::new(path[0], options);
    let mut hash = Hash(0xcbf2_9ce4_8422_2325);
    let (mut contacts, mut held) = (0, 0);
    let mut previous = path[0];
    for &hip in path {
        let out = proxy.tick(scene, hip, (hip - previous) * 1e3);
        previous = hip;
        contacts += usize::from(out.contact.is_some());
        held += usize::from(out.status.deep_hold);
        hash.add(&out);
    }
    (hash.0, contacts, held)
}

/// 27 spheres 0.25 m apart, 4 of them moved every tick, the hand sliding on the corner
/// one (the scene of example 08).
fn grid(ticks: usize) -> Result<(u64, usize, usize), Box<dyn std::error::Error>> {
    let surface = Surface::new(
        Catalog::Sphere.with_triangles(1000),
        &SurfaceOptions::default(),
    )?;
    let shape = Arc::new(Shape::build(surface, &MapOptions::default())?);
    shape.prepare_clear_zones();
    let at = |k: usize| DVec3::new((k % 3) as f64, ((k / 3) % 3) as f64, (k / 9) as f64) * 0.25;
    let mut scene = Scene::local(27);
    let material = Material::builder().stiffness(1000.0).damping(1.0).build()?;
    for k in 0..27 {
        let object = SceneObject::new(
            ObjectId(k as u32),
            shape.clone(),
            Pose::from_translation(at(k))?,
            material,
        );
        scene.insert(object).map_err(|(e, _)| e)?;
    }
    let mut proxy = Proxy::new(DVec3::new(0.0, 0.0, 0.2), ProxyOptions::default());
    let mut keys: Vec<(ObjectKey, usize)> = [0, 1, 3, 13]
        .into_iter()
        .map(|k| (ObjectKey::new(ObjectId(k as u32)), k))
        .collect();
    let mut hash = Hash(0xcbf2_9ce4_8422_2325);
    let (mut contacts, mut held) = (0, 0);
    for t in 0..ticks {
        scene.begin_tick();
        let wobble = DVec3::new(0.0, 0.0, 1e-3 * (t as f64 * 0.01).sin());
        for (key, k) in &mut keys {
            scene.set_pose_keyed(key, Pose::from_translation(at(*k) + wobble)?);
        }
        let s = t as f64 * 2e-3;
        let hip = DVec3::new(0.04 * s.cos(), 0.04 * s.sin(), 0.085);
        let out = proxy.tick(&scene, hip, DVec3::ZERO);
        contacts += usize::from(out.contact.is_some());
        held += usize::from(out.status.deep_hold);
        hash.add(&out);
    }
    Ok((hash.0, contacts, held))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let ticks: usize = std::env::args().nth(1).map_or(Ok(5000), |a| a.parse())?;
    let plain = Material::default();
    let options = ProxyOptions::default();
    let contact =
        |scene: &Scene, depths| haptic_path_in_contact(scene, ticks, (0.05, 0.5), depths, 1e3, 1);
    let mut lines = Vec::new();
    for (which, triangles) in [
        (Catalog::Blob, 1000),
        (Catalog::Blob, 10_000),
        (Catalog::ThinPlate, 1000),
        (Catalog::ThinPlate, 10_000),
    ] {
        let scene = one(which, triangles, plain, None)?;
        let path = contact(&scene, (0.0005, 0.003));
        lines.push((format!("{which} {triangles}"), run(&scene, &path, options)));
    }
    let sticky = Material::builder()
        .stiffness(800.0)
        .damping(2.0)
        .friction(0.6, 0.4)
        .build()?;
    let scene = one(Catalog::Blob, 1000, sticky, None)?;
    let path = contact(&scene, (0.0005, 0.003));
    lines.push(("blob 1000 friction".into(), run(&scene, &path, options)));
    let scene = one(Catalog::Blob, 1000, plain, None)?;
    let path = contact(&scene, (0.003, 0.012));
    lines.push(("blob 1000 deep".into(), run(&scene, &path, options)));
    let path = lifted_for_tool(&scene, &contact(&scene, (0.0005, 0.003)), 0.002, 0.004);
    let tool = options.with_tool_radius(0.002)?;
    lines.push(("blob 1000 tool 2 mm".into(), run(&scene, &path, tool)));
    let texture = "sine:0.0001:0.002".parse::<Texture>()?;
    let scene = one(Catalog::Blob, 1000, plain, Some(texture))?;
    let path = contact(&scene, (0.0005, 0.003));
    lines.push(("blob 1000 texture".into(), run(&scene, &path, options)));
    let scene = one(Catalog::ThinPlate, 10_000, plain, None)?;
    let path = haptic_path(&scene, ticks, (0.05, 2.0), 1e3, 7);
    lines.push((
        "thin plate 10000 exploring".into(),
        run(&scene, &path, options),
    ));
    lines.push(("27 spheres, 4 moving".into(), grid(ticks)?));
    for (name, (hash, contacts, held)) in lines {
        println!("{name}: {contacts} of {ticks} ticks in contact ({held} held deep), {hash:016x}");
    }
    Ok(())
}
