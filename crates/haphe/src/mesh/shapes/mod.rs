//! Procedural meshes for tests, benchmarks and the demo (to be written).
