//! `haphe repair`: a mesh repaired into a closed solid (the library's
//! [`haphe::mesh::repair`]), each change reported, written to a new file.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{anyhow, bail};
use haphe::mesh::{DEFAULT_MAX_HOLE_EDGES, Mesh, RepairError, RepairOptions, Units, Weld, repair};

use crate::args::parse_units;
use crate::input::mesh::load;

/// Arguments of `haphe repair`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The mesh file to repair (OBJ, STL, PLY, OFF, glTF); never written to.
    input: PathBuf,
    /// Where to write the repaired mesh: `.obj` (text, full precision) or `.stl` (binary,
    /// single precision), in the input's units. Refused when it is the input.
    output: PathBuf,
    /// Length unit of the input (and the output): m, mm, cm, in, or metres per file unit.
    #[arg(long, default_value = "m", value_parser = parse_units)]
    units: Units,
    /// Weld vertices closer than this (metres, after scaling); by default a millionth of
    /// the bounding box's diagonal.
    #[arg(long, value_name = "METRES")]
    weld_tolerance: Option<f64>,
    /// Fill holes of at most this many edges; a larger hole is refused.
    #[arg(long, value_name = "EDGES", default_value_t = DEFAULT_MAX_HOLE_EDGES)]
    max_hole_edges: usize,
}

/// The formats `repair` writes.
#[derive(Clone, Copy)]
enum Written {
    Obj,
    Stl,
}

/// Runs the command: 0 when the repaired mesh is written.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    let format = match args
        .output
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .as_deref()
    {
        Some("obj") => Written::Obj,
        Some("stl") => Written::Stl,
        _ => bail!(
            "{}: repair writes .obj or .stl files (name the output with one of them)",
            args.output.display()
        ),
    };
    crate::output::check_outputs(&[&args.output], &[&args.input])?;
    let read = haphe::mesh::ReadOptions {
        units: args.units,
        weld: Weld::Exact,
        format: None,
    };
    let loaded = load(&args.input, &read).map_err(|e| anyhow!("{e}"))?;
    let input = args.input.display();
    let mut out = std::io::stdout().lock();
    writeln!(
        out,
        "{input}: {} triangles, {} vertices ({:?}, vertices welded exactly on reading: {} merged)",
        loaded.mesh.triangles.len(),
        loaded.mesh.vertices.len(),
        loaded.format,
        loaded.weld.merged
    )?;
    let options = RepairOptions {
        weld_tolerance: args.weld_tolerance,
        max_hole_edges: args.max_hole_edges,
    };
    let repaired = repair(&loaded.mesh, &options).map_err(|e| match e {
        RepairError::HoleTooLarge { .. } => anyhow!(
            "{input}: {e} (--max-hole-edges {}; raise it to fill this hole); nothing written",
            args.max_hole_edges
        ),
        RepairError::WeldTolerance(_) => anyhow!("--weld-tolerance: {e}"),
        RepairError::NotSolid { .. } => anyhow!("{input}: {e}; nothing written"),
    })?;
    for change in &repaired.changes {
        writeln!(out, "  {change}")?;
    }
    let scale = 1.0 / args.units.metres_per_unit();
    crate::output::write_output(&args.output, |w| {
        write_mesh(w, &repaired.mesh, scale, format)
    })?;
    let report = &repaired.report;
    writeln!(
        out,
        "{}: {} triangles, {} vertices: a valid closed solid, volume {:.6e} m³",
        args.output.display(),
        report.triangles,
        report.vertices,
        report.volume.unwrap_or(0.0)
    )?;
    Ok(ExitCode::SUCCESS)
}

/// Writes `mesh` (metres) times `scale` as `format`.
fn write_mesh(w: &mut dyn Write, mesh: &Mesh, scale: f64, format: Written) -> anyhow::Result<()> {
    match format {
        Written::Obj => {
            writeln!(w, "# repaired by haphe repair")?;
            for v in &mesh.vertices {
                let p = *v * scale;
                // Rust's shortest round-trip form: the coordinates read back exactly.
                writeln!(w, "v {:?} {:?} {:?}", p.x, p.y, p.z)?;
            }
            for t in &mesh.triangles {
                writeln!(w, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1)?;
            }
        }
        Written::Stl => {
            let triangles = mesh.triangles.iter().map(|t| {
                let [a, b, c] = t.map(|v| mesh.vertices[v as usize] * scale);
                let n = (b - a).cross(c - a).normalize_or_zero();
                let f32x3 = |p: haphe::DVec3| stl_io::Vector::new(p.as_vec3().to_array());
                stl_io::Triangle {
                    normal: f32x3(n),
                    vertices: [f32x3(a), f32x3(b), f32x3(c)],
                }
            });
            stl_io::write_stl(&mut &mut *w, triangles)?;
        }
    }
    Ok(())
}
