//! The 3D-DDA walk: the cells a segment visits, in order, and the cells its skips leave
//! out (cubes, boxes, a box until a parameter), against plain walks.

use super::*;
use crate::rng::SplitMix64;

fn grid() -> Grid {
    Grid::new(DVec3::new(-1.0, -1.0, -1.0), 0.5, [4, 4, 4]).expect("valid")
}

#[test]
fn a_segment_inside_one_cell_visits_it_once() {
    let g = grid();
    let steps: Vec<CellStep> = g
        .walk(DVec3::new(-0.9, -0.9, -0.9), DVec3::new(-0.6, -0.7, -0.8))
        .collect();
    assert_eq!(
        steps,
        [CellStep {
            cell: [0, 0, 0],
            t_enter: 0.0,
            t_exit: 1.0
        }]
    );
}

#[test]
fn a_segment_across_the_grid_enters_and_leaves_at_the_box() {
    let g = grid();
    let steps: Vec<CellStep> = g
        .walk(DVec3::new(-2.0, -0.25, 0.25), DVec3::new(2.0, -0.25, 0.25))
        .collect();
    assert_eq!(steps.len(), 4);
    assert_eq!(steps[0].t_enter, 0.25);
    assert_eq!(steps[3].t_exit, 0.75);
    for (i, s) in steps.iter().enumerate() {
        assert_eq!(s.cell, [i as u32, 1, 2]);
    }
    for w in steps.windows(2) {
        assert_eq!(w[0].t_exit, w[1].t_enter);
    }
}

#[test]
fn a_diagonal_through_corners_steps_one_axis_at_a_time() {
    let g = grid();
    let steps: Vec<CellStep> = g
        .walk(DVec3::new(-1.0, -1.0, -1.0), DVec3::new(1.0, 1.0, 1.0))
        .collect();
    assert_eq!(steps.first().map(|s| s.cell), Some([0, 0, 0]));
    assert_eq!(steps.last().map(|s| s.cell), Some([3, 3, 3]));
    assert_eq!(steps.len(), 10);
    for w in steps.windows(2) {
        let moved: u32 = (0..3).map(|a| w[0].cell[a].abs_diff(w[1].cell[a])).sum();
        assert_eq!(moved, 1, "{w:?}");
    }
}

#[test]
fn missing_or_non_finite_segments_visit_nothing() {
    let g = grid();
    assert_eq!(g.walk(DVec3::splat(2.0), DVec3::splat(3.0)).count(), 0);
    assert_eq!(g.walk(DVec3::NAN, DVec3::ZERO).count(), 0);
    assert_eq!(g.walk(DVec3::ZERO, DVec3::INFINITY).count(), 0);
    // A point segment inside the grid visits its cell.
    assert_eq!(g.walk(DVec3::ZERO, DVec3::ZERO).count(), 1);
}

/// The walk of `p0 → p1` skipping, at its `at`-th cell, the cube of `radius` around it:
/// the cells visited before and after the skip.
fn skipping_walk(g: &Grid, p0: DVec3, p1: DVec3, at: usize, radius: u32) -> Vec<CellStep> {
    walk_skipping_at(g, p0, p1, at, |walk| walk.skip_cube(radius))
}

/// The walk of `p0 → p1` calling `skip` on it after its `at`-th cell.
fn walk_skipping_at(
    g: &Grid,
    p0: DVec3,
    p1: DVec3,
    at: usize,
    skip: impl Fn(&mut CellWalk),
) -> Vec<CellStep> {
    let mut walk = g.walk(p0, p1);
    let mut steps = Vec::new();
    while let Some(step) = walk.next() {
        steps.push(step);
        if steps.len() == at + 1 {
            skip(&mut walk);
        }
    }
    steps
}

/// A box of cells: its lowest and highest cell, inclusive.
type CellBox = ([i64; 3], [i64; 3]);

/// The cube of cells within `radius` of `cell`, as a box.
fn cube(cell: [u32; 3], radius: u32) -> CellBox {
    let r = i64::from(radius);
    (
        cell.map(|c| i64::from(c) - r),
        cell.map(|c| i64::from(c) + r),
    )
}

/// What a skip of the box `lo..=hi` may leave out: the plain walk's cells after the
/// `at`-th inside the box, up to the first outside it.
fn expected_after_box(plain: &[CellStep], at: usize, (lo, hi): CellBox) -> Vec<CellStep> {
    let inside = |c: [u32; 3]| (0..3).all(|k| (lo[k]..=hi[k]).contains(&i64::from(c[k])));
    let beyond = plain[at + 1..]
        .iter()
        .position(|s| !inside(s.cell))
        .map_or(plain.len(), |i| at + 1 + i);
    plain[..=at]
        .iter()
        .chain(&plain[beyond..])
        .copied()
        .collect()
}

/// What a skip of the cube of `radius` may leave out (see [`expected_after_box`]).
fn expected_after_skip(plain: &[CellStep], at: usize, radius: u32) -> Vec<CellStep> {
    expected_after_box(plain, at, cube(plain[at].cell, radius))
}

/// On random segments over a grid, some reaching beyond it, some ending inside it, a
/// skip at a random cell of each walk of the box that `boxes` gives around that cell
/// leaves out exactly the box's cells; returns how many cells the skips left out.
fn check_random_skips(
    seed: u64,
    mut boxes: impl FnMut(&mut SplitMix64, usize, [u32; 3]) -> CellBox,
) -> usize {
    let g = Grid::new(DVec3::new(-1.0, -2.0, 0.5), 0.25, [24, 20, 22]).expect("valid");
    let (lo, hi) = (g.origin(), g.max_corner());
    let mut random = SplitMix64::new(seed);
    let mut skipped = 0;
    for i in 0..2_000 {
        let margin = DVec3::splat(0.5);
        let p0 = random.point_in(lo - margin, hi + margin);
        let p1 = random.point_in(lo - margin, hi + margin);
        let plain: Vec<CellStep> = g.walk(p0, p1).collect();
        if plain.len() < 2 {
            continue;
        }
        let at = random.index(plain.len() - 1);
        let (box_lo, box_hi) = boxes(&mut random, i, plain[at].cell);
        let skipping = walk_skipping_at(&g, p0, p1, at, |w| w.skip_box(box_lo, box_hi));
        let expected = expected_after_box(&plain, at, (box_lo, box_hi));
        skipped += plain.len() - expected.len();
        // The skip stops a millionth of a cell short of the box's face, which is a
        // larger part of the segment along an axis it hardly moves on.
        let moves = ((p1 - p0) / g.cell_size()).abs();
        let slowest = [moves.x, moves.y, moves.z]
            .into_iter()
            .filter(|&m| m > 0.0)
            .fold(f64::INFINITY, f64::min);
        assert_same_cells(
            &skipping,
            &expected,
            1e-5 * (1.0 / slowest).max(1.0),
            &format!("{p0} → {p1}, {at}, {box_lo:?}..{box_hi:?}"),
        );
    }
    skipped
}

/// The walks `skipping` and `expected` visit the same cells for the same intervals, the
/// step after a skip starting up to `early` (in units of the segment's parameter) before
/// the plain walk's.
fn assert_same_cells(skipping: &[CellStep], expected: &[CellStep], early: f64, what: &str) {
    let cells = |s: &[CellStep]| s.iter().map(|s| s.cell).collect::<Vec<_>>();
    assert_eq!(cells(skipping), cells(expected), "{what}");
    for (s, e) in skipping.iter().zip(expected) {
        // The step after a skip starts a hair early; every other boundary is the same
        // up to the rounding of its parameter.
        assert!(s.t_enter <= e.t_enter + 1e-12, "{what}: {s:?} / {e:?}");
        assert!(s.t_enter >= e.t_enter - early, "{what}: {s:?} / {e:?}");
        assert!(
            (s.t_exit - e.t_exit).abs() <= 1e-12,
            "{what}: {s:?} / {e:?}"
        );
    }
}

#[test]
fn a_skip_leaves_out_exactly_the_cells_of_the_cube() {
    // Through the box of the cube, which `skip_cube` skips (see the test below that
    // compares the two).
    let skipped = check_random_skips(5, |random, _, cell| cube(cell, 1 + random.index(6) as u32));
    assert!(skipped > 10_000, "{skipped}");
}

#[test]
fn a_box_skip_leaves_out_exactly_the_cells_of_the_box() {
    // Bricks of 8 cells and boxes of any shape around the walk's cell, some reaching
    // past the grid.
    let skipped = check_random_skips(11, |random, i, cell| {
        let cell = cell.map(i64::from);
        if i % 2 == 0 {
            let brick = cell.map(|c| c / 8 * 8);
            (brick, brick.map(|c| c + 7))
        } else {
            let lo: [i64; 3] = std::array::from_fn(|k| cell[k] - random.index(5) as i64);
            let hi: [i64; 3] = std::array::from_fn(|k| cell[k] + random.index(5) as i64);
            (lo, hi)
        }
    });
    assert!(skipped > 5_000, "{skipped}");
}

/// A skip of a brick until a parameter where the segment is still in the brick goes
/// on from the cell holding the point there, as the plain walk does from that cell;
/// until a parameter past the brick, it is the skip of the brick.
#[test]
fn a_skip_until_a_parameter_goes_on_from_its_cell() {
    let g = Grid::new(DVec3::new(-1.0, -2.0, 0.5), 0.25, [24, 20, 22]).expect("valid");
    let (lo, hi) = (g.origin(), g.max_corner());
    let mut random = SplitMix64::new(17);
    let (mut stopped, mut left) = (0, 0);
    for _ in 0..4_000 {
        let margin = DVec3::splat(0.5);
        let p0 = random.point_in(lo - margin, hi + margin);
        let p1 = random.point_in(lo - margin, hi + margin);
        let plain: Vec<CellStep> = g.walk(p0, p1).collect();
        if plain.len() < 3 {
            continue;
        }
        let at = random.index(plain.len() - 2);
        let brick = plain[at].cell.map(|c| i64::from(c) / 8 * 8);
        let (box_lo, box_hi) = (brick, brick.map(|c| c + 7));
        let inside =
            |c: [u32; 3]| (0..3).all(|k| (box_lo[k]..=box_hi[k]).contains(&i64::from(c[k])));
        let in_box = plain[at + 1..]
            .iter()
            .take_while(|s| inside(s.cell))
            .count();
        if in_box == 0 {
            // Until a parameter past the brick: the skip of the brick.
            let skip = |w: &mut CellWalk| w.skip_box_until((box_lo, box_hi), 2.0);
            assert_eq!(
                walk_skipping_at(&g, p0, p1, at, skip),
                walk_skipping_at(&g, p0, p1, at, |w| w.skip_box(box_lo, box_hi)),
                "{p0} → {p1}, {at}"
            );
            left += 1;
            continue;
        }
        let k = at + 1 + random.index(in_box);
        if plain[k].t_exit - plain[k].t_enter < 1e-6 {
            continue;
        }
        let stop = 0.5 * (plain[k].t_enter + plain[k].t_exit);
        let skip = |w: &mut CellWalk| w.skip_box_until((box_lo, box_hi), stop);
        let skipping = walk_skipping_at(&g, p0, p1, at, skip);
        let what = format!("{p0} → {p1}, {at}, until {stop} in {:?}", plain[k]);
        let cells = |s: &[CellStep]| s.iter().map(|s| s.cell).collect::<Vec<_>>();
        let expected = [&plain[..=at], &plain[k..]].concat();
        assert_eq!(cells(&skipping), cells(&expected), "{what}");
        assert_eq!(skipping[at + 1].t_enter, stop, "{what}");
        for (s, e) in skipping.iter().zip(&expected) {
            assert!(
                (s.t_exit - e.t_exit).abs() <= 1e-12,
                "{what}: {s:?} / {e:?}"
            );
        }
        stopped += 1;
    }
    assert!(stopped > 1_000 && left > 100, "{stopped} {left}");
}

#[test]
fn a_cube_skip_is_the_skip_of_its_box() {
    let g = Grid::new(DVec3::ZERO, 1.0, [16, 16, 16]).expect("valid");
    let mut random = SplitMix64::new(3);
    for _ in 0..500 {
        let (p0, p1) = (
            random.point_in(DVec3::splat(-1.0), DVec3::splat(17.0)),
            random.point_in(DVec3::splat(-1.0), DVec3::splat(17.0)),
        );
        let plain: Vec<CellStep> = g.walk(p0, p1).collect();
        if plain.len() < 2 {
            continue;
        }
        let at = random.index(plain.len() - 1);
        let radius = 1 + random.index(4) as u32;
        let (lo, hi) = cube(plain[at].cell, radius);
        assert_eq!(
            skipping_walk(&g, p0, p1, at, radius),
            walk_skipping_at(&g, p0, p1, at, |w| w.skip_box(lo, hi)),
            "{p0} → {p1}, {at}, {radius}"
        );
    }
}

#[test]
fn a_box_that_does_not_hold_the_walks_cell_is_not_skipped() {
    let g = grid();
    let (p0, p1) = (DVec3::new(-0.9, -0.8, -0.7), DVec3::new(0.9, 0.7, 0.8));
    let plain: Vec<CellStep> = g.walk(p0, p1).collect();
    let mut walk = g.walk(p0, p1);
    let mut steps = vec![walk.next().expect("a cell")];
    walk.skip_box([1, 0, 0], [3, 3, 3]);
    steps.extend(walk);
    assert_eq!(steps, plain);
}

#[test]
fn a_skip_through_cube_edges_and_corners_still_covers_the_segment() {
    // Segments along cell faces and edges and through cell corners, where the cube's
    // faces and the cell boundaries beyond it are crossed at the same parameter. There
    // the walk visits one of the cells around an edge or corner with an empty interval,
    // and which one depends on the rounding of equal parameters, so a skip may change
    // it: every cell the plain walk spends a non-empty interval in beyond the cube is
    // still visited, for the same interval, and every cell visited touches the segment.
    let g = Grid::new(DVec3::ZERO, 1.0, [16, 16, 16]).expect("valid");
    let cases = [
        (DVec3::new(0.5, 0.5, 0.5), DVec3::new(15.5, 15.5, 15.5)),
        (DVec3::new(0.0, 0.0, 0.0), DVec3::new(16.0, 16.0, 16.0)),
        (DVec3::new(16.0, 16.0, 16.0), DVec3::ZERO),
        (DVec3::new(0.0, 3.0, 4.0), DVec3::new(16.0, 3.0, 4.0)),
        (DVec3::new(15.0, 3.0, 4.5), DVec3::new(0.0, 3.0, 4.5)),
        (DVec3::new(0.5, 1.0, 2.0), DVec3::new(14.5, 8.0, 9.0)),
        (DVec3::new(3.0, 0.0, 5.0), DVec3::new(3.0, 15.0, 10.0)),
    ];
    for (p0, p1) in cases {
        let plain: Vec<CellStep> = g.walk(p0, p1).collect();
        for at in 0..plain.len() - 1 {
            for radius in 1..=4 {
                let what = format!("{p0} → {p1}, {at}, {radius}");
                let skipping = skipping_walk(&g, p0, p1, at, radius);
                let expected = expected_after_skip(&plain, at, radius);
                assert_eq!(skipping[..=at], plain[..=at], "{what}");
                let rest = &skipping[at + 1..];
                let last = |s: &[CellStep]| s.last().map(|s| s.cell);
                assert_eq!(last(rest), last(&expected[at + 1..]), "{what}");
                let centre = plain[at].cell;
                for s in rest {
                    assert!(
                        (0..3).any(|k| s.cell[k].abs_diff(centre[k]) > radius),
                        "{what}"
                    );
                    // (The step after the skip starts a hair before the cube's face.)
                    let p = p0.lerp(p1, s.t_exit);
                    let (lo, hi) = g.cell_bounds(s.cell);
                    let gap = (lo - p).max(p - hi).max_element();
                    assert!(gap <= 1e-9, "{what}: {s:?} is {gap} from the segment");
                }
                for w in rest.windows(2) {
                    let moved: u32 = (0..3).map(|k| w[0].cell[k].abs_diff(w[1].cell[k])).sum();
                    assert_eq!(moved, 1, "{what}: {w:?}");
                    assert_eq!(w[0].t_exit, w[1].t_enter, "{what}: {w:?}");
                }
                for e in expected[at + 1..]
                    .iter()
                    .filter(|e| e.t_exit > e.t_enter + 1e-9)
                {
                    let s = rest.iter().find(|s| s.cell == e.cell);
                    assert!(
                        s.is_some_and(|s| (s.t_exit - e.t_exit).abs() <= 1e-12
                            && s.t_enter <= e.t_enter + 1e-12
                            && s.t_enter >= e.t_enter - 1e-5),
                        "{what}: {e:?} / {s:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn a_skip_past_the_end_of_the_segment_or_the_grid_ends_the_walk() {
    let g = grid();
    // Ends inside the cube around its first cell.
    let mut walk = g.walk(DVec3::new(-0.9, -0.9, -0.9), DVec3::new(-0.1, -0.3, -0.6));
    assert_eq!(walk.next().map(|s| s.cell), Some([0, 0, 0]));
    walk.skip_cube(2);
    assert_eq!(walk.next(), None);
    // Leaves the grid from the cube.
    let mut walk = g.walk(DVec3::new(0.1, 0.1, 0.1), DVec3::new(3.0, 0.2, 0.3));
    assert_eq!(walk.next().map(|s| s.cell), Some([2, 2, 2]));
    walk.skip_cube(1);
    assert_eq!(walk.next(), None);
    // A radius of 0, a second skip and a skip after the end change nothing.
    let (p0, p1) = (DVec3::new(-0.9, -0.8, -0.7), DVec3::new(0.9, 0.7, 0.8));
    let plain: Vec<CellStep> = g.walk(p0, p1).collect();
    let mut walk = g.walk(p0, p1);
    let mut steps = vec![walk.next().expect("a cell")];
    walk.skip_cube(0);
    steps.extend(walk.by_ref());
    walk.skip_cube(3);
    assert_eq!(walk.next(), None);
    assert_eq!(steps, plain);
    let mut walk = g.walk(p0, p1);
    let first = walk.next().expect("a cell");
    walk.skip_cube(1);
    let once: Vec<CellStep> = walk.clone().collect();
    walk.skip_cube(1);
    assert_eq!(walk.collect::<Vec<_>>(), once);
    assert_eq!(once.first().map(|s| s.cell), Some([1, 1, 2]), "{first:?}");
}

#[test]
fn backwards_segments_visit_the_reverse_cells() {
    let g = grid();
    let (p, q) = (DVec3::new(-0.8, 0.3, -0.1), DVec3::new(0.9, -0.7, 0.6));
    let forward: Vec<[u32; 3]> = g.walk(p, q).map(|s| s.cell).collect();
    let mut backward: Vec<[u32; 3]> = g.walk(q, p).map(|s| s.cell).collect();
    backward.reverse();
    assert_eq!(forward, backward);
}
