//! A closed mesh made a volume: the signed distance to its surface on a grid, positive
//! inside by the non-zero rule, clamped to a band of two voxels either side.

use glam::{DAffine3, DVec3};

use super::{MAX_VOXELS, Volume, VolumeError};
use crate::mesh::TriId;
use crate::par::*;
use crate::query::{Side, classify_point, nearest_within};
use crate::scene::{Param, Shape};

/// Voxels of margin beyond the shape's bounds on every side, and the half-width of the band
/// of exact distances: the values are clamped to this many voxels, so that the iso-surface
/// has the whole band to be interpolated from on both sides, and the border voxels are air.
pub(crate) const VOXELISE_BAND_VOXELS: f64 = 2.0;

impl Volume {
    /// The volume of a closed shape: a grid of `voxel`-metre voxels (axis-aligned, in the
    /// shape's frame) covering its bounds and two voxels more on
    /// every side; each value is the distance to the surface (metres, `f32`), positive
    /// inside (the non-zero rule of [`classify_point`]) and negative outside, clamped to
    /// ± two voxels; iso 0. The iso-surface ([`Volume::shape`]) is the shape's surface
    /// within a voxel where it is smooth at the voxel's scale; edges and details smaller
    /// than a voxel are rounded off.
    ///
    /// In parallel over `z` slabs with the feature `parallel`, with the same result
    /// without it.
    ///
    /// # Errors
    /// [`VolumeError::VoxelSize`] for a voxel size that is not finite, above 0 and at
    /// most 1 m,
    /// [`VolumeError::VoxelCount`] when the grid would have more than 2³¹ voxels, and
    /// [`VolumeError::NotSolid`] for a shape without an inside ([`Shape::is_solid`]: open,
    /// non-manifold or inconsistently oriented).
    ///
    /// # Performance
    /// One inside test per voxel (mostly a cell lookup of the shape's map), and a nearest
    /// triangle search within the band for each voxel in a triangle's box grown by the
    /// band (marked first, on one thread).
    pub fn from_shape(shape: &Shape, voxel: f64) -> Result<Volume, VolumeError> {
        let voxel = Param::VoxelSize.check(voxel)?;
        if !shape.is_solid() {
            return Err(VolumeError::NotSolid);
        }
        let (lo, hi) = shape.surface().bounds();
        let margin = VOXELISE_BAND_VOXELS * voxel;
        let origin = lo - DVec3::splat(margin);
        // Enough voxels to reach past `hi + margin`.
        let across = ((hi - lo) / voxel).ceil() + DVec3::splat(1.0 + 2.0 * VOXELISE_BAND_VOXELS);
        let voxels = across.x * across.y * across.z;
        // (Infinite for a tiny voxel, refused too; never NaN: `voxel` is positive.)
        if voxels > MAX_VOXELS as f64 {
            return Err(VolumeError::VoxelCount { voxel, voxels });
        }
        let dims = across.to_array().map(|n| n as usize);
        let to_world =
            DAffine3::from_translation(origin) * DAffine3::from_scale(DVec3::splat(voxel));
        let grid = Grid {
            to_world,
            dims,
            voxel,
        };
        let near = grid.near_triangles(shape);
        let slabs: Vec<Vec<f32>> = (0..dims[2])
            .into_par_iter()
            .map(|k| grid.slab(shape, &near, k))
            .collect();
        Volume::new(dims, slabs.concat(), to_world, 0.0)
    }
}

/// The grid being filled.
struct Grid {
    to_world: DAffine3,
    dims: [usize; 3],
    voxel: f64,
}

impl Grid {
    /// Whether each voxel (`i` fastest) lies in the bounding box, grown by the band, of
    /// some triangle: only those can have a triangle within the band.
    fn near_triangles(&self, shape: &Shape) -> Vec<bool> {
        let surface = shape.surface();
        let band = DVec3::splat(VOXELISE_BAND_VOXELS * self.voxel);
        let origin = self.to_world.translation;
        let [nx, ny, _] = self.dims;
        let mut near = vec![false; self.dims.iter().product()];
        for t in 0..surface.triangle_count() {
            let [a, b, c] = surface.corners(TriId(t as u32));
            let lo = ((a.min(b).min(c) - band - origin) / self.voxel).floor();
            let hi = ((a.max(b).max(c) + band - origin) / self.voxel).ceil();
            let lo = lo.to_array().map(|x| x.max(0.0) as usize);
            let hi = [0, 1, 2].map(|k| (hi[k].max(0.0) as usize).min(self.dims[k] - 1));
            for k in lo[2]..=hi[2] {
                for j in lo[1]..=hi[1] {
                    let row = nx * (j + ny * k);
                    near[row + lo[0]..=row + hi[0]].fill(true);
                }
            }
        }
        near
    }

    /// The values of the slab `z = k` (`i` fastest): the distance to the nearest triangle
    /// within the band (the band where none is), positive inside.
    fn slab(&self, shape: &Shape, near: &[bool], k: usize) -> Vec<f32> {
        let (surface, map) = (shape.surface(), shape.map());
        let band = VOXELISE_BAND_VOXELS * self.voxel;
        let [nx, ny, _] = self.dims;
        let mut values = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let p = self
                    .to_world
                    .transform_point3(DVec3::new(i as f64, j as f64, k as f64));
                let distance = if near[i + nx * (j + ny * k)] {
                    nearest_within(surface, map, p, band).map_or(band, |n| n.distance)
                } else {
                    band
                };
                let inside = classify_point(surface, map, p).0 == Side::Inside;
                values.push(if inside { distance } else { -distance } as f32);
            }
        }
        values
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::MapOptions;
    use crate::mesh::{Mesh, Surface, SurfaceOptions, shapes};
    use crate::volume::Chunks;

    /// The shape of `mesh`.
    fn shape_of(mesh: Mesh) -> Shape {
        Shape::from_mesh("test", mesh, &MapOptions::default()).expect("a shape")
    }

    /// The volume a closed mesh encloses (divergence theorem), m³.
    fn enclosed(mesh: &Mesh) -> f64 {
        (0..mesh.triangles.len())
            .map(|t| {
                let [a, b, c] = mesh.corners(t);
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    /// The extracted mesh of `volume`, checked closed and solid.
    fn closed_mesh(volume: &Volume) -> Mesh {
        let mesh = Chunks::extract(volume).mesh();
        let surface = Surface::new(mesh.clone(), &SurfaceOptions::default()).expect("a surface");
        assert!(surface.is_solid(), "{:?}", surface.report().problems());
        mesh
    }

    #[test]
    fn a_sphere_comes_back_within_a_voxel() {
        let r = 0.05;
        let sphere = shapes::sphere(r, 4);
        let voxel = r / 20.0;
        let volume = Volume::from_shape(&shape_of(sphere.clone()), voxel).expect("a volume");
        assert_eq!(volume.iso(), 0.0);
        let mesh = closed_mesh(&volume);
        for p in &mesh.vertices {
            let off = (p.length() - r).abs();
            assert!(off < voxel, "vertex {p} is {off} m off the sphere");
        }
        // Against the polyhedron voxelised (a little smaller than the sphere).
        let exact = enclosed(&sphere);
        let error = (enclosed(&mesh) - exact).abs() / exact;
        assert!(error < 0.03, "volume off by {error}");
    }

    #[test]
    fn a_box_comes_back_with_its_volume() {
        let half = DVec3::new(0.03, 0.02, 0.01);
        let voxel = 0.001;
        let volume = Volume::from_shape(&shape_of(shapes::cuboid(half, [2, 2, 2])), voxel)
            .expect("a volume");
        // 60, 40 and 20 voxels across (or one more, as the division rounds), 2 more on
        // each side, and the last voxel.
        for (n, across) in volume.dims().into_iter().zip([60, 40, 20]) {
            assert!(
                n == across + 5 || n == across + 6,
                "{n} voxels for {across}"
            );
        }
        let mesh = closed_mesh(&volume);
        let exact = 8.0 * half.x * half.y * half.z;
        let error = (enclosed(&mesh) - exact).abs() / exact;
        assert!(error < 0.03, "volume off by {error}");
        for p in &mesh.vertices {
            let outside = (p.abs() - half).max_element();
            assert!(outside < voxel, "vertex {p} is {outside} m beyond the box");
        }
    }

    #[test]
    fn an_open_shape_is_refused() {
        let mut mesh = shapes::sphere(0.05, 2);
        mesh.triangles.pop();
        let open = shape_of(mesh);
        assert_eq!(Volume::from_shape(&open, 0.005), Err(VolumeError::NotSolid));
    }

    #[test]
    fn a_bad_voxel_size_is_refused() {
        let shape = shape_of(shapes::sphere(0.05, 2));
        for bad in [0.0, -0.001, f64::NAN, f64::INFINITY] {
            let error = Volume::from_shape(&shape, bad).expect_err("refused");
            assert!(matches!(error, VolumeError::VoxelSize(_)), "{bad}: {error}");
            assert!(error.to_string().contains("voxel size"));
        }
        let error = Volume::from_shape(&shape, 1e-7).expect_err("too many voxels");
        assert!(matches!(error, VolumeError::VoxelCount { .. }), "{error}");
        assert!(error.to_string().contains("voxel size"));
    }
}
