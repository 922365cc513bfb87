//! `haphe view` from the command line: bad input is refused with where it is; a live view
//! and a replay serve their page, and Ctrl-C stops them cleanly with the servo's figures.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

fn haphe(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_haphe"))
        .args(args)
        .output()
        .expect("haphe runs")
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("haphe-view-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch dir");
    dir.join(name)
}

#[test]
fn bad_input_is_refused_with_where_it_is() {
    let bad = scratch("bad.csv");
    std::fs::write(&bad, "t,x,y,z\n0,0,0,0\n").expect("write");
    let out = haphe(&[
        "view",
        "--replay",
        bad.to_str().expect("utf-8"),
        "--no-open",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("bad.csv: line 1: not a haphe trace"), "{err}");
    let _ = std::fs::remove_file(&bad);

    let out = haphe(&[
        "view",
        "--shape",
        "sphere",
        "--device",
        "phantom",
        "--no-open",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--device \"phantom\": unknown device"),
        "{err}"
    );
    let out = Command::new(env!("CARGO_BIN_EXE_haphe"))
        .env("HAPHE_DHD_LIBRARY", "/nonexistent/libdhd.so")
        .args(["view", "--shape", "sphere", "--device", "dhd", "--no-open"])
        .output()
        .expect("haphe runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("/nonexistent/libdhd.so") && err.contains("HAPHE_DHD_LIBRARY"),
        "{err}"
    );

    let out = haphe(&["view", "--no-open"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("say what to show"), "{err}");
}

/// Kills the child if the test fails half way.
struct Running(Child);

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Starts `haphe view ARGS --no-open --port 0`, reads its address, fetches `/info`,
/// interrupts it and returns the info and everything it printed.
fn serve_and_interrupt(args: &[&str]) -> (String, String) {
    serve_then_interrupt(args, |_| {})
}

/// [`serve_and_interrupt`], running `during` with the view's address before the Ctrl-C.
fn serve_then_interrupt(args: &[&str], during: impl FnOnce(&str)) -> (String, String) {
    let mut child = Running(
        Command::new(env!("CARGO_BIN_EXE_haphe"))
            .arg("view")
            .args(args)
            .args(["--no-open", "--port", "0"])
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("haphe runs"),
    );
    let mut lines = BufReader::new(child.0.stdout.take().expect("stdout")).lines();
    let mut printed = String::new();
    let addr = loop {
        let line = lines
            .next()
            .expect("haphe prints the address")
            .expect("utf-8");
        printed.push_str(&line);
        printed.push('\n');
        if let Some(rest) = line.strip_prefix("view: http://") {
            break rest.split('/').next().expect("host:port").to_string();
        }
    };
    let mut s = TcpStream::connect(&addr).expect("the view listens");
    s.set_read_timeout(Some(Duration::from_secs(10)))
        .expect("timeout");
    write!(
        s,
        "GET /info HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n"
    )
    .expect("request");
    let mut response = String::new();
    s.read_to_string(&mut response).expect("response");
    let info = response
        .split_once("\r\n\r\n")
        .map(|(_, b)| b.to_string())
        .unwrap_or_default();
    during(&addr);
    // Ctrl-C: the view stops the servo and prints how it ran.
    let status = Command::new("kill")
        .args(["-INT", &child.0.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(status.success());
    let started = Instant::now();
    for line in lines {
        printed.push_str(&line.expect("utf-8"));
        printed.push('\n');
        assert!(started.elapsed() < Duration::from_secs(20), "no clean stop");
    }
    let code = child.0.wait().expect("exits");
    assert!(code.success(), "{printed}");
    (info, printed)
}

#[test]
fn a_live_view_and_a_replay_serve_and_stop_on_ctrl_c() {
    let (info, printed) = serve_and_interrupt(&["--shape", "sphere", "--triangles", "500"]);
    assert!(
        info.contains("\"mode\":\"live\"") && info.contains("\"device\":\"mouse\""),
        "{info}"
    );
    assert!(
        printed.contains("servo: ") && printed.contains(" ticks at "),
        "{printed}"
    );

    let trace = scratch("press.csv");
    let out = haphe(&[
        "simulate",
        "--shape",
        "sphere",
        "--triangles",
        "500",
        "--path",
        "press",
        "--seconds",
        "0.2",
        "--out",
        trace.to_str().expect("utf-8"),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (info, _) = serve_and_interrupt(&[
        "--replay",
        trace.to_str().expect("utf-8"),
        "--shape",
        "sphere",
        "--triangles",
        "500",
    ]);
    assert!(
        info.contains("\"mode\":\"replay\"") && info.contains("\"trace_rows\":200"),
        "{info}"
    );
    let _ = std::fs::remove_file(&trace);
}

/// A mesh in millimetres read as metres is warned about in the view as in `simulate`
/// (the device named next is refused, after the mesh was read).
#[test]
fn a_millimetre_mesh_is_warned_about_in_the_view_too() {
    let cube = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../meshes/models/20mm-xyz-cube.stl"
    );
    let out = haphe(&["view", "--mesh", cube, "--device", "phantom", "--no-open"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("spans 20 m") && err.contains("looks like millimetres: add `--units mm`"),
        "{err}"
    );
    let out = haphe(&[
        "view",
        "--mesh",
        cube,
        "--units",
        "mm",
        "--device",
        "phantom",
        "--no-open",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("warning"), "{err}");
}

/// The page learns the tool's radius: the flag's on a live view, a scene file's on a replay
/// (the flag overriding it), 0 for a point.
#[test]
fn the_view_tells_the_page_the_tool_radius() {
    let (info, _) = serve_and_interrupt(&[
        "--shape",
        "sphere",
        "--triangles",
        "500",
        "--tool-radius",
        "0.004",
    ]);
    assert!(info.contains("\"tool_radius\":0.004"), "{info}");
    let scene = scratch("tool.toml");
    std::fs::write(
        &scene,
        "tool_radius = 0.003\n[[object]]\nshape = \"sphere\"\ntriangles = 500\n",
    )
    .expect("write");
    let trace = scratch("tool-press.csv");
    let out = haphe(&[
        "simulate",
        "--scene",
        scene.to_str().expect("utf-8"),
        "--path",
        "press",
        "--seconds",
        "0.2",
        "--out",
        trace.to_str().expect("utf-8"),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let replay = |extra: &[&str]| {
        let mut args = vec![
            "--replay",
            trace.to_str().expect("utf-8"),
            "--scene",
            scene.to_str().expect("utf-8"),
        ];
        args.extend_from_slice(extra);
        serve_and_interrupt(&args).0
    };
    let info = replay(&[]);
    assert!(info.contains("\"tool_radius\":0.003"), "{info}");
    let info = replay(&["--tool-radius", "0"]);
    assert!(info.contains("\"tool_radius\":0.0"), "{info}");
    let _ = std::fs::remove_file(&trace);
    let _ = std::fs::remove_file(&scene);
}

/// The page learns where the effects act, from the flags and from a scene file.
#[test]
fn the_view_tells_the_page_where_the_effects_act() {
    let effects = |info: &str| {
        let info: serde_json::Value = serde_json::from_str(info).expect("JSON");
        info["effects"].as_array().expect("a list").clone()
    };
    let (info, printed) = serve_and_interrupt(&[
        "--shape",
        "sphere",
        "--triangles",
        "500",
        "--texture",
        "sine:0.0002:0.002",
        "--effect",
        "viscosity:2:box:0.2:-0.1:-0.1:0.3:0.1:0.1",
        "--effect",
        "spring:10:0:0:0.2",
    ]);
    let list = effects(&info);
    assert_eq!(list.len(), 2, "{info}\n{printed}");
    assert_eq!(list[0]["effect"], "viscosity");
    let place = &list[0]["place"];
    assert_eq!(place["kind"], "box");
    assert_eq!(place["min"], serde_json::json!([0.2, -0.1, -0.1]));
    assert_eq!(place["max"], serde_json::json!([0.3, 0.1, 0.1]));
    assert_eq!(list[1]["place"]["at"], serde_json::json!([0.0, 0.0, 0.2]));
    let scene = scratch("effects.toml");
    std::fs::write(
        &scene,
        "effects = [\"viscosity:2:inside:4\"]\n[[object]]\nid = 4\nshape = \"sphere\"\ntriangles = 500\n",
    )
    .expect("write");
    let (info, _) = serve_and_interrupt(&["--scene", scene.to_str().expect("utf-8")]);
    let list = effects(&info);
    assert_eq!(list.len(), 1, "{info}");
    assert_eq!(
        list[0]["place"],
        serde_json::json!({"kind": "object", "id": 4})
    );
    let _ = std::fs::remove_file(&scene);
}

/// A deforming object's vertices reach the page: binary messages `HPD1` of the object's
/// every vertex, their version rising, each the breathing sphere's at some scale; the
/// deformer's report after Ctrl-C.
#[test]
fn a_deforming_view_sends_the_pages_the_current_vertices() {
    let (_, printed) = serve_then_interrupt(
        &[
            "--shape",
            "sphere",
            "--triangles",
            "320",
            "--device",
            "hand",
            "--deform",
            "breathe",
        ],
        |addr| {
            let (mut socket, _) =
                tungstenite::connect(format!("ws://{addr}/ws")).expect("the stream");
            if let tungstenite::stream::MaybeTlsStream::Plain(tcp) = socket.get_ref() {
                tcp.set_read_timeout(Some(Duration::from_secs(10)))
                    .expect("timeout");
            }
            let mut versions = Vec::new();
            let mut radii = Vec::new();
            let started = Instant::now();
            while versions.len() < 3 {
                assert!(started.elapsed() < Duration::from_secs(30), "{versions:?}");
                let tungstenite::Message::Binary(bytes) = socket.read().expect("a message") else {
                    continue;
                };
                assert_eq!(&bytes[..4], b"HPD1");
                let u32_at = |i: usize| u32::from_le_bytes(bytes[i..i + 4].try_into().expect("4"));
                let f32_at = |i: usize| f32::from_le_bytes(bytes[i..i + 4].try_into().expect("4"));
                let version = u64::from_le_bytes(bytes[8..16].try_into().expect("8"));
                let n = u32_at(16) as usize;
                assert_eq!((u32_at(4), bytes.len()), (0, 20 + 12 * n));
                // Every vertex of the geodesic sphere at the same distance from its centre.
                let r: Vec<f64> = (0..n)
                    .map(|v| {
                        let p = [0, 1, 2].map(|k| f64::from(f32_at(20 + 12 * v + 4 * k)));
                        (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()
                    })
                    .collect();
                let (lo, hi) = r
                    .iter()
                    .fold((f64::MAX, 0.0f64), |(l, h), &x| (l.min(x), h.max(x)));
                assert!(
                    hi - lo < 1e-6 && (0.085 - 1e-6..0.115 + 1e-6).contains(&lo),
                    "{lo} {hi}"
                );
                versions.push(version);
                radii.push(lo);
            }
            assert!(versions.windows(2).all(|w| w[0] < w[1]), "{versions:?}");
            assert!(
                radii.windows(2).any(|w| (w[0] - w[1]).abs() > 1e-5),
                "{radii:?}"
            );
        },
    );
    assert!(
        printed.contains("deformation: breathe of sphere (id 0, 320 triangles) at 100 Hz, each version made by a deformer thread on the wall clock"),
        "{printed}"
    );
    assert!(printed.contains("  refreshes         "), "{printed}");
}
