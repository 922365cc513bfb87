//! `haphe generate`: write a procedural test mesh as a binary STL file.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use haphe::mesh::shapes::Catalog;

/// Arguments of `haphe generate`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The shape: sphere, torus, box, thin-plate, concave-corner or blob (about 0.2 m across).
    shape: Catalog,
    /// Target triangle count (the closest the shape's resolution allows).
    #[arg(long, default_value_t = 10_000)]
    triangles: usize,
    /// Output file (binary STL, metres).
    #[arg(short, long)]
    output: PathBuf,
    /// Write the faces in a random order fixed by this seed, as a file from a tool that
    /// scattered them (the same triangles; for measuring what face order costs).
    #[arg(long, value_name = "SEED")]
    shuffle_faces: Option<u64>,
}

/// Runs the command.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    let mut out = std::io::stdout().lock();
    Catalog::check_triangles(args.triangles).map_err(|e| anyhow::anyhow!("--triangles: {e}"))?;
    crate::output::check_outputs(&[&args.output], &[])?;
    let start = Instant::now();
    let mut mesh = args.shape.with_triangles(args.triangles);
    if let Some(seed) = args.shuffle_faces {
        haphe::mesh::shapes::shuffle_faces(&mut mesh, seed);
    }
    let generated = start.elapsed();
    let triangles = mesh.triangles.iter().map(|t| {
        let [a, b, c] = t.map(|v| mesh.vertices[v as usize]);
        let n = (b - a).cross(c - a).normalize_or_zero();
        let f32x3 = |p: haphe::DVec3| stl_io::Vector::new(p.as_vec3().to_array());
        stl_io::Triangle {
            normal: f32x3(n),
            vertices: [f32x3(a), f32x3(b), f32x3(c)],
        }
    });
    crate::output::write_output(&args.output, |out| {
        Ok(stl_io::write_stl(&mut &mut *out, triangles)?)
    })?;
    writeln!(
        out,
        "{}: {}{} ({} triangles, {} vertices), generated in {:.1} ms",
        args.output.display(),
        args.shape,
        if args.shuffle_faces.is_some() {
            ", faces shuffled"
        } else {
            ""
        },
        mesh.triangles.len(),
        mesh.vertices.len(),
        generated.as_secs_f64() * 1e3
    )?;
    Ok(ExitCode::SUCCESS)
}
