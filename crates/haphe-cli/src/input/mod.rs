//! Reading what a command is given: files opened once within limits (`files`), mesh files
//! (`mesh`), map files and their errors (`map`, `mapped`), the object of the query
//! commands, a map or a mesh (`object`), scene files and the shapes of built-in and mesh
//! objects (`scene`), the objects of a session (`model`), and volume files (`volume`).

pub mod files;
pub mod map;
pub mod mapped;
pub mod mesh;
pub mod model;
pub mod object;
pub mod scene;
pub mod volume;
