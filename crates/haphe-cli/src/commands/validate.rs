//! `haphe validate`: the mesh stage's report for each mesh file, and what a volume file
//! (`.nii`, `.nii.gz`) holds (`volume`).

mod volume;

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use haphe::mesh::{GltfSummary, ReadOptions, Units};
use haphe::query::{SELF_INTERSECTION_BUDGET_PER_TRIANGLE, Validation, self_intersection_budget};

use crate::args::{parse_units, weld_mode};
use crate::input::mesh::{UnitsGiven, load_reported, warn_units};
use crate::input::volume::is_volume_path;

/// Shown after `haphe validate --help`.
pub const EXIT_CODES: &str = "\
Exit codes (the worst file decides):
  0  every file is a valid closed solid (closed, manifold, consistently oriented, not inside out)
  1  some file is usable only as an open, two-sided surface, or is closed but passes
     through itself (no inside where it does)
  2  some file is unusable (no triangle with area; a volume without a value at least iso)
     or unreadable

JSON (--json) prints one object per file and line: file, format, seconds, weld, then the report:
  triangles, vertices, edges, components, closed (every edge shared by exactly two
  triangles), boundary_edges (edges used by one), nonmanifold_edges (used by three or more),
  nonmanifold_vertices, orientation_conflicts, inverted_components, nested_solids,
  degenerate_triangles,
  sliver_triangles, duplicate_faces, genus, bounds_min, bounds_max (m), area (m²),
  volume (m³, null unless closed and oriented), usable_as (solid | surface | unusable),
  component_list, defects (the places: vertex, edge and triangle indices after welding),
  self_intersections (pairs of triangles that cross or touch other than in shared corners;
  null for an unusable mesh), self_intersections_crossing (of those, pairs that pass through
  each other: a closed mesh with any is not a valid solid), self_intersection_pairs (the
  first 100 pairs), self_intersections_complete (false when the search stopped at its
  budget of 256 candidate pairs per triangle: the counts are then lower bounds).
  A glTF file adds gltf: scene, nodes (node, name, mesh, triangles, closed, translation,
  rotation [x, y, z, w], scale, exact_trs) and skipped (mesh, primitive, mode).
  A volume file (.nii, .nii.gz) gives: file, format, seconds, datatype, byte_order, gzip,
  dims, voxel_size_mm, affine (4x4 rows, voxel indices to metres), affine_from,
  metres_per_unit, value_range, iso, iso_default, material_voxels, material_voxels_min,
  material_voxels_max, material_bounds_min, material_bounds_max (m), notes.
  An unreadable file gives {\"file\": ..., \"error\": ...}.";

/// Arguments of `haphe validate`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Mesh files (OBJ, STL, PLY, OFF, glTF; the format is detected from the content), or
    /// volume files (NIfTI-1: names ending in .nii or .nii.gz).
    #[arg(required = true)]
    files: Vec<PathBuf>,
    /// Print one JSON object per file instead of the text report.
    #[arg(long)]
    json: bool,
    /// Length unit of the files: m, mm, cm, in, or a factor in metres per file unit.
    #[arg(long, default_value = "m", value_parser = parse_units)]
    units: Units,
    /// Merge vertices closer than this (metres, after scaling); exact welding by default.
    #[arg(long, value_name = "METRES")]
    weld_tolerance: Option<f64>,
    /// Skip the search for self-intersections (it builds the surface's voxel map, which
    /// takes a few seconds on meshes of millions of triangles); `self_intersections` is
    /// then null.
    #[arg(long)]
    skip_self_intersections: bool,
    /// Volume files: material is where a value is at least this (the default: the midpoint
    /// of the range of the finite values, which the report states).
    #[arg(long, value_name = "V", allow_negative_numbers = true)]
    iso: Option<f32>,
}

/// One line of `--json`: the record's fields in their order, then a glTF file's `gltf`.
#[derive(serde::Serialize)]
struct Line<'a, R: serde::Serialize> {
    #[serde(flatten)]
    record: R,
    #[serde(skip_serializing_if = "Option::is_none")]
    gltf: Option<&'a GltfSummary>,
}

/// Runs the command; the exit code is the worst file's.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    let mut out = std::io::stdout().lock();
    let options = ReadOptions {
        units: args.units,
        weld: weld_mode(args.weld_tolerance)?,
        format: None,
    };
    let mut worst = 0u8;
    for path in &args.files {
        if is_volume_path(path) {
            worst = worst.max(volume::report(&mut out, path, args.iso, args.json)?);
            continue;
        }
        let start = Instant::now();
        let code = match load_reported(path, &options) {
            Err(failure) => {
                if args.json {
                    let line = serde_json::json!({
                        "file": path.display().to_string(),
                        "error": failure.to_string(),
                    });
                    writeln!(out, "{line}")?;
                } else {
                    // The message names the file and the place.
                    writeln!(out, "{failure}\n  verdict: unreadable\n")?;
                }
                2
            }
            Ok(loaded) => {
                if let Some(bounds) = loaded.mesh.bounds() {
                    let name = path.display().to_string();
                    warn_units(&name, bounds, args.units, UnitsGiven::Flag);
                }
                let triangles = loaded.mesh.triangles.len();
                let validated = Instant::now();
                let validation = Validation::of(loaded.mesh, !args.skip_self_intersections)?;
                let t_validate = validated.elapsed();
                let seconds = start.elapsed().as_secs_f64();
                if args.json {
                    let line = validation.record(
                        &path.display().to_string(),
                        loaded.format,
                        loaded.weld,
                        seconds,
                    );
                    let line = Line {
                        record: line,
                        gltf: loaded.gltf.as_ref(),
                    };
                    writeln!(out, "{}", serde_json::to_string(&line)?)?;
                } else {
                    writeln!(
                        out,
                        "{}  ({:?}, {triangles} triangles read and welded in {:.1} ms, validated in {:.1} ms; {} vertices merged, {} unreferenced dropped)",
                        path.display(),
                        loaded.format,
                        loaded.elapsed.as_secs_f64() * 1e3,
                        t_validate.as_secs_f64() * 1e3,
                        loaded.weld.merged,
                        loaded.weld.unreferenced,
                    )?;
                    print_text(&mut out, triangles, &validation)?;
                    if let Some(gltf) = &loaded.gltf {
                        print_gltf(&mut out, gltf)?;
                    }
                    writeln!(out)?;
                }
                validation.exit_code()
            }
        };
        worst = worst.max(code);
    }
    Ok(ExitCode::from(worst))
}

/// The text report of a mesh of `triangles` triangles: the report, the
/// self-intersections and the problems.
fn print_text(
    out: &mut impl Write,
    triangles: usize,
    validation: &Validation,
) -> anyhow::Result<()> {
    let (report, intersections) = (&validation.report, &validation.intersections);
    let crossing_itself = validation.crosses_itself();
    write!(out, "{}", report.text(crossing_itself))?;
    if let Some(s) = intersections
        .as_ref()
        .filter(|s| s.count > 0 || s.coincident > 0 || !s.complete)
    {
        let at_least = if s.complete { "" } else { "at least " };
        writeln!(
            out,
            "  self-intersections: {at_least}{} triangle pairs ({} crossing, {} only touching{})",
            s.count,
            s.crossing,
            s.touching,
            if s.coincident > 0 {
                format!(
                    "; {} pairs of coincident triangles, duplicate faces not counted here",
                    s.coincident
                )
            } else {
                String::new()
            }
        )?;
        if !s.complete {
            writeln!(
                out,
                "  self-intersections: the search stopped at its budget of {} candidate pairs ({} per triangle); the counts are lower bounds",
                self_intersection_budget(triangles),
                SELF_INTERSECTION_BUDGET_PER_TRIANGLE
            )?;
        }
        let shown: Vec<String> = s.pairs.iter().take(8).map(|p| format!("{p:?}")).collect();
        if s.count > 0 {
            writeln!(
                out,
                "  self-intersecting triangle pairs ({}): {}{}",
                s.count,
                shown.join(" "),
                if s.count > 8 {
                    format!(" … and {} more", s.count - 8)
                } else {
                    String::new()
                }
            )?;
        }
    }
    for problem in report.problems() {
        writeln!(out, "  problem: {problem}")?;
    }
    if crossing_itself {
        writeln!(
            out,
            "  problem: the surface passes through itself: inside and outside are not defined where it does"
        )?;
    }
    Ok(())
}

/// The nodes of a glTF file's scene: each one's mesh, triangles, closedness and world
/// transform; then the primitives skipped.
fn print_gltf(out: &mut impl Write, gltf: &GltfSummary) -> std::io::Result<()> {
    let scene = gltf.scene.map_or_else(
        || "no scene, root nodes".to_owned(),
        |s| format!("scene {s}"),
    );
    writeln!(
        out,
        "  glTF {scene}: {} node(s) with a mesh",
        gltf.nodes.len()
    )?;
    for n in &gltf.nodes {
        // The quaternion with w >= 0: the same rotation by an angle of at most 180°.
        let [x, y, z, w] = if n.rotation[3] < 0.0 {
            n.rotation.map(|c| -c)
        } else {
            n.rotation
        };
        let angle = 2.0 * w.clamp(-1.0, 1.0).acos().to_degrees();
        let axis = haphe::DVec3::new(x, y, z).normalize_or_zero();
        writeln!(
            out,
            "    node {} '{}': mesh {}, {} triangles, {}; at {:?} m, turned {angle:.1}° about {:?}, scale {:?}{}",
            n.node,
            n.name,
            n.mesh,
            n.triangles,
            if n.closed { "closed" } else { "open" },
            n.translation,
            axis.to_array(),
            n.scale,
            if n.exact_trs { "" } else { " (with shear)" },
        )?;
    }
    for s in &gltf.skipped {
        writeln!(
            out,
            "  skipped: mesh {} primitive {} ({}): points and lines have no surface to touch",
            s.mesh, s.primitive, s.mode
        )?;
    }
    Ok(())
}
