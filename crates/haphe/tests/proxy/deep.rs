//! Deep penetration: beyond the saturation depth the proxy holds where it was, so the
//! force never pulls the hand on through a thick object.

use haphe::DVec3;
use haphe::mesh::shapes::Catalog;
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::scene::Material;
use haphe::verify::{
    ENOUGH_DEEP_STRIKES, STRIKE_FORCE_TOLERANCE_N, StrikeCheck, StrikeEntry, StrikeTicks,
    WindingOracle, check_proxy, check_strikes, hand_goes_deep, hand_sized, required_deep_strikes,
    strike_path,
};

use super::{fit_to_hand_size, scene_of, shape, support};

/// The strike of the deep-penetration report: the hand held 3 cm above a 0.2 m sphere
/// (20 000 triangles) for 0.1 s, then driven at 1.5 m/s, 35° from the vertical, straight
/// through it for 0.3 s. The god-object slid a quarter of the way around the sphere and
/// on 30 ticks pulled the hand on (up to 0.9 N); now it holds near the entry.
#[test]
fn the_sphere_strike_never_pulls_the_hand_on() {
    let scene = scene_of(
        shape(Catalog::Sphere.with_triangles(20_000)),
        Material::default(),
    );
    let dir = DVec3::new(35f64.to_radians().sin(), 0.0, -35f64.to_radians().cos());
    let start = DVec3::new(0.0, 0.0, 0.13);
    let mut path = vec![start; 100];
    path.extend((1..=300).map(|k| start + dir * (1.5 * k as f64 * 1e-3)));
    let mut proxy = Proxy::new(start, ProxyOptions::default());
    let (mut pushes, mut held, mut contact, mut worst) = (0, 0, 0, 0.0f64);
    let mut previous = start;
    for &hip in &path {
        let out = proxy.tick(&scene, hip, (hip - previous) * 1e3);
        previous = hip;
        contact += usize::from(out.contact.is_some());
        held += usize::from(out.status.deep_hold);
        worst = worst.max(out.force.dot(dir));
        pushes += usize::from(out.force.dot(dir) > STRIKE_FORCE_TOLERANCE_N);
        if let Some(c) = out.contact {
            assert!(c.normal.dot(dir) < 0.0, "far side: {c:?}");
        }
    }
    println!("contact {contact}, held {held}, pushes on {pushes}, largest {worst:.3e} N");
    assert!(contact > 250 && held > 200, "{contact} {held}");
    assert_eq!(pushes, 0, "largest push {worst} N");
    // The brute-force proxy holds the same way.
    let check = check_proxy(&scene, &path, ProxyOptions::default());
    assert_eq!(check.mismatches, 0, "{check:?}");
}

/// No tick from the one the hand went deeper than the saturation depth (by its path)
/// lost contact, pushed the hand on or faced the far side, and at least the stated share
/// of the strikes went that deep.
fn assert_holds(name: &str, check: &StrikeCheck) {
    println!(
        "{name}: {} of {} strikes deep (at least {}): {check:?}",
        check.deep.strikes, check.strikes, check.min_deep_strikes
    );
    assert!(check.strikes >= 20, "{name}: {check:?}");
    assert!(
        check.min_deep_strikes == required_deep_strikes(check.strikes)
            && check.deep.strikes >= check.min_deep_strikes,
        "{name}: {check:?}"
    );
    assert!(check.passed(), "{name}: {check:?}");
}

/// Deep strikes, straight and oblique (0–70°), 0.5–10 m/s at 1 kHz, to depths up to
/// passing out of the far side, on the convex and concave procedural shapes, with the
/// default material and a stiff one.
#[test]
fn deep_strikes_never_pull_the_hand_on_procedural_shapes() {
    let stiff = Material::builder()
        .stiffness(2_000.0)
        .damping(2.0)
        .build()
        .expect("a valid material");
    for which in [
        Catalog::Sphere,
        Catalog::Blob,
        Catalog::Torus,
        Catalog::ConcaveCorner,
    ] {
        for (m, material) in [Material::default(), stiff].into_iter().enumerate() {
            let scene = scene_of(shape(which.with_triangles(2_000)), material);
            let check = check_strikes(&scene, ProxyOptions::default(), 30, 0.25, 1e3, 7 + m as u64);
            assert_holds(&format!("{which} material {m}"), &check);
        }
    }
}

/// The fast proxy equals the brute-force one along deep strikes (the proxy holds, lets go
/// and holds again).
#[test]
fn fast_proxy_equals_brute_force_along_deep_strikes() {
    for which in [Catalog::Sphere, Catalog::ConcaveCorner, Catalog::Torus] {
        let scene = scene_of(shape(which.with_triangles(2_000)), Material::default());
        let mut path = Vec::new();
        for (k, angle) in [0.0f64, 30.0, 60.0].into_iter().enumerate() {
            let dir = DVec3::new(
                angle.to_radians().sin(),
                0.1 * k as f64,
                -angle.to_radians().cos(),
            )
            .normalize();
            let start = DVec3::new(0.07, 0.01, 0.14) - 0.05 * dir;
            let (out, _) = strike_path(start, dir, 1.0 + k as f64, 0.3, 1e3);
            // Back out along the same line, so the proxy lets go.
            path.extend(out.iter().chain(out.iter().rev()));
        }
        let check = check_proxy(&scene, &path, ProxyOptions::default());
        println!("{which}: {check:?}");
        assert!(check.contact_ticks > 100, "{which}: {check:?}");
        assert_eq!(check.mismatches, 0, "{which}: {check:?}");
        assert_eq!(check.inside, 0, "{which}: {check:?}");
    }
}

/// The deep ticks of a strike come from the hand's path alone: on a 0.1 m cube (plane
/// faces, so the depth of a point inside is its distance to the nearest face, computed
/// here from the coordinates), the first point of a line that lies deeper than a given
/// depth is the one [`hand_goes_deep`] finds, for straight and oblique lines, lines that
/// never go that deep and lines that pass out of the far side.
#[test]
fn deep_ticks_are_decided_by_the_hand_path() {
    let half = 0.05;
    let scene = scene_of(
        shape(haphe::mesh::shapes::cuboid(DVec3::splat(half), [2, 2, 2])),
        Material::default(),
    );
    let surface = scene.objects()[0].shape.surface();
    let winding = WindingOracle::new(surface);
    let depth_in_cube = |p: DVec3| {
        let d = DVec3::splat(half) - p.abs();
        if d.min_element() > 0.0 {
            d.min_element()
        } else {
            -1.0
        }
    };
    let mut examined = 0;
    let mut found = 0;
    for (k, (angle, along, depth)) in [
        (0.0f64, 0.3, 0.0066),
        (30.0, 0.3, 0.0066),
        (60.0, 0.3, 0.0066),
        (70.0, 0.05, 0.0066),
        (0.0, 0.005, 0.0066),
        (45.0, 0.3, 0.02),
        (10.0, 0.3, 0.045),
    ]
    .into_iter()
    .enumerate()
    {
        let dir = DVec3::new(angle.to_radians().sin(), 0.0, -angle.to_radians().cos());
        let start = DVec3::new(-0.02 + 0.003 * k as f64, 0.01, half + 0.01);
        let speed = 0.5 + k as f64;
        let (path, last) = strike_path(start, dir, speed, along, 1e3);
        let path = &path[..=last];
        let expected = path.iter().position(|&p| depth_in_cube(p) > depth);
        let step = speed / 1e3;
        assert_eq!(
            hand_goes_deep(&scene, &winding, path, step, depth),
            expected,
            "line {k}: {angle}° {along} m to {depth} m"
        );
        examined += 1;
        found += usize::from(expected.is_some());
    }
    // Both outcomes were examined: the 5 mm line and the 10° line to 45 mm (the side face
    // is nearer than 45 mm by the time the top is that far) never go that deep.
    assert_eq!(examined, 7);
    assert_eq!(found, 5);
}

/// The far side of a strike is what faces along it behind the plane it entered through,
/// where a proxy that crawled round the object ends up. The strike of the
/// deep-penetration report (35°, 1.5 m/s, through a 0.2 m sphere of 2 000 triangles):
/// the plain god-object (a device whose force never saturates, so it never holds) slides
/// round the sphere after the hand and pulls it on, and [`StrikeEntry::far_side`] flags
/// its deep ticks there: on a convex solid every surface point off the entry plane lies
/// behind it, so they are exactly the ticks whose contact plane faces along the strike.
/// The holding proxy has no tick there, pushes nothing on and stays in contact.
#[test]
fn far_side_contacts_are_caught_behind_the_entry_plane() {
    let scene = scene_of(
        shape(Catalog::Sphere.with_triangles(2_000)),
        Material::default(),
    );
    let surface = scene.objects()[0].shape.surface();
    let dir = DVec3::new(35f64.to_radians().sin(), 0.0, -35f64.to_radians().cos());
    let start = DVec3::new(0.0, 0.0, 0.13);
    let speed = 1.5;
    let (path, last) = strike_path(start, dir, speed, 0.45, 1e3);
    let hit = haphe::verify::BruteCrossing::new(surface)
        .first_crossing(start, path[last])
        .expect("the strike enters the sphere");
    let entry = StrikeEntry {
        point: hit.point,
        normal: surface.frame(hit.triangle).normal,
        dir,
    };
    let options = ProxyOptions::default();
    let saturation = options.max_force() / Material::default().stiffness();
    let winding = WindingOracle::new(surface);
    let deep_from = hand_goes_deep(&scene, &winding, &path[..=last], speed / 1e3, saturation)
        .expect("the strike goes deep");
    // 50 N at 500 N/m saturates 0.1 m behind a plane: the sphere's radius.
    let never_saturates = options.with_max_force(50.0).expect("a valid force");
    let skin = options.skin();
    // Per proxy: deep ticks on the far side, pushing the hand on.
    let mut counts = [[0; 2]; 2];
    for (p, proxy_options) in [never_saturates, options].into_iter().enumerate() {
        let mut proxy = Proxy::new(start, proxy_options);
        let mut previous = start;
        for (k, &hip) in path.iter().enumerate() {
            let out = proxy.tick(&scene, hip, (hip - previous) * 1e3);
            previous = hip;
            if k < deep_from || k > last {
                continue;
            }
            // The god-object lets go once the hand is out of the far side; the holding
            // proxy never does.
            let Some(c) = out.contact else {
                assert_eq!(p, 0, "holding proxy out of contact on tick {k}");
                continue;
            };
            let far = entry.far_side(c.point, c.normal, skin);
            assert_eq!(far, c.normal.dot(dir) > 0.0, "proxy {p}, tick {k}: {c:?}");
            counts[p][0] += usize::from(far);
            counts[p][1] += usize::from(out.force.dot(dir) > STRIKE_FORCE_TOLERANCE_N);
        }
    }
    println!(
        "deep ticks {}: god-object (far side, pushing on) {:?}, holding {:?}",
        last + 1 - deep_from,
        counts[0],
        counts[1]
    );
    let [god, held] = counts;
    assert!(god[0] > 0 && god[1] > 0, "{counts:?}");
    assert_eq!(held, [0, 0], "{counts:?}");
}

/// `meshes/models/20mm-xyz-cube.stl` as `haphe verify --strikes` runs it: welded, scaled
/// so that its largest side is 0.2 m from its lowest corner, with verify's material
/// (800 N/m, 1 N·s/m, no friction; saturation depth 4.1 mm).
fn xyz_cube_as_verify_runs_it() -> haphe::scene::Scene {
    in_tree_model_as_verify_runs_it("20mm-xyz-cube.stl")
}

/// The in-tree model `name` as `haphe verify` checks the proxy on it: hand-sized, with its
/// material.
fn in_tree_model_as_verify_runs_it(name: &str) -> haphe::scene::Scene {
    let path = support::in_tree_meshes().join("models").join(name);
    let bytes = std::fs::read(&path).expect("readable");
    let mesh = haphe::mesh::read_mesh(&path.to_string_lossy(), &bytes, &Default::default())
        .expect("a mesh");
    let surface = haphe::mesh::Surface::new(mesh, &Default::default()).expect("a usable surface");
    let (scaled, _) = hand_sized(&surface);
    let material = Material::builder()
        .stiffness(800.0)
        .damping(1.0)
        .friction(0.0, 0.0)
        .build()
        .expect("a valid material");
    scene_of(shape(scaled), material)
}

/// The strikes `haphe verify --strikes 2000 --seed 1` runs on the 20 mm calibration cube
/// (the first 200 are those of `--strikes 200 --seed 1`), which the in-tree family (20
/// strikes, seed 3, another material) does not draw. The cube's raised letters meet its
/// face in acute notches: a strike into a notch's wall leaves the god-object pinned in
/// the notch against two or three planes, the hand beyond the saturation depth by its
/// path, and the contact plane the notch's other wall, facing 89° from the strike, on
/// the entry plane. The check used to count those ticks as the far side; the force there
/// points back along the strike. Every deep tick holds the hand back.
#[test]
fn deep_strikes_on_the_xyz_cube_as_verify_runs_them() {
    let scene = xyz_cube_as_verify_runs_it();
    let check = check_strikes(&scene, ProxyOptions::default(), 2000, 0.25, 1e3, 1);
    assert_holds("20mm-xyz-cube.stl", &check);
}

/// The strikes `haphe verify --strikes 1600 --seed 1` runs on the plate with holes: a thin
/// plate at verify's scale, most of whose points lie within the 4.1 mm saturation depth
/// of its surface, so that few strikes go deep. Those few are
/// enough ([`ENOUGH_DEEP_STRIKES`]): the family passes, where half of its strikes could
/// never go deep.
#[test]
fn a_thin_model_needs_enough_deep_strikes_not_half() {
    let scene = in_tree_model_as_verify_runs_it("plate_holes.STL");
    let check = check_strikes(&scene, ProxyOptions::default(), 1600, 0.25, 1e3, 1);
    assert!(check.deep.strikes * 4 < check.strikes, "{check:?}");
    assert_eq!(check.min_deep_strikes, ENOUGH_DEEP_STRIKES, "{check:?}");
    assert_holds("plate_holes.STL", &check);
}

/// A family whose strikes never go deeper than the saturation depth fails, whatever its
/// proxy did: strikes to 2 mm past the entry (the hand can be no deeper than its distance
/// from the entry, below the 6.6 mm of the default material) have no deep ticks at all,
/// so they check nothing of the hold.
#[test]
fn a_family_of_shallow_strikes_fails() {
    let scene = scene_of(
        shape(Catalog::Sphere.with_triangles(2_000)),
        Material::default(),
    );
    let check = check_strikes(&scene, ProxyOptions::default(), 20, 0.002, 1e3, 5);
    assert!(check.strikes >= 10, "{check:?}");
    assert_eq!(check.deep.strikes, 0, "{check:?}");
    assert_eq!(check.deep.ticks, 0, "{check:?}");
    assert!(check.shallow.ticks > 0, "{check:?}");
    assert!(check.min_deep_strikes >= check.strikes / 2, "{check:?}");
    assert!(!check.passed(), "{check:?}");
}

/// The closed models of a folder, each scaled to 0.2 m, by file name.
fn closed_models(dir: &std::path::Path) -> Vec<(String, haphe::mesh::Mesh)> {
    let mut names: Vec<_> = std::fs::read_dir(dir)
        .expect("listable")
        .map(|e| e.expect("entry").path())
        .collect();
    names.sort();
    let mut models = Vec::new();
    for path in names {
        let bytes = std::fs::read(&path).expect("readable");
        let Ok(mut mesh) =
            haphe::mesh::read_mesh(&path.to_string_lossy(), &bytes, &Default::default())
        else {
            continue;
        };
        fit_to_hand_size(&mut mesh);
        models.push((
            path.file_name().unwrap().to_string_lossy().into_owned(),
            mesh,
        ));
    }
    models
}

/// Runs `count` strikes on each closed mesh and asserts that at least the stated share of
/// the family's strikes went deeper than the saturation depth (by the hand's path) and
/// that no tick from the one a strike went that deep lost contact, pushed the hand on or
/// faced the far side;
/// prints
/// one line of counts per mesh and returns the number of solids.
fn strike_family(meshes: Vec<(String, haphe::mesh::Mesh)>, count: usize) -> usize {
    let mut solids = 0;
    let (mut strikes, mut deep_strikes) = (0, 0);
    for (name, mesh) in meshes {
        let shape = shape(mesh);
        if !shape.is_solid() {
            println!("{name}: not closed, skipped");
            continue;
        }
        solids += 1;
        let scene = scene_of(shape, Material::default());
        let started = std::time::Instant::now();
        let check = check_strikes(&scene, ProxyOptions::default(), count, 0.25, 1e3, 3);
        let by_speed = |t: &[StrikeTicks; 4]| {
            t.iter()
                .map(|t| {
                    format!(
                        "{}/{}/{}/{}",
                        t.strikes, t.pushes_on, t.far_side, t.no_contact
                    )
                })
                .collect::<Vec<_>>()
                .join(" ")
        };
        println!(
            "{name}: {} strikes ({} skipped), {} held ticks, {:.2} µs/tick; deep: {} strikes \
             (at least {}), {} ticks, {} pushing on, {} far side, {} out of contact, by speed \
             (strikes/pushing/far/out) {}; \
             shallow (the physical range): {} strikes, {} ticks, {} pushing on (largest \
             {:.2} N), {} far side, by speed {}",
            check.strikes,
            check.skipped,
            check.held_ticks,
            started.elapsed().as_secs_f64() * 1e6 / check.ticks.max(1) as f64,
            check.deep.strikes,
            check.min_deep_strikes,
            check.deep.ticks,
            check.deep.pushes_on,
            check.deep.far_side,
            check.deep.no_contact,
            by_speed(&check.deep_by_speed),
            check.shallow.strikes,
            check.shallow.ticks,
            check.shallow.pushes_on,
            check.shallow.max_push_n,
            check.shallow.far_side,
            by_speed(&check.shallow_by_speed),
        );
        // Strikes drawn onto a face that lies inside another part (box.STL's overlapping
        // parts: about half) are skipped, since the line meets the outer part first.
        assert!(check.strikes >= count / 3, "{name}: {check:?}");
        // Every deep tick held the hand back. A thin model (the in-tree cylinder) has few
        // points farther than the saturation depth from its surface, so the least share of
        // deep strikes is asked of the family, below.
        assert!(check.deep.held_back(), "{name}: {check:?}");
        strikes += check.strikes;
        deep_strikes += check.deep.strikes;
    }
    let required = required_deep_strikes(strikes);
    println!("the family: {deep_strikes} of {strikes} strikes went deep (at least {required})");
    assert!(
        strikes > 0 && deep_strikes >= required,
        "{deep_strikes} of {strikes} strikes went deep, at least {required} required"
    );
    solids
}

/// The family on the repository's own closed models (CI-sized: 20 strikes each).
#[test]
fn deep_strikes_on_in_tree_models() {
    let solids = strike_family(closed_models(&support::in_tree_meshes().join("models")), 20);
    assert!(solids >= 4, "{solids}");
}

/// The whole family: 20 000-triangle shapes and every closed shared model, 200 strikes
/// each.
#[test]
#[ignore = "needs ../shared/meshes and minutes in the test profile: run with --ignored"]
fn deep_strikes_on_every_closed_model() {
    let mut meshes: Vec<(String, haphe::mesh::Mesh)> = [
        Catalog::Sphere,
        Catalog::Blob,
        Catalog::Torus,
        Catalog::ConcaveCorner,
    ]
    .into_iter()
    .map(|which| (which.to_string(), which.with_triangles(20_000)))
    .collect();
    meshes.extend(closed_models(&support::meshes().join("models")));
    assert!(strike_family(meshes, 200) >= 10);
}

/// Sliding sideways under a hard press: the hand presses 10 mm into a flat floor (beyond
/// the saturation depth of 6.6 mm), then slides 40 mm across at 0.1 m/s while staying
/// that deep. The proxy holds all along and follows the hand across: it stays over the
/// hand within a skin (1 µm), the dead band a held proxy keeps; it used to stay at the
/// point where the hand went deep. The brute-force proxy does the same.
#[test]
fn sliding_under_a_hard_press_moves_the_held_proxy_with_the_hand() {
    let scene = super::floor(Material::default());
    let above = DVec3::new(-0.02, 0.01, 0.005);
    let mut path: Vec<DVec3> = (0..=150)
        .map(|k| above - DVec3::Z * (0.015 * k as f64 / 150.0))
        .collect();
    let pressed = *path.last().unwrap();
    path.extend((1..=400).map(|k| pressed + DVec3::new(1e-4, 0.0, 0.0) * k as f64));
    let mut proxy = Proxy::new(above, ProxyOptions::default());
    let (mut held, mut worst, mut previous) = (0, 0.0f64, above);
    for (k, &hip) in path.iter().enumerate() {
        let out = proxy.tick(&scene, hip, (hip - previous) * 1e3);
        previous = hip;
        if k > 150 {
            assert!(out.status.deep_hold, "tick {k}: {out:?}");
            held += 1;
            let across = (out.proxy - hip).truncate().length();
            worst = worst.max(across);
            assert!(out.proxy.z >= 0.0, "tick {k}: {out:?}");
        }
    }
    println!("held {held} ticks; proxy off the hand across by at most {worst:.3e} m");
    assert_eq!(held, 400);
    assert!(worst <= ProxyOptions::default().skin(), "{worst}");
    let check = check_proxy(&scene, &path, ProxyOptions::default());
    assert_eq!(check.mismatches, 0, "{check:?}");
    assert_eq!(check.inside, 0, "{check:?}");
}
