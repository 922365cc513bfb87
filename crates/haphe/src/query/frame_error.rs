//! The error bound of a triangle frame's directions, shared by every test that uses them.

/// Bound on the relative error of a triangle frame's normal and duals (and so on the
/// error of a height or weight computed from them, relative to the distance from the
/// triangle's first corner): the cross product behind them loses about `ε / h` where `h`
/// is the smallest altitude over the longest edge, at most `2e-7` for a triangle that is
/// not degenerate ([`DEGENERATE_MAX_RELATIVE_HEIGHT`](crate::mesh::DEGENERATE_MAX_RELATIVE_HEIGHT));
/// fifty times that, so that [`cannot_cross`](super::crossing::cannot_cross) never skips a triangle the watertight test
/// would hit.
pub(crate) const FRAME_DIRECTION_ERROR: f64 = 1e-5;
