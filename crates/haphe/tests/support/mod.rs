//! Helpers shared by the integration tests (`mod support;` in each test file).

#![allow(dead_code)]

use std::path::PathBuf;

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
