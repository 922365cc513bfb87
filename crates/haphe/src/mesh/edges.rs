//! The edge table: every undirected edge with the triangles that use it.
//!
//! Shared by the validation report (which counts defects) and the topology (which links
//! neighbours), so that both agree on what an edge is.

use crate::par::*;

/// One use of an undirected edge by a triangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct HalfEdge {
    /// `(low vertex << 32) | high vertex`: the undirected edge.
    pub key: u64,
    /// The triangle using the edge.
    pub tri: u32,
    /// The triangle's corner opposite the edge (0, 1 or 2).
    pub corner: u8,
    /// Whether the triangle runs the edge from the low to the high vertex.
    pub forward: bool,
}

impl HalfEdge {
    /// The edge's two vertices, low first.
    #[inline]
    pub fn vertices(&self) -> [u32; 2] {
        [(self.key >> 32) as u32, self.key as u32]
    }
}

/// All half-edges sorted by edge, so the uses of one edge are adjacent.
///
/// Triangles with a repeated vertex index (`[a, a, b]`) have no area and no proper edges;
/// they are left out of the table (the report counts them as degenerate).
pub(crate) struct EdgeTable {
    pub half_edges: Vec<HalfEdge>,
}

impl EdgeTable {
    /// Builds the table: a counting sort by the edge's low vertex, then a small sort of
    /// each vertex's bucket. Linear in the number of triangles, and deterministic.
    pub fn build(triangles: &[[u32; 3]]) -> EdgeTable {
        let half_edge = |tri: usize, corner: u8| {
            let t = &triangles[tri];
            let c = corner as usize;
            let (a, b) = (t[(c + 1) % 3], t[(c + 2) % 3]);
            let (lo, hi) = if a < b { (a, b) } else { (b, a) };
            HalfEdge {
                key: (u64::from(lo) << 32) | u64::from(hi),
                tri: tri as u32,
                corner,
                forward: a < b,
            }
        };
        let vertex_count = triangles
            .iter()
            .flat_map(|t| t.iter())
            .max()
            .map_or(0, |&v| v as usize + 1);
        // start[v]..start[v + 1]: the half-edges whose low vertex is v.
        let mut start = vec![0u32; vertex_count + 1];
        let proper = || {
            triangles
                .iter()
                .enumerate()
                .filter(|(_, t)| has_distinct_corners(t))
        };
        for (tri, _) in proper() {
            for corner in 0..3 {
                start[half_edge(tri, corner).vertices()[0] as usize + 1] += 1;
            }
        }
        for v in 0..vertex_count {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let placeholder = HalfEdge {
            key: 0,
            tri: 0,
            corner: 0,
            forward: false,
        };
        let mut half_edges = vec![placeholder; start[vertex_count] as usize];
        for (tri, _) in proper() {
            for corner in 0..3 {
                let h = half_edge(tri, corner);
                let slot = &mut fill[h.vertices()[0] as usize];
                half_edges[*slot as usize] = h;
                *slot += 1;
            }
        }
        sort_buckets(&mut half_edges, &start);
        EdgeTable { half_edges }
    }

    /// The uses of each undirected edge, one slice per edge, in edge order.
    pub fn groups(&self) -> impl Iterator<Item = &[HalfEdge]> {
        self.half_edges.chunk_by(|a, b| a.key == b.key)
    }
}

/// Vertices whose buckets [`sort_buckets`] sorts in one parallel task.
const BUCKET_RUN: usize = 8192;

/// Sorts each bucket `half_edges[start[v]..start[v + 1]]`, in parallel over runs of
/// vertices (each bucket on its own, so the result is that of one thread).
fn sort_buckets(half_edges: &mut [HalfEdge], start: &[u32]) {
    let vertex_count = start.len() - 1;
    let mut runs: Vec<(usize, &mut [HalfEdge])> = Vec::new();
    let mut rest = half_edges;
    for first in (0..vertex_count).step_by(BUCKET_RUN) {
        let end = (first + BUCKET_RUN).min(vertex_count);
        let (run, tail) = rest.split_at_mut((start[end] - start[first]) as usize);
        runs.push((first, run));
        rest = tail;
    }
    runs.par_iter_mut().for_each(|(first, run)| {
        let base = start[*first] as usize;
        for v in *first..(*first + BUCKET_RUN).min(vertex_count) {
            run[start[v] as usize - base..start[v + 1] as usize - base].sort_unstable();
        }
    });
}

/// Whether the three vertex indices of a triangle differ.
#[inline]
pub(crate) fn has_distinct_corners(t: &[u32; 3]) -> bool {
    t[0] != t[1] && t[1] != t[2] && t[0] != t[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shared_edge_is_grouped_with_opposite_directions() {
        let table = EdgeTable::build(&[[0, 1, 2], [2, 1, 3], [4, 4, 5]]);
        let groups: Vec<_> = table.groups().collect();
        assert_eq!(groups.len(), 5, "the repeated-index triangle has no edges");
        let shared = groups
            .iter()
            .find(|g| g[0].vertices() == [1, 2])
            .expect("edge 1-2 is listed");
        assert_eq!(shared.len(), 2);
        assert_ne!(shared[0].forward, shared[1].forward);
        assert_eq!((shared[0].tri, shared[0].corner), (0, 0));
        assert_eq!((shared[1].tri, shared[1].corner), (1, 2));
    }
}
