//! Surfaces made of axis-aligned rectangles on an integer lattice, each cut into a grid of
//! square-ish cells: the common builder of boxes, plates and the concave corner.
//!
//! Rectangles meet only along their borders, so only border points can be shared: they are
//! looked up by lattice coordinates, interior points are simply appended.

use glam::DVec3;
use rustc_hash::FxHashMap;

use crate::mesh::Mesh;

/// A regular lattice of points over a box: `cells[k] + 1` points along axis `k`, from `min`
/// to `min + extent`.
pub(super) struct Lattice {
    /// The lattice point `(0, 0, 0)`, metres.
    pub min: DVec3,
    /// The size of the box, metres.
    pub extent: DVec3,
    /// Cells along x, y, z.
    pub cells: [u32; 3],
}

impl Lattice {
    fn position(&self, point: [u32; 3]) -> DVec3 {
        let fraction = |axis: usize| f64::from(point[axis]) / f64::from(self.cells[axis]);
        self.min + self.extent * DVec3::new(fraction(0), fraction(1), fraction(2))
    }
}

/// Which way a rectangle's outward normal points along its axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Outward {
    /// Toward increasing coordinate.
    Positive,
    /// Toward decreasing coordinate.
    Negative,
}

/// A rectangle of the surface, in lattice coordinates: the plane `axis = level`, spanning
/// `u` along axis `(axis + 1) % 3` and `v` along axis `(axis + 2) % 3`.
pub(super) struct LatticeRect {
    /// The axis the rectangle is normal to (0, 1 or 2).
    pub axis: usize,
    /// Which side of the rectangle is outside the solid.
    pub outward: Outward,
    /// The lattice coordinate of the plane along `axis`.
    pub level: u32,
    /// The lattice range `[start, end]` along axis `(axis + 1) % 3`, `start < end`.
    pub u: [u32; 2],
    /// The lattice range `[start, end]` along axis `(axis + 2) % 3`, `start < end`.
    pub v: [u32; 2],
}

impl LatticeRect {
    fn cells(&self) -> (usize, usize) {
        (
            (self.u[1] - self.u[0]) as usize,
            (self.v[1] - self.v[0]) as usize,
        )
    }
}

/// Triangulates `rects`, each cell of each rectangle into two triangles wound so that they
/// face `outward`, sharing the vertices of points several rectangles have in common.
///
/// The vertex buffer is sized for a closed surface of genus 0 (`triangles / 2 + 2`
/// vertices), which every caller builds.
pub(super) fn lattice_surface(lattice: &Lattice, rects: &[LatticeRect]) -> Mesh {
    let triangle_count: usize = rects
        .iter()
        .map(|rect| {
            let (nu, nv) = rect.cells();
            2 * nu * nv
        })
        .sum();
    let border_points: usize = rects
        .iter()
        .map(|rect| {
            let (nu, nv) = rect.cells();
            2 * (nu + nv)
        })
        .sum();
    let mut vertices = Vec::with_capacity(triangle_count / 2 + 2);
    let mut triangles = Vec::with_capacity(triangle_count);
    // Every border point belongs to at least two rectangles.
    let mut shared: FxHashMap<[u32; 3], u32> =
        FxHashMap::with_capacity_and_hasher(border_points / 2, Default::default());
    let mut lower_row: Vec<u32> = Vec::new();
    let mut upper_row: Vec<u32> = Vec::new();

    for rect in rects {
        let (u_axis, v_axis) = ((rect.axis + 1) % 3, (rect.axis + 2) % 3);
        let (nu, nv) = rect.cells();
        for row in 0..=nv {
            upper_row.clear();
            for column in 0..=nu {
                let mut point = [0; 3];
                point[rect.axis] = rect.level;
                point[u_axis] = rect.u[0] + column as u32;
                point[v_axis] = rect.v[0] + row as u32;
                let on_border = column == 0 || column == nu || row == 0 || row == nv;
                let mut append = || {
                    vertices.push(lattice.position(point));
                    (vertices.len() - 1) as u32
                };
                let index = if on_border {
                    *shared.entry(point).or_insert_with(append)
                } else {
                    append()
                };
                upper_row.push(index);
            }
            if row > 0 {
                for column in 0..nu {
                    // The cell's corners, counter-clockwise seen from +axis (u × v = axis).
                    let p00 = lower_row[column];
                    let p10 = lower_row[column + 1];
                    let p11 = upper_row[column + 1];
                    let p01 = upper_row[column];
                    match rect.outward {
                        Outward::Positive => {
                            triangles.push([p00, p10, p11]);
                            triangles.push([p00, p11, p01]);
                        }
                        Outward::Negative => {
                            triangles.push([p00, p11, p10]);
                            triangles.push([p00, p01, p11]);
                        }
                    }
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
