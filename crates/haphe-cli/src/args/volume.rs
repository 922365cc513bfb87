//! The volume of a session, `--volume`, `--iso`, `--voxel` and `--layer` (shared by `simulate`, `run`
//! and `view`): a NIfTI-1 file, or a mesh voxelised, whose material the tool can cut
//! (`--cut`, [`super::cut`]).

use std::path::{Path, PathBuf};

/// The flags of a session's volume.
#[derive(clap::Args, Debug, Clone)]
pub struct VolumeArgs {
    /// A volume (NIfTI-1, `.nii` or `.nii.gz`): the material where a value is at least
    /// --iso, its surface extracted, placed with the centre of its grid at the origin.
    #[arg(long, value_name = "FILE.nii")]
    pub volume: Option<PathBuf>,
    /// With --volume: material is where a value is at least this (default: the middle of
    /// the values' range).
    #[arg(
        long,
        value_name = "V",
        allow_negative_numbers = true,
        requires = "volume"
    )]
    pub iso: Option<f32>,
    /// With --mesh: voxelise the (closed) mesh on a grid of this spacing, metres, and
    /// render it as a volume the tool can cut (--cut).
    #[arg(
        long,
        value_name = "SIZE",
        allow_negative_numbers = true,
        requires = "mesh"
    )]
    pub voxel: Option<f64>,
    /// With a volume: a material of its values, repeatable, e.g. `enamel:2:0.002:900:0.4`
    /// (its lowest value, the rate it is cut at in m/s, stiffness N/m, static and dynamic
    /// friction). A value takes the layer with the highest FROM at most the value; each
    /// triangle feels like the material beside it.
    #[arg(
        long = "layer",
        value_name = "NAME:FROM:RATE:STIFFNESS[:FRICTION[:DYNAMIC]]"
    )]
    pub layers: Vec<String>,
}

impl VolumeArgs {
    /// The volume file with its iso value, when one is given.
    pub fn file(&self) -> Option<(&Path, Option<f32>)> {
        self.volume.as_deref().map(|v| (v, self.iso))
    }
}
