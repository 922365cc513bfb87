//! What the device tests of the command share: the vendors' stand-in libraries, built
//! from crates/haphe-devices/tests/standin with the system's C compiler, and a child
//! process that is killed if a test fails half way.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Child, Command};
use std::sync::OnceLock;

/// A stand-in library of the tests' C sources.
#[derive(Debug, Clone, Copy)]
pub enum Standin {
    /// Force Dimension's `libdhd.so` (`dhd.c`).
    Dhd,
    /// OpenHaptics' `libHD.so` (`hd.c`), with its scheduler thread.
    Hd,
}

/// Builds the stand-in once per test process (the tests run in parallel, and one must not
/// load the library while another is still writing it) and returns its file.
pub fn standin(which: Standin) -> PathBuf {
    static DHD: OnceLock<PathBuf> = OnceLock::new();
    static HD: OnceLock<PathBuf> = OnceLock::new();
    let (cell, source, name) = match which {
        Standin::Dhd => (&DHD, "dhd.c", "libdhd_cli_standin.so"),
        Standin::Hd => (&HD, "hd.c", "libHD_cli_standin.so"),
    };
    cell.get_or_init(|| {
        let source = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../haphe-devices/tests/standin")
            .join(source);
        let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
        let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
        let status = Command::new(&cc)
            .args(["-shared", "-fPIC", "-O2", "-o"])
            .arg(&out)
            .arg(&source)
            .args(["-lpthread", "-lm"])
            .status()
            .expect("a C compiler");
        assert!(
            status.success(),
            "{cc} could not build {}",
            source.display()
        );
        out
    })
    .clone()
}

/// A child process, killed if the test fails half way.
pub struct Running(pub Child);

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Sends `signal` (`INT`, `TERM`) to the child.
pub fn signal(child: &Child, signal: &str) {
    let status = Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(status.success());
}
