//! Fuzzes format detection and whichever reader it picks; no file name hint, so the
//! content alone decides.
#![no_main]

use haphe::mesh::{ReadOptions, read_mesh};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let _ = read_mesh("fuzz", bytes, &ReadOptions::default());
});
