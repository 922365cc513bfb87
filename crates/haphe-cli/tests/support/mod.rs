//! What the device tests of the command share: the vendors' stand-in libraries, built
//! from crates/haphe-devices/tests/standin with the system's C compiler, and a child
//! process that is killed if a test fails half way.

#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Child, Command};

#[path = "../../../haphe-devices/tests/standin/library.rs"]
mod library;

/// A stand-in library of the tests' C sources.
#[derive(Debug, Clone, Copy)]
pub enum Standin {
    /// Force Dimension's `libdhd.so` (`dhd.c`).
    Dhd,
    /// OpenHaptics' `libHD.so` (`hd.c`), with its scheduler thread.
    Hd,
}

/// The stand-in's library file, built once per test process.
pub fn standin(which: Standin) -> PathBuf {
    library::standin(match which {
        Standin::Dhd => "dhd",
        Standin::Hd => "hd",
    })
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
