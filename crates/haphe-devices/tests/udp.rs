//! The UDP device over loopback (127.0.0.1 only) with a peer process (this test binary
//! run again as `udp_peer`): the peer sends the press trajectory at about 1 kHz with
//! malformed, reordered, repeated, lost and late datagrams mixed in, then stops; haphe's
//! servo, on its real-time thread, counts each kind as documented, renders the press,
//! and when no position comes within the timeout sends zero force with the timeout
//! status and stops — no panic, no hang.

mod common;

use std::io::{BufRead, BufReader};
use std::net::UdpSocket;
use std::process::{Command, Stdio};
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

use haphe::servo::{DeviceFault, RealtimeOptions, Servo, ServoLoop, ServoOptions, StopReason};
use haphe_devices::udp::datagram::{ForceDatagram, PositionDatagram, Status};
use haphe_devices::{UdpDevice, UdpOptions};

use common::{reference, scene};

const PEER_VARIABLE: &str = "HAPHE_TEST_UDP_PEER";
/// Every this many datagrams, the peer also sends two malformed ones.
const MALFORMED_EVERY: u64 = 500;
/// A generous timeout: the peer runs beside other builds on a loaded machine.
const TIMEOUT_S: f64 = 0.2;
/// The peer's pause, under the timeout: late datagrams, no fault.
const PAUSE_MS: u64 = 60;

/// The peer: sends the press trajectory to `$HAPHE_TEST_UDP_PEER` and reports what came
/// back. Does nothing when run without it.
#[test]
#[ignore = "the peer process of udp_loopback_with_a_peer_process"]
fn udp_peer() {
    let Ok(address) = std::env::var(PEER_VARIABLE) else {
        return;
    };
    let records = reference(3_000);
    let socket = UdpSocket::bind("127.0.0.1:0").expect("bind");
    socket.set_nonblocking(true).expect("non-blocking");
    let start = Instant::now();
    let mut buffer = [0u8; 128];
    let (mut forces, mut max_force, mut last) = (0u64, 0.0f64, None::<ForceDatagram>);
    let mut position_sequences_rise = true;
    let mut take = |last: &mut Option<ForceDatagram>| {
        while let Ok((n, _)) = socket.recv_from(&mut buffer) {
            let f = ForceDatagram::decode(&buffer[..n]).expect("a force datagram");
            forces += 1;
            max_force = max_force.max(f.force.length());
            if let Some(l) = last {
                position_sequences_rise &= f.position_sequence >= l.position_sequence;
            }
            *last = Some(f);
        }
    };
    let datagram = |k: usize| {
        let r = &records[k];
        PositionDatagram {
            sequence: k as u64 + 1,
            timestamp_us: (r.t * 1e6) as u64,
            position: r.hip,
            buttons: 0,
            stop: false,
        }
        .encode()
    };
    let send = |bytes: &[u8]| {
        socket.send_to(bytes, &address).expect("send");
    };
    let mut k = 0usize;
    while k < records.len() {
        let seq = k as u64 + 1;
        if seq.is_multiple_of(MALFORMED_EVERY) {
            send(b"not a datagram");
            let mut wrong = datagram(k);
            wrong[0] = b'X';
            send(&wrong);
        }
        match seq {
            // 1001 before 1000: 1000 counted lost, then dropped as reordered.
            1000 => {
                send(&datagram(k + 1));
                send(&datagram(k));
                k += 2;
            }
            // Sent twice: the second dropped.
            1500 => {
                send(&datagram(k));
                send(&datagram(k));
                k += 1;
            }
            // Ten never sent.
            2000 => k += 10,
            2500 => {
                std::thread::sleep(Duration::from_millis(PAUSE_MS));
                send(&datagram(k));
                k += 1;
            }
            _ => {
                send(&datagram(k));
                k += 1;
            }
        }
        take(&mut last);
        // About 1 kHz on absolute deadlines.
        let due = start + Duration::from_micros(1_000 * k as u64);
        if let Some(wait) = due.checked_duration_since(Instant::now()) {
            std::thread::sleep(wait);
        }
    }
    // Silence: haphe must time out and say so.
    let silent = Instant::now();
    while silent.elapsed() < Duration::from_secs(3)
        && last.is_none_or(|f| f.status == Status::Running)
    {
        take(&mut last);
        std::thread::sleep(Duration::from_millis(1));
    }
    let last = last.expect("forces came back");
    println!(
        "PEER forces={forces} max={max_force} rising={position_sequences_rise} status={:?} \
         last_force={} waited_ms={}",
        last.status,
        last.force.length(),
        silent.elapsed().as_millis()
    );
}

#[test]
fn udp_loopback_with_a_peer_process() {
    let options = UdpOptions {
        timeout_s: TIMEOUT_S,
        first_timeout_s: 30.0,
        ..UdpOptions::default()
    };
    let mut device = UdpDevice::new("127.0.0.1:0", options).expect("an address");
    let address = device.bind().expect("bind");
    assert!(address.ip().is_loopback());
    let counters = device.counters();
    let peer = Command::new(std::env::current_exe().expect("this test"))
        .args([
            "--ignored",
            "--exact",
            "udp_peer",
            "--nocapture",
            "--test-threads=1",
        ])
        .env(PEER_VARIABLE, address.to_string())
        .stdout(Stdio::piped())
        .spawn()
        .expect("the peer starts");
    // Opening waits for the peer's first position.
    let servo = Servo::new(device, scene(), ServoOptions::default()).expect("the peer sends");
    let realtime = RealtimeOptions::default().with_realtime_priority(false);
    let started = Instant::now();
    let running = ServoLoop::spawn(servo, Some(30.0), realtime).expect("spawn");
    let mut deepest = 0.0f64;
    let run = running
        .wait(|r| deepest = deepest.max(r.penetration))
        .expect("no panic");
    let seconds = started.elapsed().as_secs_f64();
    let output = peer.wait_with_output().expect("the peer ends");
    let line = BufReader::new(output.stdout.as_slice())
        .lines()
        .map_while(Result::ok)
        .find_map(|l| l.find("PEER ").map(|i| l[i..].to_string()))
        .expect("the peer reports");
    println!("{line}\n{}", counters.summary());
    assert!(output.status.success());

    assert_eq!(run.stop, StopReason::Fault(DeviceFault::Disconnected));
    assert!(seconds < 10.0, "no hang: {seconds} s");
    let g = |a: &std::sync::atomic::AtomicU64| a.load(Ordering::Relaxed);
    assert_eq!(g(&counters.malformed), 2 * (3_000 / MALFORMED_EVERY));
    assert_eq!(g(&counters.reordered), 2, "1000 after 1001, 1500 twice");
    assert_eq!(
        g(&counters.lost),
        11,
        "1000 (until it came late), 2000..=2009"
    );
    assert_eq!(g(&counters.received), 3_000 - 11);
    assert!(g(&counters.late_ticks) > 30, "the pause and the end");
    assert_eq!(g(&counters.timed_out), 1);
    assert!(deepest > 1e-3, "the press was rendered: {deepest}");
    assert!(line.contains("rising=true"), "{line}");
    assert!(line.contains("status=Timeout last_force=0 "), "{line}");
    let max: f64 = line
        .split_whitespace()
        .find_map(|w| w.strip_prefix("max="))
        .and_then(|v| v.parse().ok())
        .expect("max");
    assert!(max > 0.5 && max <= 3.3 + 1e-9, "{max}");
    assert_eq!(run.servo.spec().max_force, 3.3);
}
