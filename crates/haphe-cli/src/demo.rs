//! `haphe demo`: the README's main command. Until the simulated haptic session exists it
//! runs the mesh stage on the built-in procedural models and prints what a user of the
//! library gets from it.

use std::io::Write;
use std::process::ExitCode;
use std::time::Instant;

use haphe::mesh::shapes::Shape;
use haphe::mesh::{MeshReport, Surface, SurfaceOptions, Usability, Weld, weld};

/// Arguments of `haphe demo`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Triangles per built-in model.
    #[arg(long, default_value_t = 20_000)]
    triangles: usize,
}

/// Runs the demo; fails (exit 2) if a built-in model is not a valid solid.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    let mut out = std::io::stdout().lock();
    writeln!(
        out,
        "haphe demo: the mesh stage on the built-in models (about 0.2 m across, ~{} triangles each)\n",
        args.triangles
    )?;
    writeln!(
        out,
        "| model          | triangles | vertices | verdict | genus | area (m²)  | volume (m³) | generate | weld+validate | topology | topology bytes/triangle |"
    )?;
    writeln!(
        out,
        "|----------------|----------:|---------:|---------|------:|-----------:|------------:|---------:|--------------:|---------:|------------------------:|"
    )?;
    let mut all_solid = true;
    for shape in Shape::ALL {
        let start = Instant::now();
        let generated = shape.with_triangles(args.triangles);
        let t_generate = start.elapsed();

        // The same path a file takes: weld (a no-op here: shared vertices already), validate.
        let start = Instant::now();
        let (mesh, _) = weld(&generated, Weld::Exact);
        let report = MeshReport::of(&mesh);
        let t_validate = start.elapsed();

        let start = Instant::now();
        let surface = Surface::new(mesh, &SurfaceOptions::default())?;
        let t_topology = start.elapsed();

        all_solid &= report.usable_as == Usability::Solid;
        writeln!(
            out,
            "| {:<14} | {:>9} | {:>8} | {:<7} | {:>5} | {:>10.4e} | {:>11.4e} | {:>5.1} ms | {:>10.1} ms | {:>5.1} ms | {:>23.0} |",
            shape.name(),
            report.triangles,
            report.vertices,
            format!("{:?}", report.usable_as).to_lowercase(),
            report.genus.map_or("-".to_owned(), |g| g.to_string()),
            report.area,
            report.volume.unwrap_or(f64::NAN),
            t_generate.as_secs_f64() * 1e3,
            t_validate.as_secs_f64() * 1e3,
            t_topology.as_secs_f64() * 1e3,
            surface.heap_bytes() as f64 / surface.triangle_count() as f64,
        )?;
    }
    writeln!(
        out,
        "\nEvery model is a closed, oriented, manifold solid: {}",
        if all_solid { "yes" } else { "NO" }
    )?;
    writeln!(
        out,
        "Next: `haphe validate FILE` on your own meshes (see `haphe validate --help`)."
    )?;
    Ok(if all_solid {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(2)
    })
}
