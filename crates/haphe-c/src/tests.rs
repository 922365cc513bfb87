//! The committed header equals what cbindgen makes of the sources; failures and panics
//! come back as statuses with messages.

use std::ffi::CStr;

use super::*;

mod effects;

#[test]
fn header_is_current() {
    let dir = env!("CARGO_MANIFEST_DIR");
    let config =
        cbindgen::Config::from_file(format!("{dir}/cbindgen.toml")).expect("cbindgen.toml");
    let mut generated = Vec::new();
    cbindgen::Builder::new()
        .with_crate(dir)
        .with_config(config)
        .generate()
        .expect("cbindgen runs on the crate")
        .write(&mut generated);
    let path = format!("{dir}/include/haphe.h");
    if std::env::var_os("HAPHE_BLESS").is_some() {
        std::fs::write(&path, &generated).expect("write the header");
    }
    let committed = std::fs::read(&path).unwrap_or_default();
    assert!(
        committed == generated,
        "{path} differs from the generated header: run HAPHE_BLESS=1 cargo test -p haphe-c header"
    );
}

fn last_error() -> String {
    // SAFETY: haphe_last_error never returns null and the string lives until the next
    // failing call on this thread.
    unsafe { CStr::from_ptr(haphe_last_error()) }
        .to_string_lossy()
        .into_owned()
}

#[test]
fn bad_file_names_the_file() {
    let dir = std::env::temp_dir().join(format!("haphe-c-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let bad = dir.join("bad.obj");
    std::fs::write(&bad, "v 0 0 0\nf 1 2 9\n").expect("write");
    let path = std::ffi::CString::new(bad.to_str().expect("utf-8")).expect("no NUL");
    let mut shape = std::ptr::null_mut();
    assert_eq!(
        haphe_shape_from_file(path.as_ptr(), 1.0, &mut shape),
        HapheStatus::Format
    );
    assert!(shape.is_null());
    let message = last_error();
    assert!(
        message.contains("bad.obj") && message.contains("line 2"),
        "{message}"
    );
    let missing = std::ffi::CString::new("/nonexistent/x.stl").expect("no NUL");
    assert_eq!(
        haphe_shape_from_file(missing.as_ptr(), 1.0, &mut shape),
        HapheStatus::Io
    );
    assert!(last_error().contains("/nonexistent/x.stl"));
    assert_eq!(
        haphe_shape_inside(
            std::ptr::null(),
            std::ptr::null(),
            0,
            0,
            std::ptr::null_mut()
        ),
        HapheStatus::InvalidArgument
    );
    std::fs::remove_dir_all(&dir).expect("clean up");
}

#[test]
fn a_panic_becomes_a_status() {
    let status = error::guard(|| panic!("boom"));
    assert_eq!(status, HapheStatus::Panic);
    assert!(last_error().contains("boom"));
}

/// The unit cube [0, 1]³ from arrays.
fn cube() -> *mut HapheShape {
    cube_of(1.0)
}

/// The cube [0, side]³.
fn cube_of(side: f64) -> *mut HapheShape {
    let mut vertices = Vec::new();
    for z in [0.0, side] {
        for (x, y) in [(0.0, 0.0), (side, 0.0), (side, side), (0.0, side)] {
            vertices.extend([x, y, z]);
        }
    }
    let faces: [u32; 36] = [
        0, 2, 1, 0, 3, 2, 0, 1, 5, 0, 5, 4, 1, 2, 6, 1, 6, 5, 2, 3, 7, 2, 7, 6, 3, 0, 4, 3, 4, 7,
        4, 5, 6, 4, 6, 7,
    ];
    let mut shape = std::ptr::null_mut();
    assert_eq!(
        haphe_shape_from_arrays(vertices.as_ptr(), 8, faces.as_ptr(), 12, &mut shape),
        HapheStatus::Ok,
        "{}",
        last_error()
    );
    shape
}

#[test]
fn a_non_finite_row_is_refused_by_name_or_skipped_on_request() {
    let shape = cube();
    // Row 0 inside, row 1 outside, row 2 not finite, row 3 inside, row 4 infinite.
    let points: [[f64; 3]; 5] = [
        [0.5, 0.5, 0.5],
        [2.0, 0.5, 0.5],
        [0.5, f64::NAN, 0.5],
        [0.25, 0.75, 0.5],
        [f64::INFINITY, 0.5, 0.5],
    ];
    let mut inside = [7u8; 5];
    let status = haphe_shape_inside(shape, points.as_ptr().cast(), 5, 0, inside.as_mut_ptr());
    assert_eq!(status, HapheStatus::InvalidArgument);
    assert!(
        last_error().starts_with("points: row 2 is not finite"),
        "{}",
        last_error()
    );
    assert_eq!(inside, [7; 5], "nothing written when refused");
    let status = haphe_shape_inside(
        shape,
        points.as_ptr().cast(),
        5,
        HAPHE_SKIP_NONFINITE,
        inside.as_mut_ptr(),
    );
    assert_eq!(status, HapheStatus::Ok);
    assert_eq!(inside, [1, 0, 0, 1, 0]);
    assert_eq!(
        haphe_shape_inside(shape, points.as_ptr().cast(), 5, 6, inside.as_mut_ptr()),
        HapheStatus::InvalidArgument
    );
    assert!(
        last_error().starts_with("flags: unknown bits 0x6"),
        "{}",
        last_error()
    );

    // Segments straight down through the top face at z = 1, from z = 2 to z = 0.5.
    let p0: [[f64; 3]; 3] = [[0.5, 0.5, 2.0], [0.25, 0.25, 2.0], [0.75, 0.5, 2.0]];
    let mut p1: [[f64; 3]; 3] = [[0.5, 0.5, 0.5], [0.25, 0.25, 0.5], [0.75, 0.5, 0.5]];
    p1[1][2] = f64::NEG_INFINITY;
    let blank = HapheCrossing {
        t: 0.0,
        triangle: 99,
        point: [0.0; 3],
        normal: [0.0; 3],
        entering: 9,
    };
    let mut out = [blank; 3];
    let call = |flags, out: &mut [HapheCrossing; 3]| {
        haphe_shape_first_crossing(
            shape,
            p0.as_ptr().cast(),
            p1.as_ptr().cast(),
            3,
            flags,
            out.as_mut_ptr(),
        )
    };
    assert_eq!(call(0, &mut out), HapheStatus::InvalidArgument);
    assert!(
        last_error().starts_with("p1: row 1 is not finite"),
        "{}",
        last_error()
    );
    assert!(
        out.iter().all(|c| c.triangle == 99),
        "nothing written when refused"
    );
    assert_eq!(call(HAPHE_SKIP_NONFINITE, &mut out), HapheStatus::Ok);
    assert!(out[1].t.is_nan() && out[1].triangle == -1 && out[1].entering == 0);
    for i in [0, 2] {
        // From z = 2 to 0.5, the top face is met at two thirds of the way.
        assert!((out[i].t - 2.0 / 3.0).abs() < 1e-12, "{}", out[i].t);
        assert!(matches!(out[i].triangle, 10 | 11) && out[i].entering == 1);
    }
    haphe_shape_free(shape);
}

/// The records of a C run of the simulated hand pressing onto a centred cube for 3 s,
/// with the clutch on button 1 and the presses given.
fn run_with_buttons(presses: &[HapheButtonPress]) -> Vec<HapheTickRecord> {
    extern "C" fn keep(record: *const HapheTickRecord, user: *mut std::ffi::c_void) {
        // SAFETY: `user` is the vector passed below, `record` valid for the call.
        unsafe { (*user.cast::<Vec<HapheTickRecord>>()).push(*record) };
    }
    let scene = cube_scene();
    let mut records: Vec<HapheTickRecord> = Vec::new();
    let status = haphe_run_with_buttons(
        scene,
        c"hand".as_ptr(),
        c"press".as_ptr(),
        3.0,
        1000.0,
        1,
        presses.as_ptr(),
        presses.len(),
        Some(keep),
        (&raw mut records).cast(),
        std::ptr::null_mut(),
    );
    assert_eq!(status, HapheStatus::Ok, "{}", last_error());
    haphe_scene_free(scene);
    records
}

/// One tick of `proxy` against `scene` with the device point at `hip`, at rest.
fn tick(proxy: *mut HapheProxy, scene: *mut HapheScene, hip: [f64; 3]) -> HapheTick {
    let mut out = std::mem::MaybeUninit::<HapheTick>::uninit();
    let status = haphe_proxy_tick(
        proxy,
        scene,
        hip.as_ptr(),
        std::ptr::null(),
        out.as_mut_ptr(),
    );
    assert_eq!(status, HapheStatus::Ok, "{}", last_error());
    // SAFETY: written on success.
    unsafe { out.assume_init() }
}

/// A scene holding the unit cube centred on the origin.
fn cube_scene() -> *mut HapheScene {
    let shape = cube();
    let mut scene = std::ptr::null_mut();
    assert_eq!(haphe_scene_new(2, &mut scene), HapheStatus::Ok);
    let position = [-0.5, -0.5, -0.5];
    let status = haphe_scene_add(
        scene,
        shape,
        position.as_ptr(),
        std::ptr::null(),
        std::ptr::null(),
        std::ptr::null_mut(),
    );
    assert_eq!(status, HapheStatus::Ok, "{}", last_error());
    haphe_shape_free(shape);
    scene
}

/// Through the C ABI: the records carry the buttons and the clutch; held on the way down
/// (no force in either run, so the hand moves as without the press), the tool stays and
/// then continues moved by minus the hand's travel.
#[test]
fn the_records_carry_the_buttons_and_the_clutch_keeps_the_tool() {
    let free = run_with_buttons(&[]);
    assert!(free.iter().all(|r| r.buttons == 0 && r.clutch == 0));
    let first_force = free
        .iter()
        .position(|r| r.force != [0.0; 3])
        .expect("the press touches");
    let (start, end) = (first_force / 4, 3 * first_force / 4);
    let press = HapheButtonPress {
        button: 1,
        from: start as f64 / 1000.0,
        until: end as f64 / 1000.0,
    };
    let held = run_with_buttons(&[press]);
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let norm = |a: [f64; 3]| a.iter().map(|x| x * x).sum::<f64>().sqrt();
    let before = free[start - 1].hip;
    let travel = sub(free[end - 1].hip, before);
    assert!(norm(travel) > 5e-3, "the hand travels {travel:?}");
    for k in 0..=end {
        let is_held = (start..end).contains(&k);
        let r = &held[k];
        assert_eq!(
            (r.buttons, r.clutch),
            (if is_held { 2 } else { 0 }, u8::from(is_held))
        );
        let tool = if k < start {
            free[k].hip
        } else if is_held {
            before
        } else {
            sub(free[k].hip, travel)
        };
        assert!(norm(sub(r.hip, tool)) < 1e-12, "tick {k}");
    }
    let bad = HapheButtonPress {
        button: 32,
        from: 0.0,
        until: 1.0,
    };
    let scene = cube_scene();
    let call = |clutch: i32, presses: &[HapheButtonPress]| {
        haphe_run_with_buttons(
            scene,
            c"hand".as_ptr(),
            c"press".as_ptr(),
            0.1,
            1000.0,
            clutch,
            presses.as_ptr(),
            presses.len(),
            None,
            std::ptr::null_mut(),
            std::ptr::null_mut(),
        )
    };
    assert_eq!(call(32, &[]), HapheStatus::InvalidArgument);
    assert!(
        last_error().contains("clutch_button 32"),
        "{}",
        last_error()
    );
    assert_eq!(call(-1, &[bad]), HapheStatus::InvalidArgument);
    assert!(
        last_error().contains("presses: press of button 32"),
        "{}",
        last_error()
    );
    haphe_scene_free(scene);
}

/// Through the C ABI: a tool of radius r pressed onto the top face of a cube rests with its
/// centre r above the face, where a point at the same device position is free; a radius
/// outside its domain is refused naming `tool_radius`.
#[test]
fn the_proxy_takes_a_tool_radius() {
    let scene = cube_scene(); // the cube [-0.5, 0.5]³: its top face at z = 0.5
    let r = 0.05;
    let start = [0.0, 0.0, 1.0];
    let (mut tool, mut point) = (std::ptr::null_mut(), std::ptr::null_mut());
    assert_eq!(
        haphe_proxy_new(start.as_ptr(), 3.3, r, &mut tool),
        HapheStatus::Ok
    );
    assert_eq!(
        haphe_proxy_new(start.as_ptr(), 3.3, 0.0, &mut point),
        HapheStatus::Ok
    );
    let hip = [0.0, 0.0, 0.5 + r - 1e-3];
    let tick = |proxy| tick(proxy, scene, hip);
    let free = tick(point);
    assert_eq!(free.in_contact, 0);
    let touching = tick(tool);
    assert_eq!(touching.in_contact, 1);
    assert!(
        (touching.proxy[2] - (0.5 + r)).abs() < 1e-5,
        "{:?}",
        touching.proxy
    );
    assert!(
        (touching.point[2] - 0.5).abs() < 1e-9,
        "{:?}",
        touching.point
    );
    assert!(
        (touching.penetration - 1e-3).abs() < 1e-5,
        "{}",
        touching.penetration
    );
    haphe_proxy_free(tool);
    haphe_proxy_free(point);
    // The scene's box is the unit cube: a tool fits up to its diagonal, √3 m, beyond the
    // domain's 0.5 m.
    assert_eq!(haphe_scene_check_tool_radius(scene, 0.5), HapheStatus::Ok);
    haphe_scene_free(scene);
    // A scene of a 1 cm cube: a tool fits up to 1 cm × √3.
    let shape = cube_of(0.01);
    let mut small = std::ptr::null_mut();
    assert_eq!(haphe_scene_new(1, &mut small), HapheStatus::Ok);
    let status = haphe_scene_add(
        small,
        shape,
        std::ptr::null(),
        std::ptr::null(),
        std::ptr::null(),
        std::ptr::null_mut(),
    );
    assert_eq!(status, HapheStatus::Ok, "{}", last_error());
    haphe_shape_free(shape);
    let diagonal = 0.01 * 3f64.sqrt();
    assert_eq!(
        haphe_scene_check_tool_radius(small, 0.99 * diagonal),
        HapheStatus::Ok
    );
    let status = haphe_scene_check_tool_radius(small, 1.01 * diagonal);
    assert_eq!(status, HapheStatus::InvalidArgument);
    let message = last_error();
    assert!(
        message.starts_with("tool_radius must be at most 0.01732 m"),
        "{message}"
    );
    assert_eq!(
        haphe_scene_check_tool_radius(std::ptr::null_mut(), 0.001),
        HapheStatus::InvalidArgument
    );
    haphe_scene_free(small);
    for bad in [-1e-3, f64::NAN, f64::INFINITY, 10.0] {
        let mut proxy = std::ptr::null_mut();
        let status = haphe_proxy_new(std::ptr::null(), 3.3, bad, &mut proxy);
        assert_eq!(status, HapheStatus::InvalidArgument, "{bad}");
        assert!(proxy.is_null());
        let message = last_error();
        assert!(message.starts_with("tool_radius must be"), "{message}");
    }
}
