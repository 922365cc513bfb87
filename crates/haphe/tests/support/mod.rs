//! Helpers shared by the integration tests (`mod support;` in each test file).

#![allow(dead_code)]

use std::path::PathBuf;

use haphe::DVec3;
use haphe::mesh::Mesh;

/// Whether the larger collection of test meshes, `shared/meshes` beside the repository root
/// (for a clone at `/work/<name>`, that is `/work/shared/meshes`), was found when the crate
/// was built (see `build.rs`). Tests that need it are marked
/// `#[cfg_attr(not(shared_meshes), ignore = "needs ../shared/meshes")]`.
pub const SHARED: bool = cfg!(shared_meshes);

/// The repository's own real meshes, `meshes/` at its root (see `meshes/README.md`): a
/// subset of the shared collection, the same files.
pub fn in_tree_meshes() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../meshes"))
}

/// The real meshes the tests read (folders `models/` and `odd/`): the shared collection
/// when it is present, the repository's own `meshes/` otherwise.
pub fn meshes() -> PathBuf {
    if SHARED {
        PathBuf::from(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../../shared/meshes"
        ))
    } else {
        in_tree_meshes()
    }
}

/// The real models, the files of `models/` in [`meshes`], sorted, each with its file name.
pub fn model_files() -> Vec<(String, PathBuf)> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(meshes().join("models"))
        .expect("models/ is readable")
        .map(|e| e.expect("entry").path())
        .collect();
    paths.sort();
    paths
        .into_iter()
        .map(|path| {
            let name = path.file_name().expect("name").to_string_lossy();
            (name.into_owned(), path)
        })
        .collect()
}

/// Appends `part` to `mesh`: its vertices, each mapped by `place`, and its triangles with
/// their corners renumbered.
fn push_part(mesh: &mut Mesh, part: &Mesh, place: impl Fn(DVec3) -> DVec3) {
    let n = mesh.vertices.len() as u32;
    mesh.vertices
        .extend(part.vertices.iter().map(|&v| place(v)));
    mesh.triangles
        .extend(part.triangles.iter().map(|t| t.map(|v| v + n)));
}

/// `a` and `b` in one mesh, neither moved.
pub fn append(a: &Mesh, b: &Mesh) -> Mesh {
    let mut out = a.clone();
    push_part(&mut out, b, |v| v);
    out
}

/// `parts`, each moved by its offset, in one mesh.
pub fn union(parts: &[(Mesh, DVec3)]) -> Mesh {
    let mut mesh = Mesh::default();
    for (part, offset) in parts {
        push_part(&mut mesh, part, |v| v + *offset);
    }
    mesh
}
