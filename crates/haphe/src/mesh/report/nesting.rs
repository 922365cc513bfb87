//! Nesting of closed components: a closed component with inward normals (negative volume)
//! inside another is a cavity, not an inside-out solid. Only with nesting known can the
//! two be told apart; a component with outward normals inside another is an overlapping
//! solid (parts of an assembly), reported separately.

use crate::par::*;
use glam::DVec3;

use super::findings::ComponentReport;
use crate::mesh::Mesh;
use crate::mesh::solid_angle::solid_angle;

/// Upper bound on (closed components) × (triangles) for which nesting is computed exactly
/// with winding numbers; past it, a closed component is taken as inside out when its
/// volume is negative (the usual case of one solid).
pub(crate) const MAX_NESTING_WORK: usize = 200_000_000;

/// Sets `depth` and `inverted` of every closed, oriented component.
/// `component_of[t]` is the index in `list` of triangle `t`'s component, or `usize::MAX`.
pub(super) fn mark_nesting(mesh: &Mesh, component_of: &[usize], list: &mut [ComponentReport]) {
    let closed: Vec<usize> = (0..list.len())
        .filter(|&c| list[c].manifold_oriented)
        .collect();
    if closed.len() <= 1 || closed.len().saturating_mul(mesh.triangles.len()) > MAX_NESTING_WORK {
        for &c in &closed {
            list[c].depth = (closed.len() <= 1).then_some(0);
            list[c].inverted = list[c].volume < 0.0;
        }
        return;
    }
    // Triangles of each closed component, and one probe point per component: the centroid
    // of its first triangle (on its own surface, so off every other disjoint component).
    let component_of_first: Vec<u32> = closed.iter().map(|&c| list[c].first_triangle).collect();
    let owner = triangle_owners(component_of, &closed);
    let probes: Vec<DVec3> = component_of_first
        .iter()
        .map(|&t| {
            let [a, b, c] = mesh.corners(t as usize);
            (a + b + c) / 3.0
        })
        .collect();
    let depths: Vec<u32> = (0..closed.len())
        .into_par_iter()
        .map(|i| {
            // Winding number of the probe with respect to each other closed component.
            let mut winding = vec![0.0f64; closed.len()];
            for (t, &k) in owner.iter().enumerate() {
                if k != u32::MAX && k as usize != i {
                    winding[k as usize] += solid_angle(mesh.corners(t), probes[i]);
                }
            }
            winding
                .iter()
                .filter(|w| (*w / (4.0 * std::f64::consts::PI)).abs() > 0.5)
                .count() as u32
        })
        .collect();
    for (i, &c) in closed.iter().enumerate() {
        list[c].depth = Some(depths[i]);
        // A negative volume is a cavity at odd depth (inside a solid), and inside out at even
        // depth. A positive volume at odd depth is a solid inside another (an overlapping
        // part of an assembly): not inverted, and under the non-zero winding rule the
        // union of both is inside.
        list[c].inverted = list[c].volume < 0.0 && depths[i].is_multiple_of(2);
    }
}

/// For each triangle, the position in `closed` of its component, or `u32::MAX`.
fn triangle_owners(component_of: &[usize], closed: &[usize]) -> Vec<u32> {
    let mut slot_of = vec![
        u32::MAX;
        component_of
            .iter()
            .filter(|&&c| c != usize::MAX)
            .max()
            .map_or(0, |&c| c + 1)
    ];
    for (slot, &c) in closed.iter().enumerate() {
        slot_of[c] = slot as u32;
    }
    component_of
        .iter()
        .map(|&c| slot_of.get(c).copied().unwrap_or(u32::MAX))
        .collect()
}
