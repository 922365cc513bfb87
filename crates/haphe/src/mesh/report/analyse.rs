//! The analysis behind [`MeshReport::of`].

use crate::par::*;
use glam::DVec3;
use rustc_hash::FxHashMap;

use super::findings::{ComponentReport, Defects, EdgeUse, MeshReport, Usability};
use super::nesting;
use crate::mesh::Mesh;
use crate::mesh::edges::{EdgeTable, HalfEdge, has_distinct_corners};
use crate::mesh::frame::{
    DEGENERATE_MAX_RELATIVE_HEIGHT, SLIVER_MAX_RELATIVE_HEIGHT, relative_height,
};
use crate::mesh::repair::{faces_to_flip, hole_loops};
use crate::mesh::weld::{find, union};

/// Per-triangle measures: area (m²), signed volume of the tetrahedron with the origin (m³),
/// relative height (see [`relative_height`]).
struct TriMeasure {
    area: f64,
    volume: f64,
    relative_height: f64,
}

pub(super) fn analyse(mesh: &Mesh) -> MeshReport {
    analyse_with_edges(mesh).0
}

/// The report and the edge table it was computed from (which the topology reuses).
pub(crate) fn analyse_with_edges(mesh: &Mesh) -> (MeshReport, EdgeTable) {
    let tris = &mesh.triangles;
    // Measure relative to the box centre, so signed volumes of far-away meshes keep digits.
    let (lo, hi) = mesh.bounds().unwrap_or((DVec3::ZERO, DVec3::ZERO));
    let measures = measure(mesh, 0.5 * (lo + hi));

    let mut defects = Defects::default();
    for (t, m) in measures.iter().enumerate() {
        if m.relative_height <= DEGENERATE_MAX_RELATIVE_HEIGHT {
            defects.degenerate_triangles.push(t as u32);
        } else if m.relative_height < SLIVER_MAX_RELATIVE_HEIGHT {
            defects.sliver_triangles.push(t as u32);
        }
    }

    let table = EdgeTable::build(tris);
    let Joined {
        edges,
        mut component_parent,
        mut corner_parent,
    } = join_edges(tris, &table, &mut defects);
    defects.nonmanifold_vertices =
        nonmanifold_vertices(tris, &mut corner_parent, mesh.vertices.len());
    defects.duplicate_faces = duplicate_faces(tris, &table);
    if !defects.orientation_conflicts.is_empty() {
        defects.faces_to_flip = faces_to_flip(tris, &table);
    }
    if !defects.boundary_edges.is_empty() {
        defects.holes = hole_loops(&table);
    }

    let (mut component_list, component_of) =
        components(mesh, &table, &measures, &mut component_parent, &defects);
    nesting::mark_nesting(mesh, &component_of, &mut component_list);
    defects.inverted_components = component_list
        .iter()
        .enumerate()
        .filter(|(_, c)| c.inverted)
        .map(|(i, _)| i as u32)
        .collect();
    defects.nested_solids = component_list
        .iter()
        .enumerate()
        .filter(|(_, c)| c.volume > 0.0 && c.depth.is_some_and(|d| !d.is_multiple_of(2)))
        .map(|(i, _)| i as u32)
        .collect();

    let closed = defects.boundary_edges.is_empty() && defects.nonmanifold_edges.is_empty();
    let oriented = defects.orientation_conflicts.is_empty();
    let usable_as = usability(&defects, tris.len(), closed && oriented);
    let genus = component_list
        .iter()
        .filter_map(|c| c.genus)
        .reduce(|a, b| a + b);
    let report = MeshReport {
        triangles: tris.len(),
        vertices: mesh.vertices.len(),
        edges,
        components: component_list.len(),
        closed,
        boundary_edges: defects.boundary_edges.len(),
        nonmanifold_edges: defects.nonmanifold_edges.len(),
        nonmanifold_vertices: defects.nonmanifold_vertices.len(),
        orientation_conflicts: defects.orientation_conflicts.len(),
        inverted_components: defects.inverted_components.len(),
        nested_solids: defects.nested_solids.len(),
        degenerate_triangles: defects.degenerate_triangles.len(),
        sliver_triangles: defects.sliver_triangles.len(),
        duplicate_faces: defects.duplicate_faces.len(),
        genus,
        bounds_min: lo.to_array(),
        bounds_max: hi.to_array(),
        area: measures.iter().map(|m| m.area).sum(),
        volume: (closed && oriented).then(|| measures.iter().map(|m| m.volume).sum()),
        usable_as,
        component_list,
        defects,
    };
    (report, table)
}

/// The measures of every triangle, relative to `centre`.
fn measure(mesh: &Mesh, centre: DVec3) -> Vec<TriMeasure> {
    let tris = &mesh.triangles;
    (0..tris.len())
        .into_par_iter()
        .map(|t| {
            let [a, b, c] = mesh.corners(t).map(|p| p - centre);
            TriMeasure {
                area: 0.5 * (b - a).cross(c - a).length(),
                volume: a.dot(b.cross(c)) / 6.0,
                relative_height: if has_distinct_corners(&tris[t]) {
                    relative_height(a, b, c)
                } else {
                    0.0
                },
            }
        })
        .collect()
}

/// What the edges join: the number of distinct edges, the triangles joined by any shared
/// edge (union–find parents of the components), and the corners `3·t + i` joined across
/// manifold edges around their shared vertex (fans: a vertex with more than one fan is
/// non-manifold).
struct Joined {
    edges: usize,
    component_parent: Vec<u32>,
    corner_parent: Vec<u32>,
}

/// Joins the triangles and corners across the edges of `table`, recording boundary,
/// non-manifold and conflicting edges in `defects`.
fn join_edges(tris: &[[u32; 3]], table: &EdgeTable, defects: &mut Defects) -> Joined {
    let mut edges = 0;
    let mut component_parent: Vec<u32> = (0..tris.len() as u32).collect();
    let mut corner_parent: Vec<u32> = (0..3 * tris.len() as u32).collect();
    for group in table.groups() {
        edges += 1;
        let edge = group[0].vertices();
        for pair in group.windows(2) {
            union(&mut component_parent, pair[0].tri, pair[1].tri);
        }
        match group {
            [_] => defects.boundary_edges.push(edge),
            [h0, h1] => {
                if h0.forward == h1.forward {
                    defects.orientation_conflicts.push(edge_use(edge, group));
                }
                for v in edge {
                    union(
                        &mut corner_parent,
                        corner_of(tris, h0.tri, v),
                        corner_of(tris, h1.tri, v),
                    );
                }
            }
            _ => defects.nonmanifold_edges.push(edge_use(edge, group)),
        }
    }
    Joined {
        edges,
        component_parent,
        corner_parent,
    }
}

/// What haphe can do with a mesh of `triangles` triangles with `defects`, closed and
/// consistently oriented or not.
fn usability(defects: &Defects, triangles: usize, closed_and_oriented: bool) -> Usability {
    let has_area = defects.degenerate_triangles.len() < triangles;
    if !has_area {
        Usability::Unusable
    } else if closed_and_oriented
        && defects.nonmanifold_vertices.is_empty()
        && defects.inverted_components.is_empty()
        && defects.duplicate_faces.is_empty()
    {
        Usability::Solid
    } else {
        Usability::Surface
    }
}

fn edge_use(edge: [u32; 2], group: &[HalfEdge]) -> EdgeUse {
    EdgeUse {
        edge,
        triangles: group.iter().map(|h| h.tri).collect(),
    }
}

/// The corner index `3·t + i` of vertex `v` in triangle `t`.
fn corner_of(tris: &[[u32; 3]], t: u32, v: u32) -> u32 {
    let i = tris[t as usize].iter().position(|&w| w == v).unwrap_or(0);
    3 * t + i as u32
}

/// Vertices with more than one fan. Corners are only ever joined with corners of the same
/// vertex, so each set of joined corners is one fan, and its root (the smallest corner, see
/// [`union`]) is a corner of that vertex: a vertex has as many fans as it has root corners.
fn nonmanifold_vertices(
    tris: &[[u32; 3]],
    corner_parent: &mut [u32],
    vertex_count: usize,
) -> Vec<u32> {
    let mut fans = vec![0u32; vertex_count];
    for (t, tri) in tris.iter().enumerate() {
        if !has_distinct_corners(tri) {
            continue;
        }
        for (i, &v) in tri.iter().enumerate() {
            let corner = (3 * t + i) as u32;
            if find(corner_parent, corner) == corner {
                fans[v as usize] += 1;
            }
        }
    }
    (0..vertex_count as u32)
        .filter(|&v| fans[v as usize] > 1)
        .collect()
}

/// Pairs `[first, duplicate]` of triangles with the same vertex set (in any order),
/// sorted by the duplicate. Two such triangles share all their edges; each pair is found
/// once, at the edge between its two smallest vertices, by comparing third vertices.
fn duplicate_faces(tris: &[[u32; 3]], table: &EdgeTable) -> Vec<[u32; 2]> {
    let mut out = Vec::new();
    let mut thirds: Vec<(u32, u32)> = Vec::new();
    for group in table.groups().filter(|g| g.len() > 1) {
        let [_, hi] = group[0].vertices();
        thirds.clear();
        thirds.extend(group.iter().filter_map(|h| {
            let third = tris[h.tri as usize][h.corner as usize];
            (third > hi).then_some((third, h.tri))
        }));
        thirds.sort_unstable();
        for same in thirds.chunk_by(|a, b| a.0 == b.0) {
            out.extend(same[1..].iter().map(|&(_, dup)| [same[0].1, dup]));
        }
    }
    out.sort_unstable_by_key(|&[_, dup]| dup);
    out
}

/// Per-component measures, and the component of each triangle (`usize::MAX` for triangles
/// with a repeated vertex, which belong to none). Components are numbered in the order of
/// their first triangle.
fn components(
    mesh: &Mesh,
    table: &EdgeTable,
    measures: &[TriMeasure],
    parent: &mut [u32],
    defects: &Defects,
) -> (Vec<ComponentReport>, Vec<usize>) {
    let tris = &mesh.triangles;
    // Degenerate triangles with a repeated vertex have no edges: they are their own
    // component of zero area, which would only confuse; fold them into no component.
    let mut index_of_root: FxHashMap<u32, usize> = FxHashMap::default();
    let mut component_of = vec![usize::MAX; tris.len()];
    let mut list: Vec<ComponentReport> = Vec::new();
    let mut counts = Vec::new(); // (vertices, edges, boundary, nonmanifold edges, conflicts)
    for t in 0..tris.len() {
        if !has_distinct_corners(&tris[t]) {
            continue;
        }
        let root = find(parent, t as u32);
        let c = *index_of_root.entry(root).or_insert_with(|| {
            list.push(ComponentReport {
                triangles: 0,
                first_triangle: t as u32,
                closed: true,
                manifold_oriented: true,
                genus: None,
                volume: 0.0,
                area: 0.0,
                depth: None,
                inverted: false,
            });
            counts.push([0usize; 5]);
            list.len() - 1
        });
        component_of[t] = c;
        list[c].triangles += 1;
        list[c].volume += measures[t].volume;
        list[c].area += measures[t].area;
    }
    // Vertices per component: each (vertex, component) pair once. A vertex almost always
    // belongs to one component; the rare others (non-manifold vertices) go to a set.
    let mut first_component = vec![usize::MAX; mesh.vertices.len()];
    let mut also: rustc_hash::FxHashSet<(u32, usize)> = Default::default();
    for (t, tri) in tris.iter().enumerate() {
        let c = component_of[t];
        if c == usize::MAX {
            continue;
        }
        for &v in tri {
            let first = &mut first_component[v as usize];
            let new = if *first == usize::MAX {
                *first = c;
                true
            } else {
                *first != c && also.insert((v, c))
            };
            if new {
                counts[c][0] += 1;
            }
        }
    }
    for group in table.groups() {
        let c = component_of[group[0].tri as usize];
        counts[c][1] += 1;
        match group.len() {
            1 => counts[c][2] += 1,
            2 if group[0].forward == group[1].forward => counts[c][4] += 1,
            2 => {}
            _ => counts[c][3] += 1,
        }
    }
    let nonmanifold_vertex_components: Vec<bool> = {
        let mut flag = vec![false; list.len()];
        let is_nm: rustc_hash::FxHashSet<u32> =
            defects.nonmanifold_vertices.iter().copied().collect();
        for (t, tri) in tris.iter().enumerate() {
            if component_of[t] != usize::MAX && tri.iter().any(|v| is_nm.contains(v)) {
                flag[component_of[t]] = true;
            }
        }
        flag
    };
    for (c, comp) in list.iter_mut().enumerate() {
        let [v, e, boundary, nonmanifold, conflicts] = counts[c];
        comp.closed = boundary == 0 && nonmanifold == 0;
        comp.manifold_oriented = comp.closed && conflicts == 0 && !nonmanifold_vertex_components[c];
        if comp.manifold_oriented {
            // Euler: V − E + F = 2 − 2g for a closed orientable surface.
            let chi = v as i64 - e as i64 + comp.triangles as i64;
            comp.genus = u32::try_from((2 - chi) / 2).ok();
        }
    }
    (list, component_of)
}
