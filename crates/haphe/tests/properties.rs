//! Property tests of the mesh stage: welding, topology and barycentric frames.

use haphe::DVec3;
use haphe::mesh::{Mesh, MeshReport, Surface, SurfaceOptions, TriFrame, TriId, Weld, shapes, weld};
use proptest::prelude::*;

/// Bounded finite coordinates, metres.
fn coordinate() -> impl Strategy<Value = f64> {
    -1.0f64..1.0
}

fn point() -> impl Strategy<Value = DVec3> {
    (coordinate(), coordinate(), coordinate()).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// A triangle soup whose corners are drawn from a small pool of points (so many corners
/// coincide exactly), some nudged by less than a micrometre (so tolerance welding has
/// chains to merge).
fn soup() -> impl Strategy<Value = Mesh> {
    (
        prop::collection::vec(point(), 1..12),
        prop::collection::vec((0usize..12, 0usize..12, 0usize..12), 1..40),
        prop::collection::vec(-1e-7f64..1e-7, 120),
    )
        .prop_map(|(pool, picks, nudges)| {
            let mut vertices = Vec::new();
            let mut triangles = Vec::new();
            for (k, (a, b, c)) in picks.into_iter().enumerate() {
                let base = vertices.len() as u32;
                for (j, i) in [a, b, c].into_iter().enumerate() {
                    let nudge = if (k + j) % 3 == 0 {
                        nudges[(3 * k + j) % 120]
                    } else {
                        0.0
                    };
                    vertices.push(pool[i % pool.len()] + DVec3::splat(nudge));
                }
                triangles.push([base, base + 1, base + 2]);
            }
            Mesh {
                vertices,
                triangles,
            }
        })
}

/// A closed manifold mesh: one of the procedural shapes at a random resolution, rigidly
/// moved, its vertices jittered radially (which keeps the topology).
fn closed_manifold() -> impl Strategy<Value = Mesh> {
    (0usize..5, 1u32..4, point(), -0.3f64..0.3, any::<u64>()).prop_map(
        |(kind, resolution, offset, angle, seed)| {
            let mut mesh = match kind {
                0 => shapes::sphere(0.1, resolution),
                1 => shapes::torus(0.08, 0.03, 6 * resolution + 3, 4 * resolution + 3),
                2 => shapes::cuboid(DVec3::new(0.1, 0.05, 0.02), [resolution; 3]),
                3 => shapes::concave_corner(0.2, resolution),
                _ => shapes::blob(0.1, resolution, 0.02, seed),
            };
            let rotation =
                glam::DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), angle);
            let mut state = seed | 1;
            for p in &mut mesh.vertices {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                let jitter = 1.0 + 1e-3 * ((state % 1000) as f64 / 1000.0 - 0.5);
                *p = rotation * (*p * jitter) + offset;
            }
            mesh
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn welding_is_idempotent(mesh in soup(), tolerance in prop::option::of(1e-9f64..1e-6)) {
        let mode = tolerance.map_or(Weld::Exact, Weld::Tolerance);
        let (once, _) = weld(&mesh, mode);
        let (twice, stats) = weld(&once, mode);
        prop_assert_eq!(&once, &twice);
        prop_assert_eq!(stats.merged, 0);
        prop_assert_eq!(stats.unreferenced, 0);
        // Welding never moves a vertex: every corner keeps a position of its own cluster.
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for (k, &v) in tri.iter().enumerate() {
                let before = mesh.vertices[v as usize];
                let after = once.vertices[once.triangles[t][k] as usize];
                let limit = tolerance.map_or(0.0, |tol| tol * mesh.vertices.len() as f64);
                prop_assert!(before.distance(after) <= limit);
            }
        }
    }

    #[test]
    fn exact_weld_merges_exactly_the_equal_positions(mesh in soup()) {
        let (welded, _) = weld(&mesh, Weld::Exact);
        let mut positions: Vec<[u64; 3]> = welded.vertices.iter().map(|p| p.to_array().map(f64::to_bits)).collect();
        positions.sort_unstable();
        positions.dedup();
        prop_assert_eq!(positions.len(), welded.vertices.len(), "no two welded vertices are equal");
        for (t, tri) in mesh.triangles.iter().enumerate() {
            for (k, &v) in tri.iter().enumerate() {
                prop_assert_eq!(mesh.vertices[v as usize], welded.vertices[welded.triangles[t][k] as usize]);
            }
        }
    }

    #[test]
    fn closed_manifold_topology_is_symmetric_with_opposite_edges(mesh in closed_manifold()) {
        let report = MeshReport::of(&mesh);
        prop_assert!(report.closed);
        prop_assert_eq!(report.orientation_conflicts, 0);
        prop_assert_eq!(report.nonmanifold_vertices, 0);
        let surface = Surface::new(mesh, &SurfaceOptions::default()).expect("valid");
        prop_assert!(surface.is_solid());
        for t in 0..surface.triangle_count() as u32 {
            let tri = surface.triangle(TriId(t));
            for corner in 0..3 {
                let n = surface.neighbour(TriId(t), corner).expect("closed: a neighbour across every edge");
                // The edge opposite `corner`, as `t` runs it.
                let (a, b) = (tri[(corner + 1) % 3], tri[(corner + 2) % 3]);
                let other = surface.triangle(n);
                let back: Vec<usize> = (0..3).filter(|&k| surface.neighbour(n, k) == Some(TriId(t))).collect();
                prop_assert_eq!(back.len(), 1, "symmetric");
                let k = back[0];
                // The neighbour runs the same edge the other way: b -> a.
                prop_assert_eq!((other[(k + 1) % 3], other[(k + 2) % 3]), (b, a));
            }
        }
        // Every vertex fan is one closed cycle of edge-adjacent triangles.
        for v in 0..surface.vertex_count() as u32 {
            let fan = surface.fan(haphe::mesh::VertId(v));
            prop_assert!(fan.len() >= 3);
            for k in 0..fan.len() {
                let (a, b) = (fan[k], fan[(k + 1) % fan.len()]);
                prop_assert!(surface.neighbours(TriId(a)).contains(&b));
            }
        }
    }

    #[test]
    fn barycentric_coordinates_rebuild_the_point(
        a in point(), b in point(), c in point(), p in point(),
    ) {
        let frame = TriFrame::new(a, b, c);
        prop_assume!(!frame.is_degenerate());
        let w = frame.barycentric(p);
        prop_assert!((w[0] + w[1] + w[2] - 1.0).abs() < 1e-12);
        let rebuilt = w[0] * a + w[1] * b + w[2] * c + frame.height(p) * frame.normal;
        // Error grows with the triangle's condition (long thin triangles amplify rounding).
        let scale = (a - b).length().max((b - c).length()).max((c - a).length()).max(1.0);
        let condition = 1.0 / haphe::mesh::relative_height(a, b, c);
        prop_assert!(rebuilt.distance(p) <= 1e-13 * scale * condition.max(1.0), "{} vs {}", rebuilt, p);
    }

    #[test]
    fn surface_frames_rebuild_points_on_real_triangles(mesh in closed_manifold(), u in 0.0f64..1.0, v in 0.0f64..1.0, h in -0.01f64..0.01) {
        let surface = Surface::new(mesh, &SurfaceOptions::default()).expect("valid");
        for t in (0..surface.triangle_count() as u32).step_by(7) {
            let [a, b, c] = surface.corners(TriId(t));
            let (u, v) = if u + v > 1.0 { (1.0 - u, 1.0 - v) } else { (u, v) };
            let frame = surface.frame(TriId(t));
            let p = a + u * (b - a) + v * (c - a) + h * frame.normal;
            let w = frame.barycentric(p);
            prop_assert!((w[1] - u).abs() < 1e-9 && (w[2] - v).abs() < 1e-9, "{:?} vs ({}, {})", w, u, v);
            prop_assert!((frame.height(p) - h).abs() < 1e-12);
            let n = surface.shading_normal(TriId(t), w);
            prop_assert!((n.length() - 1.0).abs() < 1e-12);
            prop_assert!(n.dot(frame.normal) > 0.5, "shading normal stays near the face normal");
        }
    }
}
