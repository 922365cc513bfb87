//! What the command-line tests share: running the binary, reading what it printed, scratch
//! folders and small files. Each test binary uses its own part of it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Runs `haphe` with `args`, killing it (and failing the test) after `limit`. Its output
/// is read while it runs (a full pipe would stop it).
pub fn haphe_within(args: &[&str], limit: Duration) -> Output {
    let child = Command::new(env!("CARGO_BIN_EXE_haphe"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the haphe binary runs");
    finish_within(child, limit, &format!("haphe {args:?}"))
}

/// Waits for `child` (started with piped standard output and error), reading its output
/// meanwhile; kills it and fails the test, naming it as `what`, after `limit`.
pub fn finish_within(mut child: Child, limit: Duration, what: &str) -> Output {
    use std::io::Read;
    let drain = |mut pipe: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            pipe.read_to_end(&mut bytes).expect("read the output");
            bytes
        })
    };
    let stdout = drain(Box::new(child.stdout.take().expect("stdout")));
    let stderr = drain(Box::new(child.stderr.take().expect("stderr")));
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break status;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{what} ran longer than {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    Output {
        status,
        stdout: stdout.join().expect("stdout reader"),
        stderr: stderr.join().expect("stderr reader"),
    }
}

/// Runs `haphe` with `args` (at most two minutes).
pub fn haphe(args: &[&str]) -> Output {
    haphe_within(args, Duration::from_secs(120))
}

/// Runs `haphe` with `args`, expects success, and returns its standard output.
pub fn ok(args: &[&str]) -> String {
    let out = haphe(args);
    assert!(
        out.status.success(),
        "haphe {args:?} failed:\n{}{}",
        stdout(&out),
        stderr(&out)
    );
    stdout(&out)
}

/// `haphe simulate` on a small sphere (100 triangles), `args` added.
pub fn simulate_sphere(args: &[&str]) -> Output {
    let mut all = vec!["simulate", "--shape", "sphere", "--triangles", "100"];
    all.extend_from_slice(args);
    haphe(&all)
}

/// `haphe simulate` on the scene file `text`, written as `dir/s.toml`.
pub fn simulate_scene(dir: &Path, text: &str) -> Output {
    let scene = write(dir, "s.toml", text);
    haphe(&["simulate", "--scene", &scene])
}

/// Standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Standard output as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Asserts that the run failed with exit code 2 and a message containing every one of
/// `parts`, on one line, shown once, with no Debug output.
pub fn assert_error(o: &Output, parts: &[&str]) {
    let err = stderr(o);
    assert_eq!(
        o.status.code(),
        Some(2),
        "stderr: {err}\nstdout: {}",
        stdout(o)
    );
    for part in parts {
        assert!(err.contains(part), "{part:?} missing from: {err}");
    }
    for debug in ["Os {", "kind:", "IoError(", "ImageError"] {
        assert!(!err.contains(debug), "Debug output in: {err}");
    }
}

/// A fresh scratch folder for one test.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("haphe-cli-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// A path as text (the tests' paths are UTF-8).
pub fn s(p: &Path) -> &str {
    p.to_str().expect("a UTF-8 path")
}

/// Writes `bytes` to `dir/name` and returns the path as a string.
pub fn write(dir: &Path, name: &str, bytes: impl AsRef<[u8]>) -> String {
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("write");
    path.display().to_string()
}

/// A closed tetrahedron (OBJ) with its corner at `x` on the x axis, 0.1 m across.
pub fn tetrahedron(x: f64) -> String {
    format!(
        "v {x} 0 0\nv {} 0 0\nv {x} 0.1 0\nv {x} 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
        x + 0.1
    )
}

/// Writes a sphere of about `triangles` triangles to `path` with `haphe generate`.
pub fn generate_sphere(path: &Path, triangles: usize) {
    let o = haphe(&[
        "generate",
        "sphere",
        "--triangles",
        &triangles.to_string(),
        "-o",
        s(path),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

/// The names of the files in `dir`, sorted.
pub fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("read dir")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}
