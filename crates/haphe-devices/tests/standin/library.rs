//! Builds the stand-in vendor libraries of this folder with the system's C compiler. Shared
//! by the device tests of haphe-devices and those of the command (haphe-cli), which
//! include this file by its path.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::{Mutex, OnceLock};

/// Builds `standin/{name}.c` into a shared library, once per test process, and returns its
/// file. The tests run in parallel: one must not load the library while another is still
/// writing it, hence the lock held while the compiler runs.
pub fn standin(name: &str) -> PathBuf {
    static BUILT: OnceLock<Mutex<Vec<(String, PathBuf)>>> = OnceLock::new();
    let built = BUILT.get_or_init(|| Mutex::new(Vec::new()));
    let mut built = built
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if let Some((_, p)) = built.iter().find(|(n, _)| n == name) {
        return p.clone();
    }
    // Both crates sit side by side in crates/, so this path holds from either.
    let source = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../haphe-devices/tests/standin")
        .join(format!("{name}.c"));
    // The crates share the target's scratch folder: each builds its own copy.
    let out = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("lib{name}_{}_standin.so", env!("CARGO_PKG_NAME")));
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let status = Command::new(&cc)
        .args(["-shared", "-fPIC", "-O2", "-Wall", "-Werror", "-o"])
        .arg(&out)
        .arg(&source)
        .args(["-lpthread", "-lm"])
        .status()
        .unwrap_or_else(|e| panic!("cannot run the C compiler {cc}: {e}"));
    assert!(status.success(), "{cc} failed on {}", source.display());
    built.push((name.to_string(), out.clone()));
    out
}
