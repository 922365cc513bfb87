//! Shading normals: one normal per triangle corner, smooth across gentle bends and sharp
//! across creases, for force shading (the normal interpolated with barycentric weights
//! makes a coarse mesh feel smooth, while CAD edges stay edges).

use glam::DVec3;
use rayon::prelude::*;

use super::frame::TriFrame;

/// Default crease angle, radians (30°): where two faces meet at a sharper angle than this,
/// their normals are not blended, so the edge is felt as an edge.
pub const DEFAULT_CREASE_ANGLE_RAD: f64 = std::f64::consts::PI / 6.0;

/// The shading normals of a triangle's three corners, single precision (36 bytes a
/// triangle instead of 72: a force direction needs far less than the 1e-7 that keeps).
pub(crate) type CornerNormals = [[f32; 3]; 3];

/// Corner normals: for corner `i` of triangle `t` at vertex `v`, the angle-weighted average
/// of the face normals of the triangles around `v` that bend less than `crease_angle_rad`
/// from `t` (always including `t` itself). Unit length; a degenerate triangle gets zeros.
///
/// `fan(v)` lists the triangles around vertex `v`.
pub(crate) fn corner_normals<'a>(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    frames: &[TriFrame],
    fan: impl Fn(u32) -> &'a [u32] + Sync,
    crease_angle_rad: f64,
) -> Vec<CornerNormals> {
    let cos_crease = crease_angle_rad.clamp(0.0, std::f64::consts::PI).cos();
    // Face normals and corner angles once, compactly: the loop below visits each triangle
    // once per corner of each of its neighbours around a vertex.
    let normal: Vec<DVec3> = frames.par_iter().map(|f| f.normal).collect();
    let angle: Vec<[f64; 3]> = triangles
        .par_iter()
        .map(|tri| {
            let p = tri.map(|v| vertices[v as usize]);
            [0, 1, 2].map(|i| (p[(i + 1) % 3] - p[i]).angle_between(p[(i + 2) % 3] - p[i]))
        })
        .collect();
    triangles
        .par_iter()
        .enumerate()
        .map(|(t, tri)| {
            let n_t = normal[t];
            if n_t == DVec3::ZERO {
                return [[0.0; 3]; 3];
            }
            tri.map(|v| {
                let sum: DVec3 = fan(v)
                    .iter()
                    .map(|&s| s as usize)
                    .filter(|&s| s == t || normal[s].dot(n_t) >= cos_crease)
                    .map(|s| {
                        let i = triangles[s].iter().position(|&w| w == v).unwrap_or(0);
                        angle[s][i] * normal[s]
                    })
                    .sum();
                sum.try_normalize().unwrap_or(n_t).as_vec3().to_array()
            })
        })
        .collect()
}
