//! Spheres: an icosahedron whose faces are split into triangular grids, every vertex
//! projected radially onto the sphere (a geodesic polyhedron).
//!
//! Vertices are numbered so that no point is stored twice, without any lookup table: the 12
//! icosahedron corners first, then the points inside each of its 30 edges, then the points
//! inside each of its 20 faces. A face grid finds the index of a point on its border from
//! the corner or edge it lies on, so neighbouring faces share those vertices by
//! construction.

use glam::DVec3;

use super::length::is_positive_length;
use crate::mesh::Mesh;

/// Largest `subdivisions` [`sphere`] and [`blob`](super::blob) accept; larger values are
/// clamped (20·4¹³ ≈ 1.3 billion triangles).
pub const MAX_SPHERE_SUBDIVISIONS: u32 = 13;

/// Largest `frequency` [`geodesic_sphere`] and [`geodesic_blob`](super::geodesic_blob)
/// accept; larger values are clamped. Equal to `2^MAX_SPHERE_SUBDIVISIONS`.
pub const MAX_SPHERE_FREQUENCY: u32 = 1 << MAX_SPHERE_SUBDIVISIONS;

/// A sphere of `radius` metres centred on the origin (object frame): the icosahedron with
/// each face subdivided `subdivisions` times into four, `20·4^subdivisions` triangles and
/// `10·4^subdivisions + 2` vertices, every vertex exactly on the sphere (up to rounding).
///
/// Each subdivision halves every edge, so this is [`geodesic_sphere`] with frequency
/// `2^subdivisions`. The polyhedron is inscribed: its volume and area are slightly below
/// those of the sphere.
///
/// `subdivisions` is clamped to at most [`MAX_SPHERE_SUBDIVISIONS`]. A `radius` that is not
/// finite and positive gives an empty mesh.
///
/// # Examples
/// ```
/// use haphe::mesh::shapes::sphere;
/// let ball = sphere(0.1, 2);
/// assert_eq!(ball.triangles.len(), 320);
/// assert_eq!(ball.vertices.len(), 162);
/// assert!(ball.vertices.iter().all(|p| (p.length() - 0.1).abs() < 1e-15));
/// assert!(sphere(f64::NAN, 2).triangles.is_empty());
/// ```
pub fn sphere(radius: f64, subdivisions: u32) -> Mesh {
    geodesic_sphere(radius, 1 << subdivisions.min(MAX_SPHERE_SUBDIVISIONS))
}

/// A sphere of `radius` metres centred on the origin (object frame): the icosahedron with
/// each edge cut into `frequency` equal parts and each face into a grid of `frequency²`
/// triangles, projected onto the sphere; `20·frequency²` triangles and
/// `10·frequency² + 2` vertices.
///
/// Unlike [`sphere`], any frequency is allowed, so the triangle count can be close to any
/// budget. Frequency 1 is the icosahedron itself.
///
/// `frequency` is clamped into `1..=`[`MAX_SPHERE_FREQUENCY`]. A `radius` that is not
/// finite and positive gives an empty mesh.
///
/// # Examples
/// ```
/// use haphe::mesh::shapes::geodesic_sphere;
/// let ball = geodesic_sphere(0.05, 3);
/// assert_eq!(ball.triangles.len(), 180);
/// assert_eq!(ball.vertices.len(), 92);
/// ```
pub fn geodesic_sphere(radius: f64, frequency: u32) -> Mesh {
    if !is_positive_length(radius) {
        return Mesh::default();
    }
    let mut mesh = unit_geodesic_sphere(frequency);
    for p in &mut mesh.vertices {
        *p *= radius;
    }
    mesh
}

/// The 12 corners of an icosahedron, before projection onto the unit sphere: the cyclic
/// permutations of `(0, ±1, ±φ)`.
fn icosahedron_corners() -> [DVec3; 12] {
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    [
        DVec3::new(-1.0, phi, 0.0),
        DVec3::new(1.0, phi, 0.0),
        DVec3::new(-1.0, -phi, 0.0),
        DVec3::new(1.0, -phi, 0.0),
        DVec3::new(0.0, -1.0, phi),
        DVec3::new(0.0, 1.0, phi),
        DVec3::new(0.0, -1.0, -phi),
        DVec3::new(0.0, 1.0, -phi),
        DVec3::new(phi, 0.0, -1.0),
        DVec3::new(phi, 0.0, 1.0),
        DVec3::new(-phi, 0.0, -1.0),
        DVec3::new(-phi, 0.0, 1.0),
    ]
    .map(DVec3::normalize)
}

/// The 20 faces of the icosahedron, counter-clockwise seen from outside.
const ICOSAHEDRON_FACES: [[usize; 3]; 20] = [
    [0, 11, 5],
    [0, 5, 1],
    [0, 1, 7],
    [0, 7, 10],
    [0, 10, 11],
    [1, 5, 9],
    [5, 11, 4],
    [11, 10, 2],
    [10, 7, 6],
    [7, 1, 8],
    [3, 9, 4],
    [3, 4, 2],
    [3, 2, 6],
    [3, 6, 8],
    [3, 8, 9],
    [4, 9, 5],
    [2, 4, 11],
    [6, 2, 10],
    [8, 6, 7],
    [9, 8, 1],
];

/// Number of icosahedron corners, edges and faces.
const CORNERS: usize = 12;
const EDGES: usize = 30;
const FACES: usize = 20;

/// The 30 icosahedron edges, numbered in the order they first appear (as `low → high`)
/// when walking the faces, and the number of each corner pair.
struct IcosahedronEdges {
    /// `ends[e] = [low, high]`, the corners of edge `e`, `low < high`.
    ends: [[usize; 2]; EDGES],
    /// `id[a][b] = id[b][a]`: the number of the edge between corners `a` and `b`.
    id: [[usize; CORNERS]; CORNERS],
}

impl IcosahedronEdges {
    fn new() -> IcosahedronEdges {
        let mut edges = IcosahedronEdges {
            ends: [[0; 2]; EDGES],
            id: [[0; CORNERS]; CORNERS],
        };
        // A closed, consistently oriented mesh uses every edge once in each direction, so
        // taking the `low → high` occurrences numbers each edge exactly once.
        let mut next = 0;
        for face in &ICOSAHEDRON_FACES {
            for side in 0..3 {
                let (from, to) = (face[side], face[(side + 1) % 3]);
                if from < to && next < EDGES {
                    edges.ends[next] = [from, to];
                    edges.id[from][to] = next;
                    edges.id[to][from] = next;
                    next += 1;
                }
            }
        }
        edges
    }
}

/// Where the vertices of a geodesic sphere of frequency `n` are numbered.
struct Numbering {
    /// Edge cuts per icosahedron edge.
    n: usize,
    edges: IcosahedronEdges,
}

impl Numbering {
    /// Vertices strictly inside one icosahedron edge.
    fn per_edge(&self) -> usize {
        self.n - 1
    }

    /// Vertices strictly inside one icosahedron face.
    fn per_face(&self) -> usize {
        (self.n - 1) * (self.n.saturating_sub(2)) / 2
    }

    fn vertex_count(&self) -> usize {
        CORNERS + EDGES * self.per_edge() + FACES * self.per_face()
    }

    /// The vertex `k` steps from corner `from` toward corner `to` (`0 < k < n`).
    fn on_edge(&self, from: usize, to: usize, k: usize) -> usize {
        let edge = self.edges.id[from][to];
        let along = if from < to { k - 1 } else { self.n - k - 1 };
        CORNERS + edge * self.per_edge() + along
    }

    /// The vertex at grid point `(i, j)` of face `face`, whose corners are `a, b, c`: the
    /// point `a + (b − a)·i/n + (c − a)·j/n`, with `i + j ≤ n`.
    fn on_face(&self, face: usize, i: usize, j: usize) -> usize {
        let n = self.n;
        let [a, b, c] = ICOSAHEDRON_FACES[face];
        match (i, j) {
            (0, 0) => a,
            (_, 0) if i == n => b,
            (0, _) if j == n => c,
            (_, 0) => self.on_edge(a, b, i),
            (0, _) => self.on_edge(a, c, j),
            _ if i + j == n => self.on_edge(b, c, j),
            _ => {
                // Interior points are stored row by row (j = 1..n−2), each row i = 1..n−1−j.
                let rows_before = (j - 1) * (n - 1) - (j - 1) * j / 2;
                CORNERS + EDGES * self.per_edge() + face * self.per_face() + rows_before + i - 1
            }
        }
    }
}

/// The geodesic sphere of radius 1 with `frequency` (clamped) cuts per icosahedron edge.
pub(super) fn unit_geodesic_sphere(frequency: u32) -> Mesh {
    let n = frequency.clamp(1, MAX_SPHERE_FREQUENCY) as usize;
    let numbering = Numbering {
        n,
        edges: IcosahedronEdges::new(),
    };
    let corners = icosahedron_corners();

    // Integer weights keep the arithmetic exact until the projection normalises.
    let mut vertices = Vec::with_capacity(numbering.vertex_count());
    vertices.extend_from_slice(&corners);
    for &[low, high] in &numbering.edges.ends {
        for k in 1..n {
            let flat = corners[low] * (n - k) as f64 + corners[high] * k as f64;
            vertices.push(flat.normalize());
        }
    }
    for &[a, b, c] in &ICOSAHEDRON_FACES {
        for j in 1..n.saturating_sub(1) {
            for i in 1..n - j {
                let flat =
                    corners[a] * (n - i - j) as f64 + corners[b] * i as f64 + corners[c] * j as f64;
                vertices.push(flat.normalize());
            }
        }
    }

    let mut triangles = Vec::with_capacity(FACES * n * n);
    let mut lower_row = Vec::with_capacity(n + 1);
    let mut upper_row = Vec::with_capacity(n + 1);
    for face in 0..FACES {
        fill_row(&numbering, face, 0, &mut lower_row);
        for j in 0..n {
            fill_row(&numbering, face, j + 1, &mut upper_row);
            // Row j has n + 1 − j points, row j + 1 one fewer. Between them: n − j triangles
            // pointing up (like the face) and n − j − 1 pointing down, all wound like the face.
            for i in 0..n - j {
                triangles.push([lower_row[i], lower_row[i + 1], upper_row[i]]);
                if i + 1 < n - j {
                    triangles.push([lower_row[i + 1], upper_row[i + 1], upper_row[i]]);
                }
            }
            std::mem::swap(&mut lower_row, &mut upper_row);
        }
    }
    Mesh {
        vertices,
        triangles,
    }
}

/// Writes the vertex indices of row `j` of a face grid (`i = 0..=n−j`) into `row`.
fn fill_row(numbering: &Numbering, face: usize, j: usize, row: &mut Vec<u32>) {
    row.clear();
    row.extend((0..=numbering.n - j).map(|i| numbering.on_face(face, i, j) as u32));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn icosahedron_faces_wind_outward() {
        let corners = icosahedron_corners();
        for [a, b, c] in ICOSAHEDRON_FACES {
            let normal = (corners[b] - corners[a]).cross(corners[c] - corners[a]);
            assert!(
                normal.dot(corners[a]) > 0.0,
                "face {a} {b} {c} winds inward"
            );
        }
    }

    #[test]
    fn icosahedron_has_thirty_edges_each_numbered_once() {
        let edges = IcosahedronEdges::new();
        let mut seen = edges.ends.to_vec();
        seen.sort_unstable();
        seen.dedup();
        assert_eq!(seen.len(), EDGES);
        for (e, [low, high]) in edges.ends.iter().enumerate() {
            assert!(low < high);
            assert_eq!(edges.id[*low][*high], e);
            assert_eq!(edges.id[*high][*low], e);
        }
    }

    #[test]
    fn every_vertex_index_is_used_by_the_numbering() {
        for n in 1..8 {
            let mesh = unit_geodesic_sphere(n);
            let mut used = vec![false; mesh.vertices.len()];
            for tri in &mesh.triangles {
                for &v in tri {
                    used[v as usize] = true;
                }
            }
            assert!(used.iter().all(|&u| u), "frequency {n}");
            assert_eq!(mesh.triangles.len(), 20 * (n * n) as usize);
        }
    }
}
