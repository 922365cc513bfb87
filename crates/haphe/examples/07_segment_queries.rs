//! Segment crossings on random segments across a procedural shape, for measuring what a
//! query costs: the segments `haphe bench` uses for its `segment_random` rows (random end
//! points in the grown bounding box), each answered by [`first_crossing`], with the query
//! times: of all segments, then of those that cross the surface and of those that do not
//! (most of which miss the object's box and cost next to nothing).
//!
//! ```sh
//! cargo run --release --example 07_segment_queries -- 1000000 blob 50000
//! cargo run --release --example 07_segment_queries -- 1000 thin-plate 100000 5
//! ```
//!
//! Arguments: triangles (default 1000), shape (default `blob`), segments (default 50000),
//! rounds (default 1), grow (default none). With more than one round, every segment is
//! answered once per round and its time is the fastest of its rounds: the cost of the
//! query with the mesh and map warm in the cache, free of most of a shared machine's
//! noise. The shape may also be a mesh file (read in metres, the triangles argument then
//! ignored). With `grow`, the segments are those of `tools/bench_python.py` instead: both
//! ends uniform in the mesh's bounding box grown by that fraction of its size along each
//! axis (the script's 0.05):
//!
//! ```sh
//! cargo run --release --example 07_segment_queries -- 0 ../shared/meshes/models/nefertiti.obj 200000 1 0.05
//! ```
//!
//! For an instruction count that does not depend on the machine's load, run it under
//! callgrind, counting inside the query only:
//!
//! ```sh
//! valgrind --tool=callgrind --toggle-collect='*segment_once*' \
//!     target/release/examples/07_segment_queries 1000000 blob 50000
//! ```

use std::time::Instant;

use haphe::DVec3;
use haphe::map::{MapOptions, VoxelMap};
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Mesh, ReadOptions, Surface, SurfaceOptions, read_mesh};
use haphe::query::{Crossing, first_crossing};
use haphe::rng::SplitMix64;
use haphe::verify::{SegmentKind, segments};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let triangles: usize = args.next().map_or(Ok(1000), |a| a.parse())?;
    let which = args.next().unwrap_or_else(|| "blob".to_owned());
    let count: usize = args.next().map_or(Ok(50_000), |a| a.parse())?;
    let rounds: usize = args.next().map_or(Ok(1), |a| a.parse())?;
    let grow: Option<f64> = args.next().map(|a| a.parse()).transpose()?;

    let surface = Surface::new(mesh(&which, triangles)?, &SurfaceOptions::default())?;
    let map = VoxelMap::build(&surface, &MapOptions::default())?;
    let queries = match grow {
        Some(grow) => in_grown_box(&surface, grow, count),
        None => segments(&surface, SegmentKind::Random, count, 1),
    };
    // Query times (ns, clock included) of the segments that cross the surface and of
    // those that do not: two populations, the second mostly cheap (segments that miss
    // the object's box), so the percentiles of all of them mix the two.
    let mut fastest = vec![(u64::MAX, false); queries.len()];
    for _ in 0..rounds.max(1) {
        for (&(p0, p1), best) in queries.iter().zip(&mut fastest) {
            let started = Instant::now();
            let found = segment_once(&surface, &map, p0, p1).is_some();
            let ns = started.elapsed().as_nanos() as u64;
            *best = (best.0.min(ns), found);
        }
    }
    let (mut crossing, mut missing) = (Vec::new(), Vec::new());
    for (ns, found) in fastest {
        if found {
            crossing.push(ns);
        } else {
            missing.push(ns);
        }
    }
    let hits = crossing.len();
    let mut all = [crossing.as_slice(), missing.as_slice()].concat();
    let Some(all) = percentiles(&mut all) else {
        println!("no segment");
        return Ok(());
    };
    let rounds = if rounds > 1 {
        format!(" (fastest of {rounds} rounds)")
    } else {
        String::new()
    };
    println!(
        "{which} ({} triangles): {} random segments, {hits} crossing; query time{rounds} {all} (clock included)",
        surface.triangle_count(),
        queries.len(),
    );
    for (what, times) in [("crossing", &mut crossing), ("not crossing", &mut missing)] {
        if let Some(line) = percentiles(times) {
            println!("  {what}: {line}");
        }
    }
    Ok(())
}

/// The mesh of the shape argument: a mesh file when one is there by that name (metres),
/// else a procedural shape of about `triangles` triangles.
fn mesh(which: &str, triangles: usize) -> Result<Mesh, Box<dyn std::error::Error>> {
    if std::path::Path::new(which).is_file() {
        return Ok(read_mesh(
            which,
            &std::fs::read(which)?,
            &ReadOptions::default(),
        )?);
    }
    Ok(which.parse::<Catalog>()?.with_triangles(triangles))
}

/// `count` segments whose ends are uniform in the bounding box of `surface` grown by `grow`
/// times its size along each axis, on both sides (seed 7).
fn in_grown_box(surface: &Surface, grow: f64, count: usize) -> Vec<(DVec3, DVec3)> {
    let (lo, hi) = surface.bounds();
    let pad = grow * (hi - lo);
    let mut random = SplitMix64::new(7);
    (0..count)
        .map(|_| {
            let p0 = random.point_in(lo - pad, hi + pad);
            (p0, random.point_in(lo - pad, hi + pad))
        })
        .collect()
}

/// `p50, p99, p99.9 and max` of `times` (ns), sorting them; `None` when empty.
fn percentiles(times: &mut [u64]) -> Option<String> {
    times.sort_unstable();
    let &max = times.last()?;
    let at = |q: f64| times[((times.len() - 1) as f64 * q) as usize];
    Some(format!(
        "p50 {} ns, p99 {} ns, p99.9 {} ns, max {max} ns",
        at(0.5),
        at(0.99),
        at(0.999)
    ))
}

/// One query, never inlined, so that callgrind can count inside it whatever the compiler
/// inlined into it.
#[inline(never)]
fn segment_once(surface: &Surface, map: &VoxelMap, p0: DVec3, p1: DVec3) -> Option<Crossing> {
    first_crossing(surface, map, p0, p1)
}
