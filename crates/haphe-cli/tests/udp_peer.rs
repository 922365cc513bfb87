//! The network device's peer as docs/devices.md shows it: run as written (the program and
//! the `haphe run` command of the docs), it feels the sphere and the run ends with exit
//! code 0 when it says stop; and a peer held at the safe start for the whole run is told
//! so, and nothing that contradicts it.

mod common;

use std::net::UdpSocket;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use common::{finish_within, scratch, stderr, stdout, write};
use haphe::DVec3;
use haphe_devices::udp::datagram::PositionDatagram;

const DOCS: &str = include_str!("../../../docs/devices.md");

/// The fenced block after `<!-- file NAME -->` in the docs, without its fences.
fn docs_file(name: &str) -> String {
    let marker = format!("<!-- file {name} -->\n");
    let at = DOCS.find(&marker).expect("the docs name the peer's file") + marker.len();
    let body = &DOCS[at..];
    let start = body.find('\n').expect("a fence") + 1;
    let end = body.find("\n```\n").expect("a closing fence");
    body[start..end + 1].to_string()
}

/// The arguments of the docs' `$ haphe run ...` command line that starts the peer's run
/// (up to its redirection).
fn docs_run_arguments() -> Vec<String> {
    let line = DOCS
        .lines()
        .find(|l| l.starts_with("$ haphe run --device udp:") && l.contains("udp_peer.py"))
        .expect("the docs run the peer");
    let command = line["$ haphe ".len()..]
        .split(" >")
        .next()
        .expect("a command");
    command.split_whitespace().map(str::to_string).collect()
}

/// A UDP port free on the loopback interface now.
fn free_port() -> u16 {
    let socket = UdpSocket::bind("127.0.0.1:0").expect("bind");
    socket.local_addr().expect("address").port()
}

/// `haphe` with the docs' run arguments, listening on `port` instead of 7700.
fn haphe_run(arguments: &[String], port: u16) -> Child {
    let arguments: Vec<String> = arguments
        .iter()
        .map(|a| a.replace(":7700", &format!(":{port}")))
        .collect();
    assert!(arguments.iter().any(|a| a.ends_with(&format!(":{port}"))));
    Command::new(env!("CARGO_BIN_EXE_haphe"))
        .args(&arguments)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("haphe runs")
}

/// The number after `label` in `text`.
fn number_after(text: &str, label: &str) -> f64 {
    let at = text
        .find(label)
        .unwrap_or_else(|| panic!("no {label:?} in:\n{text}"))
        + label.len();
    text[at..]
        .split_whitespace()
        .next()
        .and_then(|w| w.parse().ok())
        .unwrap_or_else(|| panic!("no number after {label:?} in:\n{text}"))
}

#[test]
fn the_docs_udp_peer_feels_the_sphere_and_ends_with_exit_0() {
    let dir = scratch("udp-docs-peer");
    let peer = write(&dir, "udp_peer.py", docs_file("udp_peer.py"));
    let port = free_port();
    let run = haphe_run(&docs_run_arguments(), port);
    let peer = Command::new("python3")
        .arg(&peer)
        .arg(port.to_string())
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("python3 runs the docs' peer");
    let peer = finish_within(peer, Duration::from_secs(120), "the peer");
    let run = finish_within(run, Duration::from_secs(120), "haphe run");
    let (said, summary) = (stdout(&peer), stdout(&run));
    assert!(peer.status.success(), "peer: {said}{}", stderr(&peer));
    assert_eq!(
        run.status.code(),
        Some(0),
        "haphe run:\n{summary}{}",
        stderr(&run)
    );
    // What the peer felt, and what haphe says it rendered.
    let felt = number_after(&said, "largest force felt");
    assert!(felt > 0.5, "the peer felt {felt} N: {said}");
    assert!(said.contains("last status 2"), "{said}");
    let rendered = number_after(&summary, "max force");
    assert!(rendered > 0.5, "{summary}");
    assert!((felt - rendered).abs() <= 0.05 + 1e-9, "{said}\n{summary}");
    assert!(summary.contains("the peer sent stop"), "{summary}");
    assert!(!summary.contains("warning"), "{summary}");
}

#[test]
fn a_peer_held_at_the_safe_start_is_told_so_and_nothing_else() {
    let port = free_port();
    let run = haphe_run(
        &[
            "run",
            "--device",
            "udp:127.0.0.1:7700",
            "--shape",
            "sphere",
            "--triangles",
            "500",
        ]
        .map(String::from),
        port,
    );
    // The centre of the sphere, for 0.3 s of haphe's ticks, then stop.
    let socket = UdpSocket::bind("127.0.0.1:0").expect("bind");
    socket
        .set_read_timeout(Some(Duration::from_millis(1)))
        .expect("timeout");
    let started = Instant::now();
    let (mut sequence, mut answers) = (0u64, 0u32);
    let mut buffer = [0u8; 64];
    while answers < 300 {
        assert!(
            started.elapsed() < Duration::from_secs(60),
            "haphe never answered"
        );
        sequence += 1;
        let d = PositionDatagram {
            sequence,
            timestamp_us: started.elapsed().as_micros() as u64,
            position: DVec3::ZERO,
            buttons: 0,
            stop: false,
        };
        socket
            .send_to(&d.encode(), ("127.0.0.1", port))
            .expect("send");
        answers += u32::from(socket.recv(&mut buffer).is_ok());
    }
    let stop = PositionDatagram {
        sequence: sequence + 1,
        timestamp_us: started.elapsed().as_micros() as u64,
        position: DVec3::ZERO,
        buttons: 0,
        stop: true,
    };
    socket
        .send_to(&stop.encode(), ("127.0.0.1", port))
        .expect("send");
    let run = finish_within(run, Duration::from_secs(60), "haphe run");
    let summary = stdout(&run);
    assert_eq!(run.status.code(), Some(0), "{summary}{}", stderr(&run));
    // Held on every tick but the last, which found the peer's stop.
    let ticks = number_after(&summary, "\n  ticks");
    let held = number_after(&summary, "safe start        held");
    assert_eq!(held, ticks - 1.0, "held on every tick: {summary}");
    assert!(
        summary.contains("inside an object for the whole run"),
        "{summary}"
    );
    assert!(!summary.contains("never touched"), "{summary}");
}
