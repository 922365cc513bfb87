//! Opening a saved map file in place: the file is mapped into memory, so loading it copies
//! nothing (the checksum and the checks read it once, from the page cache).
//!
//! This is the one place where the binary uses `unsafe`:
//! mapping a file is `unsafe` because the program would see the file change if another
//! program modified it while mapped. `haphe build` never writes over an existing map file
//! in place (it writes a new file and renames it over the old one, so a running reader
//! keeps the old contents), which is the discipline the safety argument relies on.
#![allow(unsafe_code)]

use haphe::map::MapBytes;
use std::fs::File;

/// The bytes of the open map file `file`, mapped read-only and prefaulted.
///
/// # Errors
/// When the file cannot be mapped.
pub fn map_file(file: &File) -> std::io::Result<MapBytes> {
    // SAFETY: the mapping is read-only and private to this process; map files are
    // replaced by renaming a new file over them, never rewritten in place (see the module
    // documentation), so the mapped bytes do not change while haphe uses them. Everything
    // read from them is checked (checksum, then invariants) before use.
    let map = unsafe { memmap2::MmapOptions::new().populate().map(file) }?;
    Ok(MapBytes::from_mmap(map))
}
