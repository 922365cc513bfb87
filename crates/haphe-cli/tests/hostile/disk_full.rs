//! A full disk: every command that writes leaves either the old file intact or the
//! complete new one, and no temporary file. On a 1 MiB tmpfs mounted for the test: where
//! the build has no power to mount (`cfg(can_mount)`, see `build.rs`), the test is ignored
//! with the reason, and the test summary counts it.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::{files_in, generate_sphere, haphe};

/// A 1 MiB tmpfs, unmounted when dropped.
struct Tmpfs(PathBuf);

impl Tmpfs {
    fn mount(name: &str) -> Result<Tmpfs, String> {
        let dir = crate::common::scratch(name);
        let status = Command::new("mount")
            .args(["-t", "tmpfs", "-o", "size=1m", "tmpfs"])
            .arg(&dir)
            .output()
            .map_err(|e| format!("cannot run mount: {e}"))?;
        if status.status.success() {
            Ok(Tmpfs(dir))
        } else {
            Err(String::from_utf8_lossy(&status.stderr).trim().to_owned())
        }
    }
}

impl Drop for Tmpfs {
    fn drop(&mut self) {
        let _ = Command::new("umount").arg(&self.0).status();
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn old_file(dir: &Path, name: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, b"the old contents\n").expect("write the old file");
    path
}

#[test]
#[cfg_attr(
    not(can_mount),
    ignore = "needs the power to mount a tmpfs (CAP_SYS_ADMIN, as root)"
)]
fn a_full_disk_leaves_the_old_file_and_no_temporary_file() {
    let disk = Tmpfs::mount("disk-full")
        .unwrap_or_else(|why| panic!("cannot mount a 1 MiB tmpfs although allowed: {why}"));
    let dir = &disk.0;
    let mesh = std::env::temp_dir().join(format!("haphe-hostile-{}-mesh.stl", std::process::id()));
    let m = mesh.to_str().unwrap();
    generate_sphere(&mesh, 40_000);
    let cases: Vec<(&str, Vec<String>)> = vec![
        (
            "big.stl",
            vec![
                "generate".into(),
                "sphere".into(),
                "--triangles".into(),
                "100000".into(),
                "-o".into(),
            ],
        ),
        ("big.map", vec!["build".into(), m.into(), "-o".into()]),
        (
            "trace.csv",
            vec![
                "simulate".into(),
                "--shape".into(),
                "sphere".into(),
                "--triangles".into(),
                "200".into(),
                "--seconds".into(),
                "20".into(),
                "--out".into(),
            ],
        ),
    ];
    for (name, mut args) in cases {
        let target = old_file(dir, name);
        args.push(target.display().to_string());
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = haphe(&args);
        let err = crate::common::stderr(&o);
        assert_eq!(
            o.status.code(),
            Some(2),
            "{args:?} should fail on a full disk: {err}"
        );
        assert!(err.contains(name) && err.contains("No space left"), "{err}");
        assert_eq!(
            std::fs::read(&target).unwrap(),
            b"the old contents\n",
            "{name}"
        );
        assert_eq!(files_in(dir), [name], "{args:?} left a temporary file");
        std::fs::remove_file(&target).unwrap();
    }
    // A plot fits: written whole, nothing else left.
    let plot = dir.join("p.png");
    let o = haphe(&[
        "simulate",
        "--shape",
        "sphere",
        "--triangles",
        "200",
        "--seconds",
        "0.2",
        "--plot",
        plot.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", crate::common::stderr(&o));
    assert!(std::fs::read(&plot).unwrap().starts_with(b"\x89PNG"));
    assert_eq!(files_in(dir), ["p.png"]);
    let _ = std::fs::remove_file(&mesh);
}
