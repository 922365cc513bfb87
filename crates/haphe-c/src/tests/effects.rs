//! Textures and force effects through the C ABI: felt and rendered as their definitions
//! say, refused naming the parameter and the specification.

use std::f64::consts::TAU;
use std::ffi::{CStr, CString, c_void};

use super::*;

/// The texture the tests set: 0.2 mm high, 2 mm long.
const AMPLITUDE: f64 = 2e-4;
const WAVELENGTH: f64 = 2e-3;
const TEXTURE: &CStr = c"sine:0.0002:0.002";

/// The forces of a proxy (500 N/m, the default material) whose device point slides along
/// x from -0.2 to -0.18 m, 1 mm under the top face of `cube_scene` (z = 0.5), with its
/// x positions.
fn slide(scene: *mut HapheScene) -> Vec<(f64, [f64; 3])> {
    let start = [-0.2, 0.0, 0.6];
    let mut proxy = std::ptr::null_mut();
    assert_eq!(
        haphe_proxy_new(start.as_ptr(), 3.3, 0.0, &mut proxy),
        HapheStatus::Ok
    );
    let mut out = Vec::new();
    for k in 0..=2000 {
        let x = -0.2 + 1e-5 * f64::from(k);
        let t = tick(proxy, scene, [x, 0.0, 0.499]);
        assert_eq!(t.in_contact, 1, "tick {k}");
        out.push((x, t.force));
    }
    haphe_proxy_free(proxy);
    out
}

/// The force of the texture's rule (the library's `scene::texture` module) 1 mm deep on
/// the top face at world x: the height `h = A sin(2πx₀/L) / 3` at the object's
/// `x₀ = x + 0.5` (its sines along y and z are 0 there), felt depth `e = d + h`, the force
/// `k e` out of the face and `−k e ∂h/∂x` along x.
fn textured_force(x: f64) -> [f64; 3] {
    let (k, d) = (500.0, 1e-3);
    let w = TAU / WAVELENGTH;
    let x0 = x + 0.5;
    let h = AMPLITUDE * (w * x0).sin() / 3.0;
    let slope = AMPLITUDE * w * (w * x0).cos() / 3.0;
    [-k * (d + h) * slope, 0.0, k * (d + h)]
}

/// Through the C ABI: a texture set on an object is felt as its rule says, cleared by null
/// or "" (the plain face pushes straight out), and a refused one is named and leaves the
/// texture as it was.
#[test]
fn a_texture_is_felt_as_its_rule_says_and_refused_by_name() {
    let scene = cube_scene();
    let plain = slide(scene);
    for (x, f) in &plain {
        assert!(
            f[0].abs() < 1e-9 && (f[2] - 0.5).abs() < 1e-3,
            "plain at {x}: {f:?}"
        );
    }
    assert_eq!(
        haphe_scene_set_texture(scene, 0, TEXTURE.as_ptr()),
        HapheStatus::Ok
    );
    let felt = slide(scene);
    let most = felt.iter().map(|(_, f)| f[0].abs()).fold(0.0, f64::max);
    // Guard: the slide crosses 10 wavelengths, the force along x swings both ways.
    assert!(most > 0.1, "{most}");
    for (x, f) in &felt {
        let expected = textured_force(*x);
        for axis in [0, 2] {
            assert!(
                (f[axis] - expected[axis]).abs() < 0.01 * most,
                "at x = {x}: {f:?}, the rule gives {expected:?}"
            );
        }
    }
    // Refused, named, and the texture stays.
    for (spec, says) in [
        (c"sine:-0.0002:0.002", "texture amplitude must be"),
        (c"sine:nan:0.002", "texture amplitude must be"),
        (c"noise:0.0001:inf", "texture wavelength must be"),
        (c"sine:0.001:0.001", "steeper bumps"),
        (c"bumps:1:2", "unknown kind `bumps`"),
        (c"sine:0.001", "expected `KIND:AMPLITUDE:WAVELENGTH`"),
    ] {
        let status = haphe_scene_set_texture(scene, 0, spec.as_ptr());
        assert_eq!(status, HapheStatus::InvalidArgument);
        let message = last_error();
        let prefix = format!("texture: `{}`: ", spec.to_str().expect("UTF-8"));
        assert!(
            message.starts_with(&prefix) && message.contains(says),
            "{message}"
        );
    }
    assert_eq!(slide(scene), felt, "a refusal leaves the texture");
    let not_utf8 = CString::new(vec![b's', 0xff]).expect("no NUL");
    assert_eq!(
        haphe_scene_set_texture(scene, 0, not_utf8.as_ptr()),
        HapheStatus::InvalidArgument
    );
    assert_eq!(last_error(), "texture is not UTF-8");
    assert_eq!(
        haphe_scene_set_texture(scene, 7, TEXTURE.as_ptr()),
        HapheStatus::InvalidArgument
    );
    assert_eq!(last_error(), "no object 7 in the scene");
    assert_eq!(
        haphe_scene_set_texture(std::ptr::null_mut(), 0, TEXTURE.as_ptr()),
        HapheStatus::InvalidArgument
    );
    assert_eq!(last_error(), "scene is null");
    // Cleared by null and by "".
    for none in [std::ptr::null(), c"".as_ptr()] {
        assert_eq!(
            haphe_scene_set_texture(scene, 0, TEXTURE.as_ptr()),
            HapheStatus::Ok
        );
        assert_eq!(haphe_scene_set_texture(scene, 0, none), HapheStatus::Ok);
        assert_eq!(slide(scene), plain);
    }
    haphe_scene_free(scene);
}

/// The records of 1 s of the simulated hand pressing onto `scene` at `rate_hz`, or the
/// status of the refused run.
fn press(scene: *mut HapheScene, rate_hz: f64) -> Result<Vec<HapheTickRecord>, HapheStatus> {
    extern "C" fn keep(record: *const HapheTickRecord, user: *mut c_void) {
        // SAFETY: `user` is the vector passed below, `record` valid for the call.
        unsafe { (*user.cast::<Vec<HapheTickRecord>>()).push(*record) };
    }
    let mut records: Vec<HapheTickRecord> = Vec::new();
    let status = haphe_run(
        scene,
        c"hand".as_ptr(),
        c"press".as_ptr(),
        1.0,
        rate_hz,
        Some(keep),
        (&raw mut records).cast(),
        std::ptr::null_mut(),
    );
    if status == HapheStatus::Ok {
        Ok(records)
    } else {
        Err(status)
    }
}

/// The free-space ticks after the safe start's 50 ms ramp.
fn free(records: &[HapheTickRecord]) -> Vec<&HapheTickRecord> {
    records
        .iter()
        .filter(|r| r.t >= 0.05 && r.in_contact == 0)
        .collect()
}

/// Through the C ABI: a viscosity drags by −B v in free space in a run (clamped to the
/// maximum force), gone once the effects are cleared; refused specifications name
/// `effect` and the specification; a vibration above half the rate is refused by the run.
#[test]
fn effects_are_rendered_by_the_run_and_refused_by_name() {
    let scene = cube_scene();
    assert_eq!(
        haphe_scene_add_effect(scene, c"viscosity:2".as_ptr()),
        HapheStatus::Ok
    );
    let records = press(scene, 1000.0).expect("the run");
    let free_ticks = free(&records);
    let mut unclamped = 0;
    for r in &free_ticks {
        let drag = r.velocity.map(|v| -2.0 * v);
        let length = drag.iter().map(|d| d * d).sum::<f64>().sqrt();
        let scale = (3.3 / length).min(1.0);
        unclamped += usize::from(scale == 1.0 && length > 0.02);
        for axis in 0..3 {
            assert!(
                (r.force[axis] - scale * drag[axis]).abs() <= 1e-12,
                "tick {}: {:?} against -2 v = {drag:?}",
                r.tick,
                r.force
            );
        }
    }
    // Guard: many free ticks with the hand moving and the drag below the maximum.
    assert!(unclamped > 200, "{unclamped} of {}", free_ticks.len());
    assert_eq!(haphe_scene_clear_effects(scene), HapheStatus::Ok);
    let records = press(scene, 1000.0).expect("the run");
    assert!(free(&records).iter().all(|r| r.force == [0.0; 3]));

    for (spec, says) in [
        (
            c"wobble:1",
            "unknown kind `wobble` (expected one of `vibration`",
        ),
        (c"", "unknown kind ``"),
        (c"viscosity:-2", "viscosity must be a finite number from 0"),
        (c"viscosity:nan", "viscosity must be a finite number from 0"),
        (c"vibration:inf:0.3", "vibration frequency must be"),
        (c"spring:10:0:0", "expected `spring:K:X:Y:Z`"),
        (c"magnet:0:1", "magnet distance must be"),
        (c"constant:0:x:0", "`x` is not a number"),
    ] {
        let status = haphe_scene_add_effect(scene, spec.as_ptr());
        assert_eq!(status, HapheStatus::InvalidArgument);
        let message = last_error();
        let prefix = format!("effect: `{}`: ", spec.to_str().expect("UTF-8"));
        assert!(
            message.starts_with(&prefix) && message.contains(says),
            "{message}"
        );
    }
    assert_eq!(
        haphe_scene_add_effect(scene, std::ptr::null()),
        HapheStatus::InvalidArgument
    );
    assert_eq!(last_error(), "effect is null");
    assert_eq!(
        haphe_scene_add_effect(std::ptr::null_mut(), c"viscosity:2".as_ptr()),
        HapheStatus::InvalidArgument
    );
    assert_eq!(
        haphe_scene_clear_effects(std::ptr::null_mut()),
        HapheStatus::InvalidArgument
    );

    // 600 Hz is a vibration, renderable from 1200 Hz up.
    assert_eq!(
        haphe_scene_add_effect(scene, c"vibration:600:0.3".as_ptr()),
        HapheStatus::Ok
    );
    assert_eq!(
        press(scene, 1000.0).err(),
        Some(HapheStatus::InvalidArgument)
    );
    assert_eq!(
        last_error(),
        "effect: `vibration:600:0.3`: vibration frequency must be at most half the servo rate (500 Hz at 1000 Hz), not 600"
    );
    assert!(press(scene, 1200.0).is_ok(), "{}", last_error());

    // At most 16 effects.
    for _ in 1..16 {
        assert_eq!(
            haphe_scene_add_effect(scene, c"constant:0:0:0.01".as_ptr()),
            HapheStatus::Ok
        );
    }
    assert_eq!(
        haphe_scene_add_effect(scene, c"viscosity:1".as_ptr()),
        HapheStatus::Full
    );
    assert!(
        last_error().starts_with("effect: `viscosity:1`: the scene holds 16 effects"),
        "{}",
        last_error()
    );
    haphe_scene_free(scene);
}
