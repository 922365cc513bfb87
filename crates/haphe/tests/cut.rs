//! Cutting: a tool drilling into volumes while the proxy and its brute-force oracle touch
//! every version of the surface; what is removed and what is left; strikes at the seams
//! of the chunks the surface is extracted in.

use glam::DAffine3;
use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::proxy::ProxyOptions;
use haphe::scene::{Material, Pose};
use haphe::verify::{CutCheck, check_cutting};
use haphe::volume::{CutOptions, Cutter, Volume};

/// Voxel spacing of the test blocks, metres.
const VOXEL: f64 = 5e-4;
/// The tool's radius, metres.
const RADIUS: f64 = 2e-3;

/// A block of `n`³ voxels at [`VOXEL`], material (value 1) from voxel `margin` to
/// `n - 1 - margin` on each axis, air (0) around it, iso 0.5.
fn block(n: usize, margin: usize) -> Volume {
    let inside = |i: usize| i >= margin && i < n - margin;
    let mut values = Vec::with_capacity(n * n * n);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                values.push(if inside(i) && inside(j) && inside(k) { 1.0 } else { 0.0 });
            }
        }
    }
    Volume::new([n; 3], values, DAffine3::from_scale(DVec3::splat(VOXEL)), 0.5).expect("a volume")
}

/// The pose putting the centre of `volume`'s grid at the origin.
fn centred(volume: &Volume) -> Pose {
    Pose::from_translation(-volume.centre()).expect("a pose")
}

/// A straight path from `from` to `to` at `speed` m/s, 1 kHz, then `hold` ticks at `to`.
fn straight(from: DVec3, to: DVec3, speed: f64, hold: usize) -> Vec<DVec3> {
    let ticks = (from.distance(to) / speed * 1e3).ceil() as usize;
    (0..=ticks)
        .map(|t| from.lerp(to, t as f64 / ticks as f64))
        .chain(std::iter::repeat_n(to, hold))
        .collect()
}

fn drill(volume: Volume, path: &[DVec3], cut: bool, refresh_every: usize) -> (CutCheck, Volume) {
    let pose = centred(&volume);
    let options = CutOptions::new(RADIUS, CutOptions::DEFAULT_CUT_FORCE).expect("options");
    let mut cutter = Cutter::new("block", volume, MapOptions::default()).expect("a cutter");
    cutter.set_options(options);
    let proxy = ProxyOptions::default()
        .with_tool_radius(RADIUS)
        .expect("a radius");
    let check = check_cutting(
        &mut cutter,
        (pose, Material::DEFAULT),
        path,
        (proxy, 1e3),
        (cut, refresh_every),
    )
    .expect("material left");
    (check, cutter.into_volume())
}

/// The distance from `p` to the segment `a`–`b`.
fn to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
    p.distance(a + t * ab)
}

fn assert_clean(check: &CutCheck) {
    let p = &check.proxy;
    assert_eq!(
        (p.mismatches, p.inside, p.bad_forces, check.too_close),
        (0, 0, 0, 0),
        "mismatches, inside, bad forces, too close: {check:?}"
    );
}

/// Acceptance 1: a block drilled along a straight path at 10 mm/s with a 2 mm tool: every
/// voxel within r − 1 voxel of the path removed, none farther than r + 2 voxels changed,
/// the tool at the hand at the end; without cutting, the tool rests on the top face.
#[test]
fn a_block_drilled_along_a_straight_path() {
    let before = block(40, 4);
    let pose = centred(&before);
    let top = before.point(0.0, 0.0, 35.5).z + pose.to_world(DVec3::ZERO).z;
    let (from, to) = (
        DVec3::new(3e-4, 2e-4, top + RADIUS + 3e-3),
        DVec3::new(3e-4, 2e-4, top - 8e-3),
    );
    let path = straight(from, to, 0.01, 500);

    let (rests, _) = drill(before.clone(), &path, false, 10);
    assert_clean(&rests);
    assert!(
        (rests.end.z - (top + RADIUS)).abs() < 1e-5,
        "without cutting the tool rests on the top: {:?}",
        rests.end
    );

    let (drilled, after) = drill(before.clone(), &path, true, 10);
    assert_clean(&drilled);
    eprintln!(
        "drilled: {} versions, {} voxels removed, end {:?}",
        drilled.versions, drilled.removed, drilled.end
    );
    assert!(drilled.end.distance(to) < 1e-5, "the tool ends at the hand: {:?}", drilled.end);
    let [n, _, _] = before.dims();
    let (mut inner, mut changed_far) = (0, 0);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let at = i + n * (j + n * k);
                let p = pose.to_world(before.point(i as f64, j as f64, k as f64));
                let d = to_segment(p, from, to);
                let (was, now) = (before.values()[at], after.values()[at]);
                if d <= RADIUS - VOXEL && was >= 0.5 {
                    inner += 1;
                    assert!(now < 0.5, "voxel {i} {j} {k} at {d} m from the path is left");
                }
                if d > RADIUS + 2.0 * VOXEL && was != now {
                    changed_far += 1;
                }
            }
        }
    }
    assert!(inner > 1000, "{inner} voxels near the path");
    assert_eq!(changed_far, 0, "voxels changed beyond r + 2 voxels");
}
