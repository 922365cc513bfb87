//! `haphe verify`: check haphe's accelerated queries against brute-force oracles and
//! `parry3d-f64` on any mesh.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{anyhow, bail};
use haphe::map::VoxelMap;
use haphe::mesh::{ReadOptions, Surface};
use haphe::verify::{
    CrossingCheck, InsideCheck, STRIKE_SPEED_CLASSES, SegmentKind, WalkCheck, bounds,
    check_crossings_with_peer, check_inside_with_peer, check_walk,
};
use serde::Serialize;

mod deform;
mod peer;
mod proxy;

use self::peer::Parry;
use crate::args::{map_options, parse_units, weld_mode};
use crate::input::object::open;

/// Arguments of `haphe verify`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// A mesh file (or a map file from `haphe build`).
    file: PathBuf,
    /// Samples per check: segments of each kind, points, and walk targets.
    #[arg(long, default_value_t = 10_000)]
    samples: usize,
    /// Random segments (default: --samples).
    #[arg(long)]
    random: Option<usize>,
    /// Segments of each adversarial kind (default: --samples).
    #[arg(long)]
    adversarial: Option<usize>,
    /// Random points for inside/outside (default: --samples).
    #[arg(long)]
    points: Option<usize>,
    /// Surface-walk targets (default: --samples).
    #[arg(long)]
    walks: Option<usize>,
    /// Proxy ticks per kind of path (exploring, strikes, steady contact), compared with
    /// the brute-force proxy on the model scaled to 0.2 m (default: --samples; 0 skips).
    #[arg(long)]
    ticks: Option<usize>,
    /// Deep strikes on a closed model scaled to 0.2 m: the force never pulls the hand on
    /// through the object once the proxy holds (0 skips).
    #[arg(long, default_value_t = 0)]
    strikes: usize,
    /// The tool's radius for --ticks and --strikes, metres on the model scaled to 0.2 m:
    /// the proxy is a sphere of this radius (0: a point).
    #[arg(long, default_value_t = 0.0, value_name = "METRES")]
    tool_radius: f64,
    /// Also check the proxy against the brute-force proxy while the model (scaled to
    /// 0.2 m) deforms at every tick: breathe, dent, breathe-dent, twist, or all (breathe,
    /// dent and twist); --ticks ticks of pressing paths each, with --tool-radius.
    #[arg(long, value_name = "KIND", value_parser = deform::parse_kinds)]
    deform: Option<deform::Kinds>,
    /// Seed of the samples (the same seed gives the same samples).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Print one JSON object instead of the tables.
    #[arg(long)]
    json: bool,
    /// Length unit of the file: m, mm, cm, in, or a factor in metres per file unit.
    #[arg(long, default_value = "m", value_parser = parse_units)]
    units: haphe::mesh::Units,
}

#[derive(Serialize)]
struct CrossingRow {
    #[serde(flatten)]
    check: CrossingCheck,
    /// Segments that cross the surface (by brute force) where parry's ray cast finds nothing.
    parry_misses: Option<usize>,
    /// Of the segments from outside to inside a solid, those parry's ray cast finds no
    /// crossing on: where a parry-based renderer lets the user through.
    parry_leaks: Option<usize>,
    /// Seconds for the check (haphe, the oracles and parry together).
    seconds: f64,
}

#[derive(Serialize)]
struct InsideRow {
    #[serde(flatten)]
    check: InsideCheck,
    /// Points (off the surface) where parry's `contains_point` disagrees with the oracle.
    parry_disagreements: Option<usize>,
    /// Seconds for the check (haphe, the oracles and parry together).
    seconds: f64,
}

#[derive(Serialize)]
struct Verification {
    file: String,
    triangles: usize,
    solid: bool,
    map_cells: [u32; 3],
    /// Seconds to open the object: decode a map file, or read, build surface and map.
    open_seconds: f64,
    /// Whether the object came from a map file.
    from_map_file: bool,
    /// The mesh a map file was built from (name, size and hash), when it records one.
    source: Option<String>,
    seconds: f64,
    crossings: Vec<CrossingRow>,
    inside: InsideRow,
    walk: WalkCheck,
    walk_seconds: f64,
    /// The proxy against the brute-force proxy, when run.
    proxy: Option<proxy::ProxyReport>,
    /// Deep strikes, when run on a closed model.
    strikes: Option<proxy::StrikeReport>,
    /// The proxy on the deforming model, when asked for.
    deforming: Option<deform::DeformReport>,
    passed: bool,
}

/// Runs the command; exit 0 when every check passes, 1 otherwise.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    let n = args.samples;
    let checked = checked(args)?;
    let start = Instant::now();
    let read = ReadOptions {
        units: args.units,
        weld: weld_mode(None)?,
        format: None,
    };
    let object = open(&args.file, &read, &map_options(None, None)).map_err(|e| anyhow!("{e:#}"))?;
    let (surface, map) = (&object.surface, &object.map);
    if checked == 0 && !surface.is_solid() {
        bail!(
            "nothing to check: {}: deep strikes need a closed model and this one is not (see `haphe validate`)",
            args.file.display()
        );
    }
    let parry = Parry::of(surface);

    let crossings = check_segments(args, surface, map, parry.as_ref());
    let inside = check_points(args, surface, map, parry.as_ref());
    let clock = Instant::now();

    // Steps of 0.05–0.5 mm on a 0.2 m object, scaled to this object's size.
    let (_, _, size) = bounds(surface);
    let scale = size / (0.2 * 3f64.sqrt());
    let steps = 100;
    let walk = check_walk(
        surface,
        args.walks.unwrap_or(n).div_ceil(steps),
        steps,
        (0.05e-3 * scale, 0.5e-3 * scale),
        args.seed,
    );
    let walk_seconds = clock.elapsed().as_secs_f64();

    let ticks = args.ticks.unwrap_or(n);
    let options = tool_options(args.tool_radius)?;
    let proxy = (ticks > 0)
        .then(|| proxy::check(surface, options, ticks, args.seed))
        .transpose()?;
    let strikes = (args.strikes > 0 && surface.is_solid())
        .then(|| proxy::strikes(surface, options, args.strikes, args.seed))
        .transpose()?;
    let deforming = match &args.deform {
        Some(kinds) if ticks > 0 => {
            Some(deform::check(surface, &kinds.0, options, ticks, args.seed)?)
        }
        _ => None,
    };

    let passed = crossings
        .iter()
        .all(|r| r.check.mismatches == 0 && r.check.leaks == 0)
        && inside.check.mismatches == 0
        && walk.not_local_minimum == 0
        && walk.not_nearest == 0
        && proxy.as_ref().is_none_or(|p| p.passed())
        && strikes.as_ref().is_none_or(|s| s.passed())
        && deforming.as_ref().is_none_or(|d| d.passed());
    let report = Verification {
        file: args.file.display().to_string(),
        triangles: surface.triangle_count(),
        solid: surface.is_solid(),
        map_cells: map.grid().dims(),
        open_seconds: object.elapsed.as_secs_f64(),
        from_map_file: object.from_map_file,
        source: object.map.provenance().map(|p| p.to_string()),
        seconds: start.elapsed().as_secs_f64(),
        crossings,
        inside,
        walk,
        walk_seconds,
        proxy,
        strikes,
        deforming,
        passed,
    };
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::to_string(&report)?)?;
    } else {
        print_tables(&mut out, &report)?;
    }
    Ok(if passed {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// How many samples the checks take (but the strikes), after refusing a run that would
/// check nothing.
///
/// # Errors
/// Nothing to check: every count 0, or `--deform` with no ticks.
fn checked(args: &Args) -> anyhow::Result<usize> {
    let n = args.samples;
    let checked = [
        args.random,
        args.adversarial,
        args.points,
        args.walks,
        args.ticks,
    ]
    .into_iter()
    .map(|count| count.unwrap_or(n))
    .sum::<usize>();
    if checked + args.strikes == 0 {
        bail!(
            "nothing to check: --samples 0 (and no --random, --adversarial, --points, --walks, --ticks or --strikes above 0) would pass having checked nothing"
        );
    }
    if args.deform.is_some() && args.ticks.unwrap_or(n) == 0 {
        bail!(
            "nothing to check: --deform runs --ticks ticks (default --samples) of each deformation, and they are 0"
        );
    }
    Ok(checked)
}

fn print_tables(out: &mut impl Write, r: &Verification) -> std::io::Result<()> {
    let opt = |v: Option<usize>| v.map_or("-".to_owned(), |v| v.to_string());
    writeln!(
        out,
        "{}: {} triangles, {}, map {}x{}x{} cells ({} in {:.2} s; checks took {:.1} s)\n",
        r.file,
        r.triangles,
        if r.solid {
            "closed solid"
        } else {
            "open surface"
        },
        r.map_cells[0],
        r.map_cells[1],
        r.map_cells[2],
        if r.from_map_file {
            "map file decoded"
        } else {
            "surface and map built"
        },
        r.open_seconds,
        r.seconds
    )?;
    if let Some(source) = &r.source {
        writeln!(out, "a map of {source}\n")?;
    }
    writeln!(
        out,
        "| segments         | samples | crossing | mismatches vs brute force | outside→inside | leaks | parry misses | parry leaks |"
    )?;
    writeln!(
        out,
        "|------------------|--------:|---------:|--------------------------:|---------------:|------:|-------------:|------------:|"
    )?;
    for row in &r.crossings {
        let c = &row.check;
        writeln!(
            out,
            "| {:<16} | {:>7} | {:>8} | {:>25} | {:>14} | {:>5} | {:>12} | {:>11} |",
            serde_json::to_value(c.kind)
                .map(|v| v.as_str().unwrap_or("").to_owned())
                .unwrap_or_default(),
            c.samples,
            c.crossing,
            c.mismatches,
            c.outside_to_inside,
            c.leaks,
            opt(row.parry_misses),
            opt(row.parry_leaks)
        )?;
    }
    let i = &r.inside.check;
    writeln!(
        out,
        "\ninside/outside: {} points, {} inside, {} mismatches vs winding numbers (non-zero rule; {} excused within 1 nm of the surface), {} where parts overlap (winding number not 0 or 1), parry disagreements: {}",
        i.samples,
        i.inside,
        i.mismatches,
        i.on_surface,
        i.overlap,
        opt(r.inside.parry_disagreements)
    )?;
    if !peer::BUILT {
        writeln!(
            out,
            "(parry columns: `-`, parry3d-f64 is not in this build: cargo feature `bench`)"
        )?;
    }
    let w = &r.walk;
    writeln!(
        out,
        "surface walk: {} coherent walks on {} trajectories, {} not a local minimum, {} step caps hit{}",
        w.walks,
        w.trajectories,
        w.not_local_minimum,
        w.bound_hits,
        if w.convex {
            format!(", convex: {} not the nearest point", w.not_nearest)
        } else {
            String::new()
        }
    )?;
    if let Some(p) = &r.proxy {
        print_proxy(out, p)?;
    }
    if let Some(s) = &r.strikes {
        print_strikes(out, s)?;
    }
    if let Some(d) = &r.deforming {
        print_deforming(out, d)?;
    }
    writeln!(out, "\n{}", if r.passed { "PASSED" } else { "FAILED" })?;
    Ok(())
}

/// The table of the proxy against the brute-force proxy.
fn print_proxy(out: &mut impl Write, p: &proxy::ProxyReport) -> std::io::Result<()> {
    writeln!(
        out,
        "\nproxy against the brute-force proxy (model scaled by {:.4} to 0.2 m{}; {:.1} s):\n",
        p.scale,
        tool_words(p.tool_radius_m),
        p.seconds
    )?;
    writeln!(
        out,
        "| path      | speeds (m/s) | ticks   | in contact | mismatches | largest gap (m) | inside | bad forces |"
    )?;
    writeln!(
        out,
        "|-----------|--------------|--------:|-----------:|-----------:|----------------:|-------:|-----------:|"
    )?;
    for row in &p.rows {
        let c = &row.check;
        writeln!(
            out,
            "| {:<9} | {:>5}–{:<6} | {:>7} | {:>10} | {:>10} | {:>15.1e} | {:>6} | {:>10} |",
            row.path,
            row.speeds_m_s.0,
            row.speeds_m_s.1,
            c.ticks,
            c.contact_ticks,
            c.mismatches,
            c.max_deviation_m,
            c.inside,
            c.bad_forces
        )?;
    }
    Ok(())
}

/// The table of the proxy against the brute-force proxy on the deforming model.
fn print_deforming(out: &mut impl Write, d: &deform::DeformReport) -> std::io::Result<()> {
    writeln!(
        out,
        "\ndeforming: the proxy against the brute-force proxy while the model deforms at every tick (model scaled by {:.4} to 0.2 m{}; pressing paths at 1 kHz; {:.1} s):\n",
        d.scale,
        tool_words(d.tool_radius_m),
        d.seconds
    )?;
    writeln!(
        out,
        "| deformation  | ticks   | in contact | mismatches | largest gap (m) | inside | bad forces |"
    )?;
    writeln!(
        out,
        "|--------------|--------:|-----------:|-----------:|----------------:|-------:|-----------:|"
    )?;
    for row in &d.rows {
        let c = &row.check;
        writeln!(
            out,
            "| {:<12} | {:>7} | {:>10} | {:>10} | {:>15.1e} | {:>6} | {:>10} |",
            row.deformation,
            c.ticks,
            c.contact_ticks,
            c.mismatches,
            c.max_deviation_m,
            c.inside,
            c.bad_forces
        )?;
    }
    Ok(())
}

/// The deep strikes: what they check, and the table by kind and speed.
fn print_strikes(out: &mut impl Write, s: &proxy::StrikeReport) -> std::io::Result<()> {
    let c = &s.check;
    writeln!(
        out,
        "\ndeep strikes (model scaled by {:.4} to 0.2 m{}, saturation depth {:.1} mm; {:.1} s, {:.2} µs per proxy tick):\n",
        s.scale,
        tool_words(s.tool_radius_m),
        s.saturation_depth_m * 1e3,
        s.seconds,
        s.us_per_tick
    )?;
    writeln!(
        out,
        "{} strikes ({} drawn not run), {} ticks, {} held. Deep ticks, from the one where the hand first lies deeper than the saturation depth inside the model (by its path and brute force) until it stops, must stay in contact and never push the hand on along the strike (above 1e-6 N) nor face the far side. Shallow ticks, from the entry until then, are the physical range: past a crest the surface pushes the hand on along its normal, as a rigid one does.\n",
        c.strikes, c.skipped, c.ticks, c.held_ticks
    )?;
    writeln!(
        out,
        "deep strikes: {} of {} (at least {} required); deep ticks out of contact: {}\n",
        c.deep.strikes, c.strikes, c.min_deep_strikes, c.deep.no_contact
    )?;
    writeln!(
        out,
        "| ticks | speed m/s | strikes | ticks checked | pushing on | far side | largest push N |\n|---|---|---:|---:|---:|---:|---:|"
    )?;
    for (kind, all, by_speed) in [
        ("deep", &c.deep, &c.deep_by_speed),
        ("shallow", &c.shallow, &c.shallow_by_speed),
    ] {
        let classes = STRIKE_SPEED_CLASSES
            .windows(2)
            .map(|w| format!("{}–{}", w[0], w[1]));
        for (speeds, t) in classes
            .chain(std::iter::once("all".to_string()))
            .zip(by_speed.iter().chain(std::iter::once(all)))
        {
            writeln!(
                out,
                "| {kind} | {speeds} | {} | {} | {} | {} | {:.3} |",
                t.strikes, t.ticks, t.pushes_on, t.far_side, t.max_push_n
            )?;
        }
    }
    Ok(())
}

/// Every segment kind's crossings against brute force (and parry, when built in).
fn check_segments(
    args: &Args,
    surface: &Surface,
    map: &VoxelMap,
    parry: Option<&Parry>,
) -> Vec<CrossingRow> {
    SegmentKind::ALL
        .iter()
        .enumerate()
        .map(|(k, &kind)| {
            let seed = args.seed.wrapping_mul(1000).wrapping_add(k as u64);
            let n = if kind.is_adversarial() {
                args.adversarial.unwrap_or(args.samples)
            } else {
                args.random.unwrap_or(args.samples)
            };
            let clock = Instant::now();
            let peer =
                |p0: haphe::DVec3, p1: haphe::DVec3| parry.is_some_and(|mesh| mesh.crosses(p0, p1));
            let (check, parry_counts) = check_crossings_with_peer(
                surface,
                map,
                kind,
                n,
                seed,
                parry.is_some().then_some(&peer as _),
            );
            CrossingRow {
                check,
                parry_misses: parry_counts.map(|p| p.misses),
                parry_leaks: parry_counts.map(|p| p.leaks),
                seconds: clock.elapsed().as_secs_f64(),
            }
        })
        .collect()
}

/// Inside/outside of random points against winding numbers (and parry, when built in).
fn check_points(
    args: &Args,
    surface: &Surface,
    map: &VoxelMap,
    parry: Option<&Parry>,
) -> InsideRow {
    let n_points = args.points.unwrap_or(args.samples);
    let clock = Instant::now();
    let peer = |p: haphe::DVec3| parry.is_some_and(|mesh| mesh.contains(p));
    let (inside_check, parry_disagreements) = check_inside_with_peer(
        surface,
        map,
        n_points,
        args.seed,
        parry.is_some().then_some(&peer as _),
    );
    InsideRow {
        check: inside_check,
        parry_disagreements,
        seconds: clock.elapsed().as_secs_f64(),
    }
}

/// The proxy's options of the checks: a tool of `--tool-radius`.
fn tool_options(radius: f64) -> anyhow::Result<haphe::proxy::ProxyOptions> {
    haphe::proxy::ProxyOptions::default()
        .with_tool_radius(radius)
        .map_err(|e| anyhow::anyhow!("{}", e.named("--tool-radius")))
}

/// How a table's heading names the tool: nothing for a point, else its radius.
fn tool_words(radius: f64) -> String {
    if radius > 0.0 {
        format!(", a tool of radius {:.2} mm", radius * 1e3)
    } else {
        String::new()
    }
}
