//! Fuzzes scene files: any text gives checked objects or an error naming the file, never a
//! panic or a hang; every object read has a finite pose, a usable material and motion, and
//! a unique id.
#![no_main]

use std::path::Path;

use haphe::servo::scene_file::{MAX_OBJECTS, parse_scene};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return;
    };
    let entries = match parse_scene(Path::new("fuzz.toml"), text) {
        Ok(entries) => entries,
        Err(e) => {
            assert!(e.message.starts_with("fuzz.toml: "), "{}", e.message);
            return;
        }
    };
    assert!(!entries.is_empty() && entries.len() <= MAX_OBJECTS);
    for (i, entry) in entries.iter().enumerate() {
        assert!(entry.pose.translation().is_finite() && entry.pose.rotation().is_finite());
        assert_eq!(entry.material.to_builder().build(), Ok(entry.material));
        if let Some(motion) = &entry.motion {
            assert_eq!(motion.id, entry.id);
            assert!(motion.motion.checked().is_ok());
        }
        assert!(entries[..i].iter().all(|e| e.id != entry.id));
    }
});
