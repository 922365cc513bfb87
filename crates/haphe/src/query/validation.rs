//! The full validation of a mesh as the front ends print it: the mesh stage's report and,
//! when the mesh has a usable surface, its self-intersections (found with the surface's
//! voxel map), in one serialisable record. `haphe validate --json`, the Python `validate`
//! and the C API all print this record.

use serde::Serialize;

use super::self_intersect::{SelfIntersections, self_intersections};
use crate::map::{MapError, MapOptions, VoxelMap};
use crate::mesh::{
    Format, Mesh, MeshReport, Surface, SurfaceError, SurfaceOptions, Usability, WeldStats,
    is_degenerate_triangle,
};

/// Why a mesh that was read could not be validated (its surface or map could not be built).
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ValidationError {
    /// The surface could not be built.
    #[error(transparent)]
    Surface(#[from] SurfaceError),
    /// The voxel map for the self-intersection search could not be built.
    #[error(transparent)]
    Map(#[from] MapError),
}

/// The report of a mesh and its self-intersections.
#[derive(Debug, Clone)]
pub struct Validation {
    /// The mesh stage's report.
    pub report: MeshReport,
    /// The self-intersections; `None` for a mesh with no usable surface (every triangle
    /// degenerate), or when the search was skipped.
    pub intersections: Option<SelfIntersections>,
}

impl Validation {
    /// Validates a welded mesh: its report and, when `search_intersections` is set and a
    /// triangle has an area, its self-intersections (builds the surface's voxel map: a few
    /// seconds on meshes of millions of triangles).
    ///
    /// # Errors
    /// When the surface or its map cannot be built.
    pub fn of(mesh: Mesh, search_intersections: bool) -> Result<Validation, ValidationError> {
        let has_area = (0..mesh.triangles.len()).any(|t| {
            let [a, b, c] = mesh.corners(t);
            !is_degenerate_triangle(a, b, c)
        });
        if !(search_intersections && has_area) {
            return Ok(Validation {
                report: MeshReport::of(&mesh),
                intersections: None,
            });
        }
        let surface = Surface::new(mesh, &SurfaceOptions::default())?;
        let map = VoxelMap::build(&surface, &MapOptions::default())?;
        let intersections = self_intersections(&surface, &map);
        Ok(Validation {
            report: surface.report().clone(),
            intersections: Some(intersections),
        })
    }

    /// Whether the surface passes through itself (so a closed mesh has no inside where it
    /// does).
    pub fn crosses_itself(&self) -> bool {
        self.intersections.as_ref().is_some_and(|s| s.crossing > 0)
    }

    /// The verdict as an exit code: 0 a valid closed solid, 1 usable only as an open,
    /// two-sided surface or closed but crossing itself, 2 unusable.
    pub fn exit_code(&self) -> u8 {
        match self.report.usable_as {
            Usability::Solid if self.crosses_itself() => 1,
            Usability::Solid => 0,
            Usability::Surface => 1,
            Usability::Unusable => 2,
        }
    }

    /// The record of `haphe validate --json` for the file named `file`, read as `format`
    /// and welded as `weld` said, in `seconds`.
    pub fn record<'a>(
        &'a self,
        file: &str,
        format: Format,
        weld: WeldStats,
        seconds: f64,
    ) -> ValidationRecord<'a> {
        let s = self.intersections.as_ref();
        ValidationRecord {
            file: file.to_owned(),
            format: format!("{format:?}").to_lowercase(),
            seconds,
            weld: WeldRecord {
                vertices_before: weld.vertices_before,
                merged: weld.merged,
                unreferenced: weld.unreferenced,
            },
            report: &self.report,
            self_intersections: s.map(|s| s.count),
            self_intersections_crossing: s.map(|s| s.crossing),
            self_intersection_pairs: s.map(|s| s.pairs.as_slice()),
            self_intersections_complete: s.map(|s| s.complete),
        }
    }
}

/// One file's validation as serialised (one JSON object): file, format, seconds, weld,
/// then the report's fields, then the self-intersections.
#[derive(Debug, Serialize)]
pub struct ValidationRecord<'a> {
    /// The file's name as given.
    pub file: String,
    /// Its format, lower case (`obj`, `stl`, `ply`, `off`).
    pub format: String,
    /// Time to read, weld and validate, seconds.
    pub seconds: f64,
    /// What welding did.
    pub weld: WeldRecord,
    /// The mesh report (its fields are the record's).
    #[serde(flatten)]
    pub report: &'a MeshReport,
    /// Triangle pairs that intersect (other than in shared corners); `null` when the mesh
    /// has no usable surface or the search was skipped.
    pub self_intersections: Option<usize>,
    /// Of those, pairs that cross each other (or overlap in a plane).
    pub self_intersections_crossing: Option<usize>,
    /// The first intersecting pairs.
    pub self_intersection_pairs: Option<&'a [[u32; 2]]>,
    /// Whether the search tested every candidate pair (else it stopped at its budget and
    /// the counts are lower bounds).
    pub self_intersections_complete: Option<bool>,
}

/// What welding did, as serialised.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct WeldRecord {
    /// Vertices before welding.
    pub vertices_before: usize,
    /// Vertices merged into an earlier one.
    pub merged: usize,
    /// Vertices no triangle used, dropped.
    pub unreferenced: usize,
}
