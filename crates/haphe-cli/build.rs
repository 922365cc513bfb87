//! Sets `cfg(can_mount)` when the build runs with the power to mount file systems (an
//! effective `CAP_SYS_ADMIN`, as root usually has outside a restricted container). The
//! disk-full test (`tests/hostile/disk_full.rs`) mounts a 1 MiB tmpfs and is marked
//! `#[cfg_attr(not(can_mount), ignore = "...")]`, so that a test summary counts it as
//! ignored, with the reason, where it cannot run.
//!
//! Decided when the build script runs (the first build, or after a change to this file):
//! the tests run as the user who built them.

fn main() {
    println!("cargo::rustc-check-cfg=cfg(can_mount)");
    println!("cargo::rerun-if-changed=build.rs");
    if can_mount() {
        println!("cargo::rustc-cfg=can_mount");
    }
}

/// Whether this process's effective capabilities include `CAP_SYS_ADMIN` (bit 21), read from
/// `/proc/self/status` (Linux; elsewhere, no).
fn can_mount() -> bool {
    const CAP_SYS_ADMIN: u32 = 21;
    let Ok(status) = std::fs::read_to_string("/proc/self/status") else {
        return false;
    };
    status
        .lines()
        .find_map(|line| line.strip_prefix("CapEff:"))
        .and_then(|hex| u64::from_str_radix(hex.trim(), 16).ok())
        .is_some_and(|caps| caps & (1 << CAP_SYS_ADMIN) != 0)
}
