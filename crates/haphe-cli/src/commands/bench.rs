//! `haphe bench`: haphe's queries side by side with `parry3d-f64` (and brute force on
//! small meshes), in one process, on the same query streams.
//!
//! # What runs
//!
//! For each mesh — procedural shapes at several triangle counts ([`Catalog::with_triangles`],
//! by default a noisy blob and a 0.1 mm thin plate, about 0.2 m across) and any files
//! given — the structures of both libraries are built and weighed
//! ([`structures`]), the query streams generated with fixed seeds ([`streams`]), and
//! every query kind ([`methods::Query`]) timed with every method, interleaved
//! ([`methods`]). Each mesh's structures are dropped before the next mesh is made, so the
//! peak memory is that of the largest mesh alone.
//!
//! # How a query is timed
//!
//! One query at a time: the clock is read before and after each query, the input and the
//! answer pass through `black_box`, and the cost of reading the clock — measured the same
//! way around an empty query, interleaved with the real ones — is subtracted
//! ([`timing`]). Percentiles (p50, p99, p99.9, max) are taken over the individual queries,
//! so the tail shows what a servo tick would meet: cache misses, a long walk, an
//! interrupt. Methods alternate chunk by chunk (one trajectory of 250 positions), the
//! order rotating every round, so that a slow spell of the shared machine falls on every
//! method alike. Queries run on the calling thread; pin it (`taskset -c 1 haphe bench`)
//! for steadier figures.
//!
//! # Memory
//!
//! A counting global allocator ([`alloc`]) gives the heap bytes each library's structures
//! hold once built, and the number of allocations made while each method's queries ran.

mod alloc;
mod json;
mod methods;
mod objects;
mod plot;
mod streams;
mod structures;
mod table;
mod texture;
mod timing;
mod tool;

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context as _, anyhow, bail};
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Mesh, ReadOptions, Units, Weld};
use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject};
use haphe::verify::WindingOracle;

use crate::args::parse_units;
use crate::input::mesh::load;
use crate::output::check_outputs;
use methods::{Context, MeshResult, Query};
use streams::Streams;

/// Triangle counts of the procedural meshes by default.
const DEFAULT_SIZES: [usize; 5] = [1_000, 10_000, 100_000, 1_000_000, 4_000_000];
/// Triangle counts of the procedural meshes with `--quick`.
const QUICK_SIZES: [usize; 3] = [1_000, 10_000, 100_000];
/// Queries per kind and mesh by default, and with `--quick`.
const DEFAULT_SAMPLES: usize = 50_000;
const QUICK_SAMPLES: usize = 5_000;
/// Brute force runs on meshes of at most this many triangles.
const BRUTE_FORCE_MAX_TRIANGLES: usize = 20_000;
/// Triangles brute force may test per query of the other methods: its sample count is
/// this times the samples, divided by the triangle count (at least one).
const BRUTE_FORCE_TESTS_PER_SAMPLE: usize = 500;

/// Arguments of `haphe bench`.
#[derive(clap::Args, Debug)]
#[command(after_long_help = json::FIELDS)]
pub struct Args {
    /// Small sizes only (1k, 10k, 100k triangles) and 5 000 queries per kind.
    #[arg(long)]
    quick: bool,
    /// A mesh file to measure as well (OBJ, STL, PLY, OFF); repeat for several. Without
    /// --sizes, only the files are measured.
    #[arg(long = "mesh", value_name = "FILE")]
    meshes: Vec<PathBuf>,
    /// Triangle counts of the procedural meshes, comma-separated [default:
    /// 1000,10000,100000,1000000,4000000; with --quick: 1000,10000,100000].
    #[arg(long, value_delimiter = ',', value_name = "N,N,...")]
    sizes: Option<Vec<usize>>,
    /// Procedural shape families, comma-separated (sphere, torus, box, thin-plate,
    /// concave-corner, blob).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "blob,thin-plate",
        value_name = "SHAPE,..."
    )]
    shapes: Vec<Catalog>,
    /// Queries per query kind and mesh [default: 50000; with --quick: 5000].
    #[arg(long, value_name = "N")]
    samples: Option<usize>,
    /// Write one JSON record per (mesh, query, method) to this file (fields below).
    #[arg(long, value_name = "OUT")]
    json: Option<PathBuf>,
    /// Write one PNG per query kind into this folder: cost against triangle count, log-log.
    #[arg(long, value_name = "DIR")]
    plot: Option<PathBuf>,
    /// Seed of the query streams (the same seed gives the same queries).
    #[arg(long, default_value_t = 1, value_name = "S")]
    seed: u64,
    /// Object counts of the object-count series, comma-separated [default:
    /// 1,10,100,1000,10000,100000; with --quick: up to 10000; none when only --mesh files
    /// are given].
    #[arg(long, value_delimiter = ',', value_name = "N,N,...")]
    objects: Option<Vec<usize>>,
    /// Timed ticks per configuration of the object-count series [default: 20000; with
    /// --quick: 5000].
    #[arg(long, value_name = "N")]
    object_ticks: Option<usize>,
    /// Run the object-count series alone (no mesh is measured).
    #[arg(long)]
    objects_only: bool,
    /// Length unit of the --mesh files: m, mm, cm, in, or a factor in metres per file unit.
    #[arg(long, default_value = "m", value_parser = parse_units)]
    units: Units,
}

/// A mesh to measure.
enum Source {
    /// A procedural shape with about this many triangles.
    Catalog(Catalog, usize),
    /// A mesh file.
    File(PathBuf),
}

/// Runs the command.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    let sizes = match (&args.sizes, args.meshes.is_empty(), args.quick) {
        (Some(sizes), _, _) => sizes.clone(),
        (None, false, _) => Vec::new(),
        (None, true, true) => QUICK_SIZES.to_vec(),
        (None, true, false) => DEFAULT_SIZES.to_vec(),
    };
    if sizes.contains(&0) {
        bail!("--sizes: a triangle count must be at least 1");
    }
    let samples = args.samples.unwrap_or(if args.quick {
        QUICK_SAMPLES
    } else {
        DEFAULT_SAMPLES
    });
    if samples == 0 {
        bail!("--samples must be at least 1");
    }
    for &n in &sizes {
        Catalog::check_triangles(n).map_err(|e| anyhow!("--sizes: {e}"))?;
    }
    let counts = match (
        &args.objects,
        args.meshes.is_empty() || args.objects_only,
        args.quick,
    ) {
        (Some(counts), _, _) => counts.clone(),
        (None, false, _) => Vec::new(),
        (None, true, true) => objects::QUICK_COUNTS.to_vec(),
        (None, true, false) => objects::DEFAULT_COUNTS.to_vec(),
    };
    if counts.iter().any(|&n| n == 0 || n > 1_000_000) {
        bail!("--objects: an object count must be from 1 to 1000000");
    }
    let object_ticks = args
        .object_ticks
        .unwrap_or(if args.quick { 5_000 } else { 20_000 });
    if object_ticks == 0 {
        bail!("--object-ticks must be at least 1");
    }
    if args.objects_only {
        eprintln!("haphe bench: object-count series ...");
        let rows = objects::series(&counts, object_ticks)?;
        objects::write(&mut std::io::stdout().lock(), &rows, object_ticks)?;
        return Ok(ExitCode::SUCCESS);
    }
    let sources: Vec<Source> = args
        .shapes
        .iter()
        .flat_map(|&shape| sizes.iter().map(move |&n| Source::Catalog(shape, n)))
        .chain(args.meshes.iter().cloned().map(Source::File))
        .collect();
    if sources.is_empty() {
        bail!("nothing to measure: give --sizes, --shapes or --mesh");
    }

    // The outputs are checked before the run, not after it.
    let inputs: Vec<&Path> = args.meshes.iter().map(PathBuf::as_path).collect();
    if let Some(path) = &args.json {
        check_outputs(&[path], &inputs)?;
    }
    if let Some(dir) = &args.plot {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("cannot create the plot folder {}", dir.display()))?;
        check_outputs(
            &[&dir.join(format!("{}.png", Query::ALL[0].name()))],
            &inputs,
        )?;
    }

    // Start the build thread pool before anything is weighed.
    let threads = rayon::current_num_threads();
    let started = Instant::now();
    let mut results = Vec::new();
    for source in &sources {
        let (name, family, mesh) = match source {
            Source::Catalog(shape, n) => (
                format!("{shape}-{}", short_count(*n)),
                shape.to_string(),
                shape.with_triangles(*n),
            ),
            Source::File(path) => {
                let read = ReadOptions {
                    units: args.units,
                    weld: Weld::Exact,
                    format: None,
                };
                let mesh = load(path, &read).map_err(|e| anyhow!("{e}"))?.mesh;
                let name = path.file_name().map_or_else(
                    || path.display().to_string(),
                    |n| n.to_string_lossy().into(),
                );
                (name.clone(), name, mesh)
            }
        };
        eprintln!(
            "haphe bench: {name} ({} triangles) ...",
            mesh.triangles.len()
        );
        results.push(measure_mesh(name, family, mesh, samples, args.seed)?);
    }
    let object_rows = if counts.is_empty() {
        Vec::new()
    } else {
        eprintln!("haphe bench: object-count series ...");
        objects::series(&counts, object_ticks)?
    };
    let wall = started.elapsed();

    let clocks = results.iter().flat_map(|r| &r.measured).map(|m| m.clock);
    let clock_ns = clocks.fold((f64::INFINITY, 0.0f64, 0.0f64), |(lo, hi, p99), c| {
        (lo.min(c.p50), hi.max(c.p50), p99.max(c.p99))
    });
    let records = json::records(&results);
    let header = table::Header {
        machine: machine(),
        threads,
        seed: args.seed,
        samples,
        brute_force_max_triangles: BRUTE_FORCE_MAX_TRIANGLES,
        wall,
        clock_ns,
    };
    table::write(&mut std::io::stdout().lock(), &records, &header)?;
    if !object_rows.is_empty() {
        objects::write(&mut std::io::stdout().lock(), &object_rows, object_ticks)?;
    }
    if let Some(path) = &args.json {
        json::write(path, &records)?;
    }
    if let Some(dir) = &args.plot {
        for path in plot::write(dir, &records)? {
            eprintln!("haphe bench: wrote {}", path.display());
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Builds, weighs and times everything on one mesh; its structures are dropped on return.
fn measure_mesh(
    name: String,
    family: String,
    mesh: Mesh,
    samples: usize,
    seed: u64,
) -> anyhow::Result<MeshResult> {
    let triangles = mesh.triangles.len();
    let built = structures::build(mesh).map_err(|e| anyhow!("{name}: {e:#}"))?;
    if let Err(e) = &built.parry {
        eprintln!("haphe bench: {name}: parry refuses the mesh ({e}); no parry figures");
    }
    let (shape, parry, mut cost) = (
        Arc::new(haphe::scene::Shape::new(built.surface, built.map)),
        built.parry,
        built.cost,
    );
    // As a servo application does when it loads a shape: no timed tick computes a zone.
    let start = Instant::now();
    shape.prepare_clear_zones();
    cost.zones.push(start.elapsed());
    let (surface, map) = (shape.surface(), shape.map());
    let mut scene = Scene::local(1);
    scene
        .insert(SceneObject::new(
            ObjectId(0),
            shape.clone(),
            Pose::IDENTITY,
            Material::default(),
        ))
        .map_err(|(e, _)| anyhow!("{name}: {e}"))?;
    let mut streams = Streams::new(surface, map, samples, seed);
    streams.add_contact(&scene, seed);
    let small = triangles <= BRUTE_FORCE_MAX_TRIANGLES;
    let oracle = small.then(|| WindingOracle::new(surface));
    let cx = Context {
        surface,
        map,
        parry: parry.as_ref().ok(),
        oracle: oracle.as_ref(),
        brute_samples: if small {
            (BRUTE_FORCE_TESTS_PER_SAMPLE * samples / triangles.max(1)).max(1)
        } else {
            0
        },
        streams: &streams,
        scene: &scene,
    };
    let measured = Query::TIMED
        .iter()
        .map(|&query| methods::measure(query, cx))
        .collect();
    Ok(MeshResult {
        name,
        family,
        triangles,
        cost,
        measured,
    })
}

/// `1000` as `1k`, `4000000` as `4M`; other numbers as they are.
fn short_count(n: usize) -> String {
    match n {
        n if n >= 1_000_000 && n % 1_000_000 == 0 => format!("{}M", n / 1_000_000),
        n if n >= 1_000 && n % 1_000 == 0 => format!("{}k", n / 1_000),
        n => n.to_string(),
    }
}

/// The machine a run measured, as far as the system tells: processor model, logical CPUs
/// this process may use, memory (Linux `/proc`; "unknown" elsewhere).
pub fn machine() -> String {
    let cpuinfo = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let model = cpuinfo
        .lines()
        .find_map(|l| l.strip_prefix("model name"))
        .and_then(|l| l.split_once(':'))
        .map_or("unknown processor", |(_, m)| m.trim());
    let cpus = std::thread::available_parallelism().map_or(0, usize::from);
    let meminfo = std::fs::read_to_string("/proc/meminfo").unwrap_or_default();
    let memory = meminfo
        .lines()
        .find_map(|l| l.strip_prefix("MemTotal:"))
        .and_then(|l| l.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or_else(
            || "unknown memory".to_owned(),
            |kib| format!("{:.0} GiB", kib / (1024.0 * 1024.0)),
        );
    format!(
        "{model}, {cpus} logical CPU(s) available to this process, {memory}, {} {}",
        std::env::consts::OS,
        std::env::consts::ARCH
    )
}
