//! Real devices in `haphe view`, and the signals that stop a session with a device: the
//! Force Dimension and OpenHaptics stand-in libraries (scripted through
//! `HAPHE_STANDIN_PATH`, see crates/haphe-devices/tests/standin/env.h) and a UDP peer in
//! this process push the device point into a sphere; the view's WebSocket reports the
//! contact and a force pointing out of the sphere; SIGTERM (and Ctrl-C) stop `haphe view`
//! and `haphe run` after zero force was written to the device.

mod support;

use std::io::{BufRead, BufReader, Lines};
use std::net::UdpSocket;
use std::path::{Path, PathBuf};
use std::process::{ChildStdout, Command, Stdio};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use haphe::DVec3;
use haphe_devices::udp::datagram::{ForceDatagram, PositionDatagram, Status};
use serde_json::Value;
use support::{Running, Standin, signal, standin};

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("view-device");
    std::fs::create_dir_all(&dir).expect("a directory");
    dir.join(name)
}

/// A straight press at 1 kHz from `from` to `to` in `ticks` samples, then holding at `to`
/// (the stand-ins hold their last sample): six numbers a line, the library's units.
fn press_file(name: &str, from: DVec3, to: DVec3, ticks: usize, per_second: f64) -> PathBuf {
    let v = (to - from) / (ticks as f64 / 1000.0) * per_second;
    let mut text = String::new();
    for i in 0..=ticks {
        let p = from.lerp(to, i as f64 / ticks as f64);
        text.push_str(&format!(
            "{} {} {} {} {} {}\n",
            p.x, p.y, p.z, v.x, v.y, v.z
        ));
    }
    let file = scratch(name);
    std::fs::write(&file, text).expect("the path file");
    file
}

/// Reads what the view prints up to its address: the address (host:port) and the lines.
fn address(lines: &mut Lines<BufReader<ChildStdout>>) -> (String, String) {
    let mut printed = String::new();
    loop {
        let line = lines
            .next()
            .unwrap_or_else(|| panic!("haphe prints the address; it printed:\n{printed}"))
            .expect("utf-8");
        printed.push_str(&line);
        printed.push('\n');
        if let Some(rest) = line.strip_prefix("view: http://") {
            return (
                rest.split('/').next().expect("host:port").to_string(),
                printed,
            );
        }
    }
}

/// Starts `haphe view --shape sphere --device DEVICE --no-open --port 0` and returns it,
/// its address and the rest of its output.
fn view(device: &str, env: &[(&str, &Path)]) -> (Running, String, Lines<BufReader<ChildStdout>>) {
    let mut command = Command::new(env!("CARGO_BIN_EXE_haphe"));
    command
        .args(["view", "--shape", "sphere", "--triangles", "2000"])
        .args(["--device", device, "--no-open", "--port", "0"])
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit());
    for (k, v) in env {
        command.env(k, v);
    }
    let mut child = Running(command.spawn().expect("haphe runs"));
    let mut lines = BufReader::new(child.0.stdout.take().expect("stdout")).lines();
    let (addr, printed) = address(&mut lines);
    assert!(printed.contains("device: "), "{printed}");
    assert!(printed.contains("mapping: "), "{printed}");
    (child, addr, lines)
}

/// Reads the view's frames until one reports contact with a force of more than 1 N
/// pointing out of the sphere (centred on the origin); returns that frame.
fn contact_frame(addr: &str) -> Result<Value, String> {
    let (mut socket, _) = tungstenite::connect(format!("ws://{addr}/ws")).expect("the stream");
    if let tungstenite::stream::MaybeTlsStream::Plain(tcp) = socket.get_ref() {
        tcp.set_read_timeout(Some(Duration::from_secs(5)))
            .expect("a timeout");
    }
    let started = Instant::now();
    let mut last = Value::Null;
    while started.elapsed() < Duration::from_secs(30) {
        let Ok(message) = socket.read() else {
            return Err(format!("no frame for 5 s; the last frame: {last}"));
        };
        let Ok(text) = message.to_text() else {
            continue;
        };
        let Ok(frame) = serde_json::from_str::<Value>(text) else {
            continue;
        };
        let v = |k: &str| {
            DVec3::new(
                frame[k][0].as_f64().unwrap_or(0.0),
                frame[k][1].as_f64().unwrap_or(0.0),
                frame[k][2].as_f64().unwrap_or(0.0),
            )
        };
        let (force, proxy) = (v("force"), v("proxy"));
        if !frame["object"].is_null()
            && force.length() > 1.0
            && force.normalize().dot(proxy.normalize()) > 0.8
        {
            return Ok(frame);
        }
        last = frame;
    }
    Err(format!(
        "no contact with an outward force in 30 s; the last frame: {last}"
    ))
}

/// The frame of [`contact_frame`]; without one, the view is stopped and the test fails
/// with what it printed.
fn contact(
    addr: &str,
    child: Running,
    lines: Lines<BufReader<ChildStdout>>,
) -> (Value, Running, Lines<BufReader<ChildStdout>>) {
    match contact_frame(addr) {
        Ok(frame) => (frame, child, lines),
        Err(e) => {
            signal(&child.0, "TERM");
            let printed: Vec<String> = lines.map_while(Result::ok).collect();
            panic!("{e}\nthe view printed: {printed:#?}");
        }
    }
}

/// Sends SIGTERM and waits for a clean exit; returns everything printed after it.
fn terminate(mut child: Running, lines: Lines<BufReader<ChildStdout>>) -> String {
    signal(&child.0, "TERM");
    let started = Instant::now();
    let mut printed = String::new();
    for line in lines {
        printed.push_str(&line.expect("utf-8"));
        printed.push('\n');
        assert!(started.elapsed() < Duration::from_secs(20), "no clean stop");
    }
    let status = child.0.wait().expect("exits");
    assert!(status.success(), "{status}: {printed}");
    printed
}

/// The stand-in's report at close: forces written, the last force, force still enabled,
/// the largest force written.
fn standin_report(file: &Path) -> (u64, DVec3, bool, f64) {
    let text = std::fs::read_to_string(file).expect("the stand-in was closed");
    let v: Vec<&str> = text.split_whitespace().collect();
    assert_eq!(v.len(), 6, "{text}");
    let f = |i: usize| v[i].parse::<f64>().expect("a number");
    (
        v[0].parse().expect("a count"),
        DVec3::new(f(1), f(2), f(3)),
        v[4] == "1",
        f(5),
    )
}

/// `haphe view --device DEVICE` on the stand-in `which`, selected by `variable`, pressed
/// from `start` (the SDK's units and frame) to the centre of its workspace, which the
/// default mapping puts at the sphere's centre: contact with an outward force on the
/// WebSocket; after SIGTERM the last force written is zero and force output is off.
fn vendor_in_the_view(device: &str, which: Standin, variable: &str, start: DVec3) {
    let path = press_file(
        &format!("{device}-press.txt"),
        start,
        DVec3::ZERO,
        1500,
        1.0,
    );
    let forces = scratch(&format!("{device}-forces.txt"));
    let _ = std::fs::remove_file(&forces);
    let lib = standin(which);
    let (child, addr, lines) = view(
        device,
        &[
            (variable, &lib),
            ("HAPHE_STANDIN_PATH", &path),
            ("HAPHE_STANDIN_FORCES", &forces),
        ],
    );
    let (frame, child, lines) = contact(&addr, child, lines);
    assert!(frame["penetration"].as_f64().expect("penetration") > 0.0);
    let printed = terminate(child, lines);
    assert!(printed.contains("servo: "), "{printed}");
    let (written, last, enabled, largest) = standin_report(&forces);
    assert!(written > 100, "{written} forces");
    assert!(largest > 1.0, "the press gave {largest} N at most");
    assert_eq!(last, DVec3::ZERO, "the last force written");
    assert!(!enabled, "force output left enabled");
}

#[test]
fn the_view_shows_the_force_dimension_device_and_sigterm_zeroes_its_force() {
    // Force Dimension frame, metres, z up.
    vendor_in_the_view(
        "dhd",
        Standin::Dhd,
        "HAPHE_DHD_LIBRARY",
        DVec3::new(0.0, 0.0, 0.06),
    );
}

#[test]
fn the_view_runs_openhaptics_on_its_scheduler_and_sigterm_zeroes_its_force() {
    // OpenHaptics frame, millimetres, y up.
    vendor_in_the_view(
        "openhaptics",
        Standin::Hd,
        "HAPHE_HD_LIBRARY",
        DVec3::new(0.0, 70.0, 0.0),
    );
}

#[test]
fn the_view_shows_a_udp_peer_and_sigterm_sends_it_zero_force() {
    let port = UdpSocket::bind("127.0.0.1:0")
        .and_then(|s| s.local_addr())
        .expect("a free port")
        .port();
    let peer = UdpSocket::bind("127.0.0.1:0").expect("the peer's socket");
    peer.set_nonblocking(true).expect("non-blocking");
    let done = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&done);
    // The peer: a press from above the workspace (±0.1 m) to its centre, then holding,
    // one position a millisecond; it keeps the last force datagram it received.
    let peer_thread = std::thread::spawn(move || {
        let mut last: Option<ForceDatagram> = None;
        let mut sequence = 0u64;
        let started = Instant::now();
        while !flag.load(Ordering::Relaxed) {
            let s = (started.elapsed().as_secs_f64() / 1.5).min(1.0);
            let position = DVec3::new(0.0, 0.0, 0.12 * (1.0 - s));
            sequence += 1;
            let datagram = PositionDatagram {
                sequence,
                timestamp_us: started.elapsed().as_micros() as u64,
                position,
                buttons: 0,
                stop: false,
            };
            let _ = peer.send_to(&datagram.encode(), ("127.0.0.1", port));
            let mut buf = [0u8; 64];
            while let Ok(n) = peer.recv(&mut buf) {
                if let Some(f) = ForceDatagram::decode(&buf[..n]) {
                    last = Some(f);
                }
            }
            std::thread::sleep(Duration::from_millis(1));
        }
        // What haphe sent last, after it stopped.
        let until = Instant::now() + Duration::from_millis(200);
        let mut buf = [0u8; 64];
        while Instant::now() < until {
            if let Ok(n) = peer.recv(&mut buf)
                && let Some(f) = ForceDatagram::decode(&buf[..n])
            {
                last = Some(f);
            }
            std::thread::sleep(Duration::from_millis(1));
        }
        last
    });
    let (child, addr, lines) = view(&format!("udp:127.0.0.1:{port}"), &[]);
    let (_, child, lines) = contact(&addr, child, lines);
    let printed = terminate(child, lines);
    assert!(printed.contains("servo: "), "{printed}");
    done.store(true, Ordering::Relaxed);
    let last = peer_thread
        .join()
        .expect("the peer")
        .expect("force datagrams");
    assert_eq!(last.status, Status::Stopped, "{last:?}");
    assert_eq!(last.force, DVec3::ZERO, "{last:?}");
}

#[test]
fn sigterm_and_ctrl_c_stop_haphe_run_after_zero_force() {
    let path = press_file(
        "run-press.txt",
        DVec3::new(0.0, 0.0, 0.06),
        DVec3::ZERO,
        1500,
        1.0,
    );
    let lib = standin(Standin::Dhd);
    for sig in ["TERM", "INT"] {
        let forces = scratch(&format!("run-forces-{sig}.txt"));
        let _ = std::fs::remove_file(&forces);
        let mut child = Running(
            Command::new(env!("CARGO_BIN_EXE_haphe"))
                .env("HAPHE_DHD_LIBRARY", &lib)
                .env("HAPHE_STANDIN_PATH", &path)
                .env("HAPHE_STANDIN_FORCES", &forces)
                .args(["run", "--device", "dhd", "--shape", "sphere"])
                .args(["--triangles", "2000", "--normal-priority"])
                .args(["--overrun-budget", "1000000"])
                .stdout(Stdio::piped())
                .spawn()
                .expect("haphe runs"),
        );
        let mut lines = BufReader::new(child.0.stdout.take().expect("stdout")).lines();
        for line in lines.by_ref() {
            if line.expect("a line").contains("running until Ctrl-C") {
                break;
            }
        }
        // Into the sphere: the device is pressed when the signal comes.
        std::thread::sleep(Duration::from_millis(1500));
        signal(&child.0, sig);
        let rest: Vec<String> = lines.map_while(Result::ok).collect();
        let status = child.0.wait().expect("ends");
        assert!(status.success(), "SIG{sig}: {status} {rest:?}");
        assert!(rest.iter().any(|l| l.contains("(stopped)")), "{rest:?}");
        let (written, last, enabled, largest) = standin_report(&forces);
        assert!(written > 1000, "SIG{sig}: {written} forces");
        assert!(
            largest > 1.0,
            "SIG{sig}: the press gave {largest} N at most"
        );
        assert_eq!(last, DVec3::ZERO, "SIG{sig}: the last force written");
        assert!(!enabled, "SIG{sig}: force output left enabled");
    }
}

/// `haphe view` with two devices (two simulated hands): each is listed, and every frame
/// carries the second device's tool beside the first's, each where its own hand is.
#[test]
fn two_devices_in_the_view() {
    let mut command = Command::new(env!("CARGO_BIN_EXE_haphe"));
    command
        .args(["view", "--shape", "sphere", "--triangles", "2000"])
        .args(["--device", "hand", "--device", "hand", "--seconds", "20"])
        .args(["--no-open", "--port", "0"])
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit());
    let mut child = Running(command.spawn().expect("haphe runs"));
    let mut lines = BufReader::new(child.0.stdout.take().expect("stdout")).lines();
    let (addr, printed) = address(&mut lines);
    for needed in [
        "device 1 (hand):",
        "device 2 (hand):",
        "device hand, hand on",
    ] {
        assert!(printed.contains(needed), "{needed:?} missing:\n{printed}");
    }
    let (mut socket, _) = tungstenite::connect(format!("ws://{addr}/ws")).expect("the stream");
    let started = Instant::now();
    let frame = loop {
        assert!(
            started.elapsed() < Duration::from_secs(30),
            "no frame with two tools"
        );
        let message = socket.read().expect("a frame");
        let Ok(frame) = serde_json::from_str::<Value>(message.to_text().unwrap_or("")) else {
            continue;
        };
        if frame["others"].as_array().is_some_and(|o| o.len() == 1) {
            break frame;
        }
    };
    let hip = |v: &Value| {
        (0..3)
            .map(|i| v[i].as_f64().expect("a number"))
            .collect::<Vec<_>>()
    };
    // Two hands on paths of their own: two places.
    assert_ne!(
        hip(&frame["hip"]),
        hip(&frame["others"][0]["hip"]),
        "{frame}"
    );
    signal(&child.0, "INT");
    let status = child.0.wait().expect("exits");
    assert!(status.success(), "{status:?}");
}
