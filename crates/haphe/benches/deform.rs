//! The servo tick while another thread deforms the shape it touches: a hand presses and
//! slides on a 20 000-triangle blob at 1 kHz (ticks paced on the wall clock) while a
//! second thread makes the blob breathe and carry a travelling dent, refreshing it with
//! `Shape::deformed` as fast as it can up to 100 Hz and handing each version to the
//! servo through the scene's editor: a travelling dent alone (a local refresh), and with
//! the blob breathing too (every vertex moves: a rebuild). The same run without the
//! deforming thread is the rigid reference. Prints each run's tick percentiles (the tick
//! is `begin_tick` and the proxy's tick), the refreshes made, and its p99 over the rigid
//! one's.
//!
//! `taskset -c 0,1 cargo bench -p haphe --bench deform` (both cores: the servo on one,
//! the refresh on the other); `cargo test --benches` runs it for a tenth of a second.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::scene::{Edit, Material, ObjectId, Pose, Scene, SceneObject, Shape};
use haphe::verify::{Deformation, haptic_path_in_contact};

/// Ticks of each run: 10 s at 1 kHz (a tenth of a second when not benchmarking).
fn ticks() -> usize {
    if std::env::args().any(|a| a == "--bench") {
        10_000
    } else {
        100
    }
}

fn main() {
    let surface = Surface::new(
        Catalog::Blob.with_triangles(20_000),
        &SurfaceOptions::default(),
    )
    .expect("a usable surface");
    let blob = Arc::new(
        Shape::build(surface, &MapOptions::default())
            .expect("a map")
            .with_clear_zones(),
    );
    let ticks = ticks();
    println!(
        "tick (begin_tick + proxy), ns: p50 p99 p99.9 max; contact ticks; refreshes (p50 ms); \
         p99 / rigid p99"
    );
    let rigid = run(&blob, ticks, None);
    for (name, deformation) in [
        ("rigid", None),
        ("dent", Some(Deformation::Dent)),
        ("breathe-dent", Some(Deformation::BreatheAndDent)),
    ] {
        let r = match deformation {
            None => rigid.clone(),
            Some(_) => run(&blob, ticks, deformation),
        };
        println!(
            "{name:>12}: {:>7} {:>7} {:>7} {:>8}  contact {:>5}  refreshes {:>4} ({:.1} ms)  {:.2}",
            r.percentile(0.5),
            r.percentile(0.99),
            r.percentile(0.999),
            r.percentile(1.0),
            r.contact,
            r.refreshes,
            r.refresh_ms,
            r.percentile(0.99) as f64 / rigid.percentile(0.99).max(1) as f64
        );
    }
}

#[derive(Clone)]
struct Run {
    /// Every tick's time, ns, sorted.
    ns: Vec<u64>,
    contact: usize,
    refreshes: usize,
    refresh_ms: f64,
}

impl Run {
    fn percentile(&self, q: f64) -> u64 {
        let k = ((self.ns.len() as f64 - 1.0) * q).round() as usize;
        self.ns.get(k).copied().unwrap_or(0)
    }
}

fn run(blob: &Arc<Shape>, ticks: usize, deformation: Option<Deformation>) -> Run {
    let (mut scene, mut editor) = Scene::new(2);
    let object = SceneObject::new(
        ObjectId(0),
        Arc::clone(blob),
        Pose::IDENTITY,
        Material::DEFAULT,
    );
    scene.insert(object).expect("room");
    let path = haptic_path_in_contact(&scene, ticks, (0.02, 0.2), (0.5e-3, 4e-3), 1e3, 7);
    let stop = Arc::new(AtomicBool::new(false));
    let start = Instant::now();
    let deformer = deformation.map(|deformation| {
        let (blob, stop) = (Arc::clone(blob), Arc::clone(&stop));
        std::thread::spawn(move || {
            let rest = blob.surface().vertices().to_vec();
            let mut current = blob;
            let mut times = Vec::new();
            while !stop.load(Ordering::Relaxed) {
                let began = Instant::now();
                let t = start.elapsed().as_secs_f64();
                let vertices = deformation.vertices_at(&rest, t);
                current = Arc::new(current.deformed(&vertices).expect("a deformation"));
                times.push(began.elapsed().as_secs_f64() * 1e3);
                while editor
                    .send(Edit::SetShape(ObjectId(0), Arc::clone(&current)))
                    .is_err()
                {
                    std::thread::sleep(Duration::from_millis(1));
                }
                drop(editor.collect());
                if let Some(rest) = Duration::from_millis(10).checked_sub(began.elapsed()) {
                    std::thread::sleep(rest);
                }
            }
            times.sort_by(f64::total_cmp);
            times
        })
    });
    let mut proxy = Proxy::new(path[0], ProxyOptions::default());
    let mut ns = Vec::with_capacity(ticks);
    let mut contact = 0;
    let mut previous = path[0];
    let period = Duration::from_millis(1);
    let mut deadline = Instant::now();
    for &hip in &path {
        deadline += period;
        let began = Instant::now();
        scene.begin_tick();
        let out = proxy.tick(&scene, hip, (hip - previous) * 1e3);
        ns.push(began.elapsed().as_nanos() as u64);
        previous = hip;
        contact += usize::from(out.contact.is_some());
        while Instant::now() < deadline {
            std::hint::spin_loop();
        }
    }
    stop.store(true, Ordering::Relaxed);
    let times = deformer
        .map(|d| d.join().expect("the deforming thread"))
        .unwrap_or_default();
    ns.sort_unstable();
    Run {
        ns,
        contact,
        refreshes: times.len(),
        refresh_ms: times.get(times.len() / 2).copied().unwrap_or(0.0),
    }
}
