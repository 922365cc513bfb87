//! Opening input files: once, only regular files or pipes, never more than a stated size.

use std::fs::File;
use std::io::Read;
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};

/// The most bytes one kind of input may have, with the name errors give it.
#[derive(Debug, Clone, Copy)]
pub struct Limit {
    /// What the file is, for messages ("mesh file").
    pub what: &'static str,
    /// The largest size accepted, in bytes.
    pub bytes: u64,
}

const GIB: u64 = 1 << 30;
const MIB: u64 = 1 << 20;

/// Mesh files (OBJ, STL, PLY, OFF): 2 GiB.
pub const MESH: Limit = Limit {
    what: "mesh file",
    bytes: 2 * GIB,
};
/// Map files from `haphe build`: 4 GiB.
pub const MAP: Limit = Limit {
    what: "map file",
    bytes: 4 * GIB,
};
/// The object of `query` and `verify`, a mesh or a map file: 4 GiB (a mesh file is then
/// held to [`MESH`]).
pub const OBJECT: Limit = Limit {
    what: "mesh or map file",
    bytes: 4 * GIB,
};
/// Volume files (NIfTI-1, `.nii` or `.nii.gz`): 8 GiB (2^31 float32 voxels, the library's
/// `MAX_VOXELS`).
pub const VOLUME: Limit = Limit {
    what: "volume file",
    bytes: 8 * GIB,
};
/// Query CSV files: 1 GiB.
pub const CSV: Limit = Limit {
    what: "CSV file",
    bytes: GIB,
};
/// Replay traces: 1 GiB.
pub const TRACE: Limit = Limit {
    what: "trace file",
    bytes: GIB,
};
/// Scene files: 16 MiB.
pub const SCENE: Limit = Limit {
    what: "scene file",
    bytes: 16 * MIB,
};

/// An input file opened once: a regular file (its size known) or a pipe.
pub struct Input {
    /// The path as given.
    pub path: PathBuf,
    /// The open file.
    pub file: File,
    /// Whether it is a regular file (else a pipe, read once as a stream).
    pub regular: bool,
}

/// What kind of file `metadata` describes, for messages.
pub fn kind_name(file_type: std::fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if file_type.is_dir() {
        "a directory"
    } else if file_type.is_char_device() {
        "a character device"
    } else if file_type.is_block_device() {
        "a block device"
    } else if file_type.is_socket() {
        "a socket"
    } else if file_type.is_fifo() {
        "a pipe"
    } else {
        "not a regular file"
    }
}

/// Opens `path` for reading once. Directories, devices and sockets are refused (a device
/// such as `/dev/zero` never ends); a pipe is accepted and read as a stream; a regular file
/// larger than `limit` is refused before anything is read.
///
/// # Errors
/// Naming the path: it does not exist, cannot be opened, is not a regular file or a pipe,
/// or is larger than the limit.
pub fn open_input(path: &Path, limit: Limit) -> anyhow::Result<Input> {
    use std::os::unix::fs::FileTypeExt;
    let shown = path.display();
    // Checked before opening: opening a device or a directory must not block or succeed.
    let before = std::fs::metadata(path).with_context(|| format!("cannot read {shown}"))?;
    let file_type = before.file_type();
    if !(file_type.is_file() || file_type.is_fifo()) {
        bail!(
            "cannot read {shown}: it is {}; a {} must be a regular file or a pipe",
            kind_name(file_type),
            limit.what
        );
    }
    let file = File::open(path).with_context(|| format!("cannot read {shown}"))?;
    let metadata = file
        .metadata()
        .with_context(|| format!("cannot read {shown}"))?;
    let regular = metadata.file_type().is_file();
    if !regular && !metadata.file_type().is_fifo() {
        bail!(
            "cannot read {shown}: it is {}; a {} must be a regular file or a pipe",
            kind_name(metadata.file_type()),
            limit.what
        );
    }
    if regular && metadata.len() > limit.bytes {
        bail!(too_large(path, limit));
    }
    Ok(Input {
        path: path.to_owned(),
        file,
        regular,
    })
}

fn too_large(path: &Path, limit: Limit) -> String {
    format!(
        "cannot read {}: larger than the limit for a {} ({} bytes, {})",
        path.display(),
        limit.what,
        limit.bytes,
        human(limit.bytes)
    )
}

fn human(bytes: u64) -> String {
    if bytes >= GIB {
        format!("{} GiB", bytes / GIB)
    } else {
        format!("{} MiB", bytes / MIB)
    }
}

impl Input {
    /// Reads the rest of the file, refusing more than `limit` bytes (a pipe's size is not
    /// known before).
    ///
    /// # Errors
    /// A read error or the limit, naming the path.
    pub fn read_all(self, limit: Limit) -> anyhow::Result<Vec<u8>> {
        let mut bytes = Vec::new();
        self.read_rest(limit, &mut bytes)?;
        Ok(bytes)
    }

    /// Appends the rest of the file to `bytes`, which must stay within `limit` in total.
    ///
    /// # Errors
    /// As [`Input::read_all`].
    pub fn read_rest(mut self, limit: Limit, bytes: &mut Vec<u8>) -> anyhow::Result<()> {
        let room = limit.bytes.saturating_sub(bytes.len() as u64);
        (&mut self.file)
            .take(room.saturating_add(1))
            .read_to_end(bytes)
            .with_context(|| format!("cannot read {}", self.path.display()))?;
        if bytes.len() as u64 > limit.bytes {
            bail!(too_large(&self.path, limit));
        }
        Ok(())
    }
}

/// Opens and reads the whole of `path` within `limit`.
///
/// # Errors
/// As [`open_input`] and [`Input::read_all`].
pub fn read_input(path: &Path, limit: Limit) -> anyhow::Result<Vec<u8>> {
    open_input(path, limit)?.read_all(limit)
}

/// Reads a text input (UTF-8, a leading byte-order mark dropped) within `limit`.
///
/// # Errors
/// As [`read_input`], or the text is not UTF-8 (with the byte where it stops being so).
pub fn read_text(path: &Path, limit: Limit) -> anyhow::Result<String> {
    let mut bytes = read_input(path, limit)?;
    if bytes.starts_with(b"\xEF\xBB\xBF") {
        bytes.drain(..3);
    }
    String::from_utf8(bytes).map_err(|e| {
        anyhow::anyhow!(
            "{}: byte {}: not UTF-8 text",
            path.display(),
            e.utf8_error().valid_up_to()
        )
    })
}
