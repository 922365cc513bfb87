//! `haphe query`: batches of inside/outside and segment-crossing queries from CSV.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, bail};
use haphe::DVec3;
use haphe::mesh::ReadOptions;
use haphe::query::{Side, classify_point, first_crossing};

use crate::args::{map_options, parse_units, weld_mode};
use crate::input::object::{check_source, open};

/// Arguments of `haphe query`.
#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("queries").required(true).args(["inside", "segments"])))]
pub struct Args {
    /// A map file from `haphe build`, or a mesh file (its map is built first).
    object: PathBuf,
    /// CSV of points `x,y,z` (metres, object frame): prints `inside` or `outside` per line.
    #[arg(long, value_name = "POINTS.csv")]
    inside: Option<PathBuf>,
    /// CSV of segments `x0,y0,z0,x1,y1,z1`: prints the first crossing per line
    /// (`triangle,t,x,y,z,entering`) or `none`.
    #[arg(long, value_name = "SEGS.csv")]
    segments: Option<PathBuf>,
    /// One JSON object per line instead of CSV.
    #[arg(long)]
    json: bool,
    /// Length unit of a mesh file (map files are in metres).
    #[arg(long, default_value = "m", value_parser = parse_units)]
    units: haphe::mesh::Units,
    /// Merge vertices closer than this (metres) when building from a mesh file.
    #[arg(long, value_name = "METRES")]
    weld_tolerance: Option<f64>,
    /// The mesh file the map was built from: the query is refused unless the map records
    /// this file's size and content hash (`haphe build` records them).
    #[arg(long, value_name = "MESH")]
    mesh: Option<PathBuf>,
}

/// The names a header row may use, in order: `x,y,z` for points and
/// `x0,y0,z0,x1,y1,z1` for segments (any case, spaces allowed).
fn header_names(width: usize) -> &'static [&'static str] {
    if width == 3 {
        &["x", "y", "z"]
    } else {
        &["x0", "y0", "z0", "x1", "y1", "z1"]
    }
}

/// Reads rows of `width` numbers from a CSV file. A first row is a header only when it
/// holds exactly the column names ([`header_names`]); every other line that is not
/// `width` finite numbers is an error naming the file and the line, so the output always
/// lines up with the input.
fn read_rows(path: &Path, width: usize) -> anyhow::Result<Vec<Vec<f64>>> {
    let bytes = crate::input::files::read_input(path, crate::input::files::CSV)?;
    let text = bytes
        .strip_prefix(b"\xEF\xBB\xBF".as_slice())
        .unwrap_or(&bytes);
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .trim(csv::Trim::All)
        .comment(Some(b'#'))
        .flexible(true)
        .from_reader(text);
    let mut rows = Vec::new();
    for (i, record) in reader.records().enumerate() {
        let record = record.with_context(|| format!("{}", path.display()))?;
        let line = record.position().map_or(i as u64 + 1, |p| p.line());
        if record.iter().all(|f| f.is_empty()) {
            continue;
        }
        let numbers: Result<Vec<f64>, _> = record.iter().map(str::parse::<f64>).collect();
        match numbers {
            Ok(v) if v.len() == width && v.iter().all(|x| x.is_finite()) => rows.push(v),
            Ok(v) if v.len() == width => {
                bail!("{}: line {line}: a value is not finite", path.display())
            }
            Ok(v) => bail!(
                "{}: line {line}: expected {width} numbers, found {}",
                path.display(),
                v.len()
            ),
            Err(_)
                if i == 0
                    && record.len() == width
                    && record
                        .iter()
                        .zip(header_names(width))
                        .all(|(f, name)| f.eq_ignore_ascii_case(name)) =>
            {
                continue; // the header
            }
            Err(_) => {
                let bad = record
                    .iter()
                    .find(|f| f.parse::<f64>().is_err())
                    .unwrap_or_default();
                bail!(
                    "{}: line {line}: {bad:?} is not a number (a header must be {})",
                    path.display(),
                    header_names(width).join(",")
                )
            }
        }
    }
    Ok(rows)
}

/// Runs the command.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    let read = ReadOptions {
        units: args.units,
        weld: weld_mode(args.weld_tolerance)?,
        format: None,
    };
    let object = open(&args.object, &read, &map_options(None, None))?;
    check_source(&args.object, &object, args.mesh.as_deref())?;
    if let Some(p) = object.map.provenance() {
        // On stderr (stdout holds one answer per input line); a closed stderr is no error.
        let _ = writeln!(std::io::stderr(), "{}: a map of {p}", args.object.display());
    }
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    if let Some(path) = &args.inside {
        for row in read_rows(path, 3)? {
            let p = DVec3::new(row[0], row[1], row[2]);
            let (side, _) = classify_point(&object.surface, &object.map, p);
            let word = if side == Side::Inside {
                "inside"
            } else {
                "outside"
            };
            if args.json {
                writeln!(out, "{}", serde_json::json!({ "point": row, "side": word }))?;
            } else {
                writeln!(out, "{word}")?;
            }
        }
    }
    if let Some(path) = &args.segments {
        for row in read_rows(path, 6)? {
            let (p0, p1) = (
                DVec3::new(row[0], row[1], row[2]),
                DVec3::new(row[3], row[4], row[5]),
            );
            let hit = first_crossing(&object.surface, &object.map, p0, p1);
            match (hit, args.json) {
                (None, false) => writeln!(out, "none")?,
                (None, true) => writeln!(
                    out,
                    "{}",
                    serde_json::json!({ "segment": row, "crossing": null })
                )?,
                (Some(c), false) => writeln!(
                    out,
                    "{},{:?},{:?},{:?},{:?},{}",
                    object.surface.source_triangle(c.triangle),
                    c.t,
                    c.point.x,
                    c.point.y,
                    c.point.z,
                    c.entering
                )?,
                (Some(c), true) => writeln!(
                    out,
                    "{}",
                    serde_json::json!({
                        "segment": row,
                        "crossing": {
                            "triangle": object.surface.source_triangle(c.triangle),
                            "t": c.t,
                            "point": c.point.to_array(),
                            "weights": c.weights,
                            "normal": c.face_normal.to_array(),
                            "entering": c.entering,
                        }
                    })
                )?,
            }
        }
    }
    out.flush()?;
    Ok(ExitCode::SUCCESS)
}
