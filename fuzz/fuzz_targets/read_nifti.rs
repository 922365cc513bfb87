//! Fuzzes the NIfTI-1 reader: any bytes (plain or gzip) give a volume or an error, never a
//! panic, a hang or an allocation past what the bytes (decompressed within the header's
//! size) hold. The same bytes compressed are read too, so headers that pass reach the
//! gzip path.
#![no_main]

use std::io::Write;

use flate2::write::GzEncoder;
use haphe::volume::Volume;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let _ = Volume::read_nifti("fuzz.nii", bytes, 0.5);
    let mut gz = GzEncoder::new(Vec::new(), flate2::Compression::fast());
    if gz.write_all(bytes).is_ok() {
        if let Ok(compressed) = gz.finish() {
            let _ = Volume::read_nifti("fuzz.nii.gz", &compressed, 0.5);
        }
    }
});
