//! Files for haphe's front ends (the command, the Python and C bindings): an output is
//! never written in place. It is written to a temporary file in the target's directory,
//! flushed and synced, and renamed over the target only when complete; on any failure the
//! temporary file is removed and an existing target is left as it was. A reader of the old
//! file (a map file mapped into memory, say) never sees a half-written one.
//!
//! The library's stages open no files (ARCHITECTURE.md); this crate is where the front ends
//! that do share how they write.

use std::fs::Permissions;
use std::io::{BufWriter, Write};
use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};

use tempfile::NamedTempFile;

/// Why an output could not be written: the target path and the step that failed, with the
/// operating system's error as the source.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum WriteError {
    /// No temporary file could be created beside the target.
    #[error("cannot write {}: cannot create a file in {}", path.display(), directory.display())]
    Create {
        /// The target.
        path: PathBuf,
        /// Its directory.
        directory: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// Writing, flushing, syncing or renaming failed.
    #[error("cannot write {}", path.display())]
    Write {
        /// The target.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
}

impl WriteError {
    /// The operating system's error.
    pub fn io(&self) -> &std::io::Error {
        match self {
            WriteError::Create { source, .. } | WriteError::Write { source, .. } => source,
        }
    }

    /// The message with the system's reason: "cannot write PATH: REASON".
    pub fn message(&self) -> String {
        format!("{self}: {}", self.io())
    }
}

/// The directory a file at `path` goes into (`.` for a bare name).
pub fn directory_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// The mesh file a map file at `map` was built from, when it is beside the map: the file
/// named `recorded` (the name the map's provenance records, without a folder) in the map's
/// directory. `None` when there is no such file, when the name has a folder in it, or when
/// it is the map itself. Every front end that takes a map in place of a mesh checks it
/// against this file.
pub fn source_beside(map: &Path, recorded: &str) -> Option<PathBuf> {
    if recorded.is_empty() || recorded.contains(['/', '\\']) || recorded == ".." {
        return None;
    }
    let source = map.with_file_name(recorded);
    let same = match (std::fs::canonicalize(map), std::fs::canonicalize(&source)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    (source.is_file() && !same).then_some(source)
}

/// A new temporary file beside `path`, named after it (`.name.XXXXXX.ext`, the extension
/// kept so that writers choosing a format by extension see the right one), with the
/// permissions a new file gets (0666 less the umask).
///
/// # Errors
/// [`WriteError::Create`] when no file can be created in the target's directory.
pub fn temporary_beside(path: &Path) -> Result<NamedTempFile, WriteError> {
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
        .map_err(|source| WriteError::Create {
            path: path.to_owned(),
            directory: directory.to_owned(),
            source,
        })
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
    /// [`WriteError::Create`] when no file can be created in the target's directory.
    pub fn create(path: &Path) -> Result<Staged, WriteError> {
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
    /// [`WriteError::Write`]: a write, sync or rename failure, naming the target.
    pub fn commit(self) -> Result<(), WriteError> {
        let path = self.path;
        let failed = |source| WriteError::Write {
            path: path.clone(),
            source,
        };
        let temporary = self
            .writer
            .into_inner()
            .map_err(|e| failed(e.into_error()))?;
        temporary.as_file().sync_all().map_err(failed)?;
        temporary.persist(&path).map_err(|e| failed(e.error))?;
        Ok(())
    }
}

/// Writes `bytes` to `path` whole ([`Staged`]).
///
/// # Errors
/// As [`Staged::create`] and [`Staged::commit`].
pub fn write_replacing(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    let mut staged = Staged::create(path)?;
    staged
        .writer()
        .write_all(bytes)
        .map_err(|source| WriteError::Write {
            path: path.to_owned(),
            source,
        })?;
    staged.commit()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replaces_whole_and_leaves_no_temporary() {
        let dir = tempfile::tempdir().expect("a scratch directory");
        let target = dir.path().join("out.map");
        std::fs::write(&target, b"old").expect("the old file");
        write_replacing(&target, b"new contents").expect("written");
        assert_eq!(std::fs::read(&target).expect("read back"), b"new contents");
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .expect("listed")
            .map(|e| e.expect("entry").file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("out.map")]);
    }

    #[test]
    fn a_dropped_output_leaves_the_target_as_it_was() {
        let dir = tempfile::tempdir().expect("a scratch directory");
        let target = dir.path().join("trace.csv");
        std::fs::write(&target, b"earlier run").expect("the old file");
        let mut staged = Staged::create(&target).expect("staged");
        staged.writer().write_all(b"half a run").expect("written");
        drop(staged);
        assert_eq!(std::fs::read(&target).expect("read back"), b"earlier run");
        assert_eq!(std::fs::read_dir(dir.path()).expect("listed").count(), 1);
    }

    #[test]
    fn a_missing_directory_is_named() {
        let dir = tempfile::tempdir().expect("a scratch directory");
        let target = dir.path().join("no-such-dir").join("out.map");
        let e = write_replacing(&target, b"x").expect_err("no directory");
        assert!(matches!(e, WriteError::Create { .. }), "{e:?}");
        let message = e.message();
        assert!(
            message.starts_with(&format!(
                "cannot write {}: cannot create a file in ",
                target.display()
            )),
            "{message}"
        );
        assert_eq!(e.io().kind(), std::io::ErrorKind::NotFound);
    }
}
