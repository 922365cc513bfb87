//! Cutting in a session, `--cut`, `--cut-force`, `--cut-refresh` and `--save-volume`
//! (shared by `simulate`, `run` and `view`): the tool removes the material of a volume object
//! (`--volume`, or a `--mesh` voxelised with `--voxel`) it presses on; checked before
//! anything is built.

use std::path::PathBuf;

use anyhow::{anyhow, bail};
use haphe::volume::{CutOptions, Cutter};

/// Shapes remade a second when `--cut-refresh` is not given.
pub const DEFAULT_CUT_REFRESH_HZ: f64 = 100.0;

/// The highest `--cut-refresh`, Hz (and at most the servo rate).
pub const MAX_CUT_REFRESH_HZ: f64 = 1000.0;

/// The flags of a session's cutting.
#[derive(clap::Args, Debug, Clone)]
pub struct CutArgs {
    /// Cut: the tool removes the material of the volume (--volume, or --mesh with --voxel)
    /// it presses on with at least --cut-force; the surface is extracted again where it
    /// changed and handed to the servo wait-free (docs/guide.md, "Cutting").
    #[arg(long)]
    pub cut: bool,
    /// With --cut: the contact force from which the tool cuts, N (default 0.5; 0 cuts on
    /// any contact).
    #[arg(
        long,
        value_name = "N",
        allow_negative_numbers = true,
        requires = "cut"
    )]
    pub cut_force: Option<f64>,
    /// With --cut: new shapes of the cut volume made a second, Hz (default 100; from 1 to
    /// 1000, and at most the servo rate).
    #[arg(
        long,
        value_name = "HZ",
        allow_negative_numbers = true,
        requires = "cut"
    )]
    pub cut_refresh: Option<f64>,
    /// Write the volume, as cut, to this NIfTI-1 file at the end of the run (`.nii.gz`:
    /// compressed), on the same grid and affine; written whole, never in place.
    #[arg(long, value_name = "OUT.nii")]
    pub save_volume: Option<PathBuf>,
}

/// A volume to cut, before the run: the cutter, the flags, where to save it.
pub struct CutSetup {
    pub cutter: Cutter,
    pub cut: Option<Cut>,
    pub save: Option<PathBuf>,
}

/// A checked cutting: the force and the refresh rate (the tool's radius comes from
/// `--tool-radius`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cut {
    pub cut_force: f64,
    pub refresh_hz: f64,
}

impl CutArgs {
    /// The flags' cutting when `--cut` is given, its refresh rate checked against the
    /// servo rate `servo_rate_hz`.
    ///
    /// # Errors
    /// A force or rate out of its domain, named as its flag.
    pub fn check(&self, servo_rate_hz: f64) -> anyhow::Result<Option<Cut>> {
        if !self.cut {
            return Ok(None);
        }
        let cut_force = self.cut_force.unwrap_or(CutOptions::DEFAULT_CUT_FORCE);
        CutOptions::new(0.0, cut_force).map_err(|e| anyhow!("{}", e.named("--cut-force")))?;
        let refresh_hz = self.cut_refresh.unwrap_or(DEFAULT_CUT_REFRESH_HZ);
        let high = MAX_CUT_REFRESH_HZ.min(servo_rate_hz);
        if !(refresh_hz.is_finite() && (1.0..=high).contains(&refresh_hz)) {
            bail!("--cut-refresh must be a finite number from 1 to {high} Hz, not {refresh_hz}");
        }
        Ok(Some(Cut {
            cut_force,
            refresh_hz,
        }))
    }
}

impl CutArgs {
    /// Checks that a session that cuts has one device (`devices`, how many `--device`).
    ///
    /// # Errors
    /// `--cut` with several devices.
    pub fn one_device(&self, devices: usize) -> anyhow::Result<()> {
        if self.cut && devices > 1 {
            bail!("--cut cuts with one device's tool; give one --device");
        }
        Ok(())
    }

    /// The volume of a session with its cutting: `cutter`, the loaded model's (a
    /// `--volume`, or a `--mesh` with `--voxel`), and what the flags ask of it.
    ///
    /// # Errors
    /// `--cut` or `--save-volume` without a volume, `--cut` with `--deform`, or the checks
    /// of [`CutArgs::check`].
    pub fn setup(
        &self,
        cutter: Option<Cutter>,
        servo_rate_hz: f64,
        deform: bool,
    ) -> anyhow::Result<Option<CutSetup>> {
        let cut = self.check(servo_rate_hz)?;
        let Some(cutter) = cutter else {
            if cut.is_some() || self.save_volume.is_some() {
                let flag = if cut.is_some() {
                    "--cut"
                } else {
                    "--save-volume"
                };
                bail!("{flag} needs a volume: --volume FILE.nii, or --mesh FILE with --voxel SIZE");
            }
            return Ok(None);
        };
        if cut.is_some() && deform {
            bail!("--cut and --deform cannot be used together");
        }
        Ok(Some(CutSetup {
            cutter,
            cut,
            save: self.save_volume.clone(),
        }))
    }
}
