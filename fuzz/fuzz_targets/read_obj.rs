//! Fuzzes the OBJ reader: any bytes give a mesh or an error, never a panic or a hang.
#![no_main]

use haphe::mesh::{Format, ReadOptions, read_mesh};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let options = ReadOptions {
        format: Some(Format::Obj),
        ..Default::default()
    };
    let _ = read_mesh("fuzz.obj", bytes, &options);
});
