//! Shading normals: one normal per triangle corner, smooth across gentle bends and sharp
//! across creases, for force shading (the normal interpolated with barycentric weights
//! makes a coarse mesh feel smooth, while CAD edges stay edges).

use glam::DVec3;
use rayon::prelude::*;

use super::frame::TriFrame;

/// Default crease angle, radians (30°): where two faces meet at a sharper angle than this,
/// their normals are not blended, so the edge is felt as an edge.
pub const DEFAULT_CREASE_ANGLE_RAD: f64 = std::f64::consts::PI / 6.0;

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
) -> Vec<[DVec3; 3]> {
    let cos_crease = crease_angle_rad.clamp(0.0, std::f64::consts::PI).cos();
    let corner_angle = |s: usize, v: u32| -> f64 {
        let tri = triangles[s];
        let i = tri.iter().position(|&w| w == v).unwrap_or(0);
        let p = vertices[tri[i] as usize];
        let e1 = vertices[tri[(i + 1) % 3] as usize] - p;
        let e2 = vertices[tri[(i + 2) % 3] as usize] - p;
        e1.angle_between(e2)
    };
    triangles
        .par_iter()
        .enumerate()
        .map(|(t, tri)| {
            let n_t = frames[t].normal;
            if n_t == DVec3::ZERO {
                return [DVec3::ZERO; 3];
            }
            tri.map(|v| {
                let sum: DVec3 = fan(v)
                    .iter()
                    .map(|&s| s as usize)
                    .filter(|&s| frames[s].normal.dot(n_t) >= cos_crease || s == t)
                    .map(|s| corner_angle(s, v) * frames[s].normal)
                    .sum();
                sum.try_normalize().unwrap_or(n_t)
            })
        })
        .collect()
}
