//! Slabs: encoding, the triangles of cells, bricks and regions held in their slabs,
//! windows and parts of segments in slabs, and the file's count of slabs checked.

use super::*;
use crate::map::MapOptions;
use crate::map::{InBrick, Look, RegionLook};
use crate::mesh::SurfaceOptions;
use crate::mesh::shapes::Catalog;
use crate::rng::SplitMix64;

/// Every direction code decodes to a direction of L1 norm 1, and encoding a direction
/// gives back one within a step of the octahedral grid.
#[test]
fn directions_round_trip() {
    for code in 0..65_536u32 {
        let n = direction(code);
        assert!((n.abs().element_sum() - 1.0).abs() < 1e-12, "{code}: {n}");
    }
    let mut random = SplitMix64::new(5);
    for _ in 0..10_000 {
        let n = random.unit_vector();
        let back = direction(encode_direction(n));
        let want = n / n.abs().element_sum();
        assert!((back - want).abs().max_element() < 0.02, "{n} → {back}");
    }
}

/// The axes are encoded exactly: a plane along an axis gets a slab as thin as its
/// triangles.
#[test]
fn axis_directions_are_exact() {
    for n in [DVec3::X, DVec3::Y, DVec3::Z] {
        for n in [n, -n] {
            assert_eq!(direction(encode_direction(n)), n, "{n}");
        }
    }
    // No build writes a byte of 255; one read from a file stands for 254.
    assert_eq!(direction(0xff), direction(0xfe));
    assert_eq!(direction(0xff00), direction(0xfe00));
}

/// Every point of a surface cell's triangles that lies in the cell lies in its slab
/// (random points on every listed triangle of every surface cell, on three shapes);
/// and the slabs are thin where the surface is smooth: most are under a third of a
/// cell thick on the blob and the plate, and every one of the plate's under a twentieth,
/// those of the cells at its rim too (where the side faces meet the faces at a right
/// angle).
#[test]
fn slabs_hold_the_triangles_in_their_cells() {
    let mut random = SplitMix64::new(9);
    for (shape, surface, map) in three_shapes() {
        let (mut cells, mut thin, mut points) = (0, 0, 0);
        for (c, listed, slab) in surface_cells(&map) {
            let (a, b) = bounds(slab);
            cells += 1;
            thin += usize::from(b - a < 1.0 / 3.0);
            if shape == Catalog::ThinPlate {
                assert!(b - a < 0.05, "{shape:?} {c:?}: a slab {} thick", b - a);
            }
            let block = map.grid().cell_bounds(c);
            let what = format!("{shape:?} {c:?}");
            let layer = (direction(slab), bounds(slab));
            points += check_in_slab(&mut random, &surface, listed, block, layer, 20, &what);
        }
        assert!(points > 1000, "{shape:?}: {points}");
        if shape != Catalog::Sphere {
            assert!(2 * thin > cells, "{shape:?}: {thin} thin slabs of {cells}");
        }
    }
}

/// Every surface cell lists its triangles each once, ordered by the height of their
/// centroids along its slab's direction, then by index (three shapes); so in each cell of
/// the thin plate, one face's triangles all come before the other's.
#[test]
fn cell_lists_are_ordered_along_their_slabs() {
    for (shape, surface, map) in three_shapes() {
        let (mut cells, mut both_faces) = (0, 0);
        for (c, listed, slab) in surface_cells(&map) {
            cells += 1;
            let n = direction(slab);
            let key = |t: u32| {
                let [a, b, c] = surface.corners(TriId(t));
                (n.dot(a + b + c), t)
            };
            for pair in listed.windows(2) {
                let (k0, k1) = (key(pair[0]), key(pair[1]));
                assert!(
                    k0.0 < k1.0 || (k0.0 == k1.0 && k0.1 < k1.1),
                    "{shape:?} {c:?}: {k0:?} before {k1:?}"
                );
            }
            if shape == Catalog::ThinPlate {
                // The faces' triangles in list order, by the side they face.
                let faces: Vec<bool> = listed
                    .iter()
                    .map(|&t| surface.frame(TriId(t)).normal.z)
                    .filter(|nz| nz.abs() > 0.9)
                    .map(|nz| nz > 0.0)
                    .collect();
                let changes = faces.windows(2).filter(|w| w[0] != w[1]).count();
                assert!(changes <= 1, "{c:?}: the faces interleave: {faces:?}");
                both_faces += usize::from(changes == 1);
            }
        }
        assert!(cells > 100, "{shape:?}: {cells} surface cells");
        if shape == Catalog::ThinPlate {
            assert!(
                2 * both_faces > cells,
                "{both_faces} of {cells} with both faces"
            );
        }
    }
}

/// The blob, the sphere and the thin plate with their maps: shapes whose cells hold a
/// smooth patch, a curved one and both faces of a plate.
fn three_shapes() -> Vec<(Catalog, Surface, VoxelMap)> {
    [
        (Catalog::Blob, 5_000),
        (Catalog::Sphere, 2_000),
        (Catalog::ThinPlate, 2_000),
    ]
    .into_iter()
    .map(|(shape, triangles)| {
        let surface = Surface::new(shape.with_triangles(triangles), &SurfaceOptions::default())
            .expect("a surface");
        let map = VoxelMap::build(&surface, &MapOptions::default()).expect("a map");
        (shape, surface, map)
    })
    .collect()
}

/// Every cell of `map` that lists triangles, with its list and its slab, as a walk reads
/// them (a listing cell without a slab fails).
fn surface_cells(map: &VoxelMap) -> impl Iterator<Item = ([u32; 3], &[u32], u32)> + '_ {
    let [dx, dy, dz] = map.grid().dims();
    (0..dz)
        .flat_map(move |z| (0..dy).flat_map(move |y| (0..dx).map(move |x| [x, y, z])))
        .filter(|&c| !map.triangles_in(c).is_empty())
        .map(|c| {
            let slab = surface_slab(map, c).unwrap_or_else(|| panic!("{c:?}: a surface cell"));
            (c, map.triangles_in(c), slab)
        })
}

/// Checks that `samples` random points of each of `triangles` that lie in the box
/// `(lo, hi)` lie in `slab`, the slab of that box (a cube); returns how many did.
fn check_in_slab(
    random: &mut SplitMix64,
    surface: &Surface,
    triangles: &[u32],
    (lo, hi): (DVec3, DVec3),
    (n, (a, b)): (DVec3, (f64, f64)),
    samples: usize,
    what: &str,
) -> usize {
    let (centre, side) = (0.5 * (lo + hi), hi.x - lo.x);
    let mut points = 0;
    for &t in triangles {
        let [p, q, r] = surface.corners(TriId(t));
        for _ in 0..samples {
            let (u, v) = (random.next_unit(), random.next_unit());
            let (u, v) = if u + v > 1.0 {
                (1.0 - u, 1.0 - v)
            } else {
                (u, v)
            };
            let point = p + u * (q - p) + v * (r - p);
            if (point.cmplt(lo) | point.cmpgt(hi)).any() {
                continue;
            }
            let s = n.dot(point - centre) / side;
            assert!(a - 1e-9 <= s && s <= b + 1e-9, "{what}: {s} ∉ [{a}, {b}]");
            points += 1;
        }
    }
    points
}

/// The slab of surface cell `c`, as a walk reads it.
fn surface_slab(map: &VoxelMap, c: [u32; 3]) -> Option<u32> {
    match map.look(c) {
        Look::Detailed {
            cell: InBrick::Triangles(_, slab),
            ..
        } => Some(slab),
        _ => None,
    }
}

/// Every point of a block's triangles that lies in the block lies in the block's slab,
/// for the bricks and the regions of bricks that hold surface cells (random points on
/// every triangle listed by a cell of the block, on three shapes fine enough for
/// blocks to hold many cells of surface); and the slabs are thin where the surface is
/// smooth: on the blob and the sphere, most bricks' are under two cells thick and
/// most regions' under a quarter of a region; on the plate, every one under a twentieth
/// of its block, those at the rim too.
#[test]
fn brick_and_region_slabs_hold_the_triangles_in_their_blocks() {
    let mut random = SplitMix64::new(13);
    for (shape, triangles) in [
        (Catalog::Blob, 40_000),
        (Catalog::Sphere, 20_000),
        (Catalog::ThinPlate, 20_000),
    ] {
        let surface = Surface::new(shape.with_triangles(triangles), &SurfaceOptions::default())
            .expect("a surface");
        let map = VoxelMap::build(&surface, &MapOptions::default()).expect("a map");
        let dims = map.grid().dims();
        for side in [BRICK_SIDE, REGION_SIDE] {
            let length = f64::from(side) * map.grid().cell_size();
            let mut seen = std::collections::HashSet::new();
            let (mut blocks, mut thin, mut points) = (0, 0, 0);
            for z in 0..dims[2] {
                for y in 0..dims[1] {
                    for x in 0..dims[0] {
                        let c = [x, y, z];
                        let (block, layer) = match (map.look_region(c), map.look(c)) {
                            (RegionLook::Surface(r), _) if side == REGION_SIDE => {
                                let slab = map.region_slabs[r as usize];
                                (r, (direction(slab as u32), fine_bounds(slab)))
                            }
                            (_, Look::Detailed { brick, .. }) if side == BRICK_SIDE => {
                                let slab = map.brick_slab(brick);
                                (brick, (direction(slab), bounds(slab)))
                            }
                            _ => continue,
                        };
                        if !seen.insert(block) {
                            continue;
                        }
                        let corner = c.map(|v| v & !(side - 1));
                        let (a, b) = layer.1;
                        blocks += 1;
                        if shape == Catalog::ThinPlate {
                            assert!(b - a < 0.05, "{shape:?} {side} {c:?}: {} thick", b - a);
                        }
                        // The plate's regions away from its rim: as thin as the plate and
                        // two steps of 16 bits (a tilt, or bounds of a byte, would give
                        // more than a hundredth of the region).
                        if shape == Catalog::ThinPlate && side == REGION_SIDE {
                            assert!(b - a < 0.002, "{shape:?} region {c:?}: {} thick", b - a);
                        }
                        // Under two cells for a brick, eight (a quarter) for a region.
                        let cells = (b - a) * f64::from(side);
                        thin += usize::from(cells < 2.0 * f64::from(side / BRICK_SIDE));
                        let mut all = Vec::new();
                        for z in corner[2]..(corner[2] + side).min(dims[2]) {
                            for y in corner[1]..(corner[1] + side).min(dims[1]) {
                                for x in corner[0]..(corner[0] + side).min(dims[0]) {
                                    all.extend_from_slice(map.triangles_in([x, y, z]));
                                }
                            }
                        }
                        all.sort_unstable();
                        all.dedup();
                        let (lo, _) = map.grid().cell_bounds(corner);
                        let box_ = (lo, lo + DVec3::splat(length));
                        let what = format!("{shape:?} block {block} of {side}");
                        points += check_in_slab(&mut random, &surface, &all, box_, layer, 4, &what);
                    }
                }
            }
            assert!(points > 10_000, "{shape:?} {side}: {points}");
            if shape != Catalog::ThinPlate {
                assert!(
                    2 * thin > blocks,
                    "{shape:?} {side}: {thin} thin of {blocks}"
                );
            }
        }
    }
}

/// The window of a segment in a slab holds exactly the parameters at which the
/// segment lies in it (up to the margin): sampled along random segments through
/// random slabs of a brick.
#[test]
fn a_window_holds_the_parameters_in_the_slab() {
    let mut random = SplitMix64::new(21);
    let (centre, h) = (DVec3::new(0.3, -0.2, 0.1), 0.016);
    let (mut inside, mut outside) = (0, 0);
    for _ in 0..2_000 {
        let code = encode_direction(random.unit_vector());
        let (x, y) = (random.index(256) as u32, random.index(256) as u32);
        let slab = code | (x.min(y) << 16) | (x.max(y) << 24);
        let n = direction(slab);
        let (a, b) = bounds(slab);
        let near = DVec3::splat(h);
        let p0 = random.point_in(centre - near, centre + near);
        let p1 = random.point_in(centre - near, centre + near);
        let window = interval(slab, centre, h, p0, p1);
        for k in 0..=200 {
            let t = f64::from(k) / 200.0;
            let s = n.dot(p0 + t * (p1 - p0) - centre) / h;
            let within = window.is_some_and(|(from, to)| from <= t && t <= to);
            if s > a + 1e-6 && s < b - 1e-6 {
                assert!(within, "{t} at {s} in [{a}, {b}]: {window:?}");
                inside += 1;
            } else if s < a - 1e-3 || s > b + 1e-3 {
                assert!(!within, "{t} at {s} beside [{a}, {b}]: {window:?}");
                outside += 1;
            }
        }
    }
    assert!(inside > 10_000 && outside > 10_000, "{inside} {outside}");
    // Along the slab (its direction is +z up to a step): in it, the whole segment;
    // beside it, none.
    let slab = encode_direction(DVec3::Z) | (100 << 16) | (150 << 24);
    let along = |z: f64| {
        let (p0, p1) = (DVec3::new(-h, 0.0, z), DVec3::new(h, 0.0, z));
        interval(slab, centre, h, centre + p0, centre + p1)
    };
    assert!(along(0.0).is_some_and(|(from, to)| from < 0.0 && to > 1.0));
    assert_eq!(along(0.4 * h), None);
    // Overflowing coordinates reject nothing.
    assert_eq!(
        interval(slab, centre, h, DVec3::splat(1e308), DVec3::splat(-1e308)),
        Some((f64::NEG_INFINITY, f64::INFINITY))
    );
}

/// A map file with a slab too few or too many, of the cells, the bricks or the
/// regions, is refused, naming the section.
#[test]
fn a_file_without_a_slab_per_surface_cell_is_refused() {
    let surface = Surface::new(
        Catalog::Blob.with_triangles(1_000),
        &SurfaceOptions::default(),
    )
    .expect("a surface");
    let map = VoxelMap::build(&surface, &MapOptions::default()).expect("a map");
    for want in ["slabs", "brick slabs", "region slabs"] {
        for change in [-1i64, 1] {
            let mut wrong = map.clone();
            let resize = |slabs: &mut Vec<_>, full| {
                if change < 0 {
                    slabs.pop();
                } else {
                    slabs.push(full);
                }
            };
            match want {
                "slabs" => wrong.slabs.modify(|s| resize(s, FULL_SLAB)),
                "brick slabs" => wrong.brick_slabs.modify(|s| resize(s, FULL_SLAB)),
                _ => wrong.region_slabs.modify(|s| {
                    if change < 0 {
                        s.pop();
                    } else {
                        s.push(FULL_FINE_SLAB)
                    }
                }),
            }
            check_refused(&surface, &wrong, want);
        }
    }
}

/// The map `wrong`, saved and loaded, is refused for its section `want`.
fn check_refused(surface: &Surface, wrong: &VoxelMap, want: &str) {
    use crate::map::{MapFileError, decode, encode};
    match decode(&encode(surface, wrong)) {
        Err(MapFileError::Invalid { section, .. }) => assert_eq!(section, want),
        other => panic!("expected the {want} refused, got {other:?}"),
    }
}

/// A segment beside a slab has no interval in it; of one through it or across it, the
/// part between the parameters returned holds every point of it in the slab and no point
/// far beside it: sampled along random segments through random slabs of a cell, and in
/// the plain cases.
#[test]
fn a_segment_interval_holds_the_points_in_the_slab() {
    let mut random = SplitMix64::new(23);
    let (centre, h) = (DVec3::new(1.0, 2.0, 3.0), 0.002);
    let (mut inside, mut outside) = (0, 0);
    for _ in 0..2_000 {
        let code = encode_direction(random.unit_vector());
        let (x, y) = (random.index(256) as u32, random.index(256) as u32);
        let slab = code | (x.min(y) << 16) | (x.max(y) << 24);
        let (n, (a, b)) = (direction(slab), bounds(slab));
        let half = DVec3::splat(0.5 * h);
        let q0 = random.point_in(centre - half, centre + half);
        let q1 = random.point_in(centre - half, centre + half);
        let part = interval(slab, centre, h, q0, q1)
            .map(|(a, b)| (q0.lerp(q1, a.max(0.0)), q0.lerp(q1, b.min(1.0))));
        for k in 0..=200 {
            let point = q0 + f64::from(k) / 200.0 * (q1 - q0);
            let s = n.dot(point - centre) / h;
            // Where the point lies on the part returned (its distance to that part).
            let off = part.map(|(c0, c1)| {
                let d = c1 - c0;
                let t = if d == DVec3::ZERO {
                    0.0
                } else {
                    ((point - c0).dot(d) / d.length_squared()).clamp(0.0, 1.0)
                };
                point.distance(c0 + t * d)
            });
            if s > a + 1e-6 && s < b - 1e-6 {
                assert!(off.is_some_and(|o| o < 1e-12), "{s} in [{a}, {b}]: {off:?}");
                inside += 1;
            } else if s < a - 1e-3 || s > b + 1e-3 {
                assert!(
                    off.is_none_or(|o| o > 1e-9 * h),
                    "{s} beside [{a}, {b}]: {off:?}"
                );
                outside += 1;
            }
        }
    }
    assert!(inside > 10_000 && outside > 10_000, "{inside} {outside}");
    // Direction +z, bounds −0.1 … 0.1 of a cell around the centre.
    let code = encode_direction(DVec3::Z);
    let step = 2.0 * RANGE / LEVELS;
    let level = |s: f64| ((s + RANGE) / step).round() as u32;
    let slab = code | (level(-0.1) << 16) | (level(0.1) << 24);
    let at = |x: f64, z: f64| centre + DVec3::new(x, 0.0, z) * h;
    assert_eq!(interval(slab, centre, h, at(-0.5, 0.3), at(0.5, 0.4)), None);
    assert_eq!(
        interval(slab, centre, h, at(-0.5, -0.3), at(0.5, -0.2)),
        None
    );
    let (a, b) = interval(slab, centre, h, at(-0.5, 0.3), at(0.5, -0.3)).expect("across");
    // Which way the part moves along the slab's direction (down here, then up).
    let toward = |q0, q1| interval_toward(slab, centre, h, q0, q1).map(|(_, _, up)| up);
    assert_eq!(toward(at(-0.5, 0.3), at(0.5, -0.3)), Some(false));
    assert_eq!(toward(at(0.5, -0.3), at(-0.5, 0.3)), Some(true));
    // The part crosses the slab's 0.2 of a cell over 0.2 / 0.6 of its length.
    assert!(
        (a - 1.0 / 3.0).abs() < 0.01 && (b - 2.0 / 3.0).abs() < 0.01,
        "{a} {b}"
    );
    // A part in the slab, any part with the slab that rejects nothing, and a part whose
    // products overflow are kept whole.
    let whole = |(q0, q1): (DVec3, DVec3), slab: u32| {
        interval(slab, centre, h, q0, q1).is_some_and(|(a, b)| a <= 0.0 && b >= 1.0)
    };
    assert!(whole((at(-0.5, 0.05), at(0.5, 0.05)), slab));
    assert!(whole((at(-0.5, 0.49), at(0.5, -0.49)), FULL_SLAB));
    assert!(whole((DVec3::splat(1e308), DVec3::splat(-1e308)), slab));
}

/// The inline rounding and extremes give what `f64::round` and `f64::min`/`max` give.
#[test]
fn inline_round_and_extent_match_the_library() {
    let mut rng = SplitMix64::new(3);
    let mut values = vec![
        0.5,
        -0.5,
        1.5,
        2.5,
        -2.5,
        0.499_999_999_999_999_94,
        253.5,
        1e17,
        -1e300,
    ];
    values.extend((0..10_000).map(|_| (rng.next_unit() - 0.25) * 300.0));
    for x in values {
        assert_eq!(round_half_away(x), x.round(), "{x}");
    }
    for len in [0, 1, 2, 7] {
        let corners: Vec<Corners> = (0..len)
            .map(|_| [(); 3].map(|_| DVec3::new(rng.next_unit(), rng.next_unit(), rng.next_unit())))
            .collect();
        let (centre, n) = (DVec3::new(0.3, 0.5, 0.1), DVec3::new(0.2, -0.7, 0.1));
        let (lo, hi) = corners
            .iter()
            .flatten()
            .map(|&c| n.dot(c - centre))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
                (lo.min(s), hi.max(s))
            });
        assert_eq!(extent_along(&corners, centre, n), (lo, hi));
    }
}

/// Sorting through bits gives what sorting and dropping repeats gives.
#[test]
fn sort_unique_sorts_and_drops_repeats() {
    let mut rng = SplitMix64::new(5);
    let mut bits = Vec::new();
    for (len, spread) in [
        (0, 1),
        (5, 3),
        (40, 10),
        (100, 1000),
        (100, 100_000),
        (300, 64),
    ] {
        let base = rng.index(1 << 20) as u32;
        let list: Vec<u32> = (0..len).map(|_| base + rng.index(spread) as u32).collect();
        let mut want = list.clone();
        want.sort_unstable();
        want.dedup();
        let mut got = list;
        blocks::sort_unique(&mut got, &mut bits);
        assert_eq!(got, want, "{len} {spread}");
    }
}
