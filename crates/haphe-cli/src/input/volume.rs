//! Volume files (NIfTI-1, `.nii` and `.nii.gz`): read from disk within a size limit, and
//! written whole through haphe-files (never in place).

use std::path::Path;

use anyhow::{Context, anyhow};
use haphe::volume::{NiftiInfo, Volume};

use crate::input::files::{self, read_input};

/// Whether `path` names a volume file: it ends in `.nii` or `.nii.gz` (any case).
pub fn is_volume_path(path: &Path) -> bool {
    let name = path.to_string_lossy().to_ascii_lowercase();
    name.ends_with(".nii") || name.ends_with(".nii.gz")
}

/// Reads the NIfTI-1 file at `path` (opened once, within [`files::VOLUME`]) with material
/// where a value is at least `iso`, or, without one, at least [`Volume::midpoint_iso`] of
/// its values.
///
/// # Errors
/// The file cannot be read, or is not a NIfTI-1 volume haphe reads: the message names the
/// file and the header field, byte count or voxel.
pub fn read_volume(path: &Path, iso: Option<f32>) -> anyhow::Result<(Volume, NiftiInfo)> {
    let bytes = read_input(path, files::VOLUME)?;
    let name = path.display().to_string();
    let (mut volume, info) = Volume::read_nifti(&name, &bytes, iso.unwrap_or(0.0))?;
    if iso.is_none() {
        volume.set_iso(Volume::midpoint_iso(volume.values()))?;
    }
    Ok((volume, info))
}

/// Writes `volume` to `path` as NIfTI-1 (gzip when the name ends in `.gz`), whole: a
/// temporary file beside `path` renamed over it when complete.
///
/// # Errors
/// A side of more than 32767 voxels, or the file cannot be written (naming the path).
#[allow(
    dead_code,
    reason = "the writer of volume outputs; its command option comes next"
)]
pub fn write_volume(path: &Path, volume: &Volume) -> anyhow::Result<()> {
    let gzip = path.to_string_lossy().to_ascii_lowercase().ends_with(".gz");
    let bytes = if gzip {
        volume.to_nifti_gz()
    } else {
        volume.to_nifti()
    }
    .with_context(|| format!("cannot write {}", path.display()))?;
    haphe_files::write_replacing(path, &bytes).map_err(|e| anyhow!(e.message()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use haphe::glam::DAffine3;

    #[test]
    fn a_written_volume_reads_back_and_replaces_the_file_whole() {
        let dir = std::env::temp_dir().join(format!("haphe-volume-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a scratch directory");
        let values: Vec<f32> = (0..8).map(|v| v as f32).collect();
        let volume = Volume::new(
            [2, 2, 2],
            values,
            DAffine3::from_scale(haphe::DVec3::splat(1e-3)),
            0.0,
        )
        .expect("a valid volume");
        for name in ["v.nii", "v.nii.gz"] {
            let path = dir.join(name);
            std::fs::write(&path, b"old").expect("the old file");
            write_volume(&path, &volume).expect("written");
            let (back, info) = read_volume(&path, None).expect("read back");
            assert_eq!(back.values(), volume.values());
            assert_eq!(back.iso(), 3.5, "the midpoint of 0 .. 7");
            assert_eq!(info.gzip, name.ends_with(".gz"));
            assert_eq!(std::fs::read_dir(&dir).expect("listed").count(), 1);
            std::fs::remove_file(&path).expect("removed");
        }
        let _ = std::fs::remove_dir(&dir);
    }

    #[test]
    fn the_default_iso_is_the_midpoint_of_the_finite_values() {
        assert_eq!(
            Volume::midpoint_iso(&[f32::NEG_INFINITY, -2.0, 6.0, f32::INFINITY]),
            2.0
        );
        assert_eq!(Volume::midpoint_iso(&[f32::INFINITY]), 0.0);
        assert!(is_volume_path(Path::new("a/B.NII.GZ")) && !is_volume_path(Path::new("b.obj")));
    }
}
