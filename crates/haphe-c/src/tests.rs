//! The committed header equals what cbindgen makes of the sources; failures and panics
//! come back as statuses with messages.

use std::ffi::CStr;

use super::*;

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
        haphe_shape_inside(std::ptr::null(), std::ptr::null(), 0, std::ptr::null_mut()),
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
