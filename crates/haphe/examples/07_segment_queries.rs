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
//! rounds (default 1). With more than one round, every segment is answered once per round
//! and its time is the fastest of its rounds: the cost of the query with the mesh and map
//! warm in the cache, free of most of a shared machine's noise.
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
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::query::{Crossing, first_crossing};
use haphe::verify::{SegmentKind, segments};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let triangles: usize = args.next().map_or(Ok(1000), |a| a.parse())?;
    let which: Catalog = args.next().map_or(Ok(Catalog::Blob), |a| a.parse())?;
    let count: usize = args.next().map_or(Ok(50_000), |a| a.parse())?;
    let rounds: usize = args.next().map_or(Ok(1), |a| a.parse())?;

    let surface = Surface::new(which.with_triangles(triangles), &SurfaceOptions::default())?;
    let map = VoxelMap::build(&surface, &MapOptions::default())?;
    let queries = segments(&surface, SegmentKind::Random, count, 1);
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
