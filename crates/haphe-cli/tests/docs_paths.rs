//! The paths a user reads in the docs exist in a clone of the repository: every mesh
//! path under `meshes/` in the README, `docs/` and the C examples, and every file a
//! Python example of docs/python.md opens (unless the example says the file is the
//! reader's own). The larger collection at `../shared/meshes` is not in a user's clone.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The files a user reads: the README, the docs and the C examples.
fn read_by_users() -> Vec<(String, String)> {
    let root = root();
    let mut files = vec![root.join("README.md")];
    for folder in ["docs", "examples/c"] {
        let mut entries: Vec<PathBuf> = std::fs::read_dir(root.join(folder))
            .expect("a folder of the repository")
            .map(|e| e.expect("an entry").path())
            .filter(|p| {
                p.extension()
                    .is_some_and(|e| ["md", "c", "cpp"].contains(&e.to_str().unwrap_or("")))
            })
            .collect();
        entries.sort();
        files.extend(entries);
    }
    files
        .into_iter()
        .map(|p| {
            let text = std::fs::read_to_string(&p).expect("readable");
            let name = p.strip_prefix(&root).unwrap_or(&p).display().to_string();
            (name, text)
        })
        .collect()
}

const MESH_EXTENSIONS: [&str; 8] = [
    ".obj", ".stl", ".STL", ".ply", ".off", ".glb", ".gltf", ".map",
];

/// The words of `line` that name a mesh file (a path ending in a mesh extension).
fn mesh_paths(line: &str) -> Vec<&str> {
    line.split(|c: char| c.is_whitespace() || "`\"'(),[]=".contains(c))
        .filter(|w| MESH_EXTENSIONS.iter().any(|e| w.ends_with(e)))
        .collect()
}

#[test]
fn every_mesh_path_under_meshes_in_the_docs_exists_in_a_clone() {
    let root = root();
    let mut missing = Vec::new();
    for (name, text) in read_by_users() {
        // Developer notes about the shared collection name it as such, in prose; a
        // command or an example's usage never does.
        for (i, line) in text.lines().enumerate() {
            for path in mesh_paths(line) {
                if path.starts_with("../shared/") {
                    missing.push(format!("{name}:{}: {path} (not in a clone)", i + 1));
                } else if path.starts_with("meshes/") && !root.join(path).exists() {
                    missing.push(format!("{name}:{}: {path}", i + 1));
                }
            }
        }
    }
    assert!(
        missing.is_empty(),
        "paths a user cannot open:\n{}",
        missing.join("\n")
    );
}

#[test]
fn the_python_examples_open_files_of_the_repository() {
    let text = std::fs::read_to_string(root().join("docs/python.md")).expect("readable");
    let mut foreign = Vec::new();
    for block in text.split("```python\n").skip(1) {
        let code = block.split("\n```").next().unwrap_or("");
        if code.contains("of yours") {
            continue;
        }
        for path in code.lines().flat_map(mesh_paths) {
            if !root().join(path).exists() {
                foreign.push(path.to_string());
            }
        }
    }
    assert!(
        foreign.is_empty(),
        "docs/python.md opens {foreign:?}, not in a clone"
    );
}
