//! Hostile inputs through the real `haphe` binary: every one gets a clear answer (an error
//! naming the file and the place, or a correct result) — never a hang, a silent wrong
//! answer or a lost file. One file per theme; see `docs/limits-of-input.md`.

#[path = "../common/mod.rs"]
mod common;
mod disk_full;
mod feel;
mod inputs;
mod maps;
mod messages;
mod outputs;
mod queries;
mod repair;
mod tool;
mod validate;
mod values;
