//! Fuzzes loading a saved map: any bytes are refused with an error or loaded into a
//! surface and map that every lookup can trust; never a panic.
#![no_main]

use haphe::DVec3;
use haphe::map::decode;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    if let Ok((surface, map)) = decode(bytes) {
        // Whatever loads must answer lookups anywhere without panicking.
        let dims = map.grid().dims();
        for c in [[0, 0, 0], dims, [dims[0] / 2, dims[1] / 2, dims[2] / 2]] {
            let _ = (map.state(c), map.clearance(c), map.triangles_in(c));
        }
        let _ = haphe::query::classify_point(&surface, &map, DVec3::ZERO);
    }
});
