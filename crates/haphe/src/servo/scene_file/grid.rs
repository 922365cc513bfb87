//! The grid form of a scene file's object: one `[[object]]` repeated on a regular grid,
//! so that a scene of 10^5 objects is a few lines.
//!
//! ```toml
//! [[object]]
//! shape = "sphere"
//! triangles = 1000
//! position = [0.0, 0.0, 0.0]                                  # the first copy
//! grid = { count = [100, 100, 10], spacing = [0.25, 0.25, 0.25] }   # metres, world axes
//! ```
//!
//! The copies share one shape, the material, the rotation and the motion (each copy moves
//! about its own place). Copy `(x, y, z)` sits at `position + (x·sx, y·sy, z·sz)`; they
//! are numbered x fastest, then y, then z, from the object's `id` (or from the number of
//! objects before it in the file) on, and named `NAME[x,y,z]`.

use glam::DVec3;
use serde::Deserialize;

use super::error::{MAX_OBJECTS, SceneFileError, fail};

/// The `grid` table of an object.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub struct GridSpec {
    /// Copies along x, y and z (each at least 1).
    count: [u32; 3],
    /// Distance between neighbouring copies along x, y and z, metres.
    spacing: [f64; 3],
}

/// One copy of a gridded object.
pub struct Copy {
    /// Its number among the copies (0 for the first).
    pub index: u32,
    /// Its offset from the object's position, metres.
    pub offset: DVec3,
    /// `[x,y,z]`, appended to the object's name; empty without a grid.
    pub suffix: String,
}

/// The copies of an object with the grid `grid` (one copy, at no offset, without a grid).
///
/// # Errors
/// A count of zero, a grid of more than [`MAX_OBJECTS`] copies, or a spacing that is not
/// finite, named with `place`.
pub fn copies(grid: Option<&GridSpec>, place: &str) -> Result<Vec<Copy>, SceneFileError> {
    let Some(g) = grid else {
        return Ok(vec![Copy {
            index: 0,
            offset: DVec3::ZERO,
            suffix: String::new(),
        }]);
    };
    if g.count.contains(&0) {
        bail!("{place}: `grid.count` must be at least 1 along every axis");
    }
    let total: u64 = g.count.iter().map(|&c| u64::from(c)).product();
    if total > MAX_OBJECTS as u64 {
        bail!("{place}: `grid.count` makes {total} copies, more than {MAX_OBJECTS}");
    }
    if g.spacing.iter().any(|s| !s.is_finite()) {
        bail!("{place}: `grid.spacing` must be finite");
    }
    let [nx, ny, nz] = g.count;
    let spacing = DVec3::from_array(g.spacing);
    let mut out = Vec::with_capacity(total as usize);
    for z in 0..nz {
        for y in 0..ny {
            for x in 0..nx {
                out.push(Copy {
                    index: out.len() as u32,
                    offset: DVec3::new(f64::from(x), f64::from(y), f64::from(z)) * spacing,
                    suffix: format!("[{x},{y},{z}]"),
                });
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn copies_are_numbered_x_fastest() {
        let g = GridSpec {
            count: [2, 3, 1],
            spacing: [0.5, 1.0, 2.0],
        };
        let c = copies(Some(&g), "s").unwrap();
        assert_eq!(c.len(), 6);
        assert_eq!(c[3].index, 3);
        assert_eq!(c[3].offset, DVec3::new(0.5, 1.0, 0.0));
        assert_eq!(c[3].suffix, "[1,1,0]");
        assert_eq!(copies(None, "s").unwrap().len(), 1);
    }

    #[test]
    fn bad_grids_are_refused_with_the_place() {
        let zero = GridSpec {
            count: [2, 0, 1],
            spacing: [1.0; 3],
        };
        let e = copies(Some(&zero), "f.toml: object 2 (line 9)")
            .err()
            .unwrap();
        assert!(
            e.message
                .starts_with("f.toml: object 2 (line 9): `grid.count`")
        );
        let huge = GridSpec {
            count: [1000, 1000, 2],
            spacing: [1.0; 3],
        };
        assert!(copies(Some(&huge), "s").is_err());
        let nan = GridSpec {
            count: [1; 3],
            spacing: [f64::NAN, 1.0, 1.0],
        };
        assert!(copies(Some(&nan), "s").is_err());
    }
}
