//! NIfTI-1 volumes in and out: [`Volume::read_nifti`] reads a single-file `.nii` or
//! `.nii.gz` (bytes in: the library opens no files), [`Volume::to_nifti`] writes one.
//!
//! The header is checked before anything else is read or allocated: the byte order (from
//! `sizeof_hdr`, either order), the magic, the dimensions, the datatype, where the data
//! start and whether the file holds them. A gzip file is decompressed no further than the
//! header's data need, and a header announcing more than its compressed bytes can hold is
//! refused before decompressing. The affine is chosen as nibabel chooses it
//! (`get_best_affine`) and converted to metres.

mod affine;
mod data;
mod error;
mod header;
mod write;

#[cfg(test)]
mod tests;

pub use error::ReadVolumeError;

use super::Volume;
use error::{ReadVolumeError as Kind, truncated};

/// What a NIfTI-1 file held besides the volume: what `haphe validate` reports.
// The command's plumbing, hidden like the mesh report's record (ARCHITECTURE.md, "A public
// name"): the library's documented interface stays within its count of names.
#[doc(hidden)]
#[derive(Debug, Clone, PartialEq)]
pub struct NiftiInfo {
    /// The voxel type as nibabel names it (`"int16"`, `"float32"`, ...).
    pub datatype: &'static str,
    /// The byte order of the file's numbers: `"little-endian"` or `"big-endian"`.
    pub byte_order: &'static str,
    /// Whether the file was a gzip stream (detected from its first bytes, not its name).
    pub gzip: bool,
    /// Which transform of the header placed the grid: `"sform"`, `"qform"` or `"pixdim"`
    /// (with words on the fall-back).
    pub affine_from: &'static str,
    /// Metres per unit of the header's spatial unit (`xyzt_units`): 1, 1e-3 or 1e-6.
    pub metres_per_unit: f64,
    /// The smallest and largest value, after `scl_slope` and `scl_inter`.
    pub value_range: (f32, f32),
    /// What was taken in a way the reader should know: the first volume of a 4-D file, an
    /// unknown unit taken as millimetres, header values fixed as nibabel fixes them.
    pub notes: Vec<String>,
}

impl Volume {
    /// Reads a single-file NIfTI-1 volume (`.nii`, or `.nii.gz` detected by its gzip magic)
    /// of either byte order, with material where a value is at least `iso`. `name` (usually
    /// the path) is named by errors.
    ///
    /// Datatypes: 8- to 64-bit integers, signed and unsigned, and 32- and 64-bit floats,
    /// scaled by `scl_slope` and `scl_inter` when the slope is non-zero and finite. A file
    /// of more than three dimensions gives its first volume (with a note). The affine is
    /// the sform when `sform_code` is set, else the qform when `qform_code` is set, else
    /// nibabel's fall-back (voxel sizes, `x` flipped, the grid centred on the origin); its
    /// unit is the header's (millimetres when unknown, with a note), converted to metres.
    ///
    /// # Errors
    /// [`ReadVolumeError`], naming `name` and the header field, the byte counts or the
    /// voxel: NIfTI-2 ("convert to NIfTI-1"), not NIfTI-1, `dim[0]` outside 1 to 7, a
    /// spatial dimension below 1, more than 2³¹ voxels, a datatype not
    /// read, data beyond the end of the file, a corrupt gzip stream, a NaN value.
    ///
    /// # Performance
    /// Allocates the decompressed bytes of a gzip file (up to the first volume's end) and
    /// the `f32` values; nothing is allocated before the header has been checked.
    ///
    /// # Examples
    /// ```
    /// use haphe::DVec3;
    /// use haphe::glam::DAffine3;
    /// use haphe::volume::Volume;
    ///
    /// // 2 x 2 x 2 voxels of 1 mm, material where the value is at least 3.5.
    /// let values = (0..8).map(|v| v as f32).collect();
    /// let to_world = DAffine3::from_scale(DVec3::splat(1e-3));
    /// let volume = Volume::new([2, 2, 2], values, to_world, 3.5)?;
    /// let (back, info) = Volume::read_nifti("cube.nii.gz", &volume.to_nifti_gz()?, 3.5)?;
    /// assert_eq!(back, volume);
    /// assert_eq!((info.datatype, info.gzip), ("float32", true));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn read_nifti(
        name: &str,
        bytes: &[u8],
        iso: f32,
    ) -> Result<(Volume, NiftiInfo), ReadVolumeError> {
        read(bytes, iso).map_err(|e| e.in_file(name))
    }
}

/// [`Volume::read_nifti`] without the name.
fn read(bytes: &[u8], iso: f32) -> Result<(Volume, NiftiInfo), Kind> {
    let inflated;
    let gzip = data::is_gzip(bytes);
    let (layout, file) = if gzip {
        let (layout, file) = data::inflate(bytes)?;
        inflated = file;
        (layout, &inflated[..])
    } else {
        (header::layout(bytes)?, bytes)
    };
    let end = layout.end();
    if (file.len() as u64) < end {
        return Err(truncated("file", end, file.len() as u64));
    }
    // The header's remaining fields first, then the values.
    let h = &layout.header;
    let scale = data::scaling(h.scl_slope, h.scl_inter)?;
    let mut notes = Vec::new();
    if layout.volumes > 1 {
        notes.push(format!(
            "{}-D file: the first of {} volumes is used",
            h.dim[0], layout.volumes
        ));
    }
    let (to_file, source) = affine::file_affine(h, layout.dims, &mut notes)?;
    let metres_per_unit = affine::metres_per_unit(h.xyzt_units, &mut notes)?;
    let to_world = affine::in_metres(to_file, metres_per_unit);
    let values = data::decode(
        &file[layout.offset as usize..end as usize],
        layout.datatype,
        layout.order,
        scale,
    );
    let volume = Volume::new(layout.dims, values, to_world, iso)?;
    let info = NiftiInfo {
        datatype: layout.datatype.name,
        byte_order: layout.order.name(),
        gzip,
        affine_from: source.name(),
        metres_per_unit,
        value_range: value_range(volume.values()),
        notes,
    };
    Ok((volume, info))
}

/// The smallest and largest of `values` (not empty, no NaN: a volume's).
fn value_range(values: &[f32]) -> (f32, f32) {
    values
        .iter()
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        })
}
