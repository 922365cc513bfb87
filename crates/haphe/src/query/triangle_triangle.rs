//! Triangle–triangle intersection (to be written).

use glam::DVec3;

/// Whether two triangles intersect anywhere other than in corners they share.
pub fn intersect_triangle_triangle(_t1: [DVec3; 3], _t2: [DVec3; 3]) -> bool {
    false
}
