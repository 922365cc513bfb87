//! Consistent orientation: which triangles to flip so that every edge shared by two
//! triangles is run in opposite directions by them.

use std::collections::VecDeque;

use crate::mesh::edges::EdgeTable;

/// The triangles to flip for a consistent orientation, in index order: in each group of
/// triangles joined through edges used by exactly two triangles, the smaller of the two
/// classes that a consistent orientation splits it into (on a tie, the class without the
/// group's first triangle). Empty when the mesh is consistently oriented. A group that no
/// flip can orient (a Möbius strip) keeps the classes its first sweep gave.
///
/// # Performance
/// Linear in the number of triangles (one breadth-first sweep over the edge table).
pub(crate) fn faces_to_flip(triangles: &[[u32; 3]], table: &EdgeTable) -> Vec<u32> {
    let n = triangles.len();
    // For each triangle, its neighbours through manifold edges and whether the two run
    // the edge the same way (one of them must flip relative to the other).
    let mut links: Vec<Vec<(u32, bool)>> = vec![Vec::new(); n];
    for group in table.groups() {
        if let [a, b] = group {
            let differ = a.forward == b.forward;
            links[a.tri as usize].push((b.tri, differ));
            links[b.tri as usize].push((a.tri, differ));
        }
    }
    let mut class: Vec<Option<bool>> = vec![None; n];
    let mut flips = Vec::new();
    let mut queue = VecDeque::new();
    let mut members = Vec::new();
    for start in 0..n {
        if class[start].is_some() {
            continue;
        }
        class[start] = Some(false);
        queue.push_back(start);
        members.clear();
        while let Some(t) = queue.pop_front() {
            members.push(t as u32);
            let c = class[t].unwrap_or(false);
            for &(u, differ) in &links[t] {
                if class[u as usize].is_none() {
                    class[u as usize] = Some(c ^ differ);
                    queue.push_back(u as usize);
                }
            }
        }
        let other = members
            .iter()
            .filter(|&&t| class[t as usize] == Some(true))
            .count();
        // Flip the smaller class (the first triangle's class stays on a tie).
        let flip_class = other * 2 <= members.len();
        flips.extend(
            members
                .iter()
                .filter(|&&t| class[t as usize] == Some(flip_class)),
        );
    }
    flips.sort_unstable();
    flips
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes;

    #[test]
    fn one_flipped_face_of_a_box_is_named() {
        let mut mesh = shapes::cuboid(glam::DVec3::splat(0.1), [1, 1, 1]);
        let table = EdgeTable::build(&mesh.triangles);
        assert!(faces_to_flip(&mesh.triangles, &table).is_empty());
        mesh.triangles[5].swap(1, 2);
        let table = EdgeTable::build(&mesh.triangles);
        assert_eq!(faces_to_flip(&mesh.triangles, &table), vec![5]);
        // Flipping every triangle but one: the one is the minority.
        for t in mesh.triangles.iter_mut() {
            t.swap(1, 2);
        }
        let table = EdgeTable::build(&mesh.triangles);
        assert_eq!(faces_to_flip(&mesh.triangles, &table), vec![5]);
    }
}
