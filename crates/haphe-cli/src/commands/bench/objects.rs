//! The object-count series of `haphe bench`: the proxy tick on scenes of 1 to 10^5
//! objects sharing one shape, static and with a thousand of them moving every tick, with
//! the scene's broad phase and with the linear path that tests every object.
//!
//! The scene is a cubic grid of spheres of about a thousand triangles (0.1 m radius,
//! 0.25 m apart, one [`Shape`] behind an `Arc`); the hand presses about 6 mm into the
//! sphere at the corner of the grid, which has neighbours on three sides, and slides on
//! it in circles. A tick is timed as the servo thread runs it: [`Scene::begin_tick`], the
//! poses of the moving objects (a 1 mm wobble, each set by [`Scene::set_pose_keyed`] with
//! a key made once per object), and [`Proxy::tick`]. Every configuration keeps its own
//! scene and proxy; they take turns by chunks of ticks, so that a slow spell of a shared
//! machine falls on all alike.

use std::hint::black_box;
use std::sync::Arc;
use std::time::Instant;

use anyhow::anyhow;
use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::scene::{Material, ObjectId, ObjectKey, Pose, Scene, SceneObject, Shape};

use super::timing::{Overhead, Summary, time_empty};

/// Object counts of the series by default, and with `--quick`.
pub const DEFAULT_COUNTS: [usize; 6] = [1, 10, 100, 1_000, 10_000, 100_000];
pub const QUICK_COUNTS: [usize; 5] = [1, 10, 100, 1_000, 10_000];
/// Objects moved every tick in the moving configurations (scenes of at least this many).
pub const MOVING: usize = 1_000;
/// The linear path is timed on scenes of at most this many objects.
const LINEAR_MAX: usize = 10_000;
/// Ticks per configuration taking its turn.
const CHUNK: usize = 1_000;
/// Distance between neighbouring objects of the grid, metres.
const SPACING: f64 = 0.25;

/// One configuration's times.
pub struct Row {
    /// Objects in the scene.
    pub objects: usize,
    /// Objects moved every tick.
    pub moving: usize,
    /// Every object tested in each search (the path before the broad phase).
    pub linear: bool,
    /// Per tick, nanoseconds.
    pub tick: Summary,
    /// Ticks that ended in contact.
    pub contacts: usize,
}

struct Config {
    scene: Scene,
    proxy: Proxy,
    moving: Vec<(ObjectKey, DVec3)>,
    row: Row,
    raw: Vec<u32>,
}

/// Where object `k` of a grid of `side`³ sits.
fn grid(k: usize, side: usize) -> DVec3 {
    let (x, y, z) = (k % side, (k / side) % side, k / (side * side));
    DVec3::new(x as f64, y as f64, z as f64) * SPACING
}

fn config(shape: &Arc<Shape>, objects: usize, moving: usize, linear: bool) -> Config {
    let side = (1..).find(|s: &usize| s.pow(3) >= objects).unwrap_or(1);
    let material = Material::builder()
        .stiffness(1000.0)
        .damping(1.0)
        .friction(0.0, 0.0)
        .build()
        .expect("a valid material");
    let mut scene = Scene::local(objects);
    for k in 0..objects {
        let pose = Pose::from_translation(grid(k, side)).expect("a valid pose");
        let object = SceneObject::new(ObjectId(k as u32), Arc::clone(shape), pose, material);
        let _ = scene.insert(object);
    }
    // The movers, spread over the grid, the touched sphere (0) not among them.
    let moving = (0..moving)
        .map(|m| {
            let k = 1 + m * (objects - 1) / moving.max(1);
            (ObjectKey::new(ObjectId(k as u32)), grid(k, side))
        })
        .collect();
    let proxy = Proxy::new(DVec3::new(0.0, 0.0, 0.2), ProxyOptions::default());
    Config {
        scene,
        proxy: if linear {
            proxy.with_linear_scan()
        } else {
            proxy
        },
        moving,
        row: Row {
            objects,
            moving: 0,
            linear,
            tick: Summary::of(&mut [], Overhead::NONE),
            contacts: 0,
        },
        raw: Vec::new(),
    }
}

/// The hand at tick `t`: pressing about 6 mm into the corner sphere, sliding in a circle
/// of 4 cm radius at 8 cm/s (10 kHz ticks).
fn hand(t: usize) -> DVec3 {
    let s = t as f64 * 2e-3;
    DVec3::new(0.04 * s.cos(), 0.04 * s.sin(), 0.085)
}

/// Runs the series: `ticks` timed ticks per configuration.
///
/// # Errors
/// When the sphere cannot be built.
pub fn series(counts: &[usize], ticks: usize) -> anyhow::Result<Vec<Row>> {
    let surface = Surface::new(
        Catalog::Sphere.with_triangles(1_000),
        &SurfaceOptions::default(),
    )
    .map_err(|e| anyhow!("{e}"))?;
    let shape =
        Arc::new(Shape::build(surface, &MapOptions::default()).map_err(|e| anyhow!("{e}"))?);
    shape.prepare_clear_zones();
    let mut configs = Vec::new();
    for &n in counts {
        for moving in [0, MOVING] {
            if moving > n {
                continue;
            }
            for linear in [false, true] {
                if linear && n > LINEAR_MAX {
                    continue;
                }
                let mut c = config(&shape, n, moving, linear);
                c.row.moving = moving;
                configs.push(c);
            }
        }
    }
    let mut clock = Vec::new();
    let mut done = 0;
    // One untimed chunk first: the hand comes down onto the sphere.
    for (round, timed) in std::iter::once(false)
        .chain(std::iter::repeat_n(true, ticks.div_ceil(CHUNK)))
        .enumerate()
    {
        let len = if timed {
            CHUNK.min(ticks - done)
        } else {
            CHUNK
        };
        for c in &mut configs {
            for i in 0..len {
                let t = round * CHUNK + i;
                let hip = hand(t);
                let start = Instant::now();
                c.scene.begin_tick();
                let wobble = DVec3::new(0.0, 0.0, 1e-3 * (t as f64 * 0.01).sin());
                for (key, at) in &mut c.moving {
                    c.scene.set_pose_keyed(
                        key,
                        Pose::from_translation(*at + wobble).expect("a valid pose"),
                    );
                }
                let out = c.proxy.tick(&c.scene, black_box(hip), DVec3::ZERO);
                black_box(out);
                let ns = u32::try_from(start.elapsed().as_nanos()).unwrap_or(u32::MAX);
                if timed {
                    c.raw.push(ns);
                    c.row.contacts += usize::from(out.contact.is_some());
                }
            }
            if timed {
                time_empty(len / 10 + 1, &mut clock);
            }
        }
        if timed {
            done += len;
        }
    }
    let overhead = Overhead::of(&Summary::of(&mut clock, Overhead::NONE));
    Ok(configs
        .into_iter()
        .map(|mut c| {
            c.row.tick = Summary::of(&mut c.raw, overhead);
            c.row
        })
        .collect())
}

/// Writes the series as a table, with each tick's ratios to the first row (the smallest
/// scene, static, broad phase).
pub fn write(out: &mut impl std::io::Write, rows: &[Row], ticks: usize) -> std::io::Result<()> {
    writeln!(out)?;
    writeln!(
        out,
        "## Tick against object count ({ticks} ticks each; a 1k-triangle sphere shared by every object, hand pressing and sliding on one)"
    )?;
    writeln!(out)?;
    writeln!(
        out,
        "| objects | moving | search | p50 | p99 | p99.9 | max | p50 / 1 object | p99 / 1 object | contact ticks |"
    )?;
    writeln!(out, "|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|")?;
    let us = |ns: f64| format!("{:.2} µs", ns / 1e3);
    let one = rows
        .iter()
        .find(|r| r.objects == rows[0].objects && !r.linear && r.moving == 0);
    for r in rows {
        let ratio = |f: fn(&Summary) -> f64| {
            one.map_or_else(
                || "-".into(),
                |o| format!("{:.2}x", f(&r.tick) / f(&o.tick).max(1.0)),
            )
        };
        writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.objects,
            r.moving,
            if r.linear { "linear" } else { "broad phase" },
            us(r.tick.p50),
            us(r.tick.p99),
            us(r.tick.p999),
            us(r.tick.max),
            ratio(|s| s.p50),
            ratio(|s| s.p99),
            r.contacts,
        )?;
    }
    Ok(())
}
