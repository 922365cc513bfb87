//! The constants the checks share: how near counts as on the surface, and how many
//! failures a check keeps.

/// Points closer than this to the surface (metres) may be classified either way: the
/// inside/outside and leak checks excuse them.
pub const ON_SURFACE_M: f64 = 1e-9;

/// How many failing samples a check keeps, to reproduce them.
pub const KEPT_FAILURES: usize = 5;
