//! Shading normals (stub).

/// Default crease angle, radians.
pub const DEFAULT_CREASE_ANGLE_RAD: f64 = 0.5;
