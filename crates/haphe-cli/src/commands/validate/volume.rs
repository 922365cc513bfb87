//! `haphe validate FILE.nii[.gz]`: what a volume file holds (grid, voxel size, affine,
//! datatype, byte order, values) and where its material is at the iso value.

use std::io::Write;
use std::path::Path;
use std::time::Instant;

use haphe::DVec3;
use haphe::volume::{NiftiInfo, Volume};

use crate::input::volume::read_volume;

/// Where the material (values at least iso) is: how many voxels, and their box.
struct Extent {
    voxels: u64,
    /// The smallest and largest voxel indices of the material.
    lo: [usize; 3],
    hi: [usize; 3],
}

impl Extent {
    /// The material of `volume`, if any voxel is material.
    fn of(volume: &Volume) -> Option<Extent> {
        let [nx, ny, _] = volume.dims();
        let (mut lo, mut hi) = ([usize::MAX; 3], [0; 3]);
        let mut voxels = 0u64;
        let iso = volume.iso();
        for (at, _) in volume
            .values()
            .iter()
            .enumerate()
            .filter(|(_, v)| **v >= iso)
        {
            let ijk = [at % nx, (at / nx) % ny, at / (nx * ny)];
            for a in 0..3 {
                lo[a] = lo[a].min(ijk[a]);
                hi[a] = hi[a].max(ijk[a]);
            }
            voxels += 1;
        }
        (voxels > 0).then_some(Extent { voxels, lo, hi })
    }

    /// The box of the material's voxel centres in metres (the corners of the index box
    /// through the affine).
    fn bounds_m(&self, volume: &Volume) -> (DVec3, DVec3) {
        let (mut min, mut max) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for corner in 0..8 {
            let pick = |a: usize| if corner >> a & 1 == 0 { self.lo[a] } else { self.hi[a] } as f64;
            let p = volume.point(pick(0), pick(1), pick(2));
            (min, max) = (min.min(p), max.max(p));
        }
        (min, max)
    }
}

/// Reports the volume file at `path` (as text, or one JSON line); the exit code: 0 when
/// it has material at the iso value, 2 when it has none or cannot be read.
pub fn report(
    out: &mut impl Write,
    path: &Path,
    iso: Option<f32>,
    json: bool,
) -> anyhow::Result<u8> {
    let start = Instant::now();
    let (volume, info) = match read_volume(path, iso) {
        Ok(read) => read,
        Err(e) => {
            if json {
                let line = serde_json::json!({"file": path.display().to_string(), "error": format!("{e:#}")});
                writeln!(out, "{line}")?;
            } else {
                writeln!(out, "{e:#}\n  verdict: unreadable\n")?;
            }
            return Ok(2);
        }
    };
    let seconds = start.elapsed().as_secs_f64();
    let extent = Extent::of(&volume);
    if json {
        let line = record(
            path,
            &volume,
            &info,
            iso.is_none(),
            extent.as_ref(),
            seconds,
        )?;
        writeln!(out, "{line}")?;
    } else {
        text(
            out,
            path,
            &volume,
            &info,
            iso.is_none(),
            extent.as_ref(),
            seconds,
        )?;
    }
    Ok(if extent.is_some() { 0 } else { 2 })
}

/// The voxel sizes in millimetres: the lengths of the affine's columns.
fn voxel_size_mm(volume: &Volume) -> [f64; 3] {
    let m = volume.to_world().matrix3;
    [m.x_axis, m.y_axis, m.z_axis].map(|c| c.length() * 1e3)
}

/// The affine's rows (voxel indices to metres), the last `[0, 0, 0, 1]`.
fn affine_rows(volume: &Volume) -> [[f64; 4]; 4] {
    let a = volume.to_world();
    let row = |r: usize| {
        [
            a.matrix3.x_axis[r],
            a.matrix3.y_axis[r],
            a.matrix3.z_axis[r],
            a.translation[r],
        ]
    };
    [row(0), row(1), row(2), [0.0, 0.0, 0.0, 1.0]]
}

/// The text report.
fn text(
    out: &mut impl Write,
    path: &Path,
    volume: &Volume,
    info: &NiftiInfo,
    iso_default: bool,
    extent: Option<&Extent>,
    seconds: f64,
) -> anyhow::Result<()> {
    let gzip = if info.gzip { ", gzip" } else { "" };
    writeln!(
        out,
        "{}  (NIfTI-1, {}, {}{gzip}; read in {:.1} ms)",
        path.display(),
        info.datatype,
        info.byte_order,
        seconds * 1e3
    )?;
    let iso = volume.iso();
    let verdict = match extent {
        Some(_) => format!("a volume with material at iso {iso}"),
        None => format!("unusable: no value reaches iso {iso}"),
    };
    writeln!(out, "  verdict: {verdict}")?;
    let [nx, ny, nz] = volume.dims();
    writeln!(out, "  grid: {nx} x {ny} x {nz} voxels ({})", nx * ny * nz)?;
    let [sx, sy, sz] = voxel_size_mm(volume);
    writeln!(out, "  voxel size: {sx:.6} x {sy:.6} x {sz:.6} mm")?;
    writeln!(
        out,
        "  affine (voxel indices to metres, from the {}):",
        info.affine_from
    )?;
    for row in affine_rows(volume) {
        let cells: Vec<String> = row.iter().map(|v| format!("{v:>13.9}")).collect();
        writeln!(out, "    [{} ]", cells.join(""))?;
    }
    let (lo, hi) = info.value_range;
    writeln!(out, "  values: {lo} .. {hi}")?;
    if iso_default {
        writeln!(
            out,
            "  iso: {iso} (the default: the midpoint of the finite values; set it with --iso)"
        )?;
    } else {
        writeln!(out, "  iso: {iso}")?;
    }
    if let Some(e) = extent {
        let (min, max) = e.bounds_m(volume);
        writeln!(
            out,
            "  material (value >= iso): {} of {} voxels; voxels {:?} .. {:?}; [{:.6}, {:.6}, {:.6}] .. [{:.6}, {:.6}, {:.6}] m",
            e.voxels,
            volume.values().len(),
            e.lo,
            e.hi,
            min.x,
            min.y,
            min.z,
            max.x,
            max.y,
            max.z
        )?;
    }
    for note in &info.notes {
        writeln!(out, "  note: {note}")?;
    }
    writeln!(out)?;
    Ok(())
}

/// One line of `--json`, its fields in the order `haphe validate --help` lists them.
#[derive(serde::Serialize)]
struct Record<'a> {
    file: String,
    format: &'static str,
    seconds: f64,
    datatype: &'static str,
    byte_order: &'static str,
    gzip: bool,
    dims: [usize; 3],
    voxel_size_mm: [f64; 3],
    affine: [[f64; 4]; 4],
    affine_from: &'static str,
    metres_per_unit: f64,
    value_range: [f32; 2],
    iso: f32,
    iso_default: bool,
    material_voxels: u64,
    material_voxels_min: Option<[usize; 3]>,
    material_voxels_max: Option<[usize; 3]>,
    material_bounds_min: Option<[f64; 3]>,
    material_bounds_max: Option<[f64; 3]>,
    notes: &'a [String],
}

/// The JSON line.
fn record(
    path: &Path,
    volume: &Volume,
    info: &NiftiInfo,
    iso_default: bool,
    extent: Option<&Extent>,
    seconds: f64,
) -> anyhow::Result<String> {
    let (bounds_min, bounds_max) = extent.map(|e| e.bounds_m(volume)).unzip();
    let record = Record {
        file: path.display().to_string(),
        format: "NIfTI-1",
        seconds,
        datatype: info.datatype,
        byte_order: info.byte_order,
        gzip: info.gzip,
        dims: volume.dims(),
        voxel_size_mm: voxel_size_mm(volume),
        affine: affine_rows(volume),
        affine_from: info.affine_from,
        metres_per_unit: info.metres_per_unit,
        value_range: [info.value_range.0, info.value_range.1],
        iso: volume.iso(),
        iso_default,
        material_voxels: extent.map_or(0, |e| e.voxels),
        material_voxels_min: extent.map(|e| e.lo),
        material_voxels_max: extent.map(|e| e.hi),
        material_bounds_min: bounds_min.map(|p| p.to_array()),
        material_bounds_max: bounds_max.map(|p| p.to_array()),
        notes: &info.notes,
    };
    Ok(serde_json::to_string(&record)?)
}
