//! Helpers shared by the integration tests (`mod support;` in each test file).

use std::path::PathBuf;

/// The shared test meshes: `shared/meshes` beside the repository root (for a worktree or a
/// clone at `/work/<name>`, that is `/work/shared/meshes`).
///
/// Returns `None`, after printing a notice, when the folder is absent, so tests that need it
/// pass as skipped on machines without the data.
pub fn shared_meshes() -> Option<PathBuf> {
    let dir = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/meshes"
    ));
    if dir.is_dir() {
        Some(dir)
    } else {
        eprintln!("skipping: ../shared/meshes not found");
        None
    }
}
