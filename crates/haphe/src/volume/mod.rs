//! Volumes: a regular grid of values with an affine from voxel indices to metres, and the
//! material where the value is at least `iso`. A volume comes from a NIfTI-1 file
//! ([`Volume::read_nifti`]) or from a closed mesh voxelised with the non-zero rule
//! ([`Volume::from_shape`]); its iso-surface is extracted in chunks into one closed
//! triangle surface that the map and the proxy render like any mesh (`Chunks`), and a
//! tool that cuts removes material from it ([`Cutter`]).
//!
//! Conventions: the voxel `(i, j, k)` is the grid point at `to_world * (i, j, k)`; values
//! are stored with `i` fastest (`i + nx * (j + ny * k)`). Outside the grid is air: a
//! surface that reaches the grid's border is closed there.

mod cut;
mod extract;
mod grid;
mod layers;
mod nifti;
mod voxelise;

pub use cut::{CutError, CutOptions, Cutter};
// The chunks of an extraction: the benches and tests measure and check them.
#[doc(hidden)]
pub use extract::Chunks;
pub(crate) use grid::MAX_VOXELS;
pub use grid::{Volume, VolumeError};
pub use layers::Layer;
pub use nifti::ReadVolumeError;
// What `haphe validate` reports of a volume file: the command's plumbing.
#[doc(hidden)]
pub use nifti::NiftiInfo;
