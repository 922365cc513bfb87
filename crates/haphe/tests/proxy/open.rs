//! Open meshes: surfaces, never solids, felt from one side or both.

use super::*;

/// An open square sheet in the plane z = 0, 0.2 m across, normal +z, `n × n` quads.
fn sheet(n: u32) -> Mesh {
    let mut vertices = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
            vertices.push(DVec3::new(0.2 * x - 0.1, 0.2 * y - 0.1, 0.0));
        }
    }
    let at = |i: u32, j: u32| j * (n + 1) + i;
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            triangles.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            triangles.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    Mesh {
        vertices,
        triangles,
    }
}

/// An open sheet is felt from both sides by default, and from the front only when asked.
#[test]
fn open_surfaces_are_two_sided_or_one_sided() {
    let sheet = shape(sheet(8));
    assert!(!sheet.is_solid());
    for sides in [Sides::Both, Sides::Front] {
        let mut scene = Scene::local(1);
        let object = SceneObject::new(
            ObjectId(0),
            sheet.clone(),
            Pose::IDENTITY,
            Material::default(),
        );
        assert_eq!(object.sides, Sides::Both);
        scene.insert(object.with_sides(sides)).expect("room");
        for from in [1.0, -1.0] {
            let mut proxy =
                Proxy::new(DVec3::new(0.01, 0.02, 0.01 * from), ProxyOptions::default());
            let out = proxy.tick(&scene, DVec3::new(0.01, 0.02, -0.003 * from), DVec3::ZERO);
            let blocked = sides == Sides::Both || from > 0.0;
            assert_eq!(
                out.contact.is_some(),
                blocked,
                "{sides:?} from {from}: {out:?}"
            );
            if blocked {
                assert!(out.proxy.z * from > 0.0, "{out:?}");
                assert!(out.force.z * from > 0.0, "{out:?}");
            }
        }
    }
}

/// The fast proxy equals the brute-force one on an open sheet, both ways.
#[test]
fn fast_proxy_equals_brute_force_on_open_surfaces() {
    for (k, sides) in [Sides::Both, Sides::Front].into_iter().enumerate() {
        let mut scene = Scene::local(1);
        scene
            .insert(
                SceneObject::new(ObjectId(0), shape(sheet(20)), Pose::IDENTITY, friction())
                    .with_sides(sides),
            )
            .expect("room");
        let path = haptic_path(&scene, 4_000, (0.01, 10.0), 1e3, 60 + k as u64);
        let check = check_proxy(&scene, &path, ProxyOptions::default());
        println!("{sides:?}: {check:?}");
        assert!(check.contact_ticks > 300, "{check:?}");
        assert_eq!(check.mismatches, 0, "{check:?}");
    }
}
