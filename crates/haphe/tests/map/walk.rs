//! Segments walked through the grid (3D-DDA) find every triangle they meet in a visited
//! cell: the property the overlap tolerance exists for.

use super::*;

/// Where segment `p0 → p1` meets triangle `[a, b, c]` (Möller–Trumbore, closed: hits on
/// edges and vertices count), as the segment parameter.
fn segment_hits(p0: DVec3, p1: DVec3, [a, b, c]: [DVec3; 3]) -> Option<f64> {
    let d = p1 - p0;
    let (e1, e2) = (b - a, c - a);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det == 0.0 {
        return None;
    }
    let s = p0 - a;
    let u = s.dot(p) / det;
    let q = s.cross(e1);
    let v = d.dot(q) / det;
    let t = e2.dot(q) / det;
    (u >= 0.0 && v >= 0.0 && u + v <= 1.0 && (0.0..=1.0).contains(&t)).then_some(t)
}

/// Whether the walk of `p0 → p1` visits, around parameter `t`, a cell listing triangle
/// `tri`.
fn walk_finds(map: &VoxelMap, p0: DVec3, p1: DVec3, t: f64, tri: u32) -> bool {
    const SLACK: f64 = 1e-9;
    map.grid()
        .walk(p0, p1)
        .filter(|s| s.t_enter - SLACK <= t && t <= s.t_exit + SLACK)
        .any(|s| map.triangles_in(s.cell).contains(&tri))
}

/// What the overlap tolerance is for: a segment that meets a triangle meets it in a cell
/// the 3D-DDA visits, including segments through a triangle's vertices and edges and
/// segments running exactly along cell edges and faces.
#[test]
fn segments_find_the_triangles_they_meet_in_the_cells_they_walk() {
    for (name, surface) in solids() {
        let map = build(&surface, &MapOptions::default());
        let grid = map.grid();
        let h = grid.cell_size();
        // Through points of each triangle, along the normal and obliquely.
        for t in 0..surface.triangle_count() as u32 {
            let [a, b, c] = surface.corners(TriId(t));
            let n = surface.frame(TriId(t)).normal;
            let tangent = (b - a).normalize();
            for target in [a, b, c, 0.5 * (a + b), (a + b + c) / 3.0] {
                for dir in [
                    n,
                    (n + 0.7 * tangent).normalize(),
                    (n - 1.3 * tangent).normalize(),
                ] {
                    let (p0, p1) = (target + 0.8 * h * dir, target - 1.7 * h * dir);
                    let param = 0.8 / 2.5;
                    assert!(
                        walk_finds(&map, p0, p1, param, t),
                        "{name}: walk from {p0} to {p1} misses triangle {t} at {target}"
                    );
                }
            }
        }
        // Lines along the axes lying in cell faces and along cell edges, across the object.
        let [dx, dy, _] = grid.dims();
        let (lo, hi) = (grid.origin(), grid.max_corner());
        for i in (1..dx).step_by(3) {
            for j in (1..dy).step_by(2) {
                let x = lo.x + f64::from(i) * h;
                let y = lo.y + f64::from(j) * h;
                for (p0, p1) in [
                    (DVec3::new(x, y, lo.z - h), DVec3::new(x, y, hi.z + h)),
                    (
                        DVec3::new(x, y + 0.5 * h, hi.z + h),
                        DVec3::new(x, y + 0.5 * h, lo.z - h),
                    ),
                ] {
                    for t in 0..surface.triangle_count() as u32 {
                        if let Some(param) = segment_hits(p0, p1, surface.corners(TriId(t))) {
                            assert!(
                                walk_finds(&map, p0, p1, param, t),
                                "{name}: walk along {p0} → {p1} misses triangle {t} at {param}"
                            );
                        }
                    }
                }
            }
        }
    }
}
