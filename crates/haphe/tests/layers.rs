//! Layers: a volume's materials (enamel over dentin) felt where the surface shows them,
//! cut each at its rate, and the proxy equal to its oracle while it drills through them.

use std::sync::Arc;

use glam::DAffine3;
use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject};
use haphe::verify::check_cutting;
use haphe::volume::{CutOptions, Cutter, Layer, Volume};

/// Voxel spacing, metres.
const VOXEL: f64 = 5e-4;
/// Voxels along each axis.
const N: usize = 40;
/// Air around the block, voxels.
const MARGIN: usize = 4;
/// The layer of voxel `k` (upward) where enamel begins.
const ENAMEL_FROM_K: usize = 24;

const DENTIN: &str = "dentin:1:0.02:300";
const ENAMEL: &str = "enamel:2:0.004:900:0.4";

/// A block of dentin (value 1) capped with enamel (value 2) from voxel
/// [`ENAMEL_FROM_K`] up, air (0) around it; iso 0.5.
fn tooth() -> Volume {
    let inside = |i: usize| (MARGIN..N - MARGIN).contains(&i);
    let mut values = Vec::with_capacity(N * N * N);
    for k in 0..N {
        for j in 0..N {
            for i in 0..N {
                values.push(match (inside(i) && inside(j) && inside(k), k) {
                    (false, _) => 0.0,
                    (true, k) if k >= ENAMEL_FROM_K => 2.0,
                    _ => 1.0,
                });
            }
        }
    }
    Volume::new(
        [N; 3],
        values,
        DAffine3::from_scale(DVec3::splat(VOXEL)),
        0.5,
    )
    .expect("a volume")
}

fn layers() -> Vec<Layer> {
    [DENTIN, ENAMEL]
        .iter()
        .map(|s| s.parse().expect("a layer"))
        .collect()
}

/// A cutter of [`tooth`] with its layers and a tool of `radius`.
fn cutter(radius: f64) -> Cutter {
    let mut cutter = Cutter::new("tooth", tooth(), MapOptions::default()).expect("a cutter");
    let options = CutOptions::new(radius, CutOptions::DEFAULT_CUT_FORCE)
        .expect("options")
        .with_layers(layers());
    cutter.set_options(options).expect("options set");
    cutter
}

/// The top face's height and the +x face's place, volume frame.
fn faces(volume: &Volume) -> (f64, f64) {
    let last = (N - MARGIN - 1) as f64 + 0.5;
    (
        volume.point(0.0, 0.0, last).z,
        volume.point(last, 0.0, 0.0).x,
    )
}

/// The force on a point proxy held `depth` behind the surface at `on`, pressing along
/// `-normal`, in a scene of the cutter's shape whose object material is `object`.
fn pressed(cutter: &Cutter, object: Material, on: DVec3, normal: DVec3, depth: f64) -> DVec3 {
    let mut scene = Scene::local(1);
    let shape = Arc::clone(cutter.shape());
    let o = SceneObject::new(ObjectId(0), shape, Pose::IDENTITY, object);
    scene.insert(o).map_err(|(e, _)| e).expect("room");
    let above = on + normal * 2e-3;
    let mut proxy = Proxy::new(above, ProxyOptions::default());
    proxy.tick(&scene, above, DVec3::ZERO);
    let mut force = DVec3::ZERO;
    for t in 0..=100 {
        let hip = above.lerp(on - normal * depth, f64::from(t) / 100.0);
        force = proxy.tick(&scene, hip, DVec3::ZERO).force;
    }
    force
}

/// The stiffness felt at `on` along `-normal`: the change of force over a change of depth
/// (the face may lie off `on` by a fraction of a voxel: where a value crosses iso).
fn stiffness_at(cutter: &Cutter, object: Material, on: DVec3, normal: DVec3) -> f64 {
    let (a, b) = (2e-4, 4e-4);
    let force = |d| pressed(cutter, object, on, normal, d).dot(normal);
    (force(b) - force(a)) / (b - a)
}

/// Enamel on top (900 N/m), dentin on the side below the enamel (300 N/m): each face
/// pushes back with its own stiffness, whatever the object's material says.
#[test]
fn each_layer_feels_like_its_material() {
    let cutter = cutter(0.0);
    let (top, side) = faces(cutter.volume());
    let middle = cutter.volume().centre();
    let object = Material::new(5000.0).expect("a material");
    let on_top = DVec3::new(middle.x, middle.y, top);
    let low = cutter.volume().point(0.0, 0.0, 8.0).z;
    let on_side = DVec3::new(side, middle.y, low);
    let enamel = stiffness_at(&cutter, object, on_top, DVec3::Z);
    let dentin = stiffness_at(&cutter, object, on_side, DVec3::X);
    eprintln!("felt: enamel {enamel:.1} N/m, dentin {dentin:.1} N/m");
    assert!((enamel - 900.0).abs() < 1.0, "enamel {enamel}");
    assert!((dentin - 300.0).abs() < 1.0, "dentin {dentin}");
    // Without layers the object's material holds everywhere.
    let mut plain = Cutter::new("tooth", tooth(), MapOptions::default()).expect("a cutter");
    plain
        .set_options(CutOptions::new(0.0, 0.5).expect("options"))
        .expect("options set");
    let felt = stiffness_at(&plain, object, on_top, DVec3::Z);
    assert!((felt - 5000.0).abs() < 5.0, "the object's material: {felt}");
}

/// The same press for the same time removes dentin (20 mm/s) but not yet enamel
/// (4 mm/s: a voxel of 0.5 mm takes 125 ms).
#[test]
fn enamel_is_cut_slower_than_dentin() {
    let radius = 1e-3;
    let (top, side) = faces(&tooth());
    let middle = tooth().centre();
    let low = tooth().point(0.0, 0.0, 8.0).z;
    let press = |centre: DVec3| {
        let mut cutter = cutter(radius);
        (0..100)
            .map(|_| cutter.press(centre, 1.0, 1e-3))
            .sum::<usize>()
    };
    let enamel = press(DVec3::new(middle.x, middle.y, top + radius));
    let dentin = press(DVec3::new(side + radius, middle.y, low));
    eprintln!("in 100 ms: enamel {enamel} voxels, dentin {dentin}");
    assert_eq!(enamel, 0);
    assert!(dentin > 0);
}

/// Drilling down through the enamel into the dentin, the proxy equals its oracle on every
/// tick (the friction of the enamel, the stiffness of each) and never ends inside.
#[test]
fn drilling_through_layers_never_puts_the_tool_inside() {
    let radius = 1e-3;
    let mut cutter = cutter(radius);
    let pose = Pose::from_translation(-cutter.volume().centre()).expect("a pose");
    let (top, _) = faces(cutter.volume());
    let top = top - cutter.volume().centre().z;
    let from = DVec3::new(2e-4, 1e-4, top + radius + 2e-3);
    let to = DVec3::new(2e-4, 1e-4, top - 9e-3);
    let ticks = (from.distance(to) / 0.004 * 1e3) as usize;
    // The hand down at 4 mm/s, then held there for 0.8 s: the tool rubs the hole's walls,
    // and the enamel's friction slows its way down.
    let path: Vec<DVec3> = (0..=ticks)
        .map(|t| from.lerp(to, t as f64 / ticks as f64))
        .chain(std::iter::repeat_n(to, 800))
        .collect();
    let proxy = ProxyOptions::default()
        .with_tool_radius(radius)
        .expect("a radius");
    let check = check_cutting(
        &mut cutter,
        (pose, Material::DEFAULT),
        &path,
        (proxy, 1e3),
        (true, 10),
    )
    .expect("material left");
    let p = &check.proxy;
    eprintln!(
        "{} versions, {} voxels removed, end {:?}",
        check.versions, check.removed, check.end
    );
    assert_eq!(
        (p.mismatches, p.inside, p.bad_forces, check.too_close),
        (0, 0, 0, 0),
        "mismatches, inside, bad forces, too close; first failures {:?}",
        &p.failures[..p.failures.len().min(3)]
    );
    // Through the enamel (12 voxels) into the dentin.
    let enamel_bottom = (ENAMEL_FROM_K as f64 - 0.5) * VOXEL - cutter.volume().centre().z;
    assert!(
        check.end.z < enamel_bottom,
        "the tool reached the dentin: {:?}",
        check.end
    );
}
