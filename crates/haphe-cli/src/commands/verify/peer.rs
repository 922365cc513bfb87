//! parry3d-f64 as a second opinion in `haphe verify` (feature `bench`, which also brings
//! `haphe bench`). Without the feature there is no peer, and the report's parry columns
//! read `-`, as for a mesh parry refuses.

use haphe::DVec3;
use haphe::mesh::Surface;

/// Whether this build has the peer.
pub const BUILT: bool = cfg!(feature = "bench");

/// parry's mesh with pseudo-normals (needed for its inside test).
#[cfg(feature = "bench")]
pub struct Parry(parry3d_f64::shape::TriMesh);

/// No peer in this build: never made.
#[cfg(not(feature = "bench"))]
pub enum Parry {}

impl Parry {
    /// parry's mesh of `surface`; `None` where parry refuses it, or without the feature.
    pub fn of(surface: &Surface) -> Option<Parry> {
        #[cfg(feature = "bench")]
        {
            use parry3d_f64::shape::{TriMesh, TriMeshFlags};
            TriMesh::with_flags(
                surface.vertices().to_vec(),
                surface.triangles().to_vec(),
                TriMeshFlags::ORIENTED,
            )
            .ok()
            .map(Parry)
        }
        #[cfg(not(feature = "bench"))]
        {
            let _ = surface;
            None
        }
    }

    /// Whether the segment `p0`–`p1` crosses the surface, by parry's ray cast.
    pub fn crosses(&self, p0: DVec3, p1: DVec3) -> bool {
        #[cfg(feature = "bench")]
        {
            use parry3d_f64::query::{Ray, RayCast};
            self.0
                .cast_local_ray(&Ray::new(p0, p1 - p0), 1.0, false)
                .is_some()
        }
        #[cfg(not(feature = "bench"))]
        {
            let _ = (p0, p1);
            match *self {}
        }
    }

    /// Whether `p` is inside, by parry's pseudo-normal test.
    pub fn contains(&self, p: DVec3) -> bool {
        #[cfg(feature = "bench")]
        {
            use parry3d_f64::query::PointQuery;
            self.0.contains_local_point(p)
        }
        #[cfg(not(feature = "bench"))]
        {
            let _ = p;
            match *self {}
        }
    }
}
