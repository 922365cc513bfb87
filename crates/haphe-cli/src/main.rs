//! The `haphe` command.
fn main() {}
