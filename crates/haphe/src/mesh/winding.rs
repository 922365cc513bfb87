//! Solid angles and the generalised winding number: the one definition of inside that every
//! stage shares (the non-zero rule: a point is inside when its winding number is not 0).

use crate::par::*;
use glam::DVec3;

use super::solid_angle::solid_angle;
use super::{Surface, TriId};

/// Triangles per parallel task in a winding number (fixed, so that the sum does not depend
/// on the number of threads).
const WINDING_CHUNK: usize = 4096;

/// Generalised winding number of `p` with respect to the surface: the sum of the
/// triangles' signed [`solid_angle`]s over 4π. About 1 inside a closed outward-oriented
/// part, 2 where two such parts overlap, −1 inside an inside-out part, 0 outside and in a
/// cavity; fractional near holes. Under the non-zero rule `p` is inside when the rounded
/// value is not 0. Summed in fixed chunks (in parallel), then in order: deterministic.
///
/// # Performance
/// `O(n)`: for building a map, tests and verification, never for a tick.
pub fn winding_number(surface: &Surface, p: DVec3) -> f64 {
    let count = surface.triangle_count() as u32;
    let partial: Vec<f64> = (0..count.div_ceil(WINDING_CHUNK as u32))
        .into_par_iter()
        .map(|chunk| {
            let start = chunk * WINDING_CHUNK as u32;
            (start..(start + WINDING_CHUNK as u32).min(count))
                .map(|t| solid_angle(surface.corners(TriId(t)), p))
                .sum::<f64>()
        })
        .collect();
    partial.iter().sum::<f64>() / (4.0 * std::f64::consts::PI)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Mesh, SurfaceOptions, shapes};

    #[test]
    fn overlapping_parts_add_and_an_inside_out_part_counts_minus_one() {
        let a = shapes::cuboid(DVec3::splat(0.01), [2, 2, 2]);
        let mut mesh = Mesh {
            vertices: a.vertices.clone(),
            triangles: a.triangles.clone(),
        };
        let shift = DVec3::new(0.01, 0.0, 0.0);
        let n = mesh.vertices.len() as u32;
        mesh.vertices.extend(a.vertices.iter().map(|&v| v + shift));
        mesh.triangles
            .extend(a.triangles.iter().map(|t| t.map(|v| v + n)));
        let surface = Surface::new(mesh, &SurfaceOptions::default()).unwrap();
        let w = |x: f64| winding_number(&surface, DVec3::new(x, 0.001, 0.002));
        assert!((w(0.005) - 2.0).abs() < 1e-9, "{}", w(0.005));
        assert!((w(-0.008) - 1.0).abs() < 1e-9, "{}", w(-0.008));
        assert!(w(0.05).abs() < 1e-9, "{}", w(0.05));
        let inverted = Mesh {
            vertices: a.vertices.clone(),
            triangles: a.triangles.iter().map(|&[x, y, z]| [x, z, y]).collect(),
        };
        let inverted = Surface::new(inverted, &SurfaceOptions::default()).unwrap();
        assert!((winding_number(&inverted, DVec3::ZERO) + 1.0).abs() < 1e-9);
    }
}
