//! Batch queries: many points or segments at once, every row checked finite before any is
//! answered. The entry points of the Python and C bindings' batch calls.
//!
//! A single query ([`classify_point`], [`first_crossing`]) answers a non-finite input as
//! "outside" or "no crossing", which keeps a servo tick free of errors; a batch of rows
//! from a file or an array instead refuses such a row by default, naming it, because a NaN
//! there is almost always a bug upstream (an uninitialised value, a division by zero) that
//! a silent "outside" would hide. [`NonFinite::Skip`] asks for the silent answer
//! explicitly.

use glam::DVec3;

use super::{Crossing, Side, classify_point, first_crossing};
use crate::map::VoxelMap;
use crate::mesh::Surface;

/// What a batch query does with a row that has a NaN or infinite coordinate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NonFinite {
    /// Refuse the batch, answering no row: [`BatchError::NonFinite`] names the first such
    /// row.
    #[default]
    Error,
    /// Skip the row: it answers what a query finds nowhere (not inside, no crossing,
    /// nothing near), and its output is left as the caller filled it.
    Skip,
}

/// A batch the batch queries refuse.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BatchError {
    /// A row with a NaN or infinite coordinate, under [`NonFinite::Error`]: the first one.
    #[error(
        "{argument}: row {row} is not finite: {value:?} (the skip option answers such rows as nothing found)"
    )]
    NonFinite {
        /// The argument the row belongs to (`points`, `p0`, `p1`).
        argument: &'static str,
        /// Its index, from 0.
        row: usize,
        /// Its coordinates.
        value: [f64; 3],
    },
    /// Two arrays that must have one row each per query differ in length.
    #[error("{first} has {first_len} rows but {second} has {second_len}")]
    Lengths {
        /// The first array.
        first: &'static str,
        /// Its rows.
        first_len: usize,
        /// The second array.
        second: &'static str,
        /// Its rows.
        second_len: usize,
    },
}

/// The first row of `rows` with a NaN or infinite coordinate, as an error naming
/// `argument`; `Ok` when every row is finite or `nonfinite` is [`NonFinite::Skip`].
///
/// # Errors
/// [`BatchError::NonFinite`].
pub fn check_rows<P: Copy + Into<DVec3>>(
    argument: &'static str,
    rows: &[P],
    nonfinite: NonFinite,
) -> Result<(), BatchError> {
    if nonfinite == NonFinite::Skip {
        return Ok(());
    }
    match rows.iter().position(|&p| !point(p).is_finite()) {
        None => Ok(()),
        Some(row) => Err(BatchError::NonFinite {
            argument,
            row,
            value: point(rows[row]).to_array(),
        }),
    }
}

/// A row as a point.
fn point<P: Into<DVec3>>(p: P) -> DVec3 {
    p.into()
}

/// Two arrays' lengths, which must be equal.
fn same_length(
    first: &'static str,
    first_len: usize,
    second: &'static str,
    second_len: usize,
) -> Result<(), BatchError> {
    if first_len == second_len {
        Ok(())
    } else {
        Err(BatchError::Lengths {
            first,
            first_len,
            second,
            second_len,
        })
    }
}

/// Checks `points` (named `argument`) with [`check_rows`], then calls `each(i, point)` for
/// every finite row in order; a skipped row gets no call.
///
/// # Errors
/// [`BatchError::NonFinite`], before any call.
pub fn for_each_point<P: Copy + Into<DVec3>>(
    argument: &'static str,
    points: &[P],
    nonfinite: NonFinite,
    mut each: impl FnMut(usize, DVec3),
) -> Result<(), BatchError> {
    check_rows(argument, points, nonfinite)?;
    for (i, &p) in points.iter().enumerate() {
        let p = point(p);
        if p.is_finite() {
            each(i, p);
        }
    }
    Ok(())
}

/// Checks that `p0` and `p1` have as many rows and are finite ([`check_rows`], `p0`
/// first), then calls `each(i, p0[i], p1[i])` for every segment whose two ends are finite,
/// in order; a skipped row gets no call.
///
/// # Errors
/// [`BatchError::Lengths`], then [`BatchError::NonFinite`], before any call.
pub fn for_each_segment<P: Copy + Into<DVec3>>(
    p0: &[P],
    p1: &[P],
    nonfinite: NonFinite,
    mut each: impl FnMut(usize, DVec3, DVec3),
) -> Result<(), BatchError> {
    same_length("p0", p0.len(), "p1", p1.len())?;
    check_rows("p0", p0, nonfinite)?;
    check_rows("p1", p1, nonfinite)?;
    for (i, (&a, &b)) in p0.iter().zip(p1).enumerate() {
        let (a, b) = (point(a), point(b));
        if a.is_finite() && b.is_finite() {
            each(i, a, b);
        }
    }
    Ok(())
}

/// Whether each point (metres, object frame) is inside the solid, by [`classify_point`]:
/// `out[i]` for `points[i]`. A skipped row answers `false`.
///
/// # Errors
/// [`BatchError::Lengths`] when `out` is not as long as `points`, [`BatchError::NonFinite`];
/// `out` is untouched then.
///
/// # Examples
/// ```
/// use haphe::DVec3;
/// use haphe::map::{MapOptions, VoxelMap};
/// use haphe::mesh::{shapes, Surface, SurfaceOptions};
/// use haphe::query::{inside_batch, BatchError, NonFinite};
/// let surface = Surface::new(shapes::sphere(0.1, 2), &SurfaceOptions::default()).unwrap();
/// let map = VoxelMap::build(&surface, &MapOptions::default()).unwrap();
/// let points = [DVec3::ZERO, DVec3::new(f64::NAN, 0.0, 0.0), DVec3::X];
/// let mut inside = [true; 3];
/// let refused = inside_batch(&surface, &map, &points, NonFinite::Error, &mut inside);
/// assert!(matches!(refused, Err(BatchError::NonFinite { row: 1, .. })));
/// inside_batch(&surface, &map, &points, NonFinite::Skip, &mut inside).unwrap();
/// assert_eq!(inside, [true, false, false]);
/// ```
pub fn inside_batch<P: Copy + Into<DVec3>>(
    surface: &Surface,
    map: &VoxelMap,
    points: &[P],
    nonfinite: NonFinite,
    out: &mut [bool],
) -> Result<(), BatchError> {
    same_length("points", points.len(), "out", out.len())?;
    check_rows("points", points, nonfinite)?;
    out.fill(false);
    for_each_point("points", points, nonfinite, |i, p| {
        out[i] = classify_point(surface, map, p).0 == Side::Inside;
    })
}

/// The first crossing of each segment `p0[i] → p1[i]` (metres, object frame) with the
/// surface, by [`first_crossing`]: `out[i]`. A skipped row answers `None`.
///
/// # Errors
/// [`BatchError::Lengths`] when the three slices differ in length,
/// [`BatchError::NonFinite`]; `out` is untouched then.
pub fn first_crossing_batch<P: Copy + Into<DVec3>>(
    surface: &Surface,
    map: &VoxelMap,
    p0: &[P],
    p1: &[P],
    nonfinite: NonFinite,
    out: &mut [Option<Crossing>],
) -> Result<(), BatchError> {
    same_length("p0", p0.len(), "out", out.len())?;
    same_length("p0", p0.len(), "p1", p1.len())?;
    check_rows("p0", p0, nonfinite)?;
    check_rows("p1", p1, nonfinite)?;
    out.fill(None);
    for_each_segment(p0, p1, nonfinite, |i, a, b| {
        out[i] = first_crossing(surface, map, a, b);
    })
}
