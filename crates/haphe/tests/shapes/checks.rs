//! Independent checks of closed triangle meshes: edge counting, vertex links, coincident
//! points, signed volume and area, written from scratch for these tests.

use std::collections::HashMap;
use std::f64::consts::PI;

use haphe::DVec3;
use haphe::mesh::Mesh;
use haphe::mesh::shapes::sphere;

/// Counts of a closed, consistently oriented, manifold triangle mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Topology {
    pub vertices: usize,
    pub edges: usize,
    pub faces: usize,
}

impl Topology {
    pub fn euler_characteristic(self) -> i64 {
        self.vertices as i64 - self.edges as i64 + self.faces as i64
    }
}

/// Checks that `mesh` is a closed, consistently oriented 2-manifold with shared vertices:
/// every directed edge is used once and its reverse once (so every undirected edge by
/// exactly two triangles, in opposite directions), the triangles around every vertex form
/// one cycle, every vertex is used, no two vertices are at the same point, and no triangle
/// has zero area.
pub fn check_closed_manifold(mesh: &Mesh) -> Result<Topology, String> {
    let vertex_count = mesh.vertices.len();
    if mesh.triangles.is_empty() {
        return Err("no triangles".into());
    }
    if let Some(v) = mesh.vertices.iter().position(|p| !p.is_finite()) {
        return Err(format!("vertex {v} is not finite: {:?}", mesh.vertices[v]));
    }

    let mut directed: HashMap<(u32, u32), usize> = HashMap::with_capacity(3 * mesh.triangles.len());
    let mut used = vec![false; vertex_count];
    for (t, &[a, b, c]) in mesh.triangles.iter().enumerate() {
        if [a, b, c].iter().any(|&v| v as usize >= vertex_count) {
            return Err(format!(
                "triangle {t} has an index out of range: {a} {b} {c}"
            ));
        }
        if a == b || b == c || c == a {
            return Err(format!("triangle {t} repeats a vertex: {a} {b} {c}"));
        }
        for (from, to) in [(a, b), (b, c), (c, a)] {
            if let Some(other) = directed.insert((from, to), t) {
                return Err(format!(
                    "directed edge {from}→{to} used by triangles {other} and {t} \
                     (non-manifold or inconsistently oriented)"
                ));
            }
        }
        for v in [a, b, c] {
            used[v as usize] = true;
        }
    }
    for (&(from, to), &t) in &directed {
        if !directed.contains_key(&(to, from)) {
            return Err(format!(
                "edge {from}→{to} of triangle {t} has no opposite (boundary or flipped neighbour)"
            ));
        }
    }
    if let Some(v) = used.iter().position(|&u| !u) {
        return Err(format!("vertex {v} is used by no triangle"));
    }

    // The link of every vertex (the opposite edges of its triangles) is a single cycle.
    let mut links: Vec<(u32, u32, u32)> = Vec::with_capacity(3 * mesh.triangles.len());
    for &[a, b, c] in &mesh.triangles {
        links.extend([(a, b, c), (b, c, a), (c, a, b)]);
    }
    links.sort_unstable();
    for fan in links.chunk_by(|x, y| x.0 == y.0) {
        let next: HashMap<u32, u32> = fan.iter().map(|&(_, from, to)| (from, to)).collect();
        let start = fan[0].1;
        let mut at = start;
        let mut steps = 0;
        loop {
            at = next[&at];
            steps += 1;
            if at == start || steps > fan.len() {
                break;
            }
        }
        if steps != fan.len() {
            return Err(format!(
                "vertex {} has {} triangles in more than one fan (non-manifold vertex)",
                fan[0].0,
                fan.len()
            ));
        }
    }

    let mut keys: Vec<[u64; 3]> = mesh
        .vertices
        .iter()
        .map(|p| [p.x, p.y, p.z].map(|c| (c + 0.0).to_bits()))
        .collect();
    keys.sort_unstable();
    if let Some(pair) = keys.windows(2).find(|pair| pair[0] == pair[1]) {
        let [x, y, z] = pair[0].map(f64::from_bits);
        return Err(format!("two vertices at the same point ({x}, {y}, {z})"));
    }

    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.corners(t);
        let doubled_area = (b - a).cross(c - a).length();
        if doubled_area.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return Err(format!("triangle {t} has zero area: {a} {b} {c}"));
        }
    }

    Ok(Topology {
        vertices: vertex_count,
        edges: directed.len() / 2,
        faces: mesh.triangles.len(),
    })
}

pub fn assert_closed_manifold(mesh: &Mesh, context: &str) -> Topology {
    match check_closed_manifold(mesh) {
        Ok(topology) => topology,
        Err(problem) => panic!("{context}: {problem}"),
    }
}

/// Signed volume, m³: the sum of `a·(b × c)/6`, positive for an outward-wound closed mesh.
pub fn signed_volume(mesh: &Mesh) -> f64 {
    (0..mesh.triangles.len())
        .map(|t| {
            let [a, b, c] = mesh.corners(t);
            a.dot(b.cross(c))
        })
        .sum::<f64>()
        / 6.0
}

/// Surface area, m².
pub fn area(mesh: &Mesh) -> f64 {
    (0..mesh.triangles.len())
        .map(|t| {
            let [a, b, c] = mesh.corners(t);
            0.5 * (b - a).cross(c - a).length()
        })
        .sum()
}

/// Smallest distance from the origin to the plane of a triangle, signed (negative when a
/// triangle faces the origin, i.e. the mesh is not star-shaped around it).
pub fn smallest_plane_distance(mesh: &Mesh) -> f64 {
    (0..mesh.triangles.len())
        .map(|t| {
            let [a, b, c] = mesh.corners(t);
            a.dot((b - a).cross(c - a).normalize())
        })
        .fold(f64::INFINITY, f64::min)
}

pub fn assert_relative(actual: f64, expected: f64, tolerance: f64, context: &str) {
    let error = (actual - expected).abs() / expected.abs();
    assert!(
        error <= tolerance,
        "{context}: {actual} vs {expected} (relative error {error:e} > {tolerance:e})"
    );
}

pub fn ball_volume(radius: f64) -> f64 {
    4.0 / 3.0 * PI * radius.powi(3)
}

/// Volume and area of a mesh star-shaped around the origin whose vertices all lie within
/// `outer_radius`: every cone from the origin over a triangle holds a ball sector of the
/// smallest plane distance and lies inside the ball of `outer_radius`.
pub fn assert_star_shaped_between(mesh: &Mesh, outer_radius: f64, context: &str) -> (f64, f64) {
    let inner_radius = smallest_plane_distance(mesh);
    assert!(
        inner_radius > 0.0,
        "{context}: not star-shaped around the origin"
    );
    let farthest = mesh.vertices.iter().map(|p| p.length()).fold(0.0, f64::max);
    assert!(
        farthest <= outer_radius * (1.0 + 1e-12),
        "{context}: vertex at {farthest}"
    );
    let volume = signed_volume(mesh);
    assert!(
        ball_volume(inner_radius) <= volume && volume <= ball_volume(outer_radius),
        "{context}: volume {volume} outside [{}, {}]",
        ball_volume(inner_radius),
        ball_volume(outer_radius)
    );
    let surface = area(mesh);
    assert!(
        4.0 * PI * inner_radius.powi(2) <= surface,
        "{context}: area {surface} below the inner sphere's"
    );
    (volume, surface)
}

pub fn extent(mesh: &Mesh) -> DVec3 {
    let (min, max) = mesh.bounds().expect("a mesh with vertices");
    max - min
}

/// The triangles of a tetrahedron on vertices `first..first + 4`, wound outward when the
/// last vertex lies on the side of the first three where `(b − a) × (c − a)` points.
fn tetrahedron_triangles(first: u32) -> [[u32; 3]; 4] {
    let [a, b, c, d] = [first, first + 1, first + 2, first + 3];
    [[a, c, b], [a, b, d], [b, c, d], [c, a, d]]
}

fn tetrahedron(corners: [DVec3; 4]) -> Mesh {
    Mesh {
        vertices: corners.to_vec(),
        triangles: tetrahedron_triangles(0).to_vec(),
    }
}

#[test]
fn checker_accepts_a_tetrahedron_and_rejects_each_defect() {
    let unit = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    let good = tetrahedron(unit);
    assert_eq!(
        check_closed_manifold(&good),
        Ok(Topology {
            vertices: 4,
            edges: 6,
            faces: 4
        })
    );
    assert!((signed_volume(&good) - 1.0 / 6.0).abs() < 1e-15);

    let expect_problem = |mesh: &Mesh, words: &str| match check_closed_manifold(mesh) {
        Ok(_) => panic!("accepted a mesh with a defect ({words})"),
        Err(problem) => assert!(problem.contains(words), "{problem}"),
    };
    let mut flipped = sphere(1.0, 1);
    flipped.triangles[5].swap(0, 1);
    expect_problem(&flipped, "directed edge");
    let mut open = sphere(1.0, 1);
    open.triangles.pop();
    expect_problem(&open, "no opposite");
    let mut unreferenced = sphere(1.0, 1);
    unreferenced.vertices.push(DVec3::splat(5.0));
    expect_problem(&unreferenced, "used by no triangle");
    let mut coincident = sphere(1.0, 1);
    coincident.vertices[7] = coincident.vertices[3];
    expect_problem(&coincident, "same point");
    let flat = tetrahedron([DVec3::ZERO, DVec3::X * 2.0, DVec3::X, DVec3::Z]);
    expect_problem(&flat, "zero area");
    // Two tetrahedra sharing one corner: every edge is fine, the shared vertex is not.
    let mut bowtie = tetrahedron(unit);
    bowtie.vertices.extend([-DVec3::X, -DVec3::Y, -DVec3::Z]);
    bowtie.triangles.extend(
        tetrahedron_triangles(3)
            .map(|tri| tri.map(|v| if v == 3 { 0 } else { v }))
            .map(|[a, b, c]| [a, c, b]),
    );
    expect_problem(&bowtie, "more than one fan");
}
