//! `haphe build`: build the surface and voxel map of a mesh and save them as one file.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use anyhow::{Context, anyhow};
use haphe::map::{Provenance, VoxelMap, encode};
use haphe::mesh::{ReadOptions, Surface, SurfaceOptions};
use indicatif::{ProgressBar, ProgressStyle};

use crate::args::{map_options, parse_units, weld_mode};
use crate::input::files::{self, read_input};
use crate::input::mesh::load_bytes;

/// Arguments of `haphe build`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The mesh file (OBJ, STL, PLY, OFF).
    file: PathBuf,
    /// Where to write the map file.
    #[arg(short, long)]
    output: PathBuf,
    /// Length unit of the file: m, mm, cm, in, or a factor in metres per file unit.
    #[arg(long, default_value = "m", value_parser = parse_units)]
    units: haphe::mesh::Units,
    /// Merge vertices closer than this (metres, after scaling); exact welding by default.
    #[arg(long, value_name = "METRES")]
    weld_tolerance: Option<f64>,
    /// Cell size in metres (chosen from the mesh when absent).
    #[arg(long, value_name = "METRES")]
    cell_size: Option<f64>,
    /// Memory budget for the map, MiB.
    #[arg(long, value_name = "MIB")]
    budget: Option<usize>,
}

/// Runs the command.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    let mut out = std::io::stdout().lock();
    let read = ReadOptions {
        units: args.units,
        weld: weld_mode(args.weld_tolerance)?,
        format: None,
    };
    crate::output::check_outputs(&[&args.output], &[&args.file])?;
    let source = read_input(&args.file, files::MESH)?;
    let provenance = Provenance::of(&args.file.display().to_string(), &source);
    let loaded = load_bytes(&args.file, &source, &read).map_err(|e| anyhow!("{e}"))?;
    drop(source);
    let triangles = loaded.mesh.triangles.len();
    let start = Instant::now();
    let surface = Surface::new(loaded.mesh, &SurfaceOptions::default())
        .with_context(|| format!("{}", args.file.display()))?;
    let t_surface = start.elapsed();

    let bar = if triangles >= 200_000 {
        let bar = ProgressBar::new(1000);
        bar.set_style(
            ProgressStyle::with_template("building map {bar:40} {percent:>3}% {elapsed}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        Some(bar)
    } else {
        None
    };
    let start = Instant::now();
    let options = map_options(args.cell_size, args.budget);
    let progress = |fraction: f64| {
        if let Some(bar) = &bar {
            bar.set_position((fraction.clamp(0.0, 1.0) * 1000.0) as u64);
        }
    };
    let map = VoxelMap::build_with_progress(&surface, &options, &progress)
        .with_context(|| format!("{}", args.file.display()))?
        .with_provenance(provenance);
    let t_map = start.elapsed();
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }

    let start = Instant::now();
    let bytes = encode(&surface, &map);
    crate::output::write_output(&args.output, |out| Ok(out.write_all(&bytes)?))?;
    let t_write = start.elapsed();

    let stats = map.stats();
    writeln!(out, "{} -> {}", args.file.display(), args.output.display())?;
    if let Some(p) = map.provenance() {
        writeln!(out, "  source: {p}")?;
    }
    writeln!(
        out,
        "  surface: {} triangles, {} vertices, {} ({:.1} ms)",
        surface.triangle_count(),
        surface.vertex_count(),
        if surface.is_solid() {
            "a closed solid"
        } else {
            "an open surface (two-sided, no inside)"
        },
        t_surface.as_secs_f64() * 1e3
    )?;
    writeln!(
        out,
        "  map: {} x {} x {} cells of {:.3e} m, {} surface cells, {} inside, {:.2} triangles per surface cell (max {}) ({:.1} ms)",
        stats.dims[0],
        stats.dims[1],
        stats.dims[2],
        stats.cell_size_m,
        stats.surface_cells,
        stats.inside_cells,
        stats.mean_triangles_per_surface_cell,
        stats.max_triangles_per_surface_cell,
        t_map.as_secs_f64() * 1e3
    )?;
    writeln!(
        out,
        "  bytes: map {} ({:.1} per triangle), surface {} ({:.1} per triangle), file {} (written in {:.1} ms)",
        stats.bytes,
        stats.bytes as f64 / triangles as f64,
        surface.heap_bytes(),
        surface.heap_bytes() as f64 / triangles as f64,
        bytes.len(),
        t_write.as_secs_f64() * 1e3
    )?;
    Ok(ExitCode::SUCCESS)
}
