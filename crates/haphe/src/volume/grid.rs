//! The grid of values, the affine that places it and the iso value: [`Volume`].

use glam::{DAffine3, DVec3};

use crate::map::MapOptions;
use crate::scene::ParamError;
#[cfg(doc)]
use crate::scene::Shape;

/// The most voxels a volume may have (2^31: 8 GiB of `f32`).
pub(crate) const MAX_VOXELS: usize = 1 << 31;

/// Why a volume could not be made (or written: [`Volume::to_nifti`]). File readers add the
/// file's name and the place.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum VolumeError {
    /// A dimension is 0, or the product is beyond 2³¹ voxels.
    #[error("the grid {0:?} is empty or has more than {MAX_VOXELS} voxels")]
    Dims([usize; 3]),
    /// Not one value per voxel.
    #[error("{given} values for a grid of {expected} voxels")]
    Count {
        /// How many values were given.
        given: usize,
        /// How many voxels the grid has.
        expected: usize,
    },
    /// The affine is not finite or not invertible (a zero or NaN voxel size).
    #[error("the affine from voxels to metres is not finite and invertible")]
    Affine,
    /// A NaN value (infinities are allowed: they are far inside or outside).
    #[error("voxel {0:?} is NaN")]
    NotANumber([usize; 3]),
    /// The iso value is not finite.
    #[error("the iso value {0} is not finite")]
    Iso(f32),
    /// The voxel size asked of [`Volume::from_shape`] is out of its domain
    /// ([`Param::VoxelSize`](crate::scene::Param::VoxelSize)).
    #[error(transparent)]
    VoxelSize(#[from] ParamError),
    /// The voxel size asked of [`Volume::from_shape`] makes a grid of more than 2³¹
    /// voxels.
    #[error("the voxel size {voxel} m makes a grid of {voxels:.3e} voxels, more than {MAX_VOXELS}")]
    VoxelCount {
        /// The voxel size, metres.
        voxel: f64,
        /// How many voxels the grid would have.
        voxels: f64,
    },
    /// The shape given to [`Volume::from_shape`] has no inside: it is not a closed,
    /// manifold, consistently oriented solid ([`Shape::is_solid`]).
    #[error(
        "the shape is not a closed solid (open, non-manifold or inconsistently oriented): it has no inside to voxelise"
    )]
    NotSolid,
    /// A side of the grid is beyond what a NIfTI-1 header holds (32767 voxels).
    #[error("the grid {0:?} has a side of more than 32767 voxels, beyond NIfTI-1")]
    NiftiDims([usize; 3]),
}

/// A regular grid of values and the affine that places it; material where the value is
/// at least [`Volume::iso`].
#[derive(Debug, Clone, PartialEq)]
pub struct Volume {
    // Visible to the volume's readers and writers (`nifti`), which keep its invariants.
    pub(super) dims: [usize; 3],
    pub(super) values: Vec<f32>,
    pub(super) to_world: DAffine3,
    pub(super) iso: f32,
}

impl Volume {
    /// A volume of `dims` voxels with `values` (`i` fastest), placed by `to_world` (voxel
    /// indices to metres), with material where a value is at least `iso`.
    ///
    /// # Errors
    /// [`VolumeError::Dims`], [`VolumeError::Count`], [`VolumeError::Affine`],
    /// [`VolumeError::NotANumber`] (naming the first such voxel), [`VolumeError::Iso`].
    pub fn new(
        dims: [usize; 3],
        values: Vec<f32>,
        to_world: DAffine3,
        iso: f32,
    ) -> Result<Volume, VolumeError> {
        let count = dims
            .iter()
            .try_fold(1usize, |n, &d| n.checked_mul(d))
            .filter(|&n| n > 0 && n <= MAX_VOXELS)
            .ok_or(VolumeError::Dims(dims))?;
        if values.len() != count {
            return Err(VolumeError::Count {
                given: values.len(),
                expected: count,
            });
        }
        let det = to_world.matrix3.determinant();
        let finite = to_world.matrix3.is_finite() && to_world.translation.is_finite();
        if !finite || !det.is_finite() || det == 0.0 {
            return Err(VolumeError::Affine);
        }
        if !iso.is_finite() {
            return Err(VolumeError::Iso(iso));
        }
        if let Some(at) = values.iter().position(|v| v.is_nan()) {
            return Err(VolumeError::NotANumber(index_of(dims, at)));
        }
        Ok(Volume {
            dims,
            values,
            to_world,
            iso,
        })
    }

    /// The number of voxels along each axis.
    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    /// The values, `i` fastest.
    pub fn values(&self) -> &[f32] {
        &self.values
    }

    /// The values, to change in place (material where a value is at least `iso`).
    pub fn values_mut(&mut self) -> &mut [f32] {
        &mut self.values
    }

    /// The affine from voxel indices to metres.
    pub fn to_world(&self) -> DAffine3 {
        self.to_world
    }

    /// Material is where a value is at least this.
    pub fn iso(&self) -> f32 {
        self.iso
    }

    /// Sets the iso value: material is then where a value is at least `iso`.
    ///
    /// # Errors
    /// [`VolumeError::Iso`]: `iso` is not finite (the volume is left as it was).
    pub fn set_iso(&mut self, iso: f32) -> Result<(), VolumeError> {
        if !iso.is_finite() {
            return Err(VolumeError::Iso(iso));
        }
        self.iso = iso;
        Ok(())
    }

    /// The value at voxel `(i, j, k)`; outside the grid, air (`-inf`).
    #[inline]
    pub fn value(&self, i: i64, j: i64, k: i64) -> f32 {
        let [nx, ny, nz] = self.dims.map(|d| d as i64);
        if i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz {
            return f32::NEG_INFINITY;
        }
        self.values[(i + nx * (j + ny * k)) as usize]
    }

    /// Whether voxel `(i, j, k)` is material (false outside the grid).
    #[inline]
    pub fn is_material(&self, i: i64, j: i64, k: i64) -> bool {
        self.value(i, j, k) >= self.iso
    }

    /// The point of voxel `(i, j, k)` in metres (the volume's frame).
    #[inline]
    pub fn point(&self, i: f64, j: f64, k: f64) -> DVec3 {
        self.to_world.transform_point3(DVec3::new(i, j, k))
    }

    /// The iso value the front ends take when none is given: the midpoint of the range of
    /// the finite values among `values` (0 when none is finite).
    pub fn midpoint_iso(values: &[f32]) -> f32 {
        finite_range(values).map_or(0.0, |(lo, hi)| {
            (0.5 * (f64::from(lo) + f64::from(hi))) as f32
        })
    }

    /// The largest spacing of the grid, metres: one voxel.
    pub(crate) fn voxel_size(&self) -> f64 {
        let m = self.to_world.matrix3;
        [m.x_axis, m.y_axis, m.z_axis]
            .iter()
            .map(|a| a.length())
            .fold(0.0, f64::max)
    }

    /// `options` with cells of one voxel unless they set a size: the extraction's
    /// triangles are many and small (several a voxel), and cells sized from them would be
    /// so small that a tool's sweep steps through too many.
    pub(crate) fn map_options(&self, options: &MapOptions) -> MapOptions {
        MapOptions {
            cell_size_m: options.cell_size_m.or(Some(self.voxel_size())),
            ..*options
        }
    }

    /// The centre of the grid's bounding box in metres: where the front ends place the
    /// volume's origin.
    pub fn centre(&self) -> DVec3 {
        let [nx, ny, nz] = self.dims.map(|d| (d - 1) as f64);
        self.point(0.5 * nx, 0.5 * ny, 0.5 * nz)
    }
}

/// The smallest and largest finite values among `values`, if any.
pub(crate) fn finite_range(values: &[f32]) -> Option<(f32, f32)> {
    values
        .iter()
        .filter(|v| v.is_finite())
        .fold(None, |range, &v| match range {
            None => Some((v, v)),
            Some((lo, hi)) => Some((v.min(lo), v.max(hi))),
        })
}

/// The voxel `(i, j, k)` of the flat index `at`.
pub(crate) fn index_of(dims: [usize; 3], at: usize) -> [usize; 3] {
    [
        at % dims[0],
        (at / dims[0]) % dims[1],
        at / (dims[0] * dims[1]),
    ]
}
