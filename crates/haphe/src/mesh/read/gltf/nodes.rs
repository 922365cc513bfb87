//! The node graph: checked to be a forest (one parent at most, no cycle), and walked from
//! the default scene's roots, composing each node's transform (a matrix, or translation,
//! rotation and scale) into its world transform.

use glam::{DAffine3, DMat4, DQuat, DVec3};
use gltf::json;

use super::places::{ix, place};
use crate::mesh::GltfPlace;
use crate::mesh::ReadErrorKind;

/// A node of the default scene that holds a mesh, placed in the world.
pub(super) struct Placed {
    pub node: usize,
    pub mesh: usize,
    pub world_from_node: DAffine3,
}

fn node_place(node: usize) -> GltfPlace {
    GltfPlace {
        node: Some(ix(node)),
        ..GltfPlace::default()
    }
}

fn invalid(at: GltfPlace, message: String) -> ReadErrorKind {
    ReadErrorKind::Invalid {
        at: place(at),
        message,
    }
}

/// Each node's parent, after checking that every child exists and has one parent only.
fn parents(nodes: &[json::Node]) -> Result<Vec<Option<usize>>, ReadErrorKind> {
    let mut parent: Vec<Option<usize>> = vec![None; nodes.len()];
    for (i, node) in nodes.iter().enumerate() {
        for child in node.children.iter().flatten() {
            let c = child.value();
            if c >= nodes.len() {
                return Err(invalid(
                    node_place(i),
                    format!(
                        "its child {c} does not exist (the file has {} nodes)",
                        nodes.len()
                    ),
                ));
            }
            if c == i {
                return Err(invalid(
                    node_place(i),
                    "a cycle in the node graph: the node is its own child".to_owned(),
                ));
            }
            if let Some(p) = parent[c] {
                return Err(invalid(
                    node_place(c),
                    format!(
                        "the node is a child of both node {p} and node {i}; a glTF node has \
                         one parent at most"
                    ),
                ));
            }
            parent[c] = Some(i);
        }
    }
    Ok(parent)
}

/// Fails on the first cycle of the parent links, naming its nodes.
fn check_acyclic(parent: &[Option<usize>]) -> Result<(), ReadErrorKind> {
    #[derive(Clone, Copy, PartialEq)]
    enum State {
        New,
        OnPath,
        Done,
    }
    let mut state = vec![State::New; parent.len()];
    let mut path = Vec::new();
    for start in 0..parent.len() {
        path.clear();
        let mut at = Some(start);
        while let Some(n) = at {
            match state[n] {
                State::Done => break,
                State::OnPath => {
                    // `n` is on the path: the cycle is the path from `n` on, each node a
                    // child of the next.
                    let from = path.iter().position(|&m| m == n).unwrap_or(0);
                    let mut cycle: Vec<String> = path[from..]
                        .iter()
                        .rev()
                        .map(|m| format!("node {m}"))
                        .collect();
                    cycle.push(format!("node {}", path[path.len() - 1]));
                    return Err(invalid(
                        node_place(n),
                        format!(
                            "a cycle in the node graph: {} (each the parent of the next)",
                            cycle.join(" → ")
                        ),
                    ));
                }
                State::New => {
                    state[n] = State::OnPath;
                    path.push(n);
                    at = parent[n];
                }
            }
        }
        for &n in &path {
            state[n] = State::Done;
        }
    }
    Ok(())
}

fn finite(values: &[f32]) -> bool {
    values.iter().all(|v| v.is_finite())
}

/// The node's transform, `parent_from_node`.
fn local_transform(index: usize, node: &json::Node) -> Result<DAffine3, ReadErrorKind> {
    let at = node_place(index);
    if let Some(m) = &node.matrix {
        if !finite(m) {
            return Err(invalid(
                at,
                "its matrix has a NaN or infinite entry".to_owned(),
            ));
        }
        // Column-major: the last row is entries 3, 7, 11, 15.
        if [m[3], m[7], m[11], m[15]] != [0.0, 0.0, 0.0, 1.0] {
            return Err(invalid(
                at,
                format!(
                    "its matrix's last row is [{}, {}, {}, {}], not [0, 0, 0, 1]: not an \
                     affine transform",
                    m[3], m[7], m[11], m[15]
                ),
            ));
        }
        let m: [f64; 16] = std::array::from_fn(|i| f64::from(m[i]));
        return Ok(DAffine3::from_mat4(DMat4::from_cols_array(&m)));
    }
    let t = node.translation.unwrap_or([0.0; 3]);
    let s = node.scale.unwrap_or([1.0; 3]);
    let r = node.rotation.map_or([0.0, 0.0, 0.0, 1.0], |q| q.0);
    if !(finite(&t) && finite(&s) && finite(&r)) {
        return Err(invalid(
            at,
            "its translation, rotation or scale has a NaN or infinite entry".to_owned(),
        ));
    }
    let rotation = DQuat::from_xyzw(r[0].into(), r[1].into(), r[2].into(), r[3].into());
    if rotation.length_squared() == 0.0 {
        return Err(invalid(
            at,
            "its rotation is the zero quaternion".to_owned(),
        ));
    }
    Ok(DAffine3::from_scale_rotation_translation(
        DVec3::from_array(s.map(f64::from)),
        rotation.normalize(),
        DVec3::from_array(t.map(f64::from)),
    ))
}

/// The default scene (the file's `scene`, else its first; `None` when the file has no
/// scene, and then every root node is read) and its nodes that hold a mesh, in depth-first
/// order, with their world transforms.
///
/// # Errors
/// Naming the scene or node: a reference to a node or mesh that does not exist, a node
/// with two parents, a cycle, a scene root that is a child, a transform that is not finite
/// or not affine.
pub(super) fn placed_nodes(
    root: &json::Root,
) -> Result<(Option<usize>, Vec<Placed>), ReadErrorKind> {
    let nodes = &root.nodes;
    let parent = parents(nodes)?;
    check_acyclic(&parent)?;
    let scene = match root.scene {
        Some(s) => Some(s.value()),
        None => (!root.scenes.is_empty()).then_some(0),
    };
    let roots: Vec<usize> = match scene {
        Some(s) => {
            let at = GltfPlace {
                scene: Some(ix(s)),
                ..GltfPlace::default()
            };
            let Some(scene) = root.scenes.get(s) else {
                return Err(invalid(
                    at,
                    format!(
                        "the default scene does not exist (the file has {} scenes)",
                        root.scenes.len()
                    ),
                ));
            };
            let mut listed = vec![false; nodes.len()];
            let mut roots = Vec::with_capacity(scene.nodes.len());
            for n in scene.nodes.iter().map(|n| n.value()) {
                if n >= nodes.len() {
                    return Err(invalid(
                        at,
                        format!(
                            "it lists node {n}, which does not exist (the file has {} nodes)",
                            nodes.len()
                        ),
                    ));
                }
                if let Some(p) = parent[n] {
                    return Err(invalid(
                        at,
                        format!("it lists node {n} as a root, but node {n} is a child of node {p}"),
                    ));
                }
                if std::mem::replace(&mut listed[n], true) {
                    return Err(invalid(at, format!("it lists node {n} twice")));
                }
                roots.push(n);
            }
            roots
        }
        None => (0..nodes.len()).filter(|&n| parent[n].is_none()).collect(),
    };
    let mut placed = Vec::new();
    let mut stack: Vec<(usize, DAffine3)> = roots
        .iter()
        .rev()
        .map(|&n| (n, DAffine3::IDENTITY))
        .collect();
    while let Some((n, world_from_parent)) = stack.pop() {
        let node = &nodes[n];
        let world_from_node = world_from_parent * local_transform(n, node)?;
        if !world_from_node.is_finite() {
            return Err(invalid(
                node_place(n),
                "its world transform overflows (a NaN or infinite entry)".to_owned(),
            ));
        }
        if let Some(mesh) = node.mesh {
            let mesh = mesh.value();
            if mesh >= root.meshes.len() {
                return Err(invalid(
                    node_place(n),
                    format!(
                        "its mesh {mesh} does not exist (the file has {} meshes)",
                        root.meshes.len()
                    ),
                ));
            }
            placed.push(Placed {
                node: n,
                mesh,
                world_from_node,
            });
        }
        for child in node.children.iter().flatten().rev() {
            stack.push((child.value(), world_from_node));
        }
    }
    Ok((scene, placed))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cycle_is_named_node_by_node() {
        // Node 1's parent is node 2 and node 2's is node 1: no node has two parents, and
        // only the walk up the parent links finds the cycle.
        let parent = vec![None, Some(2), Some(1)];
        let err = check_acyclic(&parent).unwrap_err().to_string();
        assert!(err.contains("cycle"), "{err}");
        assert!(err.contains("node 1") && err.contains("node 2"), "{err}");
        assert_eq!(check_acyclic(&[None, Some(0), Some(1)]), Ok(()));
    }
}
