//! The torus: a tube around a ring, a grid of quadrilaterals in the two angles.

use std::f64::consts::TAU;

use glam::DVec3;

use super::length::is_positive_length;
use crate::mesh::Mesh;

/// Fewest segments [`torus`] uses around the ring and around the tube; fewer are clamped
/// up (with two, opposite grid lines would join the same two vertices twice).
pub const MIN_TORUS_SEGMENTS: u32 = 3;

/// Most segments [`torus`] uses around the ring and around the tube; more are clamped
/// (2·32768² ≈ 2.1 billion triangles).
pub const MAX_TORUS_SEGMENTS: u32 = 32768;

/// A torus around the z axis, centred on the origin (object frame): the circle of radius
/// `major_radius` metres in the xy plane swept by a tube of radius `minor_radius` metres,
/// so it spans `2·(major_radius + minor_radius)` across and `2·minor_radius` in z.
///
/// The surface is a grid of `major_segments` steps around the z axis by `minor_segments`
/// steps around the tube, each cell split into two triangles: `2·major·minor` triangles
/// and `major·minor` vertices, every vertex on the torus. Vertex `i·minor_segments + j`
/// is at ring angle `2π·i/major_segments` (from +x toward +y) and tube angle
/// `2π·j/minor_segments` (from outward toward +z). Its Euler characteristic is 0.
///
/// Segment counts are clamped into
/// [`MIN_TORUS_SEGMENTS`]`..=`[`MAX_TORUS_SEGMENTS`]. Radii that are not finite and
/// positive, or a `minor_radius` not below `major_radius` (the tube would cross itself at
/// the axis), give an empty mesh.
///
/// # Examples
/// ```
/// use haphe::mesh::shapes::torus;
/// let ring = torus(0.07, 0.03, 24, 12);
/// assert_eq!(ring.triangles.len(), 2 * 24 * 12);
/// assert_eq!(ring.vertices.len(), 24 * 12);
/// assert!(torus(0.03, 0.07, 24, 12).triangles.is_empty());
/// ```
pub fn torus(
    major_radius: f64,
    minor_radius: f64,
    major_segments: u32,
    minor_segments: u32,
) -> Mesh {
    let valid = is_positive_length(major_radius)
        && is_positive_length(minor_radius)
        && minor_radius < major_radius
        && is_positive_length(major_radius + minor_radius);
    if !valid {
        return Mesh::default();
    }
    let ring_steps = major_segments.clamp(MIN_TORUS_SEGMENTS, MAX_TORUS_SEGMENTS) as usize;
    let tube_steps = minor_segments.clamp(MIN_TORUS_SEGMENTS, MAX_TORUS_SEGMENTS) as usize;
    let sin_cos = |step: usize, steps: usize| (TAU * step as f64 / steps as f64).sin_cos();
    let tube: Vec<(f64, f64)> = (0..tube_steps).map(|j| sin_cos(j, tube_steps)).collect();

    let mut vertices = Vec::with_capacity(ring_steps * tube_steps);
    for i in 0..ring_steps {
        let (sin_ring, cos_ring) = sin_cos(i, ring_steps);
        for &(sin_tube, cos_tube) in &tube {
            let distance_from_axis = major_radius + minor_radius * cos_tube;
            vertices.push(DVec3::new(
                distance_from_axis * cos_ring,
                distance_from_axis * sin_ring,
                minor_radius * sin_tube,
            ));
        }
    }

    // ∂p/∂ring × ∂p/∂tube is the outward normal, so the cell (i, j) → (i+1, j) →
    // (i+1, j+1) → (i, j+1) is counter-clockwise seen from outside.
    let mut triangles = Vec::with_capacity(2 * ring_steps * tube_steps);
    let index = |i: usize, j: usize| ((i % ring_steps) * tube_steps + j % tube_steps) as u32;
    for i in 0..ring_steps {
        for j in 0..tube_steps {
            let p00 = index(i, j);
            let p10 = index(i + 1, j);
            let p11 = index(i + 1, j + 1);
            let p01 = index(i, j + 1);
            triangles.push([p00, p10, p11]);
            triangles.push([p00, p11, p01]);
        }
    }
    Mesh {
        vertices,
        triangles,
    }
}
