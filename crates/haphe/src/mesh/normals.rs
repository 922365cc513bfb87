//! Shading normals: one normal per triangle corner, smooth across gentle bends and sharp
//! across creases, for force shading (the normal interpolated with barycentric weights
//! makes a coarse mesh feel smooth, while CAD edges stay edges).

use crate::par::*;
use glam::DVec3;

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
    // Face normals and corner angles once, compactly: the loop below visits each triangle
    // once per corner of each of its neighbours around a vertex.
    let normal: Vec<DVec3> = frames.par_iter().map(|f| f.normal).collect();
    let angle: Vec<[f64; 3]> = triangles
        .par_iter()
        .map(|&tri| corner_angles(tri.map(|v| vertices[v as usize])))
        .collect();
    let rule = Rule {
        triangles,
        normal: |s: usize| normal[s],
        angle: |s: usize, i: usize| angle[s][i],
        crease: Crease::new(crease_angle_rad),
    };
    let smooth: Vec<Option<DVec3>> = (0..vertices.len() as u32)
        .into_par_iter()
        .map(|v| rule.smooth_sum(fan(v), v))
        .collect();
    triangles
        .par_iter()
        .enumerate()
        .map(|(t, tri)| tri.map(|v| rule.corner(t, v, smooth[v as usize], fan(v))))
        .collect()
}

/// Recomputes, in `normals`, the corners at each vertex of `at` (every triangle of its
/// fan), after the vertices or frames around them changed: what [`corner_normals`] gives
/// there, bit for bit.
pub(super) fn refresh_corner_normals<'a>(
    vertices: &[DVec3],
    triangles: &[[u32; 3]],
    frames: &[TriFrame],
    fan: impl Fn(u32) -> &'a [u32],
    crease_angle_rad: f64,
    (at, normals): (&[u32], &mut [CornerNormals]),
) {
    let rule = Rule {
        triangles,
        normal: |s: usize| frames[s].normal,
        angle: |s: usize, i: usize| corner_angles(triangles[s].map(|v| vertices[v as usize]))[i],
        crease: Crease::new(crease_angle_rad),
    };
    for &v in at {
        let around = fan(v);
        let smooth = rule.smooth_sum(around, v);
        for &s in around {
            let s = s as usize;
            let i = corner_of(triangles[s], v);
            normals[s][i] = rule.corner(s, v, smooth, around);
        }
    }
}

/// The angles of a triangle at its three corners.
fn corner_angles(p: [DVec3; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| (p[(i + 1) % 3] - p[i]).angle_between(p[(i + 2) % 3] - p[i]))
}

/// Which corner of `tri` is at vertex `v` (0 when none is).
fn corner_of(tri: [u32; 3], v: u32) -> usize {
    tri.iter().position(|&w| w == v).unwrap_or(0)
}

/// The crease angle's cosines.
#[derive(Clone, Copy)]
struct Crease {
    /// Two faces bending less than the crease angle blend.
    cos_crease: f64,
    /// Every face around a smooth vertex lies within this of their mean direction.
    cos_half: f64,
}

impl Crease {
    fn new(crease_angle_rad: f64) -> Crease {
        let crease = crease_angle_rad.clamp(0.0, std::f64::consts::PI);
        // A vertex whose faces all lie within half the crease angle of one direction has
        // no crease: every pair of its faces passes the crease test, so every corner there
        // gets the same sum, added in the same order, and it is computed once. The margin
        // keeps the rounding of the dot products from deciding; so does the lower bound on
        // the crease angle (below it, every vertex takes the crease test).
        let cos_half = if crease >= SMOOTH_MIN_CREASE_RAD {
            (0.5 * crease - SMOOTH_MARGIN_RAD).cos()
        } else {
            f64::INFINITY
        };
        Crease {
            cos_crease: crease.cos(),
            cos_half,
        }
    }
}

/// The rule of [`corner_normals`], over face normals and corner angles however they are
/// found.
struct Rule<'a, N, A> {
    triangles: &'a [[u32; 3]],
    normal: N,
    angle: A,
    crease: Crease,
}

impl<N: Fn(usize) -> DVec3, A: Fn(usize, usize) -> f64> Rule<'_, N, A> {
    /// The angle-weighted sum of the face normals around `v`, when `v` is smooth.
    fn smooth_sum(&self, around: &[u32], v: u32) -> Option<DVec3> {
        let sum: DVec3 = around
            .iter()
            .map(|&s| s as usize)
            .map(|s| (self.angle)(s, corner_of(self.triangles[s], v)) * (self.normal)(s))
            .sum();
        let axis = sum.try_normalize()?;
        around
            .iter()
            .all(|&s| (self.normal)(s as usize).dot(axis) >= self.crease.cos_half)
            .then_some(sum)
    }

    /// The normal of triangle `t`'s corner at `v` (`smooth`: [`Rule::smooth_sum`] at `v`).
    fn corner(&self, t: usize, v: u32, smooth: Option<DVec3>, around: &[u32]) -> [f32; 3] {
        let n_t = (self.normal)(t);
        if n_t == DVec3::ZERO {
            return [0.0; 3];
        }
        let sum = smooth.unwrap_or_else(|| {
            around
                .iter()
                .map(|&s| s as usize)
                .filter(|&s| s == t || (self.normal)(s).dot(n_t) >= self.crease.cos_crease)
                .map(|s| (self.angle)(s, corner_of(self.triangles[s], v)) * (self.normal)(s))
                .sum()
        });
        sum.try_normalize().unwrap_or(n_t).as_vec3().to_array()
    }
}

/// How far inside half the crease angle (radians) every face around a vertex must lie for
/// [`corner_normals`] to take the vertex as smooth: far above the rounding of a unit
/// normal's dot product (about `1e-15`), far below any crease angle a user sets.
const SMOOTH_MARGIN_RAD: f64 = 1e-6;

/// The smallest crease angle (radians) for which [`corner_normals`] looks for smooth
/// vertices: there two faces `SMOOTH_MARGIN_RAD` inside it pass the crease test by a
/// margin (about `1e-9` in the cosine) far above rounding.
const SMOOTH_MIN_CREASE_RAD: f64 = 1e-3;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes::Catalog;
    use crate::mesh::{Surface, SurfaceOptions};

    /// The rule as documented, corner by corner, with no shortcut.
    fn plain(surface: &Surface, crease_angle_rad: f64) -> Vec<CornerNormals> {
        let cos_crease = crease_angle_rad.clamp(0.0, std::f64::consts::PI).cos();
        let (vertices, triangles) = (surface.vertices(), surface.triangles());
        let normal = |s: usize| surface.frame(crate::mesh::TriId(s as u32)).normal;
        let angle = |s: usize, v: u32| {
            let p = triangles[s].map(|w| vertices[w as usize]);
            let i = triangles[s].iter().position(|&w| w == v).unwrap_or(0);
            (p[(i + 1) % 3] - p[i]).angle_between(p[(i + 2) % 3] - p[i])
        };
        (0..triangles.len())
            .map(|t| {
                let n_t = normal(t);
                if n_t == DVec3::ZERO {
                    return [[0.0; 3]; 3];
                }
                triangles[t].map(|v| {
                    let sum: DVec3 = surface
                        .fan(crate::mesh::VertId(v))
                        .iter()
                        .map(|&s| s as usize)
                        .filter(|&s| s == t || normal(s).dot(n_t) >= cos_crease)
                        .map(|s| angle(s, v) * normal(s))
                        .sum();
                    sum.try_normalize().unwrap_or(n_t).as_vec3().to_array()
                })
            })
            .collect()
    }

    #[test]
    fn smooth_vertices_get_what_the_rule_gives_bit_for_bit() {
        let shapes = [
            Catalog::Blob,
            Catalog::Sphere,
            Catalog::Box,
            Catalog::Torus,
            Catalog::ThinPlate,
            Catalog::ConcaveCorner,
        ];
        for shape in shapes {
            for crease_deg in [0.0, 1e-5, 5.0, 30.0, 60.0, 89.0, 120.0, 180.0] {
                let crease = f64::to_radians(crease_deg);
                let options = SurfaceOptions {
                    crease_angle_rad: crease,
                    ..SurfaceOptions::default()
                };
                let surface = Surface::new(shape.with_triangles(3000), &options).expect("valid");
                let expected = plain(&surface, crease);
                let got: Vec<CornerNormals> = (0..surface.triangle_count())
                    .map(|t| {
                        surface
                            .corner_normals(crate::mesh::TriId(t as u32))
                            .map(|n| n.as_vec3().to_array())
                    })
                    .collect();
                assert_eq!(got, expected, "{shape} at a crease of {crease_deg}°");
            }
        }
    }
}
