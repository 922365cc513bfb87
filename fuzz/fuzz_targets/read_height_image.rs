//! Fuzzes the height-image reader: any bytes give an image or an error, never a panic,
//! and an image's samples are finite heights from 0 to 1.
#![no_main]

use haphe::scene::HeightImage;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    if let Ok(image) = HeightImage::from_png("fuzz.png", bytes) {
        assert!(image.values().iter().all(|v| (0.0..=1.0).contains(v)));
    }
});
