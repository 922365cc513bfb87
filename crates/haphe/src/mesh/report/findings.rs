//! What a mesh report holds: counts, components and the place of every defect.

use serde::{Deserialize, Serialize};

/// An undirected edge `[low vertex, high vertex]` and the triangles that use it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct EdgeUse {
    /// The edge's vertices, lower index first.
    pub edge: [u32; 2],
    /// The triangles that use the edge.
    pub triangles: Vec<u32>,
}

/// One connected component (triangles joined through shared edges).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ComponentReport {
    /// Number of triangles.
    pub triangles: usize,
    /// Smallest triangle index in the component (to find it).
    pub first_triangle: u32,
    /// Every edge of the component is used by exactly two of its triangles.
    pub closed: bool,
    /// Closed, with no non-manifold vertex and consistent orientation.
    pub manifold_oriented: bool,
    /// Genus (number of handles) of a closed, manifold, oriented component; `None` otherwise.
    pub genus: Option<u32>,
    /// Signed enclosed volume, m³ (meaningful when closed and oriented; positive when the
    /// normals point out).
    pub volume: f64,
    /// Surface area, m².
    pub area: f64,
    /// How many other closed components enclose this one (a cavity has depth 1); `None`
    /// when nesting was not computed (too many components, or not closed).
    pub depth: Option<u32>,
    /// A closed oriented component whose normals point inward while it is not inside
    /// another solid (so it is not a cavity): inside out.
    pub inverted: bool,
}

/// Every defect listed with its place (vertex, edge or triangle indices, after welding).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Defects {
    /// Edges used by one triangle only (the mesh is open there).
    pub boundary_edges: Vec<[u32; 2]>,
    /// Edges used by three or more triangles.
    pub nonmanifold_edges: Vec<EdgeUse>,
    /// Vertices whose triangles form more than one fan (two cones touching at a tip).
    pub nonmanifold_vertices: Vec<u32>,
    /// Edges whose two triangles run it the same way (inconsistent orientation).
    pub orientation_conflicts: Vec<EdgeUse>,
    /// Triangles with (practically) zero area or a repeated vertex.
    pub degenerate_triangles: Vec<u32>,
    /// Long thin triangles (see `SLIVER_MAX_RELATIVE_HEIGHT`).
    pub sliver_triangles: Vec<u32>,
    /// Pairs `[first, duplicate]` of triangles with the same three vertices.
    pub duplicate_faces: Vec<[u32; 2]>,
    /// The triangles to flip for a consistent orientation (where
    /// [`orientation_conflicts`](Defects::orientation_conflicts) are): in each part, the
    /// smaller of the two classes its conflicts split it into. Empty when oriented.
    #[serde(default)]
    pub faces_to_flip: Vec<u32>,
    /// The holes: the [boundary edges](Defects::boundary_edges) joined into loops, each
    /// the list of its vertices (as many as its edges), in the direction its triangles
    /// run them.
    #[serde(default)]
    pub holes: Vec<Vec<u32>>,
    /// Indices into [`MeshReport::component_list`] of inside-out components.
    pub inverted_components: Vec<u32>,
    /// Indices into [`MeshReport::component_list`] of solids that lie inside another solid
    /// (overlapping parts): inside is their union, but the surface between them cannot be
    /// touched.
    pub nested_solids: Vec<u32>,
}

/// What haphe can do with a mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Usability {
    /// A valid closed solid: closed, manifold, consistently oriented, not inside out, no
    /// duplicate faces. Inside and outside are defined.
    Solid,
    /// Usable only as a surface touched from either side (no inside).
    Surface,
    /// Nothing to touch: no triangle with area.
    Unusable,
}

/// The validation report of a mesh. Field names are also the JSON names of
/// `haphe validate --json`.
///
/// Counts are after welding. Lengths are metres, areas m², volumes m³, object frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeshReport {
    /// Number of triangles.
    pub triangles: usize,
    /// Number of vertices.
    pub vertices: usize,
    /// Number of distinct undirected edges.
    pub edges: usize,
    /// Number of connected components (through shared edges).
    pub components: usize,
    /// Every edge is shared by exactly two triangles.
    pub closed: bool,
    /// Edges used by exactly one triangle.
    pub boundary_edges: usize,
    /// Edges used by three or more triangles.
    pub nonmanifold_edges: usize,
    /// Vertices where more than one fan of triangles meet.
    pub nonmanifold_vertices: usize,
    /// Edges whose two triangles are oriented inconsistently.
    pub orientation_conflicts: usize,
    /// Closed oriented components that are inside out.
    pub inverted_components: usize,
    /// Closed components with outward normals that lie inside another solid.
    pub nested_solids: usize,
    /// Triangles with (practically) zero area or a repeated vertex.
    pub degenerate_triangles: usize,
    /// Long thin (but usable) triangles.
    pub sliver_triangles: usize,
    /// Triangles with the same vertices as an earlier one.
    pub duplicate_faces: usize,
    /// Sum of the genus of the closed, manifold, oriented components; `None` when there is
    /// none.
    pub genus: Option<u32>,
    /// Lower corner of the bounding box, metres.
    pub bounds_min: [f64; 3],
    /// Upper corner of the bounding box, metres.
    pub bounds_max: [f64; 3],
    /// Surface area, m².
    pub area: f64,
    /// Enclosed volume, m³: the sum of the components' signed volumes when the mesh is
    /// closed and consistently oriented (cavities subtract; overlapping solids count
    /// twice), else `None` (an open mesh encloses nothing).
    pub volume: Option<f64>,
    /// What haphe can use the mesh for.
    pub usable_as: Usability,
    /// Per-component details, in order of their first triangle.
    pub component_list: Vec<ComponentReport>,
    /// Every defect, with its place.
    pub defects: Defects,
}
