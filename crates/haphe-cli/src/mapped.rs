//! Opening a saved map file in place: the file is mapped into memory, so loading it copies
//! nothing (the checksum and the checks read it once, from the page cache).
//!
//! This is the one place outside the counting allocator where the binary uses `unsafe`:
//! mapping a file is `unsafe` because the program would see the file change if another
//! program modified it while mapped. `haphe build` never writes over an existing map file
//! in place (it writes a new file and renames it over the old one, so a running reader
//! keeps the old contents), which is the discipline the safety argument relies on.
#![allow(unsafe_code)]

use std::fs::File;
use std::path::Path;

use anyhow::Context;
use haphe::map::MapBytes;

/// The bytes of the map file at `path`, mapped read-only and prefaulted.
///
/// # Errors
/// When the file cannot be opened or mapped.
pub fn map_file(path: &Path) -> anyhow::Result<MapBytes> {
    let file = File::open(path).with_context(|| format!("cannot open {}", path.display()))?;
    // SAFETY: the mapping is read-only and private to this process; map files are
    // replaced by renaming a new file over them, never rewritten in place (see the module
    // documentation), so the mapped bytes do not change while haphe uses them. Everything
    // read from them is checked (checksum, then invariants) before use.
    let map = unsafe { memmap2::MmapOptions::new().populate().map(&file) }
        .with_context(|| format!("cannot map {}", path.display()))?;
    Ok(MapBytes::from_mmap(map))
}

/// Writes `bytes` to `path` through a new file renamed over it, so a process that has the
/// old file mapped keeps seeing the old contents.
///
/// # Errors
/// When the temporary file cannot be written or renamed.
pub fn write_replacing(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(format!(".{}.tmp", std::process::id()));
    let temporary = path.with_file_name(name);
    std::fs::write(&temporary, bytes)
        .with_context(|| format!("cannot write {}", temporary.display()))?;
    std::fs::rename(&temporary, path).with_context(|| {
        let _ = std::fs::remove_file(&temporary);
        format!(
            "cannot rename {} to {}",
            temporary.display(),
            path.display()
        )
    })
}
