//! Two network devices on one servo, each listening on its own port with a peer of its
//! own (threads of this test, over loopback): each device's records come from its own
//! peer's positions, each peer gets the force of its own proxy (one presses the sphere's
//! top, the other its side), and both get zero force with the stopped status at the end.

mod common;

use std::collections::HashSet;
use std::net::{SocketAddr, UdpSocket};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use haphe::DVec3;
use haphe::servo::{Device, RealtimeOptions, Servo, ServoLoop, ServoOptions, StopReason};
use haphe_devices::udp::datagram::{ForceDatagram, PositionDatagram, Status};
use haphe_devices::{UdpDevice, UdpOptions};

use common::{reference, scene};

/// A peer: sends `path` to `to` at about 1 kHz (holding its last position) until `done`,
/// then listens a little longer; every force datagram it received.
fn peer(path: Vec<DVec3>, to: SocketAddr, done: Arc<AtomicBool>) -> JoinHandle<Vec<ForceDatagram>> {
    std::thread::spawn(move || {
        let socket = UdpSocket::bind("127.0.0.1:0").expect("bind");
        socket.set_nonblocking(true).expect("non-blocking");
        let mut forces = Vec::new();
        let mut buffer = [0u8; 128];
        let mut take = |forces: &mut Vec<ForceDatagram>| {
            while let Ok((n, _)) = socket.recv_from(&mut buffer) {
                forces.push(ForceDatagram::decode(&buffer[..n]).expect("a force datagram"));
            }
        };
        let start = Instant::now();
        let mut k = 0usize;
        while !done.load(Ordering::Relaxed) {
            let datagram = PositionDatagram {
                sequence: k as u64 + 1,
                timestamp_us: k as u64 * 1000,
                position: path[k.min(path.len() - 1)],
                buttons: 0,
                stop: false,
            };
            socket.send_to(&datagram.encode(), to).expect("send");
            take(&mut forces);
            k += 1;
            let due = start + Duration::from_micros(1_000 * k as u64);
            if let Some(wait) = due.checked_duration_since(Instant::now()) {
                std::thread::sleep(wait);
            }
        }
        let until = Instant::now() + Duration::from_millis(300);
        while Instant::now() < until {
            take(&mut forces);
            std::thread::sleep(Duration::from_millis(1));
        }
        forces
    })
}

/// The bits of a point, to look it up exactly (-0 as 0: the mapping adds its offset).
fn key(p: DVec3) -> [u64; 3] {
    p.to_array().map(|x| (x + 0.0).to_bits())
}

#[test]
fn two_network_devices_on_their_own_ports() {
    // The press on the sphere's top, and the same turned a quarter about y: on its side.
    let top: Vec<DVec3> = reference(2_000).iter().map(|r| r.hip).collect();
    let side: Vec<DVec3> = top.iter().map(|p| DVec3::new(p.z, p.y, -p.x)).collect();
    // A generous timeout: the peers run beside other builds on a loaded machine.
    let options = UdpOptions {
        timeout_s: 0.5,
        ..UdpOptions::default()
    };
    let done = Arc::new(AtomicBool::new(false));
    let mut devices: Vec<(Box<dyn Device>, ServoOptions)> = Vec::new();
    let mut peers = Vec::new();
    let mut ports = HashSet::new();
    for path in [&top, &side] {
        let mut device = UdpDevice::new("127.0.0.1:0", options).expect("an address");
        let address = device.bind().expect("bind");
        ports.insert(address.port());
        peers.push(peer(path.clone(), address, Arc::clone(&done)));
        devices.push((Box::new(device), ServoOptions::default()));
    }
    assert_eq!(ports.len(), 2, "a port each");
    let servo = Servo::with_devices(devices, scene()).expect("both peers answer");
    let running = ServoLoop::spawn(
        servo,
        Some(1.5),
        RealtimeOptions::default().with_realtime_priority(false),
    )
    .expect("a thread");
    let mut records = Vec::new();
    let mut run = running.wait(|r| records.push(*r)).expect("no panic");
    run.servo.close();
    done.store(true, Ordering::Relaxed);
    let received: Vec<Vec<ForceDatagram>> = peers
        .into_iter()
        .map(|p| p.join().expect("the peer"))
        .collect();
    assert_eq!(run.stop, StopReason::Finished);
    for (i, (path, axis)) in [(&top, DVec3::Z), (&side, DVec3::X)]
        .into_iter()
        .enumerate()
    {
        let sent: HashSet<[u64; 3]> = path.iter().map(|p| key(*p)).collect();
        let mine: Vec<_> = records.iter().filter(|r| r.device == i as u32).collect();
        assert_eq!(mine.len() as u64, run.servo.stats().ticks, "device {i}");
        // Every device point is one its own peer sent (the other's are elsewhere).
        assert!(
            mine.iter().all(|r| sent.contains(&key(r.hip))),
            "device {i}"
        );
        let forces = &received[i];
        // Its own proxy's force: out of the sphere where its peer pressed.
        let largest = forces
            .iter()
            .map(|f| f.force)
            .max_by(|a, b| a.length().total_cmp(&b.length()))
            .expect("forces came back");
        assert!(largest.length() > 0.5, "device {i}: {largest}");
        assert!(
            largest.dot(axis) > 0.9 * largest.length(),
            "device {i}: {largest}"
        );
        let last = forces.last().expect("a last force");
        assert_eq!(last.status, Status::Stopped, "device {i}");
        assert_eq!(last.force, DVec3::ZERO, "device {i}");
    }
}
