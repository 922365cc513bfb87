//! The god-object proxy in a scene: a blob and a plate 0.1 mm thick, touched by a device
//! that presses, slides with friction, and strikes the plate at 10 m/s. The proxy stays on
//! the side of entry and the force pulls the device back to the surface.
//!
//! ```sh
//! cargo run --release --example 04_proxy
//! ```

use std::sync::Arc;

use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::{Proxy, ProxyOptions, TickOutput};
use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};

fn shape(which: Catalog, triangles: usize) -> Result<Arc<Shape>, Box<dyn std::error::Error>> {
    let surface = Surface::new(which.with_triangles(triangles), &SurfaceOptions::default())?;
    Ok(Arc::new(Shape::build(surface, &MapOptions::default())?))
}

fn show(label: &str, out: &TickOutput) {
    let contact = out.contact.map_or("free".to_string(), |c| {
        format!(
            "touching object {} triangle {} ({} plane(s)), {:.2} mm deep",
            c.id.0,
            c.triangle.0,
            c.constraints,
            c.penetration * 1e3
        )
    });
    println!(
        "{label:<34} proxy {:>8.4} {:>8.4} {:>8.4} m   force {:>6.3} {:>6.3} {:>6.3} N   {contact}{}",
        out.proxy.x,
        out.proxy.y,
        out.proxy.z,
        out.force.x,
        out.force.y,
        out.force.z,
        if out.status.sticking {
            ", sticking"
        } else {
            ""
        }
    );
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // One scene, owned by the servo thread; shapes are shared and immutable.
    let (mut scene, _editor) = Scene::new(8);
    let rubber = Material::builder()
        .stiffness(600.0)
        .damping(0.5)
        .friction(0.6, 0.4)
        .build()
        .expect("a valid material");
    scene
        .insert(SceneObject::new(
            ObjectId(1),
            shape(Catalog::Blob, 20_000)?,
            Pose::IDENTITY,
            rubber,
        ))
        .map_err(|(e, _)| e)?;
    let plate_pose = Pose::from_translation(DVec3::new(0.0, 0.0, 0.2)).expect("a valid pose");
    scene
        .insert(SceneObject::new(
            ObjectId(2),
            shape(Catalog::ThinPlate, 2_000)?,
            plate_pose,
            Material::default(),
        ))
        .map_err(|(e, _)| e)?;

    let dt = 1e-3; // 1 kHz
    let mut proxy = Proxy::new(DVec3::new(0.0, 0.0, 0.15), ProxyOptions::default());
    let mut tick = |scene: &mut Scene, hip: DVec3, velocity: DVec3| {
        scene.begin_tick();
        proxy.tick(scene, hip, velocity)
    };

    // Press down onto the top of the blob (about 0.1 m above the origin).
    let mut last = None;
    for k in 0..=100 {
        let hip = DVec3::new(0.0, 0.0, 0.15 - 0.0006 * k as f64);
        last = Some(tick(&mut scene, hip, DVec3::new(0.0, 0.0, -0.6)));
    }
    let pressed = last.ok_or("no tick")?;
    show("pressed into the blob", &pressed);

    // Slide sideways while pressing: friction holds, then lets go.
    let base = pressed.proxy - DVec3::new(0.0, 0.0, 0.004);
    for k in 1..=4 {
        let hip = base + DVec3::new(0.001 * k as f64, 0.0, 0.0);
        let out = tick(&mut scene, hip, DVec3::new(1.0, 0.0, 0.0) * 1e-3 / dt);
        show(&format!("slide {} mm", k), &out);
    }

    // Strike the plate from above at 10 m/s: 1 cm per tick, straight through its 0.1 mm.
    let mut proxy_strike = Proxy::new(DVec3::new(0.03, 0.02, 0.23), ProxyOptions::default());
    for k in 1..=6 {
        let hip = DVec3::new(0.03, 0.02, 0.23 - 0.01 * k as f64);
        scene.begin_tick();
        let out = proxy_strike.tick(&scene, hip, DVec3::new(0.0, 0.0, -10.0));
        show(&format!("strike, device at z = {:.3} m", hip.z), &out);
    }
    Ok(())
}
