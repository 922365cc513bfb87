//! Bounds on what a mesh may hold.

/// The largest vertex coordinate accepted, metres (a million kilometres; the proxy's
/// workspace radius has the same bound). Squared and cubed, as areas and volumes are, it
/// stays far from overflow.
pub const MAX_COORDINATE: f64 = 1e9;
