//! `haphe demo`: the README's main command. Until the simulated haptic session exists it
//! runs the mesh stage and the collision core on the built-in procedural models and prints
//! what a user of the library gets from them.

use std::io::Write;
use std::process::ExitCode;
use std::time::Instant;

use haphe::map::{MapOptions, VoxelMap};
use haphe::mesh::shapes::Shape;
use haphe::mesh::{MeshReport, Surface, SurfaceOptions, Usability, Weld, weld};
use haphe::verify::{CrossingCheck, SegmentKind, check_crossings};

/// Arguments of `haphe demo`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Triangles per built-in model.
    #[arg(long, default_value_t = 20_000)]
    triangles: usize,
}

/// Probe segments per kind in the demo's check.
const PROBES_PER_KIND: usize = 200;

/// Runs the demo; fails (exit 2) if a built-in model is not a valid solid or a probe
/// segment disagrees with brute force.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    let mut out = std::io::stdout().lock();
    writeln!(
        out,
        "haphe demo: the mesh stage and the collision core on the built-in models (about 0.2 m across, ~{} triangles each)\n",
        args.triangles
    )?;
    writeln!(
        out,
        "| model          | triangles | verdict | genus | volume (m³) | weld+validate | topology | map      | bytes/triangle | probe segments | wrong | leaks |"
    )?;
    writeln!(
        out,
        "|----------------|----------:|---------|------:|------------:|--------------:|---------:|---------:|---------------:|---------------:|------:|------:|"
    )?;
    let mut all_solid = true;
    let mut all_right = true;
    for shape in Shape::ALL {
        let generated = shape.with_triangles(args.triangles);

        // The same path a file takes: weld (a no-op here: shared vertices already), validate.
        let start = Instant::now();
        let (mesh, _) = weld(&generated, Weld::Exact);
        let report = MeshReport::of(&mesh);
        let t_validate = start.elapsed();

        let start = Instant::now();
        let surface = Surface::new(mesh, &SurfaceOptions::default())?;
        let t_topology = start.elapsed();

        let start = Instant::now();
        let map = VoxelMap::build(&surface, &MapOptions::default())?;
        let t_map = start.elapsed();

        // Probe segments through vertices and edges, against every-triangle testing.
        let probes: Vec<CrossingCheck> = [
            SegmentKind::Random,
            SegmentKind::ThroughVertex,
            SegmentKind::ThroughEdge,
        ]
        .into_iter()
        .map(|kind| check_crossings(&surface, &map, kind, PROBES_PER_KIND, 1))
        .collect();
        let wrong: usize = probes.iter().map(|c| c.mismatches).sum();
        let leaks: usize = probes.iter().map(|c| c.leaks).sum();

        all_solid &= report.usable_as == Usability::Solid;
        all_right &= wrong == 0 && leaks == 0;
        let bytes = surface.heap_bytes() + map.heap_bytes();
        writeln!(
            out,
            "| {:<14} | {:>9} | {:<7} | {:>5} | {:>11.4e} | {:>10.1} ms | {:>5.1} ms | {:>5.1} ms | {:>14.0} | {:>14} | {:>5} | {:>5} |",
            shape.name(),
            report.triangles,
            format!("{:?}", report.usable_as).to_lowercase(),
            report.genus.map_or("-".to_owned(), |g| g.to_string()),
            report.volume.unwrap_or(f64::NAN),
            t_validate.as_secs_f64() * 1e3,
            t_topology.as_secs_f64() * 1e3,
            t_map.as_secs_f64() * 1e3,
            bytes as f64 / surface.triangle_count() as f64,
            3 * PROBES_PER_KIND,
            wrong,
            leaks,
        )?;
    }
    writeln!(
        out,
        "\nEvery model is a closed, oriented, manifold solid: {}",
        if all_solid { "yes" } else { "NO" }
    )?;
    writeln!(
        out,
        "Probe segments (random, through vertices, through edges): first crossings equal to testing every triangle, and no segment from outside to inside missed: {}",
        if all_right { "yes" } else { "NO" }
    )?;
    writeln!(
        out,
        "Next: `haphe validate FILE` on your own meshes (see `haphe validate --help`)."
    )?;
    Ok(if all_solid && all_right {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(2)
    })
}
