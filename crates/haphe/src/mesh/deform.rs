//! New positions for a surface's vertices: the triangles, neighbours and fans stay (shared
//! with the surface before), the frames and shading normals are recomputed only around
//! the vertices that moved.

use glam::DVec3;

use super::frame::TriFrame;
use super::normals::refresh_corner_normals;
use super::topology::Surface;

impl Surface {
    /// This surface with its vertices at `vertices` (one per vertex, in this surface's
    /// order, every coordinate finite: the caller checked both), and the triangles that
    /// moved (a corner changed), in increasing order.
    ///
    /// Equal, array for array, to the surface [`Surface::new`] builds from these vertices
    /// and this surface's triangles in its order (no spatial reordering), but for the
    /// report, which describes the mesh as read, with its bounds those of the new
    /// vertices.
    pub(crate) fn deformed(&self, vertices: Vec<DVec3>) -> (Surface, Vec<u32>) {
        debug_assert_eq!(vertices.len(), self.vertices.len());
        let old: &[DVec3] = &self.vertices;
        let same =
            |a: DVec3, b: DVec3| a.to_array().map(f64::to_bits) == b.to_array().map(f64::to_bits);
        let mut moved_triangle = vec![false; self.triangles.len()];
        for (v, (&p, &q)) in vertices.iter().zip(old).enumerate() {
            if !same(p, q) {
                for &t in self.fan(super::VertId(v as u32)) {
                    moved_triangle[t as usize] = true;
                }
            }
        }
        let moved: Vec<u32> = (0..self.triangles.len() as u32)
            .filter(|&t| moved_triangle[t as usize])
            .collect();
        let mut frames = self.frames.to_vec();
        let mut corners_at: Vec<u32> = Vec::with_capacity(3 * moved.len());
        for &t in &moved {
            let tri = self.triangles[t as usize];
            let [a, b, c] = tri.map(|v| vertices[v as usize]);
            frames[t as usize] = TriFrame::new(a, b, c);
            corners_at.extend(tri);
        }
        corners_at.sort_unstable();
        corners_at.dedup();
        let mut normals = self.corner_normals.to_vec();
        refresh_corner_normals(
            &vertices,
            &self.triangles,
            &frames,
            |v| self.fan(super::VertId(v)),
            self.crease_angle_rad,
            (&corners_at, &mut normals),
        );
        let mut report = self.report.clone();
        let (lo, hi) = vertices
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        report.bounds_min = lo.to_array();
        report.bounds_max = hi.to_array();
        let surface = Surface {
            vertices: vertices.into(),
            triangles: self.triangles.clone(),
            neighbours: self.neighbours.clone(),
            frames: frames.into(),
            corner_normals: normals.into(),
            fan_start: self.fan_start.clone(),
            fan_triangles: self.fan_triangles.clone(),
            source: self.source.clone(),
            report,
            crease_angle_rad: self.crease_angle_rad,
            uid: super::topology::next_uid(),
        };
        (surface, moved)
    }

    /// [`Surface::deformed`], for the benches (feature `testing`).
    #[cfg(feature = "testing")]
    #[doc(hidden)]
    pub fn deformed_with_moved(&self, vertices: Vec<DVec3>) -> (Surface, Vec<u32>) {
        self.deformed(vertices)
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use crate::mesh::shapes::Catalog;
    use crate::mesh::{Mesh, Surface, SurfaceOptions, TriId};
    use crate::rng::SplitMix64;

    /// A surface rebuilt from scratch on `vertices`, in `surface`'s triangle order.
    fn rebuilt(surface: &Surface, vertices: &[DVec3]) -> Surface {
        let mesh = Mesh {
            vertices: vertices.to_vec(),
            triangles: surface.triangles().to_vec(),
        };
        let options = SurfaceOptions {
            spatial_order: false,
            ..SurfaceOptions::default()
        };
        Surface::new(mesh, &options).expect("a surface")
    }

    #[test]
    fn a_deformed_surface_equals_one_built_from_its_vertices() {
        let mut rng = SplitMix64::new(7);
        for catalog in [Catalog::Sphere, Catalog::Box, Catalog::Torus, Catalog::Blob] {
            let surface =
                Surface::new(catalog.with_triangles(2000), &SurfaceOptions::default()).unwrap();
            for fraction in [0.0, 0.01, 0.3, 1.0] {
                let mut vertices = surface.vertices().to_vec();
                let mut moved = 0;
                for p in &mut vertices {
                    if rng.next_unit() < fraction {
                        *p += 0.002 * rng.unit_vector();
                        moved += 1;
                    }
                }
                let (deformed, triangles) = surface.deformed(vertices.clone());
                let fresh = rebuilt(&surface, &vertices);
                assert_eq!(moved == 0, triangles.is_empty(), "{catalog:?} {fraction}");
                for t in 0..surface.triangle_count() as u32 {
                    let t = TriId(t);
                    assert_eq!(deformed.corners(t), fresh.corners(t));
                    assert_eq!(
                        deformed.frame(t),
                        fresh.frame(t),
                        "{catalog:?} {fraction} {t:?}"
                    );
                    let bits = |n: [DVec3; 3]| n.map(|n| n.to_array().map(f64::to_bits));
                    assert_eq!(
                        bits(deformed.corner_normals(t)),
                        bits(fresh.corner_normals(t)),
                        "{catalog:?} {fraction} {t:?}"
                    );
                    assert_eq!(deformed.neighbours(t), fresh.neighbours(t));
                }
                assert_eq!(deformed.bounds(), fresh.bounds());
            }
        }
    }
}
