//! The batch queries: a non-finite row is refused by default, naming the first one, or
//! skipped on request; every other row answers what the single query answers.

use haphe::DVec3;
use haphe::map::{MapOptions, VoxelMap};
use haphe::mesh::{Surface, SurfaceOptions, shapes};
use haphe::query::{
    BatchError, NonFinite, Side, classify_point, first_crossing, first_crossing_batch,
    for_each_point, for_each_segment, inside_batch,
};
use haphe::rng::SplitMix64;

fn torus() -> (Surface, VoxelMap) {
    let surface = Surface::new(
        shapes::torus(0.07, 0.03, 48, 24),
        &SurfaceOptions::default(),
    )
    .expect("valid surface");
    let map = VoxelMap::build(&surface, &MapOptions::default()).expect("map");
    (surface, map)
}

/// `n` points in the torus's box grown by a fifth.
fn random_points(n: usize, seed: u64) -> Vec<DVec3> {
    let mut rng = SplitMix64::new(seed);
    (0..n)
        .map(|_| {
            DVec3::new(
                rng.range(-0.12, 0.12),
                rng.range(-0.12, 0.12),
                rng.range(-0.04, 0.04),
            )
        })
        .collect()
}

/// The rows the tests spoil, each with a different kind of non-finite coordinate.
const BAD_ROWS: [(usize, usize, f64); 3] = [
    (17, 1, f64::NAN),
    (40, 2, f64::INFINITY),
    (333, 0, f64::NEG_INFINITY),
];

fn spoiled(mut points: Vec<DVec3>) -> Vec<DVec3> {
    for (row, axis, value) in BAD_ROWS {
        points[row][axis] = value;
    }
    points
}

#[test]
fn a_non_finite_point_is_refused_naming_the_first_row() {
    let (surface, map) = torus();
    let points = spoiled(random_points(500, 1));
    let mut out = vec![true; points.len()];
    let e = inside_batch(&surface, &map, &points, NonFinite::Error, &mut out)
        .expect_err("a NaN row is refused");
    let first = BAD_ROWS[0];
    assert!(
        matches!(e, BatchError::NonFinite { argument: "points", row, .. } if row == first.0),
        "{e:?}"
    );
    let message = e.to_string();
    assert!(
        message.starts_with("points: row 17 is not finite"),
        "{message}"
    );
    assert!(
        out.iter().all(|&o| o),
        "nothing is answered when the batch is refused"
    );
    // The same points as plain arrays name the same row.
    let arrays: Vec<[f64; 3]> = points.iter().map(|p| p.to_array()).collect();
    let mut calls = 0;
    let e = for_each_point("points", &arrays, NonFinite::Error, |_, _| calls += 1)
        .expect_err("refused");
    assert!(matches!(e, BatchError::NonFinite { row: 17, .. }) && calls == 0);
}

#[test]
fn skipped_points_answer_outside_and_the_others_as_alone() {
    let (surface, map) = torus();
    let points = spoiled(random_points(2000, 2));
    let mut out = vec![true; points.len()];
    inside_batch(&surface, &map, &points, NonFinite::Skip, &mut out).expect("skips");
    let mut inside = 0;
    for (i, (&p, &o)) in points.iter().zip(&out).enumerate() {
        if BAD_ROWS.iter().any(|&(row, _, _)| row == i) {
            assert!(!o, "row {i} is skipped");
        } else {
            assert_eq!(
                o,
                classify_point(&surface, &map, p).0 == Side::Inside,
                "row {i}"
            );
            inside += usize::from(o);
        }
    }
    assert!(
        inside > 100,
        "the sample reaches inside the torus: {inside}"
    );
}

#[test]
fn segments_check_both_ends_and_answer_as_alone() {
    let (surface, map) = torus();
    let p0 = random_points(600, 3);
    let p1 = spoiled(random_points(600, 4));
    let mut out = vec![None; p0.len()];
    let e = first_crossing_batch(&surface, &map, &p0, &p1, NonFinite::Error, &mut out)
        .expect_err("refused");
    assert!(
        matches!(
            e,
            BatchError::NonFinite {
                argument: "p1",
                row: 17,
                ..
            }
        ),
        "{e:?}"
    );
    // A bad row in p0 is named first, whatever p1 holds.
    let p0_bad = spoiled(p0.clone()).into_iter().rev().collect::<Vec<_>>();
    let first = BAD_ROWS.iter().map(|&(row, _, _)| p0.len() - 1 - row).min();
    let e = first_crossing_batch(&surface, &map, &p0_bad, &p1, NonFinite::Error, &mut out)
        .expect_err("refused");
    assert!(
        matches!(e, BatchError::NonFinite { argument: "p0", row, .. } if Some(row) == first),
        "{e:?}"
    );
    first_crossing_batch(&surface, &map, &p0, &p1, NonFinite::Skip, &mut out).expect("skips");
    let mut hits = 0;
    for (i, o) in out.iter().enumerate() {
        if BAD_ROWS.iter().any(|&(row, _, _)| row == i) {
            assert!(o.is_none(), "row {i} is skipped");
        } else {
            assert_eq!(*o, first_crossing(&surface, &map, p0[i], p1[i]), "row {i}");
            hits += usize::from(o.is_some());
        }
    }
    assert!(hits > 100, "the sample crosses the torus: {hits}");
}

#[test]
fn lengths_must_agree() {
    let (surface, map) = torus();
    let p = random_points(10, 5);
    let mut out = vec![None; 9];
    let e = first_crossing_batch(&surface, &map, &p, &p, NonFinite::Error, &mut out)
        .expect_err("refused");
    assert_eq!(e.to_string(), "p0 has 10 rows but out has 9");
    let e = for_each_segment(&p, &p[..4], NonFinite::Skip, |_, _, _| {}).expect_err("refused");
    assert_eq!(e.to_string(), "p0 has 10 rows but p1 has 4");
}
