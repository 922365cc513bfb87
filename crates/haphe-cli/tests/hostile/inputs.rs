//! Inputs that never end, are not files, or are opened twice.

use std::time::Duration;

use crate::common::{assert_error, haphe_within, scratch, stdout, tetrahedron, write};

/// `/dev/zero` never ends: refused at once as every kind of input, not read.
#[test]
fn an_endless_device_is_refused_as_every_kind_of_input() {
    let dir = scratch("endless");
    let mesh = write(&dir, "t.obj", tetrahedron(0.0));
    let quick = Duration::from_secs(30);
    let cases: [&[&str]; 11] = [
        &["validate", "/dev/zero"],
        &["view", "--mesh", "/dev/zero", "--no-open"],
        &["view", "--scene", "/dev/zero", "--no-open"],
        &[
            "view",
            "--shape",
            "box",
            "--triangles",
            "100",
            "--replay",
            "/dev/zero",
            "--no-open",
        ],
        &["run", "--device", "hand", "--mesh", "/dev/zero"],
        &["run", "--device", "hand", "--scene", "/dev/zero"],
        &["build", "/dev/zero", "-o", "x.map"],
        &["query", "/dev/zero", "--inside", &mesh],
        &["query", &mesh, "--inside", "/dev/zero"],
        &["simulate", "--scene", "/dev/zero"],
        &[
            "simulate",
            "--shape",
            "sphere",
            "--triangles",
            "100",
            "--replay",
            "/dev/zero",
        ],
    ];
    for args in cases {
        if args[0] == "view" && cfg!(not(feature = "view")) {
            continue; // not in this build (CI runs these with every feature too)
        }
        let o = haphe_within(args, quick);
        if args[0] == "validate" {
            // validate reports each file and goes on; the exit code says unreadable.
            assert_eq!(o.status.code(), Some(2));
            assert!(
                stdout(&o).contains("/dev/zero: it is a character device"),
                "{}",
                stdout(&o)
            );
        } else {
            assert_error(&o, &["/dev/zero", "character device"]);
        }
    }
}

/// A directory is refused with a message naming it, once.
#[test]
fn a_directory_is_refused_once() {
    let dir = scratch("dir-input");
    let o = haphe_within(
        &["build", dir.to_str().unwrap(), "-o", "x.map"],
        Duration::from_secs(30),
    );
    assert_error(
        &o,
        &["it is a directory; a mesh file must be a regular file or a pipe"],
    );
    let err = crate::common::stderr(&o);
    assert_eq!(err.matches("directory").count(), 1, "{err}");
}

/// A named pipe as the object of `haphe query` is read once as a stream: with a writer
/// on the other end, the query answers (it used to block forever, opened twice).
/// Unix systems have `mkfifo`; elsewhere the test is ignored, saying so, instead of
/// passing unrun.
#[test]
#[cfg_attr(not(unix), ignore = "needs mkfifo (a Unix system)")]
fn a_named_pipe_object_is_read_once() {
    let dir = scratch("fifo");
    let fifo = dir.join("object.obj");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    assert!(
        made.as_ref().is_ok_and(|s| s.success()),
        "mkfifo {}: {made:?}",
        fifo.display()
    );
    let points = write(&dir, "p.csv", "0.01,0.01,0.01\n1,1,1\n");
    let writer_path = fifo.clone();
    let writer = std::thread::spawn(move || {
        std::fs::write(&writer_path, tetrahedron(0.0)).expect("write to the pipe");
    });
    let o = haphe_within(
        &["query", fifo.to_str().unwrap(), "--inside", &points],
        Duration::from_secs(30),
    );
    writer.join().expect("writer");
    assert_eq!(o.status.code(), Some(0), "{}", crate::common::stderr(&o));
    assert_eq!(stdout(&o), "inside\noutside\n");
}

/// A file larger than its kind's limit is refused before it is read, naming the limit
/// (a sparse scene file of 17 MiB: the limit for scene files is 16 MiB).
#[test]
fn a_file_over_its_limit_is_refused_naming_the_limit() {
    let dir = scratch("limit");
    let path = dir.join("huge.toml");
    let file = std::fs::File::create(&path).expect("create");
    file.set_len(17 << 20).expect("sparse file");
    let o = haphe_within(
        &["simulate", "--scene", path.to_str().unwrap()],
        Duration::from_secs(30),
    );
    assert_error(
        &o,
        &[
            "huge.toml",
            "larger than the limit for a scene file",
            "16 MiB",
        ],
    );
}
