//! glTF files as scenes: one object per mesh node at its world pose, scale baked into the
//! shape, shared meshes built once, names and materials from the file.

use std::sync::Arc;

use haphe::DVec3;
use haphe::glam::DQuat;
use haphe::map::MapOptions;
use haphe::mesh::{NoSideCars, Units, Weld, read_gltf};
use haphe::scene::{GltfSceneError, Material, gltf_objects};
use serde_json::json;

use haphe::mesh::shapes::Catalog;

use crate::writer::{Writer, khronos_box};

/// A sphere of about 5000 triangles placed by `n` nodes, each moved and turned rigidly.
fn spheres(n: usize) -> Vec<u8> {
    let sphere = Catalog::Sphere.with_triangles(5000);
    let points: Vec<[f32; 3]> = sphere
        .vertices
        .iter()
        .map(|p| p.as_vec3().to_array())
        .collect();
    let mut w = Writer::new();
    let mesh = w.triangle_mesh(&points, &sphere.triangles);
    for i in 0..n {
        let q = DQuat::from_rotation_y(0.1 * i as f64);
        w.root(json!({
            "mesh": mesh,
            "name": format!("sphere {i}"),
            "translation": [0.5 * i as f64, 0.0, 0.0],
            "rotation": [q.x, q.y, q.z, q.w],
        }));
    }
    w.glb()
}

#[test]
fn nodes_sharing_a_mesh_share_one_shape_and_memory_stays_flat() {
    let build = |n: usize| {
        let scene =
            read_gltf("spheres.glb", &spheres(n), Units::Metres, &mut NoSideCars).expect("reads");
        let objects = gltf_objects(&scene).expect("objects");
        assert_eq!(objects.meshes.len(), 1, "one shape's mesh for {n} nodes");
        objects
            .build(Weld::Exact, &MapOptions::default(), Material::default(), 0)
            .expect("builds")
    };
    let hundred = build(100);
    assert_eq!(hundred.len(), 100);
    assert!(
        hundred
            .iter()
            .all(|(_, o)| Arc::ptr_eq(&o.shape, &hundred[0].1.shape)),
        "one shape for every node"
    );
    assert_eq!(hundred[7].0, "sphere 7");
    // Memory: the peak while reading and building 100 nodes is that of one node plus a
    // little per node (its part of the document and its object), not 100 shapes.
    let one = allocation_counter::measure(|| {
        std::hint::black_box(build(1));
    });
    let many = allocation_counter::measure(|| {
        std::hint::black_box(build(100));
    });
    let per_node = (many.bytes_max as f64 - one.bytes_max as f64) / 99.0;
    println!(
        "peak bytes: {} for one node, {} for 100 ({per_node:.0} per extra node)",
        one.bytes_max, many.bytes_max
    );
    assert!(
        per_node < 0.01 * one.bytes_max as f64,
        "peak bytes: {} for one node, {} for 100 ({per_node:.0} per extra node)",
        one.bytes_max,
        many.bytes_max
    );
}

#[test]
fn objects_sit_where_the_flattened_mesh_is_with_scale_baked_in() {
    // Three meshes under nested transforms: translation, rotation, non-uniform scale.
    let mut w = khronos_box();
    w.doc["nodes"] = json!([]);
    w.doc["scenes"] = json!([{"nodes": []}]);
    let q = DQuat::from_rotation_z(0.6);
    let tetra = w.triangle_mesh(
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ],
        &[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    );
    w.root(json!({"name": "base", "translation": [0.5, 0.0, 0.0], "mesh": 0, "children": [1]}));
    w.node(json!({"name": "arm", "rotation": [q.x, q.y, q.z, q.w], "translation": [0.0, 2.0, 0.0], "mesh": tetra, "children": [2], "extras": {"stiffness": 800.0, "friction": 0.4, "colour": "red"}}));
    w.node(json!({"name": "hand", "scale": [1.0, 2.0, 0.5], "translation": [3.0, 0.0, 0.0], "mesh": 0}));
    let scene = read_gltf("arm.glb", &w.glb(), Units::Metres, &mut NoSideCars).expect("reads");
    let objects = gltf_objects(&scene).expect("objects");
    let names: Vec<&str> = objects.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["base", "arm", "hand"]);
    // The box under a rigid pose and the box under a scale are two shapes.
    assert_eq!(objects.meshes.len(), 3);
    for (object, node) in objects.objects.iter().zip(&scene.nodes) {
        let placed = scene.placed(node);
        let shape = &objects.meshes[object.shape];
        for (p_object, p_world) in shape.vertices.iter().zip(&placed.vertices) {
            let got = object.pose.rotation() * *p_object + object.pose.translation();
            assert!(
                (got - *p_world).length() < 1e-9,
                "{}: {got} {p_world}",
                object.name
            );
        }
    }
    // The hand's box is 1 × 2 × 0.5 in its own frame: the scale is in the shape.
    let (lo, hi) = objects.meshes[objects.objects[2].shape]
        .bounds()
        .expect("vertices");
    let size = hi - lo;
    assert!((size - DVec3::new(1.0, 2.0, 0.5)).length() < 1e-9, "{size}");
    let material = objects.objects[1].material.expect("from extras");
    assert_eq!(
        (
            material.stiffness(),
            material.static_friction(),
            material.dynamic_friction()
        ),
        (800.0, 0.4, 0.4)
    );
    assert_eq!(objects.objects[0].material, None);
}

#[test]
fn bad_materials_and_flat_nodes_are_named() {
    let mut w = khronos_box();
    w.doc["nodes"][1]["name"] = json!("lid");
    w.doc["nodes"][1]["extras"] = json!({"stiffness": -5.0});
    let scene = read_gltf("b.glb", &w.glb(), Units::Metres, &mut NoSideCars).expect("reads");
    let err = gltf_objects(&scene).unwrap_err();
    assert_eq!(
        err.to_string(),
        "node 1 ('lid'): extras: stiffness must be a finite number above 0 and at most 1000000 N/m, not -5"
    );
    w.doc["nodes"][1]["extras"] = json!({"friction": "high"});
    let scene = read_gltf("b.glb", &w.glb(), Units::Metres, &mut NoSideCars).expect("reads");
    assert!(matches!(
        gltf_objects(&scene),
        Err(GltfSceneError::NotANumber {
            node: 1,
            field: "friction",
            ..
        })
    ));
    w.doc["nodes"][1]["extras"] = json!(null);
    w.doc["nodes"][1]["scale"] = json!([1.0, 0.0, 1.0]);
    let scene = read_gltf("b.glb", &w.glb(), Units::Metres, &mut NoSideCars).expect("reads");
    assert!(matches!(
        gltf_objects(&scene),
        Err(GltfSceneError::Singular { node: 1, .. })
    ));
}
