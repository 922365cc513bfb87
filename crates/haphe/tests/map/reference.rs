//! Independent references for the voxel map tests: a dense voxel map built the plain way
//! (every cell a slot, breadth-first searches), the generalised winding number and the
//! exact distance from a point to a triangle.

use std::collections::VecDeque;
use std::f64::consts::PI;

use haphe::DVec3;
use haphe::map::{CellState, Grid, MAX_CLEARANCE};
use haphe::mesh::{Surface, TriId};

/// A dense voxel map: one state, one clearance and one triangle list per cell.
pub struct Dense {
    pub dims: [u32; 3],
    pub states: Vec<CellState>,
    /// Exact Chebyshev distance to the nearest surface cell, capped at `MAX_CLEARANCE`
    /// (0 for surface cells).
    pub clearance: Vec<u8>,
    /// Exact Chebyshev distance to the nearest surface cell, uncapped (`u32::MAX` when
    /// there is none).
    pub distance: Vec<u32>,
    pub triangles: Vec<Vec<u32>>,
}

impl Dense {
    pub fn index(&self, c: [u32; 3]) -> usize {
        let [x, y, z] = c.map(|v| v as usize);
        let [dx, dy, _] = self.dims.map(|v| v as usize);
        (z * dy + y) * dx + x
    }

    pub fn cells(&self) -> impl Iterator<Item = [u32; 3]> + use<> {
        let [dx, dy, dz] = self.dims;
        (0..dz).flat_map(move |z| (0..dy).flat_map(move |y| (0..dx).map(move |x| [x, y, z])))
    }
}

/// Builds the dense reference on `grid`: a triangle is listed in every cell of the grid
/// (padding included) near its bounding box for which `grid.overlaps_cell` holds; a
/// six-connected breadth-first search from cell `[0, 0, 0]` through non-surface cells
/// marks the outside (when `solid`; otherwise every non-surface cell is outside), and each
/// region it does not reach is outside when the winding number at one of its cells is at
/// most ½ (a cavity); a
/// 26-connected multi-source search from the surface cells gives Chebyshev distances.
pub fn dense_reference(surface: &Surface, grid: &Grid, solid: bool) -> Dense {
    let dims = grid.dims();
    let count = dims.iter().map(|&d| d as usize).product();
    let mut dense = Dense {
        dims,
        states: vec![CellState::Inside; count],
        clearance: vec![0; count],
        distance: Vec::new(),
        triangles: vec![Vec::new(); count],
    };
    for t in 0..surface.triangle_count() {
        let corners = surface.corners(TriId(t as u32));
        let lo = corners[0].min(corners[1]).min(corners[2]);
        let hi = corners[0].max(corners[1]).max(corners[2]);
        let (a, b) = (grid.to_grid(lo).floor(), grid.to_grid(hi).floor());
        let range = |axis: usize| {
            let first = (a[axis] as i64 - 1).max(0);
            let last = (b[axis] as i64 + 1).min(i64::from(dims[axis]) - 1);
            first as u32..=last as u32
        };
        for z in range(2) {
            for y in range(1) {
                for x in range(0) {
                    if grid.overlaps_cell(corners, [x, y, z]) {
                        let i = dense.index([x, y, z]);
                        dense.triangles[i].push(t as u32);
                    }
                }
            }
        }
    }
    let cells: Vec<[u32; 3]> = dense.cells().collect();
    for &c in &cells {
        let i = dense.index(c);
        if !dense.triangles[i].is_empty() {
            dense.states[i] = CellState::Surface;
        } else if !solid {
            dense.states[i] = CellState::Outside;
        }
    }
    if solid {
        let start = dense.index([0, 0, 0]);
        assert_eq!(dense.states[start], CellState::Inside, "padding is free");
        for c in region(&dense, [0, 0, 0]) {
            let i = dense.index(c);
            dense.states[i] = CellState::Outside;
        }
        // Every enclosed region: outside when the winding number at one of its cells says
        // so (a cavity), else inside.
        let mut checked = vec![false; count];
        for &c in &cells {
            let i = dense.index(c);
            if dense.states[i] != CellState::Inside || checked[i] {
                continue;
            }
            let cavity = winding_number(surface, grid.cell_centre(c)).abs() <= 0.5;
            for n in region(&dense, c) {
                let j = dense.index(n);
                checked[j] = true;
                if cavity {
                    dense.states[j] = CellState::Outside;
                }
            }
        }
    }
    // Chebyshev distance: breadth-first over the 26 neighbours from all surface cells.
    let mut distance = vec![u32::MAX; count];
    let mut queue = VecDeque::new();
    for &c in &cells {
        if dense.states[dense.index(c)] == CellState::Surface {
            distance[dense.index(c)] = 0;
            queue.push_back(c);
        }
    }
    while let Some(c) = queue.pop_front() {
        let d = distance[dense.index(c)];
        for n in all_neighbours(c, dims) {
            let i = dense.index(n);
            if distance[i] == u32::MAX {
                distance[i] = d + 1;
                queue.push_back(n);
            }
        }
    }
    for (i, &d) in distance.iter().enumerate() {
        dense.clearance[i] = d.min(u32::from(MAX_CLEARANCE)) as u8;
    }
    dense.distance = distance;
    dense
}

/// The cells connected to `start` through face-adjacent cells of the same state.
fn region(dense: &Dense, start: [u32; 3]) -> Vec<[u32; 3]> {
    let state = dense.states[dense.index(start)];
    let mut seen = vec![false; dense.states.len()];
    seen[dense.index(start)] = true;
    let mut queue = VecDeque::from([start]);
    let mut out = Vec::new();
    while let Some(c) = queue.pop_front() {
        out.push(c);
        for n in face_neighbours(c, dense.dims) {
            let i = dense.index(n);
            if !seen[i] && dense.states[i] == state {
                seen[i] = true;
                queue.push_back(n);
            }
        }
    }
    out
}

/// The face neighbours of `c` inside the grid.
pub fn face_neighbours(c: [u32; 3], dims: [u32; 3]) -> Vec<[u32; 3]> {
    let mut out = Vec::with_capacity(6);
    for axis in 0..3 {
        if c[axis] > 0 {
            let mut n = c;
            n[axis] -= 1;
            out.push(n);
        }
        if c[axis] + 1 < dims[axis] {
            let mut n = c;
            n[axis] += 1;
            out.push(n);
        }
    }
    out
}

/// The 26 neighbours of `c` inside the grid.
pub fn all_neighbours(c: [u32; 3], dims: [u32; 3]) -> Vec<[u32; 3]> {
    let mut out = Vec::with_capacity(26);
    for dz in -1i64..=1 {
        for dy in -1i64..=1 {
            for dx in -1i64..=1 {
                if (dx, dy, dz) == (0, 0, 0) {
                    continue;
                }
                let n = [
                    i64::from(c[0]) + dx,
                    i64::from(c[1]) + dy,
                    i64::from(c[2]) + dz,
                ];
                if (0..3).all(|a| n[a] >= 0 && n[a] < i64::from(dims[a])) {
                    out.push(n.map(|v| v as u32));
                }
            }
        }
    }
    out
}

/// The generalised winding number of the surface around `p`: the sum of the signed solid
/// angles of the triangles (Van Oosterom & Strackee) over 4π. About 1 inside a closed,
/// outward-oriented solid and 0 outside.
pub fn winding_number(surface: &Surface, p: DVec3) -> f64 {
    let mut total = 0.0;
    for t in 0..surface.triangle_count() {
        let [a, b, c] = surface.corners(TriId(t as u32)).map(|v| v - p);
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let numerator = a.dot(b.cross(c));
        let denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
        total += 2.0 * numerator.atan2(denominator);
    }
    total / (4.0 * PI)
}

/// The distance from `p` to triangle `[a, b, c]` (Ericson, *Real-Time Collision
/// Detection*, 5.1.5).
pub fn distance_point_triangle(p: DVec3, [a, b, c]: [DVec3; 3]) -> f64 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return (p - a).length();
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return (p - b).length();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (p - (a + v * ab)).length();
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return (p - c).length();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (p - (a + w * ac)).length();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (p - (b + w * (c - b))).length();
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    (p - (a + ab * v + ac * w)).length()
}

/// The distance from `p` to the nearest triangle of the surface.
pub fn distance_to_surface(surface: &Surface, p: DVec3) -> f64 {
    (0..surface.triangle_count())
        .map(|t| distance_point_triangle(p, surface.corners(TriId(t as u32))))
        .fold(f64::INFINITY, f64::min)
}
