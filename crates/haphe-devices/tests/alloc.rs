//! The servo path allocates nothing with each real device: 10^5 ticks of the Force
//! Dimension and OpenHaptics devices over their stand-in libraries, and of the UDP device
//! fed by a peer, each run on this thread under a counting allocator (the allocations of
//! other threads are not counted; the HD scheduler's clocked tick is counted in
//! haphe's tests/servo_clocked.rs).

mod common;

use std::net::UdpSocket;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use haphe::servo::{Device, Servo, ServoOptions, StopReason};
use haphe_devices::udp::datagram::PositionDatagram;
use haphe_devices::{UdpDevice, UdpOptions, open_device};

use common::{Standin, reference, scene, serial, standin, trajectory, trajectory_hd};

const TICKS: u64 = 100_000;

fn set(variable: &str, value: &std::path::Path) {
    // SAFETY: the tests of this binary run one at a time (`serial`).
    unsafe { std::env::set_var(variable, value) };
}

/// Runs `device` for [`TICKS`] ticks on the virtual clock after a warm-up; the
/// allocations of those ticks, and the ticks in contact.
fn count(device: Box<dyn Device>) -> (u64, usize) {
    let mut servo = Servo::new(device, scene(), ServoOptions::default()).expect("servo");
    // Clear zones of the first contacts are computed once; the press reaches them early.
    servo.run_simulated(100, |_| {});
    let mut contact = 0usize;
    let mut stop = StopReason::Finished;
    let info = allocation_counter::measure(|| {
        stop = servo.run_simulated(TICKS, |r| contact += usize::from(r.in_contact()));
    });
    assert_eq!(stop, StopReason::Finished);
    (info.count_total, contact)
}

#[test]
fn dhd_and_openhaptics_ticks_allocate_nothing() {
    let _one = serial();
    let expected = reference(TICKS + 100);
    for (name, variable, spec) in [
        ("dhd", "HAPHE_DHD_LIBRARY", "dhd"),
        ("hd", "HAPHE_HD_LIBRARY", "openhaptics"),
    ] {
        let lib = standin(name);
        set(variable, &lib);
        let s = Standin::open(&lib);
        s.reset(1);
        s.set_path(&if name == "hd" {
            trajectory_hd(&expected)
        } else {
            trajectory(&expected)
        });
        let opened = open_device(spec, &scene(), 1.0, UdpOptions::default()).expect("opens");
        let (allocations, contact) = count(opened.device);
        println!("{spec}: {TICKS} ticks, {contact} in contact, {allocations} allocations");
        assert!(contact > 10_000, "{contact}");
        assert_eq!(allocations, 0, "{spec} allocated on the servo path");
    }
}

#[test]
fn udp_ticks_allocate_nothing() {
    let _one = serial();
    let mut device = UdpDevice::new("127.0.0.1:0", UdpOptions::default()).expect("address");
    let address = device.bind().expect("bind");
    let counters = device.counters();
    let done = Arc::new(AtomicBool::new(false));
    let stop = Arc::clone(&done);
    let path = reference(2_000);
    let peer = std::thread::spawn(move || {
        let socket = UdpSocket::bind("127.0.0.1:0").expect("bind");
        let mut k = 0u64;
        while !stop.load(Ordering::Relaxed) {
            let r = &path[(k as usize) % path.len()];
            let d = PositionDatagram {
                sequence: k + 1,
                timestamp_us: k * 100,
                position: r.hip,
                buttons: 0,
                stop: false,
            };
            let _ = socket.send_to(&d.encode(), address);
            if k.is_multiple_of(7) {
                let _ = socket.send_to(b"junk", address);
            }
            k += 1;
            std::thread::sleep(Duration::from_micros(100));
        }
    });
    device.open().expect("the peer sends");
    let (allocations, _) = count(Box::new(device));
    done.store(true, Ordering::Relaxed);
    peer.join().expect("peer");
    println!(
        "udp: {TICKS} ticks, {allocations} allocations; {}",
        counters.summary()
    );
    assert!(counters.received.load(Ordering::Relaxed) > 100);
    assert!(counters.malformed.load(Ordering::Relaxed) > 10);
    assert_eq!(allocations, 0, "udp allocated on the servo path");
}
