//! Writing output files: never in place. Each output is written to a temporary file in the
//! target's directory, flushed and synced, and renamed over the target only when complete;
//! on any failure the temporary file is removed and an existing target is left as it was.

use std::fs::Permissions;
use std::io::{BufWriter, Write};
use std::os::unix::fs::{MetadataExt, PermissionsExt};
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use tempfile::NamedTempFile;

/// An output path checked by [`check_outputs`].
#[derive(Debug, Clone)]
pub struct Output {
    /// The path as given.
    pub path: PathBuf,
}

/// The directory a file at `path` goes into (`.` for a bare name).
fn directory_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// A new temporary file beside `path`, named after it (`.name.XXXXXX.ext`, the extension
/// kept so that writers choosing a format by extension see the right one).
fn temporary_beside(path: &Path) -> anyhow::Result<NamedTempFile> {
    let directory = directory_of(path);
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    let suffix = path
        .extension()
        .map(|e| format!(".{}", e.to_string_lossy()))
        .unwrap_or_default();
    tempfile::Builder::new()
        .prefix(&format!(".{name}."))
        .suffix(&suffix)
        .permissions(Permissions::from_mode(0o666))
        .tempfile_in(directory)
        .with_context(|| {
            format!(
                "cannot write {}: cannot create a file in {}",
                path.display(),
                directory.display()
            )
        })
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
    staged.commit()
}

fn persist(temporary: NamedTempFile, path: &Path) -> anyhow::Result<()> {
    temporary
        .as_file()
        .sync_all()
        .with_context(|| format!("cannot write {}", path.display()))?;
    temporary
        .persist(path)
        .map_err(|e| e.error)
        .with_context(|| format!("cannot write {}", path.display()))?;
    Ok(())
}

/// An output being written: a buffered temporary file beside the target, which replaces
/// the target at [`Staged::commit`] and is removed if dropped before.
pub struct Staged {
    writer: BufWriter<NamedTempFile>,
    path: PathBuf,
}

impl Staged {
    /// Starts writing `path`.
    ///
    /// # Errors
    /// When no file can be created in the target's directory.
    pub fn create(path: &Path) -> anyhow::Result<Staged> {
        Ok(Staged {
            writer: BufWriter::with_capacity(1 << 20, temporary_beside(path)?),
            path: path.to_owned(),
        })
    }

    /// The writer to write the contents to.
    pub fn writer(&mut self) -> &mut impl Write {
        &mut self.writer
    }

    /// The target path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Flushes, syncs and renames the file over the target.
    ///
    /// # Errors
    /// A write, sync or rename failure, naming the target.
    pub fn commit(self) -> anyhow::Result<()> {
        let path = self.path;
        let temporary = self
            .writer
            .into_inner()
            .map_err(|e| e.into_error())
            .with_context(|| format!("cannot write {}", path.display()))?;
        persist(temporary, &path)
    }
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
