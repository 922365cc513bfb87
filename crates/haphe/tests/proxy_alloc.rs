//! The servo path allocates nothing: 10^5 proxy ticks over several meshes, with moving
//! objects, scene edits arriving from another thread, friction, and bad input mixed in,
//! one shape loaded in place from saved map bytes, and deep strikes that make the proxy
//! hold, run under a counting allocator.

use std::sync::Arc;

use haphe::DVec3;
use haphe::glam::DQuat;
use haphe::map::{MapBytes, MapOptions, decode_in_place, encode};
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::scene::{Edit, Material, ObjectId, Pose, Scene, SceneObject, Shape};
use haphe::verify::{WindingOracle, hand_goes_deep, haptic_path, strike_path};

fn shape(which: Catalog, triangles: usize) -> Arc<Shape> {
    let surface = Surface::new(which.with_triangles(triangles), &SurfaceOptions::default())
        .expect("a usable surface");
    Arc::new(Shape::build(surface, &MapOptions::default()).expect("a map"))
}

/// `shape`, saved to map bytes and loaded in place, as an application loads a built map.
fn loaded(which: Catalog, triangles: usize) -> Arc<Shape> {
    let built = shape(which, triangles);
    let bytes = MapBytes::copy_from_slice(&encode(built.surface(), built.map()));
    let (surface, map) = decode_in_place(&bytes).expect("loads");
    Arc::new(Shape::new(surface, map))
}

#[test]
fn the_counter_counts() {
    let info = allocation_counter::measure(|| {
        std::hint::black_box(vec![1u8; 10]);
    });
    assert_eq!(info.count_total, 1);
}

#[test]
fn proxy_ticks_allocate_nothing() {
    let material = Material::builder()
        .stiffness(800.0)
        .damping(1.0)
        .friction(0.5, 0.3)
        .build()
        .expect("a valid material");
    let shapes = [
        shape(Catalog::Blob, 20_000),
        shape(Catalog::ThinPlate, 5_000),
        shape(Catalog::ConcaveCorner, 5_000),
        loaded(Catalog::Torus, 5_000),
    ];
    let (mut scene, mut editor) = Scene::new(8);
    for (i, s) in shapes.iter().enumerate() {
        let pose =
            Pose::from_translation(DVec3::new(0.5 * i as f64, 0.0, 0.0)).expect("a valid pose");
        scene
            .insert(SceneObject::new(
                ObjectId(i as u32),
                s.clone(),
                pose,
                material,
            ))
            .expect("room");
    }
    // Paths over each object in turn, with bad input spliced in.
    let mut hips = Vec::new();
    for (i, s) in shapes.iter().enumerate() {
        let mut one = Scene::local(1);
        one.insert(SceneObject::new(
            ObjectId(0),
            s.clone(),
            scene.objects()[i].pose,
            material,
        ))
        .expect("room");
        hips.extend(haptic_path(&one, 25_000, (0.01, 10.0), 1e3, 40 + i as u64));
    }
    // Strikes through the blob, beyond the saturation depth (6.6 mm for 3.3 N and 500 N/m;
    // 4.1 mm for this 800 N/m): from the tick its hand first lies that deep inside (by its
    // path, brute force) to the end of the strike, the proxy must hold on every tick, and
    // those ticks run under the counter like the rest.
    let blob = {
        let mut one = Scene::local(1);
        one.insert(SceneObject::new(
            ObjectId(0),
            shapes[0].clone(),
            scene.objects()[0].pose,
            material,
        ))
        .expect("room");
        one
    };
    let winding = WindingOracle::new(shapes[0].surface());
    let saturation = ProxyOptions::default().max_force() / material.stiffness();
    let mut must_hold = Vec::new();
    for (k, angle) in [0.0f64, 35.0].into_iter().enumerate() {
        let dir = DVec3::new(angle.to_radians().sin(), 0.0, -angle.to_radians().cos());
        // Aimed near the blob's centre (radius 0.1 m), coming to rest 5 cm past it.
        let start = DVec3::new(0.01 * k as f64, 0.0, 0.0) - 0.25 * dir;
        let (path, last) = strike_path(start, dir, 1.0 + k as f64, 0.3, 1e3);
        let deep = hand_goes_deep(
            &blob,
            &winding,
            &path[..=last],
            (1.0 + k as f64) / 1e3,
            saturation,
        )
        .expect("the strike goes deep");
        // Every tick from there to the end of the strike (the hand comes to rest deep).
        must_hold.push((hips.len() + deep, hips.len() + path.len()));
        hips.extend(path);
    }
    let strikes_start = 100_000;
    for k in (0..strikes_start).step_by(997) {
        hips[k] = match k % 3 {
            0 => DVec3::NAN,
            1 => DVec3::splat(1e300),
            _ => -hips[k] * 1e6,
        };
    }
    let spare = SceneObject::new(ObjectId(99), shapes[0].clone(), Pose::IDENTITY, material);
    // The blob breathes: a deformed version made here, off the servo path, each block.
    let breathed = [1.01, 0.99].map(|scale| {
        let vertices: Vec<DVec3> = shapes[0]
            .surface()
            .vertices()
            .iter()
            .map(|&p| scale * p)
            .collect();
        Arc::new(shapes[0].deformed(&vertices).expect("a deformation"))
    });
    let mut proxy = Proxy::new(hips[0], ProxyOptions::default());
    let mut previous = hips[0];
    let mut contacts = 0usize;
    let mut held = 0usize;
    let mut held_where_due = 0usize;
    let mut tick = 0usize;
    let mut spare = Some(spare);
    let chunk = 1_000;
    let mut total_allocations = 0;
    for (c, block) in hips.chunks(chunk).enumerate() {
        // Off the servo thread's clock: another thread's edits, sent before the block.
        let t = c as f64 * 0.01;
        let _ = editor.send(Edit::SetPose(
            ObjectId(3),
            Pose::new(
                DQuat::from_rotation_z(t),
                DVec3::new(1.5, 0.0, 0.01 * t.sin()),
            )
            .expect("a valid pose"),
        ));
        let _ = editor.send(Edit::SetShape(ObjectId(0), breathed[c % 2].clone()));
        if let Some(object) = spare.take() {
            let _ = editor.send(Edit::Insert(object));
        } else if c % 2 == 0 {
            let _ = editor.send(Edit::Remove(ObjectId(99)));
        }
        let info = allocation_counter::measure(|| {
            for &hip in block {
                scene.begin_tick();
                let velocity = (hip - previous) * 1e3;
                previous = hip;
                let out = proxy.tick(&scene, hip, velocity);
                contacts += usize::from(out.contact.is_some());
                held += usize::from(out.status.deep_hold);
                held_where_due += usize::from(
                    out.status.deep_hold && must_hold.iter().any(|&(a, b)| (a..b).contains(&tick)),
                );
                tick += 1;
                assert!(out.force.is_finite());
                assert!(out.force.length() <= proxy.options().max_force() * (1.0 + 1e-12));
            }
        });
        total_allocations += info.count_total;
        // Objects that left the scene, and shapes no longer used, are dropped here, off
        // the servo thread.
        for returned in editor.collect() {
            if let haphe::scene::Returned::Removed(o) = returned {
                spare = Some(o);
            }
        }
    }
    let due: usize = must_hold.iter().map(|&(a, b)| b - a).sum();
    assert_eq!(tick, hips.len());
    assert!(hips.len() > strikes_start && due > 0, "{due}");
    assert!(contacts > 20_000, "{contacts}");
    // The hold ran under the counter on every tick where it was due.
    assert_eq!(held_where_due, due, "held {held} ticks in all");
    assert_eq!(total_allocations, 0, "the servo path allocated");
}

/// The tool's ticks (a sphere proxy of 2 mm, and one of 2 % of the blob's size) allocate
/// nothing either: exploring, in steady contact, with bad input spliced in.
#[test]
fn tool_ticks_allocate_nothing() {
    let material = Material::builder()
        .stiffness(800.0)
        .friction(0.5, 0.3)
        .build()
        .expect("a valid material");
    let mut scene = Scene::local(2);
    scene
        .insert(SceneObject::new(
            ObjectId(0),
            shape(Catalog::Blob, 20_000),
            Pose::IDENTITY,
            material,
        ))
        .expect("room");
    let mut hips = haptic_path(&scene, 20_000, (0.01, 10.0), 1e3, 9);
    hips.extend(haphe::verify::haptic_path_in_contact(
        &scene,
        20_000,
        (0.05, 0.5),
        (0.5e-3, 3e-3),
        1e3,
        10,
    ));
    for k in (0..hips.len()).step_by(997) {
        hips[k] = if k % 2 == 0 {
            DVec3::NAN
        } else {
            DVec3::splat(1e300)
        };
    }
    for radius in [0.002, 0.004] {
        let options = ProxyOptions::default()
            .with_tool_radius(radius)
            .expect("in its domain");
        let mut proxy = Proxy::new(hips[0], options);
        let mut contacts = 0usize;
        let info = allocation_counter::measure(|| {
            for &hip in &hips {
                let out = proxy.tick(&scene, hip, DVec3::ZERO);
                contacts += usize::from(out.contact.is_some());
            }
        });
        assert_eq!(info.count_total, 0, "r {radius}: {info:?}");
        assert!(contacts > 10_000, "r {radius}: {contacts}");
    }
}
