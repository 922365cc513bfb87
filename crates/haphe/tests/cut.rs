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
                values.push(if inside(i) && inside(j) && inside(k) {
                    1.0
                } else {
                    0.0
                });
            }
        }
    }
    Volume::new(
        [n; 3],
        values,
        DAffine3::from_scale(DVec3::splat(VOXEL)),
        0.5,
    )
    .expect("a volume")
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

/// Runs `path` against `volume` (centred) with a tool of `radius` cutting when `cut`,
/// refreshing every `refresh_every` ticks: the checks, and the volume as cut.
fn drill(
    volume: &Volume,
    radius: f64,
    path: &[DVec3],
    (cut, refresh_every): (bool, usize),
) -> (CutCheck, Volume) {
    let pose = centred(volume);
    let options = CutOptions::new(radius, CutOptions::DEFAULT_CUT_FORCE).expect("options");
    let mut cutter =
        Cutter::new("volume", volume.clone(), MapOptions::default()).expect("a cutter");
    cutter.set_options(options).expect("options set");
    let proxy = ProxyOptions::default()
        .with_tool_radius(radius)
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
        (
            p.mismatches,
            p.inside,
            p.bad_forces,
            check.too_close,
            check.open_versions
        ),
        (0, 0, 0, 0, 0),
        "mismatches, inside, bad forces, too close, open versions: {check:?}"
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

    let (rests, _) = drill(&before, RADIUS, &path, (false, 10));
    assert_clean(&rests);
    assert!(
        (rests.end.z - (top + RADIUS)).abs() < 1e-5,
        "without cutting the tool rests on the top: {:?}",
        rests.end
    );

    let (drilled, after) = drill(&before, RADIUS, &path, (true, 10));
    assert_clean(&drilled);
    eprintln!(
        "drilled: {} versions, {} voxels removed, end {:?}",
        drilled.versions, drilled.removed, drilled.end
    );
    // The tool ends at the hand, as near as the cut force lets it: once the hand stops,
    // the spring between them eases below the cut force and the cutting stops.
    let stop = CutOptions::DEFAULT_CUT_FORCE / Material::DEFAULT.stiffness();
    assert!(
        drilled.end.distance(to) <= stop + 5e-5,
        "the tool ends at the hand: {:?}, {} m away",
        drilled.end,
        drilled.end.distance(to)
    );
    // The tool keeps to the hand's line (the hole's walls hold it).
    let strays = drilled
        .tool_path
        .iter()
        .map(|&c| to_segment(c, from, to))
        .fold(0.0, f64::max);
    assert!(
        strays < 1e-3,
        "the tool strayed {strays} m from the hand's line"
    );
    // What was drilled, measured from the tool's path.
    let [n, _, _] = before.dims();
    let (mut inner, mut changed_far) = (0, 0);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let at = i + n * (j + n * k);
                let p = pose.to_world(before.point(i as f64, j as f64, k as f64));
                let d = drilled
                    .tool_path
                    .iter()
                    .map(|&c| c.distance_squared(p))
                    .fold(f64::MAX, f64::min)
                    .sqrt();
                let (was, now) = (before.values()[at], after.values()[at]);
                if d <= RADIUS - VOXEL && was >= 0.5 {
                    inner += 1;
                    assert!(
                        now < 0.5,
                        "voxel {i} {j} {k} at {d} m from the path is left"
                    );
                }
                if d > RADIUS + 2.0 * VOXEL && was != now {
                    changed_far += 1;
                }
            }
        }
    }
    assert!(inner > 300, "{inner} voxels near the path");
    assert_eq!(changed_far, 0, "voxels changed beyond r + 2 voxels");
}

/// The voxel index of the first border between chunks (chunk 0 holds the cells from −1).
const BORDER: f64 = (haphe::volume::Chunks::SIZE - 1) as f64;

/// Acceptance 3: strikes aimed exactly at chunk borders, at the lines where four chunks
/// meet, and where a border crosses the block's edges, with and without cutting, with a
/// point and with a tool: the surface of every version is closed, the tool never passes
/// through and never comes closer to it than its radius.
#[test]
fn strikes_at_chunk_borders_never_pass_through() {
    let volume = block(40, 4);
    let pose = centred(&volume);
    let world = |i: f64, j: f64, k: f64| pose.to_world(volume.point(i, j, k));
    let face = 35.5;
    // (aim, inward normal of the face aimed at)
    let aims = [
        (world(BORDER, BORDER, face), -DVec3::Z),
        (world(BORDER, 20.0, face), -DVec3::Z),
        (world(17.0, BORDER, face), -DVec3::Z),
        (world(face, BORDER, BORDER), -DVec3::X),
        (world(face, BORDER, 12.0), -DVec3::X),
        (world(BORDER, face, 9.0), -DVec3::Y),
        // Where a border crosses the block's edges and corner region.
        (
            world(face, BORDER, face),
            -(DVec3::X + DVec3::Z).normalize(),
        ),
        (
            world(BORDER, face, face),
            -(DVec3::Y + DVec3::Z).normalize(),
        ),
        (
            world(face, face, BORDER),
            -(DVec3::X + DVec3::Y).normalize(),
        ),
    ];
    for radius in [0.0, 1e-3] {
        for cut in [false, true] {
            for (n, &(aim, inward)) in aims.iter().enumerate() {
                // Tilted a little off the normal, to hit the seam at an angle.
                let tilt = inward.any_orthonormal_vector() * 0.3;
                let dir = (inward + tilt).normalize();
                let from = aim - dir * (radius + 4e-3);
                let path = straight(from, aim + dir * 3e-3, 0.05, 100);
                let (check, _) = drill(&volume, radius, &path, (cut, 5));
                eprintln!(
                    "radius {radius} cut {cut} aim {n}: {} contact ticks, {} versions, {} removed",
                    check.proxy.contact_ticks, check.versions, check.removed
                );
                assert!(check.proxy.contact_ticks > 0, "aim {n} touched");
                assert_clean(&check);
            }
        }
    }
}

/// The in-tree model `spot.obj` scaled to 60 mm and voxelised at 1.5 mm.
fn voxelised_spot() -> Volume {
    use haphe::mesh::{ReadOptions, read_mesh};
    let file =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes/models/spot.obj");
    let bytes = std::fs::read(&file).expect("the in-tree mesh meshes/models/spot.obj");
    let mut mesh = read_mesh("spot.obj", &bytes, &ReadOptions::default()).expect("spot.obj reads");
    let (lo, hi) = mesh.bounds().expect("vertices");
    let scale = 0.06 / (hi - lo).max_element();
    for v in &mut mesh.vertices {
        *v = (*v - lo) * scale;
    }
    let shape =
        haphe::scene::Shape::from_mesh("spot.obj", mesh, &MapOptions::default()).expect("a shape");
    Volume::from_shape(&shape, 1.5e-3).expect("a volume")
}

/// Acceptance 2: drilling at 0.5 to 20 mm/s and strikes, on a voxelised model, with a
/// tool: at no tick is the tool inside the material left, or closer to its surface than
/// its radius less the skin; the proxy equals its oracle at every tick.
#[test]
fn drilling_a_voxelised_model_never_puts_the_tool_inside() {
    let volume = voxelised_spot();
    let radius = 1.5e-3;
    let run = |path: &[DVec3]| drill(&volume, radius, path, (true, 25)).0;
    let top = 0.04;
    for (speed, seconds) in [(5e-4, 1.0), (2e-3, 1.0), (2e-2, 0.5)] {
        let from = DVec3::new(2e-3, 1e-3, top);
        let path = straight(
            from,
            from - DVec3::Z * (speed * seconds + 0.03),
            speed.max(0.03),
            0,
        );
        // Down fast to above the back, then drilling at `speed`.
        let mut path: Vec<DVec3> = path.into_iter().take(1000).collect();
        let start = *path.last().expect("a point");
        path.extend(straight(
            start,
            start - DVec3::Z * speed * seconds,
            speed,
            100,
        ));
        let check = run(&path);
        eprintln!(
            "drilling at {} mm/s: {} contact ticks, {} versions, {} voxels removed",
            speed * 1e3,
            check.proxy.contact_ticks,
            check.versions,
            check.removed
        );
        assert!(
            check.proxy.contact_ticks > 100 && check.removed > 0,
            "it drilled"
        );
        assert_clean(&check);
    }
    // Strikes at 0.2 m/s from six sides toward the centre, 10 mm past the surface.
    for dir in [
        DVec3::X,
        -DVec3::X,
        DVec3::Y,
        -DVec3::Y,
        DVec3::Z,
        -DVec3::Z,
    ] {
        let dir = (dir + 0.2 * dir.any_orthonormal_vector()).normalize();
        let path = straight(-dir * 0.045, -dir * 0.005, 0.2, 300);
        let check = run(&path);
        assert_clean(&check);
    }
}

/// Acceptance 2, on a NIfTI-1 volume the test writes (gzip, its grid turned 30° about z
/// and tilted, so no face lies along an axis) and reads back: drilling and a strike never
/// put the tool inside, the proxy equals its oracle.
#[test]
fn drilling_a_nifti_volume_never_puts_the_tool_inside() {
    let square = block(30, 4);
    let turned = DAffine3::from_rotation_z(0.52)
        * DAffine3::from_rotation_x(0.2)
        * DAffine3::from_scale(DVec3::splat(VOXEL));
    let written = Volume::new(square.dims(), square.values().to_vec(), turned, 0.5)
        .expect("a volume")
        .to_nifti_gz()
        .expect("written");
    let (volume, _) = Volume::read_nifti("block.nii.gz", &written, 0.5).expect("it reads");
    let radius = 1.5e-3;
    let top = 0.012;
    for path in [
        straight(
            DVec3::new(1e-3, 0.0, top),
            DVec3::new(1e-3, 0.0, -2e-3),
            0.005,
            200,
        ),
        straight(
            DVec3::new(-2e-3, 1e-3, top),
            DVec3::new(-2e-3, 1e-3, 0.0),
            0.3,
            300,
        ),
    ] {
        let (check, _) = drill(&volume, radius, &path, (true, 10));
        assert!(check.removed > 0, "it cut: {check:?}");
        assert_clean(&check);
    }
}

/// After a cut, the clear zones kept from the version before (the triangles of chunks the
/// cut did not touch, away from the new triangles) still hold: each is at most as clear
/// as the zone computed afresh on the new surface. Most are kept.
#[test]
fn zones_kept_across_a_cut_still_hold() {
    use haphe::mesh::TriId;
    use haphe::query::ClearZone;
    let volume = block(72, 4);
    let mut cutter = Cutter::new("block", volume, MapOptions::default()).expect("a cutter");
    let options = CutOptions::new(1e-3, CutOptions::DEFAULT_CUT_FORCE).expect("options");
    cutter.set_options(options).expect("options set");
    let top = cutter.volume().point(10.0, 10.0, 67.5);
    let removed: usize = (0..200).map(|_| cutter.press(top, 1.0, 1e-3)).sum();
    assert!(removed > 0);
    let shape = cutter.refresh().expect("a shape").expect("a new version");
    let (surface, map) = (shape.surface(), shape.map());
    let mut equal = 0;
    for t in 0..surface.triangle_count() {
        let t = TriId(t as u32);
        let (kept, fresh) = (shape.clear_zone(t), ClearZone::of(surface, map, t));
        equal += usize::from(kept == fresh);
        assert!(
            kept.front >= fresh.front
                && kept.back >= fresh.back
                && kept.height <= fresh.height
                && (!kept.below || fresh.below),
            "triangle {t:?}: kept {kept:?}, fresh {fresh:?}"
        );
    }
    eprintln!(
        "{removed} voxels removed; {equal} of {} zones equal to fresh ones",
        surface.triangle_count()
    );
}
