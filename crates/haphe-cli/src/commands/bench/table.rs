//! The markdown report on standard output: one table per query kind, build and memory,
//! growth with the triangle count, and the performance targets.

use std::io::{self, Write};
use std::time::Duration;

use super::json::{Record, ratio};
use super::methods::{Method, Query};

/// Run-wide facts printed above the tables.
pub struct Header {
    /// The machine the run measured ([`machine`](super::machine)).
    pub machine: String,
    /// Threads of the build pool (builds are parallel; queries run on one thread).
    pub threads: usize,
    /// Seed of the query streams.
    pub seed: u64,
    /// Queries per kind and mesh.
    pub samples: usize,
    /// Largest mesh that brute force runs on.
    pub brute_force_max_triangles: usize,
    /// Wall time of the measurements.
    pub wall: Duration,
    /// The clock overhead: the lowest and highest median of the empty timings over all
    /// (mesh, query) groups, and the highest 99th percentile.
    pub clock_ns: (f64, f64, f64),
}

/// Target: the free-space tick and a coherent walk step cost at most this many floors
/// (trimmed mean).
const FLOOR_TARGET: f64 = 5.0;
/// Target: haphe's per-query cost on the largest mesh of a family is at most this many
/// times its cost on the smallest (trimmed mean).
const GROWTH_TARGET: f64 = 1.3;

/// Writes the whole report.
pub fn write(out: &mut impl Write, records: &[Record], header: &Header) -> io::Result<()> {
    let (lo, hi, p99) = header.clock_ns;
    writeln!(out, "# haphe bench\n")?;
    writeln!(
        out,
        "Seed {}; about {} queries per kind and mesh (brute force: fewer, on meshes of at most {} \
         triangles); builds on {} thread(s), queries on one; measured in {:.1} s.\n",
        header.seed,
        header.samples,
        header.brute_force_max_triangles,
        header.threads,
        header.wall.as_secs_f64()
    )?;
    writeln!(out, "Machine: {}.\n", header.machine)?;
    writeln!(
        out,
        "Times are per query in ns (µs or ms where marked), each query timed on its own. The \
         clock overhead, measured by empty timings interleaved with the queries (median \
         {lo:.0}–{hi:.0} ns, p99 at most {p99:.0} ns), is subtracted: its median from the \
         percentiles, which keep the clock's granularity, and its trimmed mean from the \
         `mean` column, the mean of the fastest 99 % of the queries, which averages the \
         granularity out. `÷ floor` is p50 over the floor's p50 on the same mesh; \
         `÷ haphe` is this method over haphe on the same mesh and query; `allocations` counts \
         allocation calls while the method's queries ran.\n"
    )?;
    for query in Query::TIMED {
        query_table(out, records, query)?;
    }
    build_table(out, records)?;
    growth_table(out, records)?;
    targets(out, records)
}

/// One table of a timed query kind.
fn query_table(out: &mut impl Write, records: &[Record], query: Query) -> io::Result<()> {
    writeln!(out, "## {}\n\n{}.\n", query.name(), query.description())?;
    writeln!(
        out,
        "| mesh | triangles | method | samples | p50 | p99 | p99.9 | max | mean | ÷ floor p50 | ÷ haphe p50 | ÷ haphe p99 | allocations |"
    )?;
    writeln!(
        out,
        "|------|----------:|--------|--------:|----:|----:|------:|----:|-----:|------------:|------------:|------------:|------------:|"
    )?;
    for r in records.iter().filter(|r| r.query == query) {
        writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            r.mesh,
            r.triangles,
            r.method.name(),
            r.samples,
            ns(r.p50_ns),
            ns(r.p99_ns),
            ns(r.p999_ns),
            ns(r.max_ns),
            ns(r.trimmed_mean_ns),
            times(r.vs_floor_p50),
            times(r.vs_haphe_p50),
            times(r.vs_haphe_p99),
            r.allocations.map_or("-".to_owned(), |a| a.to_string()),
        )?;
    }
    writeln!(out)
}

/// Build and decode times, and memory per triangle.
fn build_table(out: &mut impl Write, records: &[Record]) -> io::Result<()> {
    writeln!(
        out,
        "## build and memory\n\n{}; {}. Median of the builds; bytes are heap bytes per \
         triangle held by the built structures, counted by a counting allocator (haphe's own \
         `heap_bytes` beside it), and of the saved map file; {}.\n",
        Query::Build.description(),
        Query::Decode.description(),
        Query::Zones.description()
    )?;
    writeln!(
        out,
        "| mesh | triangles | haphe build | parry build | parry ÷ haphe | haphe decode | haphe zones | haphe B/triangle | haphe heap_bytes/triangle | parry B/triangle | file B/triangle |"
    )?;
    writeln!(
        out,
        "|------|----------:|------------:|------------:|--------------:|-------------:|------------:|-----------------:|--------------------------:|-----------------:|----------------:|"
    )?;
    for haphe in records
        .iter()
        .filter(|r| r.query == Query::Build && r.method == Method::Haphe)
    {
        let find = |query, method| {
            records
                .iter()
                .find(|r| r.mesh == haphe.mesh && r.query == query && r.method == method)
        };
        let parry = find(Query::Build, Method::Parry);
        let decode = find(Query::Decode, Method::Haphe);
        let zones = find(Query::Zones, Method::Haphe);
        let per_triangle = |bytes: Option<usize>| {
            bytes.map(|b| format!("{:.0}", b as f64 / haphe.triangles as f64))
        };
        writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            haphe.mesh,
            haphe.triangles,
            ns(haphe.p50_ns),
            parry.map_or("-".to_owned(), |p| ns(p.p50_ns)),
            times(parry.and_then(|p| p.vs_haphe_p50)),
            decode.map_or("-".to_owned(), |d| ns(d.p50_ns)),
            zones.map_or("-".to_owned(), |z| ns(z.p50_ns)),
            per_triangle(haphe.bytes).unwrap_or_else(|| "-".to_owned()),
            per_triangle(haphe.heap_bytes).unwrap_or_else(|| "-".to_owned()),
            per_triangle(parry.and_then(|p| p.bytes)).unwrap_or_else(|| "-".to_owned()),
            per_triangle(decode.and_then(|d| d.bytes)).unwrap_or_else(|| "-".to_owned()),
        )?;
    }
    writeln!(out)
}

/// The smallest and largest record of each (family, query, method) with more than one
/// size, for the growth table and the targets.
fn extremes(records: &[Record]) -> Vec<(&Record, &Record)> {
    let mut pairs = Vec::new();
    for (i, r) in records.iter().enumerate() {
        let same = |s: &&Record| s.family == r.family && s.query == r.query && s.method == r.method;
        if records[..i].iter().any(|s| same(&s)) {
            continue; // the group was handled at its first record
        }
        let group: Vec<&Record> = records.iter().filter(same).collect();
        let smallest = group.iter().min_by_key(|s| s.triangles);
        let largest = group.iter().max_by_key(|s| s.triangles);
        if let (Some(&a), Some(&b)) = (smallest, largest)
            && a.triangles < b.triangles
        {
            pairs.push((a, b));
        }
    }
    pairs
}

/// How each method's cost grows from the smallest to the largest mesh of a family.
fn growth_table(out: &mut impl Write, records: &[Record]) -> io::Result<()> {
    let pairs = extremes(records);
    if pairs.is_empty() {
        return Ok(());
    }
    writeln!(
        out,
        "## growth with the triangle count\n\nCost on the largest mesh of a family over cost on \
         the smallest (brute force, which runs on small meshes only, left out).\n"
    )?;
    writeln!(
        out,
        "| family | query | method | triangles | p50 | p50 growth | p99 | p99 growth | mean | mean growth |"
    )?;
    writeln!(
        out,
        "|--------|-------|--------|----------:|----:|-----------:|----:|-----------:|-----:|------------:|"
    )?;
    for (a, b) in pairs
        .into_iter()
        .filter(|(a, _)| a.method != Method::BruteForce)
    {
        writeln!(
            out,
            "| {} | {} | {} | {} → {} | {} → {} | {} | {} → {} | {} | {} → {} | {} |",
            a.family,
            a.query.name(),
            a.method.name(),
            a.triangles,
            b.triangles,
            ns(a.p50_ns),
            ns(b.p50_ns),
            times(ratio(b.p50_ns, a.p50_ns)),
            ns(a.p99_ns),
            ns(b.p99_ns),
            times(ratio(b.p99_ns, a.p99_ns)),
            ns(a.trimmed_mean_ns),
            ns(b.trimmed_mean_ns),
            times(ratio(b.trimmed_mean_ns, a.trimmed_mean_ns)),
        )?;
    }
    writeln!(out)
}

/// The performance targets, met or missed, with the worst case. Targets on the cost of
/// one haphe query (against the floor, across sizes) are judged on the trimmed mean, which
/// resolves differences below the clock's step; the p50 ratio is shown beside it. Targets
/// against parry are judged on p50 and p99.
fn targets(out: &mut impl Write, records: &[Record]) -> io::Result<()> {
    writeln!(out, "## targets\n")?;
    let find = |mesh: &str, query: Query| {
        records
            .iter()
            .find(|r| r.mesh == mesh && r.query == query && r.method == Method::Haphe)
    };
    for (query, what) in [
        (Query::FreeSpace, "free-space tick"),
        (Query::Walk, "coherent walk step"),
        (Query::Contact, "contact tick"),
    ] {
        let worst = records
            .iter()
            .filter(|r| r.query == query && r.method == Method::Haphe)
            .filter_map(|r| {
                let floor = find(&r.mesh, Query::Floor)?;
                let mean = ratio(r.trimmed_mean_ns, floor.trimmed_mean_ns)?;
                Some((mean, ratio(r.p50_ns, floor.p50_ns), r))
            })
            .max_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((mean, p50, r)) = worst {
            verdict(
                out,
                mean <= FLOOR_TARGET,
                &format!("{what} within {FLOOR_TARGET}× the floor (mean)"),
                &format!(
                    "worst {} (p50 {}) on {}",
                    times(Some(mean)),
                    times(p50),
                    r.mesh
                ),
            )?;
        }
    }
    for (query, what) in [
        (Query::Segment, "segment crossing (trajectories)"),
        (Query::Inside, "inside/outside (trajectories)"),
        (Query::SegmentRandom, "segment crossing (random segments)"),
        (Query::InsideRandom, "inside/outside (random points)"),
    ] {
        let parry: Vec<&Record> = records
            .iter()
            .filter(|r| r.query == query && r.method == Method::Parry)
            .collect();
        for (percentile, of) in [
            (
                "p50",
                (|r: &Record| r.vs_haphe_p50) as fn(&Record) -> Option<f64>,
            ),
            ("p99", |r: &Record| r.vs_haphe_p99),
        ] {
            let worst = parry
                .iter()
                .filter_map(|r| of(r).map(|x| (x, r)))
                .min_by(|a, b| a.0.total_cmp(&b.0));
            if let Some((x, r)) = worst {
                verdict(
                    out,
                    x > 1.0,
                    &format!("{what} faster than parry at every size ({percentile})"),
                    &format!("parry ÷ haphe at least {} ({})", times(Some(x)), r.mesh),
                )?;
            }
        }
    }
    contact_targets(out, records)?;
    tool_targets(out, records)?;
    texture_target(out, records)?;
    for (a, b) in extremes(records)
        .into_iter()
        .filter(|(a, _)| a.method == Method::Haphe && a.clock_overhead_ns.is_some())
    {
        if let Some(mean) = ratio(b.trimmed_mean_ns, a.trimmed_mean_ns) {
            verdict(
                out,
                mean <= GROWTH_TARGET,
                &format!(
                    "{} on {}: cost at {} triangles within {GROWTH_TARGET}× of {} (mean)",
                    a.query.name(),
                    a.family,
                    b.triangles,
                    a.triangles
                ),
                &format!(
                    "{} (p50 {})",
                    times(Some(mean)),
                    times(ratio(b.p50_ns, a.p50_ns))
                ),
            )?;
        }
    }
    writeln!(out)
}

/// The contact tick against parry's nearest-point proxy: at least 10× faster at p50 on
/// the smallest meshes (about 1k triangles), at least 100× from about 1M triangles, and at
/// p99.9 at least 10× at every size.
fn contact_targets(out: &mut impl Write, records: &[Record]) -> io::Result<()> {
    let pairs: Vec<(&Record, &Record)> = records
        .iter()
        .filter(|r| r.query == Query::Contact && r.method == Method::Parry)
        .filter_map(|p| {
            records
                .iter()
                .find(|h| {
                    h.query == Query::Contact && h.method == Method::Haphe && h.mesh == p.mesh
                })
                .map(|h| (h, p))
        })
        .collect();
    let speedup =
        |h: &Record, p: &Record, of: fn(&Record) -> f64| ratio(of(p), of(h)).unwrap_or(0.0);
    for (what, goal, filter) in [
        (
            "contact tick ≥ 10× faster than parry's proxy at p50 (about 1k triangles)",
            10.0,
            (|t: usize| t < 5_000) as fn(usize) -> bool,
        ),
        (
            "contact tick ≥ 100× faster than parry's proxy at p50 (about 1M triangles and more)",
            100.0,
            |t: usize| t >= 500_000,
        ),
    ] {
        let worst = pairs
            .iter()
            .filter(|(h, _)| filter(h.triangles))
            .map(|&(h, p)| (speedup(h, p, |r| r.p50_ns), h))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((x, h)) = worst {
            verdict(
                out,
                x >= goal,
                what,
                &format!("worst {} ({})", times(Some(x)), h.mesh),
            )?;
        }
    }
    let worst = pairs
        .iter()
        .map(|&(h, p)| (speedup(h, p, |r| r.p999_ns), h))
        .min_by(|a, b| a.0.total_cmp(&b.0));
    if let Some((x, h)) = worst {
        verdict(
            out,
            x >= 10.0,
            "contact tick ≥ 10× faster than parry's proxy at p99.9, every size",
            &format!("worst {} ({})", times(Some(x)), h.mesh),
        )?;
    }
    Ok(())
}

/// The tool tick, at each radius: its p50 within 2× the point's contact tick on the same
/// mesh, and ahead of parry's ball proxy at p50. The worst mesh of each.
fn tool_targets(out: &mut impl Write, records: &[Record]) -> io::Result<()> {
    let find = |mesh: &str, query: Query, method: Method| {
        records
            .iter()
            .find(|r| r.mesh == mesh && r.query == query && r.method == method)
    };
    for (query, what) in [(Query::Tool, "1 mm"), (Query::ToolWide, "2 % of the size")] {
        let tools = || {
            records
                .iter()
                .filter(move |r| r.query == query && r.method == Method::Haphe)
        };
        let worst = |of: &dyn Fn(&Record) -> Option<f64>| {
            tools()
                .filter_map(|r| Some((of(r)?, r)))
                .max_by(|a, b| a.0.total_cmp(&b.0))
        };
        let point = |r: &Record| {
            ratio(
                r.p50_ns,
                find(&r.mesh, Query::Contact, Method::Haphe)?.p50_ns,
            )
        };
        if let Some((x, r)) = worst(&point) {
            verdict(
                out,
                x <= 2.0,
                &format!("tool tick (r {what}) within 2× the point's contact tick at p50"),
                &format!("worst {} ({})", times(Some(x)), r.mesh),
            )?;
        }
        let parry = |r: &Record| ratio(r.p50_ns, find(&r.mesh, query, Method::Parry)?.p50_ns);
        if let Some((x, r)) = worst(&parry) {
            verdict(
                out,
                x <= 1.0,
                &format!("tool tick (r {what}) ahead of parry's ball proxy at p50"),
                &format!("worst haphe ÷ parry {} ({})", times(Some(x)), r.mesh),
            )?;
        }
    }
    Ok(())
}

/// The textured contact tick's p50 within 1.3× the plain one's on the same mesh. The
/// worst mesh.
fn texture_target(out: &mut impl Write, records: &[Record]) -> io::Result<()> {
    let plain = |mesh: &str| {
        records
            .iter()
            .find(|r| r.mesh == mesh && r.query == Query::Contact && r.method == Method::Haphe)
    };
    let worst = records
        .iter()
        .filter(|r| r.query == Query::Textured && r.method == Method::Haphe)
        .filter_map(|r| Some((ratio(r.p50_ns, plain(&r.mesh)?.p50_ns)?, r)))
        .max_by(|a, b| a.0.total_cmp(&b.0));
    if let Some((x, r)) = worst {
        verdict(
            out,
            x <= 1.3,
            "textured contact tick within 1.3× the plain one at p50",
            &format!("worst {} ({})", times(Some(x)), r.mesh),
        )?;
    }
    Ok(())
}

fn verdict(out: &mut impl Write, met: bool, target: &str, detail: &str) -> io::Result<()> {
    writeln!(
        out,
        "- {} {target}: {detail}",
        if met { "met   " } else { "MISSED" }
    )
}

/// A time in ns, or µs or ms when large.
fn ns(v: f64) -> String {
    if !v.is_finite() {
        "-".to_owned()
    } else if v < 10.0 {
        format!("{v:.1}")
    } else if v < 1e4 {
        format!("{v:.0}")
    } else if v < 1e7 {
        format!("{:.1} µs", v / 1e3)
    } else {
        format!("{:.1} ms", v / 1e6)
    }
}

/// A ratio, with two significant digits or more.
fn times(x: Option<f64>) -> String {
    match x {
        Some(x) if x.is_finite() && x < 10.0 => format!("{x:.2}×"),
        Some(x) if x.is_finite() && x < 100.0 => format!("{x:.1}×"),
        Some(x) if x.is_finite() => format!("{x:.0}×"),
        _ => "-".to_owned(),
    }
}
