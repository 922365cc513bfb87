//! Does the view slow the servo? The same servo loop (the mouse device on a sphere, on the
//! wall clock, FIFO priority where permitted) run side by side without the view and with
//! it — a headless Chromium connected, the page animating, the pointer moving the device
//! point in and out of the sphere — at 1 kHz and 10 kHz, repeated and interleaved.
//!
//! `cargo run --release -p haphe-view --example view_overhead [SECONDS] [REPEATS]`
//! (needs Chromium, like the browser test).

#[path = "../tests/support/cdp.rs"]
mod cdp;

use std::time::{Duration, Instant};

use haphe::DVec3;
use haphe::scene::{Material, Scene};
use haphe::servo::{Device, RealtimeOptions, Servo, ServoLoop, ServoOptions, TickStats};
use haphe_view::{LiveSource, Model, MouseDevice, Source, ViewOptions, ViewServer};

fn scene() -> Scene {
    haphe::verify::sphere_scene(20_000, Material::default()).expect("the sphere scene")
}

const START: DVec3 = DVec3::new(0.0, 0.0, 0.12);

fn row(label: &str, rate: f64, s: &TickStats) {
    let us = |ns: u64| ns as f64 * 1e-3;
    println!(
        "{label:<8} {rate:>6.0} {:>7} {:>6.2} {:>6.2} {:>7.2} {:>7.2} {:>7.2} {:>8.2} {:>6}",
        s.ticks,
        us(s.compute.quantile(0.5)),
        us(s.compute.quantile(0.99)),
        us(s.compute.quantile(0.999)),
        us(s.lateness.quantile(0.5)),
        us(s.lateness.quantile(0.99)),
        us(s.lateness.quantile(0.999)),
        s.overruns + s.skipped,
    );
}

fn without_view(rate: f64, seconds: f64) -> TickStats {
    let (device, mut handle) = MouseDevice::new(START, DVec3::splat(-1.0), DVec3::ONE);
    let device: Box<dyn Device> = Box::new(device);
    let options = ServoOptions::new(rate).expect("a valid rate");
    let servo = Servo::new(device, scene(), options).expect("servo");
    let running = ServoLoop::spawn(servo, Some(seconds), RealtimeOptions::default()).expect("loop");
    // The same pointer motion as with the view, straight into the hand-off.
    let started = Instant::now();
    let mover = std::thread::spawn(move || {
        while started.elapsed().as_secs_f64() < seconds {
            handle.set(point(started.elapsed().as_secs_f64()));
            std::thread::sleep(Duration::from_millis(16));
        }
    });
    let run = running.wait(|_| {}).expect("run");
    mover.join().expect("mover");
    run.servo.stats().clone()
}

/// The pointer's path: down into the sphere and out again, once a second.
fn point(t: f64) -> DVec3 {
    let phase = (t % 1.0 - 0.5).abs() * 2.0;
    DVec3::new(0.02, 0.0, 0.05 + 0.07 * phase)
}

fn with_view(rate: f64, seconds: f64, browser: &mut cdp::Browser) -> TickStats {
    let scene = scene();
    let model = Model::from_scene(&scene, &[]);
    let (device, mouse) = MouseDevice::new(START, DVec3::splat(-1.0), DVec3::ONE);
    let source = LiveSource {
        device: Box::new(device),
        scene,
        options: ServoOptions::new(rate).expect("a valid rate"),
        motions: Vec::new(),
        seconds: Some(seconds),
        realtime: RealtimeOptions::default(),
        clock: None,
        others: Vec::new(),
        on_record: None,
    };
    let view = ViewServer::start(
        model,
        Source::Live {
            source: Box::new(source),
            mouse: Some(mouse),
        },
        &ViewOptions {
            port: 0,
            title: "overhead".into(),
        },
    )
    .expect("view");
    browser.navigate(&view.url());
    browser.wait_for(
        "!!(window.haphe && window.haphe.ready && window.haphe.frames > 0)",
        Duration::from_secs(30),
        "the page",
    );
    // Pointer events through the browser, as a person would, until the run ends.
    let started = Instant::now();
    while !view.ended() && started.elapsed().as_secs_f64() < seconds + 5.0 {
        let p = point(started.elapsed().as_secs_f64());
        let xy = browser.eval(&format!("window.haphe.project({}, {}, {})", p.x, p.y, p.z));
        if let (Some(x), Some(y)) = (xy[0].as_f64(), xy[1].as_f64()) {
            browser.mouse_move(x, y);
        }
        std::thread::sleep(Duration::from_millis(16));
    }
    let frames = browser.eval("window.haphe.frames");
    let run = view.stop().expect("stop").expect("live");
    println!("         (page received {frames} frames)");
    run.servo.stats().clone()
}

fn main() {
    let mut args = std::env::args().skip(1);
    let seconds: f64 = args.next().and_then(|s| s.parse().ok()).unwrap_or(5.0);
    let repeats: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(3);
    let mut browser = cdp::Browser::start(1280, 800);
    println!(
        "{:<8} {:>6} {:>7} {:>6} {:>6} {:>7} {:>7} {:>7} {:>8} {:>6}",
        "run", "Hz", "ticks", "c p50", "c p99", "c p99.9", "l p50", "l p99", "l p99.9", "missed"
    );
    println!("(c: compute time, l: lateness of the tick's start, µs; missed: overruns + skipped)");
    for rate in [1000.0, 10_000.0] {
        for k in 0..repeats {
            // Interleaved, the order swapped every repeat.
            if k % 2 == 0 {
                row("without", rate, &without_view(rate, seconds));
                row("with", rate, &with_view(rate, seconds, &mut browser));
            } else {
                row("with", rate, &with_view(rate, seconds, &mut browser));
                row("without", rate, &without_view(rate, seconds));
            }
        }
    }
}
