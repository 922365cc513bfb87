//! The broad phase allocates nothing on the servo thread: a scene of 10 000 objects ticked
//! under a counting allocator while another thread inserts, removes and moves objects
//! through the editor, and the servo thread itself moves a thousand objects every tick.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use haphe::DVec3;
use haphe::glam::DQuat;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::scene::{Edit, EditError, Material, ObjectId, Pose, Scene, SceneObject, Shape};

/// Where object `k` of a 22 × 22 × 22 grid sits: 0.25 m apart (0.2 m spheres).
fn grid(k: u32) -> DVec3 {
    let (x, y, z) = (k % 22, (k / 22) % 22, k / 484);
    DVec3::new(f64::from(x), f64::from(y), f64::from(z)) * 0.25
}

#[test]
fn ticks_with_edits_from_another_thread_allocate_nothing() {
    let surface = Surface::new(
        Catalog::Sphere.with_triangles(500),
        &SurfaceOptions::default(),
    )
    .expect("a surface");
    let sphere = Arc::new(Shape::build(surface, &MapOptions::default()).expect("a map"));
    let material = Material::builder()
        .stiffness(800.0)
        .damping(1.0)
        .friction(0.3, 0.2)
        .build()
        .expect("a valid material");
    let (mut scene, mut editor) = Scene::new(12_000);
    for k in 0..10_000 {
        scene
            .insert(SceneObject::new(
                ObjectId(k),
                Arc::clone(&sphere),
                Pose::from_translation(grid(k)).expect("a valid pose"),
                material,
            ))
            .expect("room");
    }
    let stop = Arc::new(AtomicBool::new(false));
    let editor_thread = {
        let stop = Arc::clone(&stop);
        let sphere = Arc::clone(&sphere);
        std::thread::spawn(move || {
            // Inserts, removals and moves, near the hand and far from it, until told to stop.
            let mut sent = 0u64;
            let mut k = 0u32;
            while !stop.load(Ordering::Relaxed) {
                k = k.wrapping_add(1);
                let id = 10_000 + k % 1_500;
                let near = DVec3::new(0.125, 0.125, 0.4 + 0.01 * f64::from(k % 7));
                let edit = match k % 4 {
                    0 => Edit::Insert(SceneObject::new(
                        ObjectId(id),
                        Arc::clone(&sphere),
                        Pose::from_translation(if k.is_multiple_of(8) { near } else { grid(id) })
                            .expect("a valid pose"),
                        material,
                    )),
                    1 => Edit::Remove(ObjectId(10_000 + (k / 2) % 1_500)),
                    2 => Edit::SetPose(
                        ObjectId(k % 10_000),
                        Pose::new(
                            DQuat::from_rotation_z(0.01 * f64::from(k)),
                            grid(k % 10_000),
                        )
                        .expect("a valid pose"),
                    ),
                    _ => Edit::SetPose(
                        ObjectId(id),
                        Pose::from_translation(grid(id) + near).expect("a valid pose"),
                    ),
                };
                match editor.send(edit) {
                    Ok(()) => sent += 1,
                    Err((EditError::Busy, _)) => std::thread::yield_now(),
                    Err(_) => {}
                }
                // Removed objects and refused insertions are dropped here.
                for r in editor.collect() {
                    drop(r);
                }
            }
            sent
        })
    };
    // The hand presses 10 mm into the sphere at the origin (0.09 m from its centre, inside
    // every facet's plane) and slides round under the press, beyond the saturation depth
    // (4.1 mm at 800 N/m), so the proxy is in contact, and holds, on every tick. It starts
    // above the sphere, outside every object (it used to start inside the sphere above,
    // whose inside it then touched for as long as the edits let it).
    let hip_at = |s: f64| DVec3::new(0.03 * s.sin(), 0.03 * s.cos(), 0.0849);
    let surface = sphere.surface();
    let inscribed = (0..surface.triangle_count() as u32)
        .map(|t| {
            let f = surface.frame(haphe::mesh::TriId(t));
            f.normal.dot(surface.corners(haphe::mesh::TriId(t))[0])
        })
        .fold(f64::INFINITY, f64::min);
    assert!(hip_at(0.0).length() < inscribed - 0.0066, "{inscribed}");
    let mut proxy = Proxy::new(DVec3::new(0.0, 0.03, 0.13), ProxyOptions::default());
    let mut contacts = 0;
    let mut held = 0;
    let mut applied = 0;
    let mut total = 0;
    for block in 0..20 {
        let info = allocation_counter::measure(|| {
            for t in 0..1_000 {
                let s = f64::from(block * 1_000 + t) * 1e-3;
                applied += scene.begin_tick();
                // A thousand objects moved by the servo thread itself every tick.
                for m in 0..1_000u32 {
                    let id = ObjectId(2_000 + m * 7);
                    let wobble = DVec3::new(0.0, 0.0, 0.01 * (s + f64::from(m)).sin());
                    scene.set_pose(
                        id,
                        Pose::from_translation(grid(id.0) + wobble).expect("a valid pose"),
                    );
                }
                let out = proxy.tick(&scene, hip_at(s), DVec3::ZERO);
                contacts += usize::from(out.contact.is_some());
                held += usize::from(out.status.deep_hold);
                assert!(out.force.is_finite());
            }
        });
        total += info.count_total;
    }
    stop.store(true, Ordering::Relaxed);
    let sent = editor_thread.join().expect("the editor thread");
    assert!(sent > 1_000, "only {sent} edits sent");
    assert!(applied > 1_000, "only {applied} edits applied");
    // The hand is inside the sphere on every tick, so every tick is a contact (contact,
    // constraints, friction and the hold all ran under the counter): a proxy that lost
    // the sphere while the other thread turned it, or one the edits left out of contact,
    // falls short of it.
    assert_eq!(contacts, 20_000, "{contacts} ticks in contact");
    assert!(held > 0, "the hold never ran");
    assert_eq!(total, 0, "the servo thread allocated");
}
