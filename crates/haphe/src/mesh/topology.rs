//! Topology (stub).
/// Surface.
#[derive(Debug)]
pub struct Surface;
/// Error.
#[derive(Debug)]
pub struct SurfaceError;
/// Options.
#[derive(Debug)]
pub struct SurfaceOptions;
