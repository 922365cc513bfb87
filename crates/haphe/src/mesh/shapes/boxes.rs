//! Boxes: the cuboid, the thin plate and the concave corner (a cube with one octant
//! removed), every face a grid of cells on one lattice, so that vertices are shared along
//! every edge.

use glam::DVec3;

use super::lattice::{Lattice, LatticeRect, Outward, lattice_surface};
use super::length::is_positive_length;
use crate::mesh::Mesh;

/// Largest number of divisions along one axis [`cuboid`] and [`thin_plate`] accept; larger
/// values are clamped (12·8192² ≈ 805 million triangles for a cube).
pub const MAX_CUBOID_DIVISIONS: u32 = 8192;

/// Largest `divisions` [`concave_corner`] accepts; larger values are clamped
/// (48·4096² ≈ 805 million triangles).
pub const MAX_CONCAVE_CORNER_DIVISIONS: u32 = 4096;

/// An axis-aligned box from `−half_extents` to `+half_extents` (metres, object frame,
/// centred on the origin) whose faces are grids: `divisions = [dx, dy, dz]` cells along x,
/// y and z, so the face normal to x is a `dy × dz` grid, and so on;
/// `4·(dx·dy + dy·dz + dz·dx)` triangles (`12·d²` for `[d, d, d]`) and half as many
/// vertices plus 2.
///
/// Every cell is split into two triangles along the same diagonal direction. Vertices are
/// shared along the box edges, so the surface is closed and manifold.
///
/// Each division is clamped into `1..=`[`MAX_CUBOID_DIVISIONS`]. Half extents that are not
/// all finite and positive give an empty mesh.
///
/// # Examples
/// ```
/// use haphe::DVec3;
/// use haphe::mesh::shapes::cuboid;
/// let brick = cuboid(DVec3::new(0.1, 0.05, 0.025), [4, 2, 1]);
/// assert_eq!(brick.triangles.len(), 4 * (4 * 2 + 2 * 1 + 1 * 4));
/// assert_eq!(brick.bounds(), Some((DVec3::new(-0.1, -0.05, -0.025), DVec3::new(0.1, 0.05, 0.025))));
/// ```
pub fn cuboid(half_extents: DVec3, divisions: [u32; 3]) -> Mesh {
    let extent = 2.0 * half_extents;
    if !extent.to_array().into_iter().all(is_positive_length) {
        return Mesh::default();
    }
    let cells = divisions.map(|d| d.clamp(1, MAX_CUBOID_DIVISIONS));
    let lattice = Lattice {
        min: -half_extents,
        extent,
        cells,
    };
    let mut rects = Vec::with_capacity(6);
    for axis in 0..3 {
        let (u_axis, v_axis) = ((axis + 1) % 3, (axis + 2) % 3);
        for (outward, level) in [(Outward::Negative, 0), (Outward::Positive, cells[axis])] {
            rects.push(LatticeRect {
                axis,
                outward,
                level,
                u: [0, cells[u_axis]],
                v: [0, cells[v_axis]],
            });
        }
    }
    lattice_surface(&lattice, &rects)
}

/// A thin plate, `width` along x, `depth` along y and `thickness` along z (metres, object
/// frame, centred on the origin), for break-through tests: a [`cuboid`] with
/// `divisions × divisions` cells on the two large faces and one cell across the thickness;
/// `4·divisions² + 8·divisions` triangles.
///
/// The thickness may be tiny (0.1 mm against a plate of 0.2 m); the side faces then have
/// long thin triangles, which is what such a plate is.
///
/// `divisions` is clamped into `1..=`[`MAX_CUBOID_DIVISIONS`]. Sizes that are not all
/// finite and positive give an empty mesh.
///
/// # Examples
/// ```
/// use haphe::mesh::shapes::thin_plate;
/// let plate = thin_plate(0.2, 0.2, 0.0001, 10);
/// assert_eq!(plate.triangles.len(), 4 * 100 + 8 * 10);
/// let (min, max) = plate.bounds().expect("a plate has vertices");
/// assert!((max.z - min.z - 0.0001).abs() < 1e-12);
/// ```
pub fn thin_plate(width: f64, depth: f64, thickness: f64, divisions: u32) -> Mesh {
    cuboid(
        0.5 * DVec3::new(width, depth, thickness),
        [divisions, divisions, 1],
    )
}

/// A cube of edge `size` (metres, object frame, centred on the origin) with the octant
/// `x > 0, y > 0, z > 0` removed: a closed, manifold solid with three concave edges along
/// the positive half axes that meet at a concave corner at the origin. Its volume is
/// `7/8·size³` and its area `6·size²`, like the whole cube.
///
/// The surface is made of 24 squares of edge `size / 2` (21 on the outside of the cube,
/// 3 facing into the removed octant), each a `divisions × divisions` grid: `48·divisions²`
/// triangles and half as many vertices plus 2.
///
/// `divisions` is clamped into `1..=`[`MAX_CONCAVE_CORNER_DIVISIONS`]. A `size` that is not
/// finite and positive gives an empty mesh.
///
/// # Examples
/// ```
/// use haphe::DVec3;
/// use haphe::mesh::shapes::concave_corner;
/// let block = concave_corner(0.2, 2);
/// assert_eq!(block.triangles.len(), 48 * 4);
/// assert!(block.vertices.contains(&DVec3::ZERO));
/// ```
pub fn concave_corner(size: f64, divisions: u32) -> Mesh {
    if !is_positive_length(size) {
        return Mesh::default();
    }
    let d = divisions.clamp(1, MAX_CONCAVE_CORNER_DIVISIONS);
    let lattice = Lattice {
        min: DVec3::splat(-0.5 * size),
        extent: DVec3::splat(size),
        cells: [2 * d; 3],
    };
    // The solid is 7 of the 8 cells of a 2×2×2 block; every cell side that faces an empty
    // cell (outside the block, or the removed octant) is a square of the surface.
    let filled = |cell: [i32; 3]| cell.iter().all(|c| (0..2).contains(c)) && cell != [1, 1, 1];
    let mut rects = Vec::with_capacity(24);
    for z in 0..2 {
        for y in 0..2 {
            for x in 0..2 {
                let cell = [x, y, z];
                if !filled(cell) {
                    continue;
                }
                for axis in 0..3 {
                    for (outward, step) in [(Outward::Negative, -1), (Outward::Positive, 1)] {
                        let mut neighbour = cell;
                        neighbour[axis] += step;
                        if filled(neighbour) {
                            continue;
                        }
                        let start = |a: usize| cell[a] as u32 * d;
                        let (u_axis, v_axis) = ((axis + 1) % 3, (axis + 2) % 3);
                        rects.push(LatticeRect {
                            axis,
                            outward,
                            level: start(axis) + if step > 0 { d } else { 0 },
                            u: [start(u_axis), start(u_axis) + d],
                            v: [start(v_axis), start(v_axis) + d],
                        });
                    }
                }
            }
        }
    }
    lattice_surface(&lattice, &rects)
}
