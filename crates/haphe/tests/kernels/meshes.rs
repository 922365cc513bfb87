//! Closed test meshes with their adjacency, brute-force segment hits and the generalised
//! winding number, written from scratch for these tests.

use std::collections::HashMap;
use std::f64::consts::PI;
use std::sync::OnceLock;

use haphe::DVec3;
use haphe::mesh::Mesh;
use haphe::mesh::shapes::{blob, concave_corner, cuboid, geodesic_sphere, sphere, torus};
use haphe::query::{Segment, SegmentHit, intersect_segment_triangle};

/// A closed mesh with the triangles around each vertex and on each edge.
pub struct Solid {
    pub name: &'static str,
    pub mesh: Mesh,
    /// Whether the solid is convex.
    pub convex: bool,
    /// Whether every vertex coordinate is a dyadic rational with few bits, so that sums and
    /// halvings of coordinates stay exact.
    pub dyadic: bool,
    /// Triangles using each vertex.
    pub fans: Vec<Vec<usize>>,
    /// The two triangles of each undirected edge `(low, high)`.
    pub edges: HashMap<(u32, u32), Vec<usize>>,
}

impl Solid {
    fn new(name: &'static str, mesh: Mesh, convex: bool, dyadic: bool) -> Solid {
        let mut fans = vec![Vec::new(); mesh.vertices.len()];
        let mut edges: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
        for (t, &[a, b, c]) in mesh.triangles.iter().enumerate() {
            for v in [a, b, c] {
                fans[v as usize].push(t);
            }
            for (p, q) in [(a, b), (b, c), (c, a)] {
                edges.entry((p.min(q), p.max(q))).or_default().push(t);
            }
        }
        assert!(
            edges.values().all(|ts| ts.len() == 2),
            "{name} is not closed"
        );
        Solid {
            name,
            mesh,
            convex,
            dyadic,
            fans,
            edges,
        }
    }

    /// Every hit of `segment` over all triangles, with the triangle index.
    pub fn hits(&self, segment: &Segment) -> Vec<(usize, SegmentHit)> {
        (0..self.mesh.triangles.len())
            .filter_map(|t| {
                intersect_segment_triangle(segment, self.mesh.corners(t)).map(|h| (t, h))
            })
            .collect()
    }

    /// Generalised winding number of `p`, rounded: 1 inside, 0 outside.
    pub fn winding(&self, p: DVec3) -> i64 {
        let total: f64 = (0..self.mesh.triangles.len())
            .map(|t| solid_angle(self.mesh.corners(t), p))
            .sum();
        (total / (4.0 * PI)).round() as i64
    }

    /// Distance from `p` to the surface, metres (brute force).
    pub fn distance(&self, p: DVec3) -> f64 {
        (0..self.mesh.triangles.len())
            .map(|t| {
                (haphe::query::closest_point_triangle(p, self.mesh.corners(t)).point - p).length()
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Outward unit normal of triangle `t`.
    pub fn normal(&self, t: usize) -> DVec3 {
        let [a, b, c] = self.mesh.corners(t);
        (b - a).cross(c - a).normalize()
    }
}

/// Signed count of hits (entering +1, leaving −1).
pub fn signed(hits: &[(usize, SegmentHit)]) -> i64 {
    hits.iter()
        .map(|(_, h)| if h.entering { 1 } else { -1 })
        .sum()
}

/// Signed solid angle of triangle `[a, b, c]` seen from `p` (Van Oosterom and Strackee),
/// positive when `p` is behind the triangle: a closed outward surface sums to 4π inside.
fn solid_angle([a, b, c]: [DVec3; 3], p: DVec3) -> f64 {
    let (a, b, c) = (a - p, b - p, c - p);
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let numerator = a.dot(b.cross(c));
    let denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    2.0 * numerator.atan2(denominator)
}

/// The closed meshes the watertightness tests run on, about 0.1–0.5 m across, built once.
pub fn solids() -> &'static [Solid] {
    static SOLIDS: OnceLock<Vec<Solid>> = OnceLock::new();
    SOLIDS.get_or_init(|| {
        vec![
            Solid::new("sphere", sphere(0.1, 2), true, false),
            Solid::new("geodesic sphere", geodesic_sphere(0.07, 5), true, false),
            // Half extents and divisions that are powers of two: every lattice point is exact.
            Solid::new(
                "dyadic box",
                cuboid(DVec3::new(0.25, 0.125, 0.0625), [4, 2, 8]),
                true,
                true,
            ),
            Solid::new(
                "box",
                cuboid(DVec3::new(0.1, 0.07, 0.03), [3, 5, 7]),
                true,
                false,
            ),
            Solid::new("concave corner", concave_corner(0.25, 2), false, true),
            Solid::new("torus", torus(0.07, 0.03, 24, 12), false, false),
            Solid::new("blob", blob(0.1, 2, 0.03, 11), false, false),
            Solid::new("pocket", pocket(), false, true),
            Solid::new("slanted pocket", slanted(pocket()), false, true),
        ]
    })
}

/// The unit cube (metres) with a pocket `[0.25, 0.75] × [0.25, 0.75] × [0.5, 1]` cut from its top:
/// the pocket's walls are perpendicular to its floor and to the top face.
pub fn pocket() -> Mesh {
    // Vertices on the lattice {0, 0.25, 0.75, 1} × {0, 0.25, 0.75, 1} × {0, 0.5, 1}: the
    // solid is the union of unit-lattice boxes, triangulated face by face.
    let xs = [0.0, 0.25, 0.75, 1.0];
    let zs = [0.0, 0.5, 1.0];
    let filled = |i: usize, j: usize, k: usize| !(i == 1 && j == 1 && k == 1);
    let mut vertices = Vec::new();
    let mut index = HashMap::new();
    let mut vertex = |p: [usize; 3], vertices: &mut Vec<DVec3>| -> u32 {
        *index.entry(p).or_insert_with(|| {
            vertices.push(DVec3::new(xs[p[0]], xs[p[1]], zs[p[2]]));
            (vertices.len() - 1) as u32
        })
    };
    let mut triangles = Vec::new();
    let inside = |i: isize, j: isize, k: isize| {
        (0..3).contains(&i)
            && (0..3).contains(&j)
            && (0..2).contains(&k)
            && filled(i as usize, j as usize, k as usize)
    };
    for i in 0..3isize {
        for j in 0..3isize {
            for k in 0..2isize {
                if !inside(i, j, k) {
                    continue;
                }
                // The six faces of box (i, j, k) that border empty space, wound outward.
                for (axis, sign) in [(0, 1), (0, -1), (1, 1), (1, -1), (2, 1), (2, -1)] {
                    let mut n = [i, j, k];
                    n[axis] += sign;
                    if inside(n[0], n[1], n[2]) {
                        continue;
                    }
                    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                    let base = |du: usize, dv: usize| {
                        let mut c = [i as usize, j as usize, k as usize];
                        if sign > 0 {
                            c[axis] += 1;
                        }
                        c[u] += du;
                        c[v] += dv;
                        c
                    };
                    let q = [base(0, 0), base(1, 0), base(1, 1), base(0, 1)]
                        .map(|c| vertex(c, &mut vertices));
                    if sign > 0 {
                        triangles.push([q[0], q[1], q[2]]);
                        triangles.push([q[0], q[2], q[3]]);
                    } else {
                        triangles.push([q[0], q[2], q[1]]);
                        triangles.push([q[0], q[3], q[2]]);
                    }
                }
            }
        }
    }
    Mesh {
        vertices,
        triangles,
    }
}

/// `mesh` under a linear map with small dyadic entries and positive determinant: still
/// exact (a few more bits per coordinate), but no face is axis-aligned any more, so the
/// shear of a segment in a face's plane rounds.
pub fn slanted(mut mesh: Mesh) -> Mesh {
    for v in &mut mesh.vertices {
        *v = slant(*v);
    }
    mesh
}

/// The map of [`slanted`], on one point.
pub fn slant(p: DVec3) -> DVec3 {
    let m = [[1.0, 0.5, 0.25], [0.125, 1.0, 0.5], [0.25, 0.375, 1.0]];
    DVec3::new(
        m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z,
        m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z,
        m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z,
    )
}
