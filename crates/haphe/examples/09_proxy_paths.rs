//! The proxy's path along fixed device paths, written to files, for comparing two versions
//! of the proxy tick by tick (`tools/shallow_contact.py` builds this example at two commits
//! and compares what they write).
//!
//! ```sh
//! cargo run --example 09_proxy_paths -- paths DIR      # writes the device paths into DIR
//! cargo run --example 09_proxy_paths -- run DIR OUT    # the proxy along each, into OUT
//! ```
//!
//! The device paths are those of the proxy suites (`haptic_path` exploring, fast strides
//! and strikes, `haptic_path_in_contact` at two depth ranges) over the sphere, blob, torus
//! and concave corner (2 000 triangles). Each is run with three materials: the default,
//! the default without friction, and 2 000 N/m. Files are little-endian `f64`: a path is
//! `x y z` per tick; an output is `proxy x y z, penetration (−1 without contact), force x
//! y z` per tick.

use std::path::Path;
use std::sync::Arc;

use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};

/// Device paths per shape.
const PATHS: usize = 5;

/// The scenes: (shape name, material index, scene).
fn scenes() -> Vec<(String, usize, Scene)> {
    let mut out = Vec::new();
    for which in [
        Catalog::Sphere,
        Catalog::Blob,
        Catalog::Torus,
        Catalog::ConcaveCorner,
    ] {
        let surface = Surface::new(which.with_triangles(2_000), &SurfaceOptions::default())
            .expect("a usable surface");
        let shape = Arc::new(Shape::build(surface, &MapOptions::default()).expect("a map"));
        let materials = [
            Material::default(),
            Material::builder()
                .friction(0.0, 0.0)
                .build()
                .expect("a valid material"),
            Material::builder()
                .stiffness(2_000.0)
                .build()
                .expect("a valid material"),
        ];
        for (m, material) in materials.into_iter().enumerate() {
            let mut scene = Scene::local(4);
            let object = SceneObject::new(ObjectId(0), shape.clone(), Pose::IDENTITY, material);
            scene.insert(object).expect("room");
            out.push((which.to_string(), m, scene));
        }
    }
    out
}

fn write_f64s(path: &Path, values: impl Iterator<Item = f64>) {
    let bytes: Vec<u8> = values.flat_map(f64::to_le_bytes).collect();
    std::fs::write(path, bytes).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    match args.get(1..).unwrap_or_default() {
        [cmd, dir] if cmd == "paths" => {
            let dir = Path::new(dir);
            for (name, _, scene) in scenes().into_iter().filter(|(_, m, _)| *m == 0) {
                let paths = [
                    haphe::verify::haptic_path(&scene, 3_000, (0.01, 2.0), 1e3, 11),
                    haphe::verify::haptic_path(&scene, 4_000, (0.01, 10.0), 1e3, 60),
                    haphe::verify::haptic_path(&scene, 5_000, (2.0, 10.0), 1e3, 100),
                    haphe::verify::haptic_path_in_contact(
                        &scene,
                        3_000,
                        (0.05, 0.5),
                        (0.0005, 0.003),
                        1e3,
                        3,
                    ),
                    haphe::verify::haptic_path_in_contact(
                        &scene,
                        3_000,
                        (0.01, 0.2),
                        (0.0, 0.006),
                        1e3,
                        4,
                    ),
                ];
                for (k, path) in paths.iter().enumerate() {
                    let values = path.iter().flat_map(|p| p.to_array());
                    write_f64s(&dir.join(format!("{name}.{k}.path")), values);
                }
            }
        }
        [cmd, dir, out] if cmd == "run" => {
            let (dir, out) = (Path::new(dir), Path::new(out));
            std::fs::create_dir_all(out).expect("an output folder");
            for (name, m, scene) in scenes() {
                for k in 0..PATHS {
                    let path = dir.join(format!("{name}.{k}.path"));
                    let bytes =
                        std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                    let points: Vec<DVec3> = bytes
                        .chunks_exact(24)
                        .map(|c| {
                            let f = |i: usize| {
                                f64::from_le_bytes(c[8 * i..8 * i + 8].try_into().expect("8"))
                            };
                            DVec3::new(f(0), f(1), f(2))
                        })
                        .collect();
                    let mut proxy = Proxy::new(points[0], ProxyOptions::default());
                    let mut previous = points[0];
                    let mut values = Vec::with_capacity(7 * points.len());
                    for &hip in &points {
                        let o = proxy.tick(&scene, hip, (hip - previous) * 1e3);
                        previous = hip;
                        let depth = o.contact.map_or(-1.0, |c| c.penetration);
                        values.extend(o.proxy.to_array());
                        values.push(depth);
                        values.extend(o.force.to_array());
                    }
                    write_f64s(
                        &out.join(format!("{name}-m{m}.{k}.out")),
                        values.into_iter(),
                    );
                }
            }
        }
        _ => {
            eprintln!("usage: 09_proxy_paths paths DIR | run DIR OUT");
            std::process::exit(2);
        }
    }
}
