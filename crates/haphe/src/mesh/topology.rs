//! The topology of a mesh: the navigable, validated form every later stage uses.

use crate::par::*;
use glam::DVec3;

use crate::array::Array;

use super::edges::{EdgeTable, has_distinct_corners};
use super::frame::TriFrame;
use super::ids::{NONE, TriId, VertId};
use super::normals::{CornerNormals, DEFAULT_CREASE_ANGLE_RAD, corner_normals};
use super::{Mesh, MeshReport, Usability};

/// How to build a [`Surface`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceOptions {
    /// Faces meeting at a sharper angle than this (radians) keep separate shading normals.
    pub crease_angle_rad: f64,
    /// Store the triangles in spatial order (along a Morton curve of their centroids) and
    /// the vertices in order of first use, so that neighbours on the surface are
    /// neighbours in memory whatever order the mesh came in: on large meshes every query
    /// then meets fewer cold cache lines (see [`Surface::source_triangle`] for the index
    /// a triangle had in the mesh). `false` keeps the mesh's own order.
    pub spatial_order: bool,
}

impl Default for SurfaceOptions {
    /// The default crease angle (π/6, 30°), spatial order.
    fn default() -> Self {
        SurfaceOptions {
            crease_angle_rad: DEFAULT_CREASE_ANGLE_RAD,
            spatial_order: true,
        }
    }
}

/// Why a mesh cannot become a [`Surface`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SurfaceError {
    /// No triangle has a usable area.
    #[error("no triangle has a usable area ({triangles} triangles, all degenerate)")]
    NoArea {
        /// How many triangles the mesh has.
        triangles: usize,
    },
    /// The mesh breaks an invariant of [`Mesh`] (hand-built meshes only).
    #[error("invalid mesh: {0}")]
    Invalid(#[from] super::ReadErrorKind),
}

/// A triangle mesh with its topology, ready for collision queries and haptic rendering.
///
/// Invariants (checked once in [`Surface::new`], trusted by every later stage):
/// - every index is in range and every coordinate finite (metres, object frame);
/// - `neighbour(t, i)` is the triangle across the edge opposite corner `i` of `t`, when
///   exactly two triangles share that edge, else [`NONE`]; the relation is symmetric;
/// - `fan(v)` lists every triangle with a corner at `v`, in rotational order where the
///   vertex is manifold;
/// - `frame(t)` gives barycentric coordinates in two dot products ([`TriFrame`]);
///   degenerate triangles have a zero frame and are never a contact;
/// - `corner_normals(t)` are unit shading normals respecting the crease angle;
/// - `source_triangle(t)` is a permutation of the triangle indices: the index in the mesh
///   given to [`Surface::new`] of each triangle (the identity without
///   [`SurfaceOptions::spatial_order`]; for a loaded map file, only checked to be in
///   range, since nothing is indexed with it).
///
/// Triangle and vertex indices ([`TriId`], [`VertId`]) are the surface's own: with the
/// default spatial order they differ from the mesh's (the corners of triangle `t` are those
/// of the mesh's triangle `source_triangle(t)`, in the same order). The
/// [`report`](Surface::report) speaks of the mesh as given, in its indices.
#[derive(Debug, Clone)]
pub struct Surface {
    pub(super) vertices: Array<DVec3>,
    pub(super) triangles: Array<[u32; 3]>,
    pub(super) neighbours: Array<[u32; 3]>,
    pub(super) frames: Array<TriFrame>,
    pub(super) corner_normals: Array<CornerNormals>,
    pub(super) fan_start: Array<u32>,
    pub(super) fan_triangles: Array<u32>,
    pub(super) source: Array<u32>,
    pub(super) report: MeshReport,
    /// The crease angle the shading normals were computed with (for a deformation).
    pub(super) crease_angle_rad: f64,
    /// A name no other surface made in this process has (see [`Surface::uid`]).
    pub(super) uid: u64,
}

/// The next [`Surface::uid`].
pub(super) fn next_uid() -> u64 {
    use std::sync::atomic::{AtomicU64, Ordering};
    static NEXT: AtomicU64 = AtomicU64::new(1);
    NEXT.fetch_add(1, Ordering::Relaxed)
}

impl Surface {
    /// Builds the topology of `mesh` and validates it.
    ///
    /// A mesh with defects still becomes a surface where that makes sense: an open or
    /// non-manifold mesh is a two-sided surface (non-manifold edges act as boundaries for
    /// navigation); [`Surface::is_solid`] says whether inside and outside are defined.
    ///
    /// # Errors
    /// [`SurfaceError::NoArea`] when no triangle has area; [`SurfaceError::Invalid`] when an
    /// index is out of range or a coordinate non-finite.
    ///
    /// # Examples
    /// ```
    /// use haphe::mesh::{shapes, Surface, SurfaceOptions};
    /// let surface = Surface::new(shapes::sphere(0.1, 2), &SurfaceOptions::default()).unwrap();
    /// assert!(surface.is_solid());
    /// assert_eq!(surface.triangle_count(), 320);
    /// ```
    pub fn new(mesh: Mesh, options: &SurfaceOptions) -> Result<Surface, SurfaceError> {
        on_pool(|| Surface::new_on_pool(mesh, options))
    }

    /// [`Surface::new`], on the thread that runs it.
    fn new_on_pool(mesh: Mesh, options: &SurfaceOptions) -> Result<Surface, SurfaceError> {
        mesh.check_indices_and_finite()?;
        let (report, edges) = super::report::analyse_with_edges(&mesh);
        if report.usable_as == Usability::Unusable {
            return Err(SurfaceError::NoArea {
                triangles: mesh.triangles.len(),
            });
        }
        // The report keeps the mesh's own indices; everything from here on uses the
        // spatial order. Its neighbours are the mesh's, renumbered: the same edges join
        // the same triangles whatever their numbers.
        let neighbours = link_neighbours(mesh.triangles.len(), &edges);
        drop(edges);
        let (mesh, source, neighbours) = if options.spatial_order {
            let (mesh, source) = super::order::spatial_order(mesh);
            let neighbours = renumber_neighbours(&neighbours, &source);
            (mesh, source, neighbours)
        } else {
            let source = (0..mesh.triangles.len() as u32).collect();
            (mesh, source, neighbours)
        };
        let Mesh {
            vertices,
            triangles,
        } = mesh;
        let (fan_start, fan_triangles) = build_fans(vertices.len(), &triangles, &neighbours);
        let frames: Vec<TriFrame> = triangles
            .par_iter()
            .map(|&[a, b, c]| {
                TriFrame::new(
                    vertices[a as usize],
                    vertices[b as usize],
                    vertices[c as usize],
                )
            })
            .collect();
        let fan = |v: u32| {
            &fan_triangles[fan_start[v as usize] as usize..fan_start[v as usize + 1] as usize]
        };
        let corner_normals = corner_normals(
            &vertices,
            &triangles,
            &frames,
            fan,
            options.crease_angle_rad,
        );
        Ok(Surface {
            vertices: vertices.into(),
            triangles: triangles.into(),
            neighbours: neighbours.into(),
            frames: frames.into(),
            corner_normals: corner_normals.into(),
            fan_start: fan_start.into(),
            fan_triangles: fan_triangles.into(),
            source: source.into(),
            report,
            crease_angle_rad: options.crease_angle_rad,
            uid: next_uid(),
        })
    }

    /// A name of this surface no other surface made in this process has (a deformed
    /// surface gets a new one), so that what is kept about a surface from tick to tick
    /// is never taken for another's that a freed one's memory now holds.
    #[inline]
    pub(crate) fn uid(&self) -> u64 {
        self.uid
    }

    /// Number of triangles.
    #[inline]
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Number of vertices.
    #[inline]
    pub fn vertex_count(&self) -> usize {
        self.vertices.len()
    }

    /// All vertex positions, metres, object frame.
    #[inline]
    pub fn vertices(&self) -> &[DVec3] {
        &self.vertices
    }

    /// All triangles as vertex index triples.
    #[inline]
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// Position of vertex `v`, metres, object frame.
    #[inline]
    pub fn vertex(&self, v: VertId) -> DVec3 {
        self.vertices[v.index()]
    }

    /// The vertex indices of triangle `t`.
    #[inline]
    pub fn triangle(&self, t: TriId) -> [u32; 3] {
        self.triangles[t.index()]
    }

    /// The corner positions of triangle `t`, metres, object frame.
    #[inline]
    pub fn corners(&self, t: TriId) -> [DVec3; 3] {
        self.triangles[t.index()].map(|v| self.vertices[v as usize])
    }

    /// The triangle across the edge opposite corner `corner` (0, 1 or 2) of `t`, or `None`
    /// at a boundary or non-manifold edge.
    #[inline]
    pub fn neighbour(&self, t: TriId, corner: usize) -> Option<TriId> {
        let n = self.neighbours[t.index()][corner];
        (n != NONE).then_some(TriId(n))
    }

    /// The three neighbours of `t` as raw indices ([`NONE`] where there is none).
    #[inline]
    pub fn neighbours(&self, t: TriId) -> [u32; 3] {
        self.neighbours[t.index()]
    }

    /// The triangles around vertex `v`, in rotational order where `v` is manifold.
    #[inline]
    pub fn fan(&self, v: VertId) -> &[u32] {
        let (s, e) = (self.fan_start[v.index()], self.fan_start[v.index() + 1]);
        &self.fan_triangles[s as usize..e as usize]
    }

    /// The precomputed barycentric frame of `t`.
    #[inline]
    pub fn frame(&self, t: TriId) -> &TriFrame {
        &self.frames[t.index()]
    }

    /// The unit shading normals at the corners of `t` (object frame; stored in single
    /// precision, unit length within about 1e-7).
    #[inline]
    pub fn corner_normals(&self, t: TriId) -> [DVec3; 3] {
        self.corner_normals[t.index()].map(|n| DVec3::from_array(n.map(f64::from)))
    }

    /// The shading normal at barycentric weights `w` of `t`: the corner normals blended
    /// and normalised (object frame, unit length; the face normal if the blend vanishes).
    #[inline]
    pub fn shading_normal(&self, t: TriId, w: [f64; 3]) -> DVec3 {
        let [n0, n1, n2] = self.corner_normals(t);
        (w[0] * n0 + w[1] * n1 + w[2] * n2)
            .try_normalize()
            .unwrap_or(self.frames[t.index()].normal)
    }

    /// Whether inside and outside are defined (a valid closed solid, see [`Usability`]).
    #[inline]
    pub fn is_solid(&self) -> bool {
        self.report.usable_as == Usability::Solid
    }

    /// The smallest axis-aligned box `(min, max)` holding every vertex, metres, object
    /// frame: every triangle lies in it.
    #[inline]
    pub fn bounds(&self) -> (DVec3, DVec3) {
        (
            DVec3::from_array(self.report.bounds_min),
            DVec3::from_array(self.report.bounds_max),
        )
    }

    /// The validation report of the mesh this surface was built from, in that mesh's
    /// triangle and vertex indices (see [`Surface::source_triangle`]).
    pub fn report(&self) -> &MeshReport {
        &self.report
    }

    /// The index that triangle `t` had in the mesh given to [`Surface::new`] (its face
    /// index in the file, for a mesh from [`read_mesh`](super::read_mesh)): what to show a
    /// user, or to look up data of their own per face. `t` itself when out of range.
    #[inline]
    pub fn source_triangle(&self, t: TriId) -> u32 {
        self.source.get(t.index()).copied().unwrap_or(t.0)
    }

    /// [`Surface::source_triangle`] of every triangle, in the surface's order: a
    /// permutation of `0..triangle_count()` (see the invariants above).
    #[inline]
    pub fn source_triangles(&self) -> &[u32] {
        &self.source
    }

    /// Bytes of memory the surface holds (without the report).
    pub fn heap_bytes(&self) -> usize {
        self.vertices.heap_bytes()
            + self.triangles.heap_bytes()
            + self.neighbours.heap_bytes()
            + self.frames.heap_bytes()
            + self.corner_normals.heap_bytes()
            + self.fan_start.heap_bytes()
            + self.fan_triangles.heap_bytes()
            + self.source.heap_bytes()
    }
}

/// The arrays of a [`Surface`], owned (to rebuild a saved surface) or borrowed (to save one).
///
/// Invariants the caller of [`Surface::from_parts`] must have checked, as [`Surface::new`]
/// establishes them: every coordinate finite; `triangles` and `neighbours` index within
/// `vertices` and `triangles` (or are [`NONE`] for a missing neighbour), and neighbours are
/// symmetric; `frames` and `corner_normals` have one entry per triangle, all finite;
/// `fan_start` has `vertices.len() + 1` non-decreasing entries from 0 to
/// `fan_triangles.len()`, and every triangle in the fan of `v` has a corner at `v`;
/// `source` holds one index below the triangle count per triangle (a permutation when
/// built by [`Surface::new`]); the report describes the mesh the surface was built from.
pub(crate) struct SurfaceParts<V, T, F, N, U> {
    pub(crate) vertices: V,
    pub(crate) triangles: T,
    pub(crate) neighbours: T,
    pub(crate) frames: F,
    pub(crate) corner_normals: N,
    pub(crate) fan_start: U,
    pub(crate) fan_triangles: U,
    pub(crate) source: U,
    pub(crate) report: MeshReport,
}

/// Owned parts, as [`Surface::from_parts`] takes them.
pub(crate) type OwnedSurfaceParts =
    SurfaceParts<Array<DVec3>, Array<[u32; 3]>, Array<TriFrame>, Array<CornerNormals>, Array<u32>>;

/// Borrowed parts, as [`Surface::parts`] gives them (the report is cloned).
pub(crate) type SurfacePartsRef<'a> =
    SurfaceParts<&'a [DVec3], &'a [[u32; 3]], &'a [TriFrame], &'a [CornerNormals], &'a [u32]>;

impl Surface {
    /// Reassembles a surface from trusted parts (a saved file, after its checks), without
    /// recomputing anything. See [`SurfaceParts`] for what the caller guarantees.
    pub(crate) fn from_parts(parts: OwnedSurfaceParts) -> Surface {
        let SurfaceParts {
            vertices,
            triangles,
            neighbours,
            frames,
            corner_normals,
            fan_start,
            fan_triangles,
            source,
            report,
        } = parts;
        Surface {
            vertices,
            triangles,
            neighbours,
            frames,
            corner_normals,
            fan_start,
            fan_triangles,
            source,
            report,
            crease_angle_rad: DEFAULT_CREASE_ANGLE_RAD,
            uid: next_uid(),
        }
    }

    /// The arrays of the surface, borrowed, for saving.
    pub(crate) fn parts(&self) -> SurfacePartsRef<'_> {
        SurfaceParts {
            vertices: &self.vertices,
            triangles: &self.triangles,
            neighbours: &self.neighbours,
            frames: &self.frames,
            corner_normals: &self.corner_normals,
            fan_start: &self.fan_start,
            fan_triangles: &self.fan_triangles,
            source: &self.source,
            report: self.report.clone(),
        }
    }
}

/// Neighbours across each edge: set for edges used by exactly two distinct triangles.
fn link_neighbours(triangle_count: usize, edges: &EdgeTable) -> Vec<[u32; 3]> {
    let mut neighbours = vec![[NONE; 3]; triangle_count];
    for group in edges.groups() {
        if let [h0, h1] = group
            && h0.tri != h1.tri
        {
            neighbours[h0.tri as usize][h0.corner as usize] = h1.tri;
            neighbours[h1.tri as usize][h1.corner as usize] = h0.tri;
        }
    }
    neighbours
}

/// `neighbours` of a mesh, for the mesh whose triangle `t` is the mesh's triangle
/// `source[t]` (with its corners in the same order).
fn renumber_neighbours(neighbours: &[[u32; 3]], source: &[u32]) -> Vec<[u32; 3]> {
    let mut new_index = vec![0u32; source.len()];
    for (t, &s) in source.iter().enumerate() {
        new_index[s as usize] = t as u32;
    }
    source
        .par_iter()
        .map(|&s| {
            neighbours[s as usize].map(|n| {
                if n == NONE {
                    NONE
                } else {
                    new_index[n as usize]
                }
            })
        })
        .collect()
}

/// The fans as compressed rows: triangles around vertex `v` are
/// `triangles[start[v]..start[v + 1]]`, each fan sorted into rotational order.
fn build_fans(
    vertex_count: usize,
    triangles: &[[u32; 3]],
    neighbours: &[[u32; 3]],
) -> (Vec<u32>, Vec<u32>) {
    let mut start = vec![0u32; vertex_count + 1];
    for tri in triangles.iter().filter(|t| has_distinct_corners(t)) {
        for &v in tri {
            start[v as usize + 1] += 1;
        }
    }
    for v in 0..vertex_count {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut fan = vec![0u32; start[vertex_count] as usize];
    for (t, tri) in triangles.iter().enumerate() {
        if has_distinct_corners(tri) {
            for &v in tri {
                fan[fill[v as usize] as usize] = t as u32;
                fill[v as usize] += 1;
            }
        }
    }
    // In parallel over runs of vertices, whose fans lie one after the other.
    let mut runs: Vec<(usize, &mut [u32])> = Vec::new();
    let mut rest: &mut [u32] = &mut fan;
    for first in (0..vertex_count).step_by(FAN_RUN) {
        let end = (first + FAN_RUN).min(vertex_count);
        let (run, tail) = rest.split_at_mut((start[end] - start[first]) as usize);
        runs.push((first, run));
        rest = tail;
    }
    runs.par_iter_mut().for_each(|(first, run)| {
        let mut scratch = FanScratch::default();
        let base = start[*first] as usize;
        for v in *first..(*first + FAN_RUN).min(vertex_count) {
            let range = start[v] as usize - base..start[v + 1] as usize - base;
            order_fan(
                v as u32,
                &mut run[range],
                triangles,
                neighbours,
                &mut scratch,
            );
        }
    });
    (start, fan)
}

/// Vertices whose fans [`build_fans`] orders in one parallel task.
const FAN_RUN: usize = 4096;

/// Puts the triangles around `v` in rotational order: from a triangle at a boundary (if
/// any), step across the edge at `v` not yet crossed, until the fan closes or ends. What is
/// left (other fans of a non-manifold vertex) follows, each ordered the same way.
/// `O(k log k)` for a fan of `k` triangles.
fn order_fan(
    v: u32,
    fan: &mut [u32],
    triangles: &[[u32; 3]],
    neighbours: &[[u32; 3]],
    scratch: &mut FanScratch,
) {
    if fan.len() < 3 {
        return;
    }
    let FanScratch {
        sorted,
        visited,
        ordered,
    } = scratch;
    sorted.clear();
    sorted.extend_from_slice(fan);
    sorted.sort_unstable();
    visited.clear();
    visited.resize(fan.len(), false);
    ordered.clear();
    let slot = |t: u32| sorted.binary_search(&t).ok();
    let corner_of = |t: u32, w: u32| triangles[t as usize].iter().position(|&x| x == w);
    let opens_at_v = |t: u32| {
        let i = corner_of(t, v).unwrap_or(0);
        neighbours[t as usize][(i + 1) % 3] == NONE
    };
    // Cursors over `fan` for the next start: they only move forward (a triangle passed
    // over is visited, or not open, for good), so a fan of many pieces (a vertex shared by
    // thousands of stacked triangles) costs `O(k log k)`, not `O(k²)`.
    let (mut open_cursor, mut any_cursor) = (0, 0);
    while ordered.len() < fan.len() {
        // Prefer a start whose one edge at `v` is open, so an open fan is walked end to end.
        while open_cursor < fan.len() {
            let t = fan[open_cursor];
            if slot(t).is_some_and(|k| !visited[k]) && opens_at_v(t) {
                break;
            }
            open_cursor += 1;
        }
        let start = if open_cursor < fan.len() {
            Some(fan[open_cursor])
        } else {
            while any_cursor < fan.len() && slot(fan[any_cursor]).is_none_or(|k| visited[k]) {
                any_cursor += 1;
            }
            fan.get(any_cursor).copied()
        };
        let Some(mut t) = start else { break };
        // Enter `t` as if across its edge opposite corner i+1, i.e. from vertex tri[i+2].
        let i = corner_of(t, v).unwrap_or(0);
        let mut came_from = triangles[t as usize][(i + 2) % 3];
        loop {
            if let Some(k) = slot(t) {
                visited[k] = true;
            }
            ordered.push(t);
            // Leave across the other edge at `v`: the one opposite the corner of `came_from`.
            let Some(j) = corner_of(t, came_from) else {
                break;
            };
            let next = neighbours[t as usize][j];
            match slot(next) {
                Some(k) if next != NONE && !visited[k] => {}
                _ => break,
            }
            // The shared edge runs from `v` to the third vertex of `t`.
            came_from = triangles[t as usize]
                .iter()
                .copied()
                .find(|&x| x != v && x != came_from)
                .unwrap_or(came_from);
            t = next;
        }
    }
    if ordered.len() == fan.len() {
        fan.copy_from_slice(ordered);
    }
}

/// Reused buffers of [`order_fan`].
#[derive(Default)]
struct FanScratch {
    sorted: Vec<u32>,
    visited: Vec<bool>,
    ordered: Vec<u32>,
}
