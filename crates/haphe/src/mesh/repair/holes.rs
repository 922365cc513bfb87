//! Holes: the loops of boundary edges, and filling one with triangles.

use glam::DVec3;

use crate::mesh::edges::EdgeTable;
use crate::mesh::frame::{DEGENERATE_MAX_RELATIVE_HEIGHT, relative_height};

/// The holes of a mesh: its boundary edges (used by one triangle) joined into loops, each
/// a list of vertices in the direction its triangles run the edges (so that a triangle
/// filling it runs them the other way). A chain that does not close (at a vertex where
/// boundaries meet unevenly) is listed as it was walked. Loops in order of their lowest
/// boundary edge.
pub(crate) fn hole_loops(table: &EdgeTable) -> Vec<Vec<u32>> {
    // The boundary edges, directed as their triangle runs them.
    let mut directed: Vec<(u32, u32)> = table
        .groups()
        .filter_map(|g| match g {
            [h] => {
                let [lo, hi] = h.vertices();
                Some(if h.forward { (lo, hi) } else { (hi, lo) })
            }
            _ => None,
        })
        .collect();
    directed.sort_unstable();
    let mut used = vec![false; directed.len()];
    let mut loops = Vec::new();
    for first in 0..directed.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        let (start, mut at) = directed[first];
        let mut vertices = vec![start];
        while at != start {
            vertices.push(at);
            // The next unused boundary edge leaving `at` (sorted: a binary search).
            let from = directed.partition_point(|&(a, _)| a < at);
            let next = (from..directed.len())
                .take_while(|&i| directed[i].0 == at)
                .find(|&i| !used[i]);
            match next {
                Some(i) => {
                    used[i] = true;
                    at = directed[i].1;
                }
                None => break,
            }
        }
        loops.push(vertices);
    }
    loops
}

/// Triangles closing the hole `cycle` (vertices in the direction the mesh's triangles run
/// the boundary): ears clipped one at a time, each time the one whose new edge is the
/// shortest (an ear of no area last), every triangle running the boundary against the mesh's triangles, so the
/// patch is oriented as the surface around it. `cycle.len() − 2` triangles.
pub(crate) fn fill(cycle: &[u32], vertices: &[DVec3]) -> Vec<[u32; 3]> {
    // The patch runs the loop the other way.
    let mut ring: Vec<u32> = cycle.iter().rev().copied().collect();
    let mut out = Vec::with_capacity(ring.len().saturating_sub(2));
    let at = |v: u32| vertices.get(v as usize).copied().unwrap_or(DVec3::ZERO);
    while ring.len() > 3 {
        let n = ring.len();
        // An ear whose triangle would have no area (three corners in a line) comes last.
        let cost = |k: usize| {
            let (a, b, c) = (
                at(ring[(k + n - 1) % n]),
                at(ring[k]),
                at(ring[(k + 1) % n]),
            );
            let flat = relative_height(a, b, c) <= DEGENERATE_MAX_RELATIVE_HEIGHT;
            (flat, a.distance(c))
        };
        let ear = (0..n)
            .min_by(|&i, &j| {
                let (ci, cj) = (cost(i), cost(j));
                ci.0.cmp(&cj.0).then(ci.1.total_cmp(&cj.1))
            })
            .unwrap_or(0);
        out.push([ring[(ear + n - 1) % n], ring[ear], ring[(ear + 1) % n]]);
        ring.remove(ear);
    }
    if let [a, b, c] = ring[..] {
        out.push([a, b, c]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes;

    #[test]
    fn a_missing_quad_is_one_hole_of_four_edges_and_its_fill_closes_it() {
        let mut mesh = shapes::cuboid(DVec3::splat(0.1), [1, 1, 1]);
        let removed: Vec<[u32; 3]> = mesh.triangles.drain(0..2).collect();
        let table = EdgeTable::build(&mesh.triangles);
        let loops = hole_loops(&table);
        assert_eq!(loops.len(), 1);
        assert_eq!(loops[0].len(), 4);
        let mut corners: Vec<u32> = removed.iter().flatten().copied().collect();
        corners.sort_unstable();
        corners.dedup();
        let mut got = loops[0].clone();
        got.sort_unstable();
        assert_eq!(got, corners);
        let patch = fill(&loops[0], &mesh.vertices);
        assert_eq!(patch.len(), 2);
        mesh.triangles.extend(patch);
        let report = crate::mesh::MeshReport::of(&mesh);
        assert!(
            report.closed && report.orientation_conflicts == 0,
            "{report}"
        );
        let (lo, hi) = mesh.bounds().expect("vertices");
        let volume = (hi - lo).x * (hi - lo).y * (hi - lo).z;
        assert!(
            report
                .volume
                .is_some_and(|v| (v - volume).abs() < 1e-9 * volume),
            "{report}"
        );
    }
}
