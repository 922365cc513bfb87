//! Writing output files: never in place. Each output is written to a temporary file in the
//! target's directory, flushed and synced, and renamed over the target only when complete;
//! on any failure the temporary file is removed and an existing target is left as it was
//! ([`haphe_files`], shared with the Python and C bindings). Here: the checks before any
//! long work, and the command's writers.

use std::io::Write;
use std::os::unix::fs::MetadataExt;
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
pub use haphe_files::Staged;
use haphe_files::{directory_of, temporary_beside};

/// An output path checked by [`check_outputs`].
#[derive(Debug, Clone)]
pub struct Output {
    /// The path as given.
    pub path: PathBuf,
}

/// Checks, before any long work, that every output can be written: its directory exists
/// and takes new files, it is not a directory, and it is none of `inputs` (same device and
/// inode, so another name for an input is caught too).
///
/// # Errors
/// Naming the output path and the reason.
pub fn check_outputs(outputs: &[&Path], inputs: &[&Path]) -> anyhow::Result<Vec<Output>> {
    let identities: Vec<(u64, u64)> = inputs
        .iter()
        .filter_map(|p| std::fs::metadata(p).ok())
        .map(|m| (m.dev(), m.ino()))
        .collect();
    let mut checked = Vec::new();
    for &path in outputs {
        let shown = path.display();
        if path.as_os_str().is_empty() {
            bail!("an output path is empty");
        }
        let directory = directory_of(path);
        match std::fs::metadata(directory) {
            Ok(m) if m.is_dir() => {}
            Ok(_) => bail!(
                "cannot write {shown}: {} is not a directory",
                directory.display()
            ),
            Err(_) => bail!(
                "cannot write {shown}: the directory {} does not exist",
                directory.display()
            ),
        }
        if let Ok(m) = std::fs::metadata(path) {
            if m.is_dir() {
                bail!("cannot write {shown}: it is a directory");
            }
            if !m.is_file() {
                // Renaming over a device or a pipe would replace it with a file.
                bail!(
                    "cannot write {shown}: it is {}; outputs are regular files, written whole and renamed into place",
                    crate::input::files::kind_name(m.file_type())
                );
            }
            if identities.contains(&(m.dev(), m.ino())) {
                bail!("cannot write {shown}: it is one of the input files");
            }
        }
        // Creating (and at once removing) a temporary file is the real test of writability.
        drop(temporary_beside(path)?);
        if checked.iter().any(|o: &Output| o.path == path) {
            bail!("{shown} is given as two outputs");
        }
        checked.push(Output {
            path: path.to_owned(),
        });
    }
    Ok(checked)
}

/// Writes `path` through `write`, which receives a buffered writer on a temporary file
/// beside `path`; the file replaces `path` only when `write` succeeded and everything was
/// flushed and synced to disk.
///
/// # Errors
/// Whatever `write` returns, or a write, sync or rename failure, naming `path`.
pub fn write_output(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    let mut staged = Staged::create(path)?;
    write(staged.writer()).with_context(|| format!("cannot write {}", path.display()))?;
    Ok(staged.commit()?)
}

/// Draws a `width` × `height` RGB picture in memory with `draw` and writes it to `path` as
/// PNG through [`write_output`] (a plot is never left half-written).
///
/// # Errors
/// When drawing fails, or as [`write_output`].
pub fn write_png(
    path: &Path,
    (width, height): (u32, u32),
    draw: impl FnOnce(&mut [u8]) -> Result<(), Box<dyn std::error::Error>>,
) -> anyhow::Result<()> {
    let mut pixels = vec![0u8; width as usize * height as usize * 3];
    draw(&mut pixels).map_err(|e| anyhow::anyhow!("cannot draw {}: {e}", path.display()))?;
    write_output(path, |out| {
        let mut encoder = png::Encoder::new(out, width, height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        // A plot is mostly flat colour: the adaptive filter and the default compression
        // keep it small.
        encoder.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(&pixels)?;
        Ok(writer.finish()?)
    })
}
