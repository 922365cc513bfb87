//! Sets `cfg(shared_meshes)` when the larger collection of test meshes lies at
//! `../shared/meshes` beside the repository root. The tests read real meshes from there when
//! it is present and from the repository's own `meshes/` otherwise; the tests that need the
//! larger collection are marked `#[cfg_attr(not(shared_meshes), ignore = "...")]`, so that a
//! test summary counts them as ignored, with the reason, where it is absent.
//!
//! Decided when the build script runs (the first build, or after a change to this file):
//! after adding or removing `../shared/meshes`, `touch crates/haphe/build.rs`.

use std::path::Path;

fn main() {
    println!("cargo::rustc-check-cfg=cfg(shared_meshes)");
    println!("cargo::rerun-if-changed=build.rs");
    let manifest = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_default();
    if Path::new(&manifest).join("../../../shared/meshes").is_dir() {
        println!("cargo::rustc-cfg=shared_meshes");
    }
}
