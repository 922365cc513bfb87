//! Cutting: what one edit costs, how soon the servo feels it, and the servo tick while a
//! tool drills. The volume is a sphere 50 mm across (a distance field on a 128³ grid of
//! 0.5 mm voxels), its surface extracted in 32³ chunks.
//!
//! 1. **One edit**: a 2 mm tool pressed into the surface at 200 places, one voxel layer
//!    each: the press (the voxels removed), the changed chunks extracted again, the shape
//!    made of the new surface (its map built), p50 and p99.
//! 2. **Drilling at 1 kHz** on both cores: the servo on this thread (ticks paced on the
//!    wall clock) drills straight into the sphere at 10 mm/s with a 2 mm tool; a cutter
//!    thread receives each tick's press through a wait-free ring, refreshes at up to 100 Hz
//!    and hands each version to the servo through the scene's editor. Prints the tick's
//!    percentiles against the same run without cutting (the rigid reference), the time
//!    from a press to the first tick that feels the version it made (p50, p99), and the
//!    deadlines missed.
//!
//! `taskset -c 0,1 cargo bench -p haphe --bench cut`; `cargo test --benches` runs it
//! briefly.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use glam::{DAffine3, DVec3};
use haphe::map::MapOptions;
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::scene::{Edit, Material, ObjectId, Pose, Scene, SceneObject};
use haphe::volume::{CutOptions, Cutter, Volume};

const N: usize = 128;
const VOXEL: f64 = 5e-4;
const RADIUS: f64 = 0.025;
const TOOL: f64 = 2e-3;

fn benchmarking() -> bool {
    std::env::args().any(|a| a == "--bench")
}

fn sphere() -> Volume {
    let c = (N - 1) as f64 * 0.5 * VOXEL;
    let mut values = Vec::with_capacity(N * N * N);
    for k in 0..N {
        for j in 0..N {
            for i in 0..N {
                let p = DVec3::new(i as f64, j as f64, k as f64) * VOXEL;
                values.push((RADIUS - p.distance(DVec3::splat(c))) as f32);
            }
        }
    }
    let to_world =
        DAffine3::from_translation(-DVec3::splat(c)) * DAffine3::from_scale(DVec3::splat(VOXEL));
    Volume::new([N; 3], values, to_world, 0.0).expect("a volume")
}

fn cutter() -> Cutter {
    let mut cutter = Cutter::new("sphere", sphere(), MapOptions::default()).expect("a cutter");
    cutter
        .set_options(CutOptions::new(TOOL, 0.5).expect("options"))
        .expect("set");
    cutter
}

fn percentiles(mut v: Vec<f64>) -> (f64, f64, f64) {
    v.sort_by(f64::total_cmp);
    let at = |q: f64| {
        v.get(((v.len() as f64 - 1.0) * q).round() as usize)
            .copied()
            .unwrap_or(0.0)
    };
    (at(0.5), at(0.99), at(1.0))
}

fn main() {
    one_edit();
    drilling();
}

fn one_edit() {
    let mut cutter = cutter();
    let triangles = cutter.shape().surface().triangle_count();
    let edits = if benchmarking() { 100 } else { 3 };
    let (mut press, mut extract, mut build) = (Vec::new(), Vec::new(), Vec::new());
    let mut rng = haphe::rng::SplitMix64::new(3);
    for _ in 0..edits {
        let dir = rng.unit_vector();
        // The tool touching the surface, pressed one voxel in.
        let centre = dir * (RADIUS + TOOL - VOXEL);
        let began = Instant::now();
        // Long enough at the default rate to remove what the tool reaches.
        cutter.press(centre, 1.0, 0.05);
        press.push(began.elapsed().as_secs_f64() * 1e3);
        cutter.refresh().expect("material left");
        let (e, b) = cutter.last_refresh_seconds();
        extract.push(e * 1e3);
        build.push(b * 1e3);
    }
    println!(
        "one edit on a sphere of {triangles} triangles (128³ voxels, 32³ chunks), ms: p50 p99 max"
    );
    for (name, v) in [
        ("press", press),
        ("chunks extracted again", extract),
        ("shape built", build),
    ] {
        let (p50, p99, max) = percentiles(v);
        println!("  {name:>24}: {p50:>8.3} {p99:>8.3} {max:>8.3}");
    }
}

struct Run {
    ticks: Vec<u64>,
    missed: usize,
    latency_ms: Vec<f64>,
    versions: usize,
    removed: u64,
}

fn drilling() {
    let ticks = if benchmarking() { 4_000 } else { 50 };
    println!(
        "\ndrilling at 10 mm/s with a 2 mm tool, 1 kHz: tick ns p50 p99 p99.9 max; missed deadlines; press to felt ms p50 p99; versions"
    );
    let rigid = drill(ticks, false);
    let cut = drill(ticks, true);
    for (name, r) in [("rigid", &rigid), ("cutting", &cut)] {
        let p = |q: f64| {
            r.ticks
                .get(((r.ticks.len() as f64 - 1.0) * q).round() as usize)
                .copied()
                .unwrap_or(0)
        };
        let (l50, l99, _) = percentiles(r.latency_ms.clone());
        println!(
            "{name:>10}: {:>7} {:>7} {:>7} {:>8}  missed {}  felt {l50:.1} {l99:.1}  versions {} ({} voxels)  p99/rigid {:.2}",
            p(0.5),
            p(0.99),
            p(0.999),
            p(1.0),
            r.missed,
            r.versions,
            r.removed,
            p(0.99) as f64
                / rigid.ticks[((rigid.ticks.len() as f64 - 1.0) * 0.99).round() as usize].max(1)
                    as f64
        );
    }
}

fn drill(ticks: usize, cut: bool) -> Run {
    let mut cutter = cutter();
    let (mut scene, mut editor) = Scene::new(2);
    let object = SceneObject::new(
        ObjectId(0),
        Arc::clone(cutter.shape()),
        Pose::IDENTITY,
        Material::DEFAULT,
    );
    scene.insert(object).expect("room");
    let (mut presses, mut pressed) = rtrb::RingBuffer::<(DVec3, f64, Instant)>::new(4096);
    let (mut made, mut versions_made) = rtrb::RingBuffer::<(u64, Instant)>::new(4096);
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    let worker = std::thread::spawn(move || {
        let mut oldest: Option<Instant> = None;
        while !flag.load(Ordering::Relaxed) {
            let began = Instant::now();
            while let Ok((c, f, at)) = pressed.pop() {
                if cutter.press(c, f, 1e-3) > 0 || oldest.is_some() {
                    oldest.get_or_insert(at);
                }
            }
            if cut && let Some(shape) = cutter.refresh().expect("material left") {
                let version = shape.version();
                while editor
                    .send(Edit::SetShape(ObjectId(0), Arc::clone(&shape)))
                    .is_err()
                {
                    std::thread::sleep(Duration::from_millis(1));
                }
                drop(editor.collect());
                if let Some(at) = oldest.take() {
                    let _ = made.push((version, at));
                }
            }
            if let Some(rest) = Duration::from_millis(10).checked_sub(began.elapsed()) {
                std::thread::sleep(rest);
            }
        }
        cutter.removed()
    });
    let top = RADIUS + TOOL + 2e-3;
    let mut proxy = Proxy::new(
        DVec3::new(1e-4, 2e-4, top),
        ProxyOptions::default()
            .with_tool_radius(TOOL)
            .expect("a radius"),
    );
    let (mut ns, mut missed, mut latency, mut versions) =
        (Vec::with_capacity(ticks), 0, Vec::new(), 0);
    let mut waiting: Option<(u64, Instant)> = None;
    let period = Duration::from_millis(1);
    let mut deadline = Instant::now();
    for t in 0..ticks {
        deadline += period;
        let hip = DVec3::new(1e-4, 2e-4, top - 1e-5 * t as f64);
        let began = Instant::now();
        scene.begin_tick();
        let out = proxy.tick(&scene, hip, DVec3::new(0.0, 0.0, -0.01));
        ns.push(began.elapsed().as_nanos() as u64);
        if out.contact.is_some() {
            let _ = presses.push((out.proxy, out.force.length(), Instant::now()));
        }
        if waiting.is_none() {
            waiting = versions_made.pop().ok();
        }
        if let (Some((v, at)), Some(c)) = (waiting, out.contact)
            && c.version >= v
        {
            latency.push(at.elapsed().as_secs_f64() * 1e3);
            versions += 1;
            waiting = None;
        }
        if Instant::now() > deadline {
            missed += 1;
        }
        while Instant::now() < deadline {
            std::hint::spin_loop();
        }
    }
    stop.store(true, Ordering::Relaxed);
    let removed = worker.join().expect("the cutter thread");
    ns.sort_unstable();
    Run {
        ticks: ns,
        missed,
        latency_ms: latency,
        versions,
        removed,
    }
}
