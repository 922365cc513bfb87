//! Fuzzes the glTF reader: any bytes give a scene or an error, never a panic, a hang or an
//! allocation beyond the reader's limits. Side-car files are answered with the input's
//! own bytes, so buffers of every length reach the accessor checks; a scene read is then
//! flattened and split into objects, as the front ends do.
#![no_main]

use haphe::mesh::{Resolve, Units, read_gltf};
use haphe::scene::gltf_objects;
use libfuzzer_sys::fuzz_target;

struct Echo<'a>(&'a [u8]);

impl Resolve for Echo<'_> {
    fn resolve(&mut self, uri: &str, byte_length: u64) -> Result<Vec<u8>, String> {
        if uri.len() % 2 == 1 {
            return Err("absent".to_owned());
        }
        let n = self.0.len().min(usize::try_from(byte_length).unwrap_or(usize::MAX));
        Ok(self.0[..n].to_vec())
    }
}

fuzz_target!(|bytes: &[u8]| {
    if let Ok(scene) = read_gltf("fuzz.gltf", bytes, Units::Metres, &mut Echo(bytes)) {
        let mesh = scene.flatten();
        let count = mesh.vertices.len();
        assert!(mesh.triangles.iter().flatten().all(|&i| (i as usize) < count));
        let _ = gltf_objects(&scene);
    }
});
