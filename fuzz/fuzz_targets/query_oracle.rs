//! Fuzzes the collision core against its brute-force oracles: a procedural closed mesh
//! chosen and jittered by the input (the jitter moves vertices radially, which keeps the
//! mesh closed and embedded), then segments and points from the input. Every first
//! crossing must equal the one found by testing every triangle, every segment from outside
//! to inside must report a crossing, and inside/outside must match the winding number.
#![no_main]

use haphe::DVec3;
use haphe::map::{MapOptions, VoxelMap};
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::query::{Side, classify_point, first_crossing, first_crossing_brute_force};
use haphe::verify::WindingOracle;
use libfuzzer_sys::fuzz_target;

/// Reads a coordinate in [-0.15, 0.15] m (the shapes are about 0.2 m across) from 2 bytes;
/// small integers on a grid of 1/4096 of the range, so inputs hit vertices and edges of
/// axis-aligned shapes exactly.
fn coordinate(bytes: &[u8]) -> f64 {
    let v = u16::from_le_bytes([bytes[0], bytes[1]]);
    (f64::from(v) / 65535.0 - 0.5) * 0.3
}

fn point(bytes: &[u8]) -> DVec3 {
    DVec3::new(coordinate(&bytes[0..2]), coordinate(&bytes[2..4]), coordinate(&bytes[4..6]))
}

fuzz_target!(|bytes: &[u8]| {
    if bytes.len() < 4 {
        return;
    }
    let shape = Catalog::ALL[bytes[0] as usize % Catalog::ALL.len()];
    let triangles = 20 + 40 * usize::from(bytes[1] % 16);
    let mut mesh = shape.with_triangles(triangles);
    // A radial jitter of at most 2% keeps star-shaped and box-like shapes embedded.
    let jitter = f64::from(bytes[2]) / 255.0 * 0.02;
    for (i, p) in mesh.vertices.iter_mut().enumerate() {
        let k = bytes[3 + i % (bytes.len() - 3)];
        *p *= 1.0 + jitter * (f64::from(k) / 255.0 - 0.5);
    }
    let Ok(surface) = Surface::new(mesh, &SurfaceOptions::default()) else {
        return;
    };
    let Ok(map) = VoxelMap::build(&surface, &MapOptions::default()) else {
        return;
    };
    let oracle = WindingOracle::new(&surface);
    let solid = surface.is_solid();
    for chunk in bytes[3..].chunks_exact(12) {
        let (p0, p1) = (point(&chunk[0..6]), point(&chunk[6..12]));
        let fast = first_crossing(&surface, &map, p0, p1);
        let brute = first_crossing_brute_force(&surface, p0, p1);
        assert_eq!(
            fast.map(|c| (c.triangle, c.t.to_bits())),
            brute.map(|c| (c.triangle, c.t.to_bits())),
            "{shape} segment {p0} -> {p1}"
        );
        if solid {
            let (w0, w1) = (oracle.winding(p0), oracle.winding(p1));
            if (w0 == 0) != (w1 == 0) {
                assert!(fast.is_some(), "{shape}: leak through {p0} -> {p1}");
            }
            for (p, w) in [(p0, w0), (p1, w1)] {
                let (side, _) = classify_point(&surface, &map, p);
                // Points on the surface may go either way; the oracle's ray decides them
                // by its own tie-break, so compare only where the two rays agree.
                let on_surface = haphe::verify::distance_to_surface(&surface, p) <= 1e-9;
                if !on_surface {
                    assert_eq!(side == Side::Inside, w != 0, "{shape}: point {p}");
                }
            }
        }
    }
});
