//! The world broad phase: a hierarchical loose hashed grid over the objects' bounding
//! spheres, so that a tick looks only at the objects near the proxy.
//!
//! Each object lives in one cell: the cell, at the level whose cell edge `h` is the
//! smallest power of two at least its bounding radius, that holds its bounding sphere's
//! centre (loose cells: the sphere reaches at most `h` beyond its cell). A query for a box
//! visits, at each level that holds objects, the cells within `h` of the box (a few cells
//! for the proxy's neighbourhood) and returns every object there: a superset of the objects
//! whose sphere meets the box. Cells are hashed into a fixed table of buckets, each an
//! intrusive doubly linked list of object slots, so that inserting, moving to another
//! cell and removing an object take constant time and never allocate: every array is
//! reserved for the scene's capacity when the scene is made.
//!
//! Objects too large for the top level, or too far out for a cell coordinate, are kept in
//! one list that every query returns.
//!
//! Invariants: slot `i` is object `i` of the scene (a removal puts the last slot in the
//! removed one's place, as the scene does with its objects); every object is in exactly one list, the one of its `cell`; a
//! level's count is the number of objects at that level.

use glam::DVec3;

/// Smallest cell edge, as a power of two (2^-20 m, about a micrometre).
const MIN_EXP: i32 = -20;
/// Number of levels: cell edges from 2^-20 m to 2^20 m (about a thousand kilometres).
const LEVELS: usize = 41;
/// A level index meaning "in the list of objects every query returns".
const HUGE: u8 = u8::MAX;
/// No slot (end of a list).
const NONE: u32 = u32::MAX;
/// Most cells a query visits per level; a larger query returns "every object"
/// ([`Near::all`]), which the callers then test one by one (bounded by the capacity).
const MAX_CELLS_PER_LEVEL: i64 = 512;
/// Largest cell coordinate kept in a cell; objects beyond go to the list of all queries.
const MAX_COORD: f64 = (1u64 << 30) as f64;

/// How many objects a [`Near`] set holds before it stands for the whole scene.
pub(crate) const NEAR_CAPACITY: usize = 96;

/// The cell of an object: a level and integer coordinates at that level.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Cell {
    level: u8,
    k: [i32; 3],
}

impl Cell {
    const HUGE: Cell = Cell {
        level: HUGE,
        k: [0; 3],
    };
}

/// The cell edge of `level` (below [`LEVELS`]), metres: an exact power of two.
#[inline]
fn edge(level: usize) -> f64 {
    f64::from_bits(((1023 + MIN_EXP + level as i32) as u64) << 52)
}

/// The level of a sphere of radius `radius` (already with its slack): the smallest whose
/// edge is at least the radius, or [`HUGE`] when none is.
fn level_of(radius: f64) -> u8 {
    if radius.is_nan() || radius > edge(LEVELS - 1) {
        return HUGE;
    }
    // From the radius's binary exponent, then one step up if the radius is not a power
    // of two.
    let exponent = ((radius.to_bits() >> 52) & 0x7FF) as i32 - 1023;
    let mut level = (exponent - MIN_EXP).clamp(0, LEVELS as i32 - 1) as usize;
    if edge(level) < radius {
        level += 1;
    }
    level as u8
}

/// The cell at `level` (from [`level_of`]) of a sphere centred at `centre`.
#[inline]
fn cell_at(level: u8, centre: DVec3) -> Cell {
    if level == HUGE || !centre.is_finite() {
        return Cell::HUGE;
    }
    // Multiplying by the inverse of a power of two is exact: the same as dividing.
    let k = centre * inverse_edge(usize::from(level));
    if k.abs().max_element() > MAX_COORD {
        return Cell::HUGE;
    }
    Cell {
        level,
        k: [floor_i32(k.x), floor_i32(k.y), floor_i32(k.z)],
    }
}

/// The cell of a sphere at `centre` of radius `radius` (already with its slack).
#[cfg(test)]
fn cell_of(centre: DVec3, radius: f64) -> Cell {
    cell_at(level_of(radius), centre)
}

/// `1 / edge(level)`, exact.
#[inline]
fn inverse_edge(level: usize) -> f64 {
    f64::from_bits(((1023 - MIN_EXP - level as i32) as u64) << 52)
}

/// `x.floor()` as an integer, for `|x|` within [`MAX_COORD`] (no call into the C library).
#[inline]
fn floor_i32(x: f64) -> i32 {
    let t = x as i32;
    if f64::from(t) > x { t - 1 } else { t }
}

/// The grid over the objects' bounding spheres (see the module documentation).
#[derive(Debug)]
pub(crate) struct Broad {
    cell: Vec<Cell>,
    /// Each object's level, from its radius ([`HUGE`] when too large for any).
    level: Vec<u8>,
    next: Vec<u32>,
    prev: Vec<u32>,
    heads: Box<[u32]>,
    huge_head: u32,
    counts: [u32; LEVELS],
    /// Bit `l` set when level `l` holds an object (its count is not 0).
    occupied: u64,
}

/// The objects a query found, in increasing index order, or the whole scene.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Near {
    idx: [u32; NEAR_CAPACITY],
    len: usize,
    all: bool,
}

impl Near {
    /// The whole scene: every object is a candidate.
    pub(crate) const ALL: Near = Near {
        idx: [0; NEAR_CAPACITY],
        len: 0,
        all: true,
    };

    /// Whether the set stands for every object.
    pub(crate) fn all(&self) -> bool {
        self.all
    }

    fn push(&mut self, i: u32) {
        if self.len == NEAR_CAPACITY {
            self.all = true;
        } else {
            self.idx[self.len] = i;
            self.len += 1;
        }
    }

    /// The candidates' indices, in increasing order, for a scene of `count` objects.
    pub(crate) fn indices(&self, count: usize) -> NearIter<'_> {
        if self.all {
            NearIter::All(0..count)
        } else {
            NearIter::Some(self.idx[..self.len].iter())
        }
    }
}

/// The indices of a [`Near`] set.
pub(crate) enum NearIter<'a> {
    All(std::ops::Range<usize>),
    Some(std::slice::Iter<'a, u32>),
}

impl Iterator for NearIter<'_> {
    type Item = usize;

    #[inline]
    fn next(&mut self) -> Option<usize> {
        match self {
            NearIter::All(r) => r.next(),
            NearIter::Some(s) => s.next().map(|&i| i as usize),
        }
    }
}

impl Broad {
    /// An empty grid with room for `capacity` objects.
    pub(crate) fn new(capacity: usize) -> Broad {
        let buckets = (2 * capacity).next_power_of_two().max(16);
        Broad {
            cell: Vec::with_capacity(capacity),
            level: Vec::with_capacity(capacity),
            next: Vec::with_capacity(capacity),
            prev: Vec::with_capacity(capacity),
            heads: vec![NONE; buckets].into_boxed_slice(),
            huge_head: NONE,
            counts: [0; LEVELS],
            occupied: 0,
        }
    }

    fn bucket(&self, c: &Cell) -> usize {
        // A multiplicative mix of the level and coordinates.
        let mut h = u64::from(c.level).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        for &k in &c.k {
            h = (h ^ u64::from(k as u32)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        }
        (h >> 17) as usize & (self.heads.len() - 1)
    }

    fn head_mut(&mut self, c: &Cell) -> &mut u32 {
        if c.level == HUGE {
            &mut self.huge_head
        } else {
            let b = self.bucket(c);
            &mut self.heads[b]
        }
    }

    fn link(&mut self, i: u32, c: Cell) {
        let head = *self.head_mut(&c);
        self.cell[i as usize] = c;
        self.prev[i as usize] = NONE;
        self.next[i as usize] = head;
        if head != NONE {
            self.prev[head as usize] = i;
        }
        *self.head_mut(&c) = i;
        if c.level != HUGE {
            self.counts[c.level as usize] += 1;
            self.occupied |= 1 << c.level;
        }
    }

    fn unlink(&mut self, i: u32) {
        let c = self.cell[i as usize];
        let (p, n) = (self.prev[i as usize], self.next[i as usize]);
        if p == NONE {
            *self.head_mut(&c) = n;
        } else {
            self.next[p as usize] = n;
        }
        if n != NONE {
            self.prev[n as usize] = p;
        }
        if c.level != HUGE {
            self.counts[c.level as usize] -= 1;
            if self.counts[c.level as usize] == 0 {
                self.occupied &= !(1 << c.level);
            }
        }
    }

    /// Adds object `len` (the next index) with its sphere. The caller keeps the count of
    /// objects within the capacity, so this never reallocates.
    pub(crate) fn push(&mut self, centre: DVec3, radius: f64) {
        let i = self.cell.len() as u32;
        let level = level_of(radius);
        self.cell.push(Cell::HUGE);
        self.level.push(level);
        self.next.push(NONE);
        self.prev.push(NONE);
        self.link(i, cell_at(level, centre));
    }

    /// Object `i` changed shape: its sphere is now at `centre` with `radius` (its level
    /// follows the radius). Returns whether it changed cell.
    pub(crate) fn reshape(&mut self, i: usize, centre: DVec3, radius: f64) -> bool {
        if i >= self.cell.len() {
            return false;
        }
        self.level[i] = level_of(radius);
        self.relink(i, centre)
    }

    /// Object `i` moved: its sphere (of the radius it was placed with) is now at `centre`.
    /// Returns whether it changed cell.
    ///
    /// # Real-time
    /// A sphere that stays in its cell costs a few multiplies and compares (no rounding
    /// to integers); a change of cell relinks it.
    #[inline]
    pub(crate) fn update(&mut self, i: usize, centre: DVec3) -> bool {
        let Some(&old) = self.cell.get(i) else {
            return false;
        };
        if old.level != HUGE {
            // Inside the cell when `k ≤ centre / h < k + 1` on every axis (false for a
            // non-finite centre).
            let u = centre * inverse_edge(usize::from(old.level));
            let d = u - DVec3::new(
                f64::from(old.k[0]),
                f64::from(old.k[1]),
                f64::from(old.k[2]),
            );
            if d.x >= 0.0 && d.y >= 0.0 && d.z >= 0.0 && d.x < 1.0 && d.y < 1.0 && d.z < 1.0 {
                return false;
            }
        }
        self.relink(i, centre)
    }

    /// Puts object `i` in the cell of its sphere at `centre`; whether that changed it.
    #[cold]
    fn relink(&mut self, i: usize, centre: DVec3) -> bool {
        let c = cell_at(self.level[i], centre);
        if self.cell[i] == c {
            return false;
        }
        self.unlink(i as u32);
        self.link(i as u32, c);
        true
    }

    /// Removes object `i`; the last object takes its index, as in the scene.
    ///
    /// # Real-time
    /// No allocation; constant time (the last object's neighbours in its list are
    /// renamed).
    pub(crate) fn swap_remove(&mut self, i: usize) {
        let Some(last) = self.cell.len().checked_sub(1) else {
            return;
        };
        if i > last {
            return;
        }
        self.unlink(i as u32);
        if i != last {
            // Slot `last` becomes slot `i`: the same place in the same list.
            let (p, n) = (self.prev[last], self.next[last]);
            self.cell[i] = self.cell[last];
            self.level[i] = self.level[last];
            self.prev[i] = p;
            self.next[i] = n;
            if p == NONE {
                let c = self.cell[i];
                *self.head_mut(&c) = i as u32;
            } else {
                self.next[p as usize] = i as u32;
            }
            if n != NONE {
                self.prev[n as usize] = i as u32;
            }
        }
        self.cell.pop();
        self.level.pop();
        self.next.pop();
        self.prev.pop();
    }

    /// Every object whose bounding sphere (of the radius given when it was placed) may
    /// come within the box `lo..hi` (world frame, metres): a superset, in increasing index
    /// order, or [`Near::ALL`] when there are too many or the box is too large.
    ///
    /// # Real-time
    /// No allocation; at most `MAX_CELLS_PER_LEVEL` cells per occupied level, and
    /// [`NEAR_CAPACITY`] objects kept.
    pub(crate) fn query(&self, lo: DVec3, hi: DVec3) -> Near {
        let mut near = Near::ALL;
        self.query_into(lo, hi, &mut near);
        near
    }

    /// [`Broad::query`] written into `near` (no set of [`NEAR_CAPACITY`] indices made and
    /// copied: the servo tick's way).
    pub(crate) fn query_into(&self, lo: DVec3, hi: DVec3, near: &mut Near) {
        near.len = 0;
        near.all = false;
        if !(lo.is_finite() && hi.is_finite()) {
            near.all = true;
            return;
        }
        // The rounding of coordinates far from the origin.
        let slack = 1e-9 * lo.abs().max(hi.abs()).max_element().max(1.0);
        // The occupied levels, lowest first.
        let mut levels = self.occupied;
        while levels != 0 {
            let level = levels.trailing_zeros() as usize;
            levels &= levels - 1;
            let h = edge(level);
            // A sphere reaches at most `h` beyond its cell. Multiplying by the inverse of
            // a power of two is exact: the same as dividing by `h`.
            let ext = DVec3::splat(h * (1.0 + 1e-6) + slack);
            let a = floor(((lo - ext) * inverse_edge(level)).to_array());
            let b = floor(((hi + ext) * inverse_edge(level)).to_array());
            let span = [0, 1, 2].map(|j| b[j] - a[j] + 1.0);
            if a.iter().chain(&b).any(|k| k.abs() > MAX_COORD + 2.0)
                || span[0] * span[1] * span[2] > MAX_CELLS_PER_LEVEL as f64
            {
                near.all = true;
                return;
            }
            let (a, b) = (a.map(|k| k as i32), b.map(|k| k as i32));
            for x in a[0]..=b[0] {
                for y in a[1]..=b[1] {
                    for z in a[2]..=b[2] {
                        let c = Cell {
                            level: level as u8,
                            k: [x, y, z],
                        };
                        let mut i = self.heads[self.bucket(&c)];
                        while i != NONE {
                            if self.cell[i as usize] == c {
                                near.push(i);
                            }
                            i = self.next[i as usize];
                        }
                    }
                }
            }
        }
        let mut i = self.huge_head;
        while i != NONE {
            near.push(i);
            i = self.next[i as usize];
        }
        if !near.all {
            near.idx[..near.len].sort_unstable();
        }
    }
}

/// `x.floor()` for each of `x` (finite), without a call into the C library: exact, as
/// every `f64` of magnitude at least 2^52 is an integer.
#[inline]
fn floor(x: [f64; 3]) -> [f64; 3] {
    x.map(|x| {
        if x.abs() < 4_503_599_627_370_496.0 {
            let t = x as i64 as f64;
            if t > x { t - 1.0 } else { t }
        } else {
            x
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    #[test]
    fn the_level_is_the_smallest_edge_at_least_the_radius() {
        for r in [
            0.0, 1e-300, 1e-7, 0.1, 0.125, 0.13, 1.0, 3.0, 1e5, 1048576.0,
        ] {
            let c = cell_of(DVec3::ZERO, r);
            let level = usize::from(c.level);
            assert!(edge(level) >= r, "{r}");
            assert!(level == 0 || edge(level - 1) < r, "{r}");
        }
        assert_eq!(cell_of(DVec3::ZERO, 2e6), Cell::HUGE);
        assert_eq!(edge(20), 1.0);
        assert_eq!(inverse_edge(17), 8.0);
        for x in [-2.5, -2.0, -0.1, 0.0, 0.3, 1.0, 7.9, 1e9] {
            assert_eq!(floor_i32(x), x.floor() as i32, "{x}");
        }
        let xs = [
            -1e300,
            -4503599627370497.0,
            -4503599627370495.5,
            -2.5,
            -1e-300,
            0.0,
            1.0f64.next_down(),
            (-2.0f64).next_up(),
            3.5,
            4503599627370495.5,
            9007199254740994.0,
            f64::MAX,
        ];
        for x in xs {
            assert_eq!(floor([x; 3]), [x.floor(); 3], "{x}");
        }
    }

    /// The grid returns every sphere that meets a box, through inserts, moves and
    /// removals, compared with a brute-force list, and only spheres from the cells
    /// around the box: each found sphere's centre lies within two cell edges of its level
    /// of the box (its cell touches the box grown by one edge), so that a grid that let
    /// through the other objects of a bucket's chain (another cell hashed to the same
    /// bucket) fails here, though its answers would still hold every sphere.
    #[test]
    fn queries_hold_every_sphere_that_meets_the_box() {
        let (mut precise_sets, mut found_checked) = (0usize, 0usize);
        let mut rng = SplitMix64::new(7);
        let mut broad = Broad::new(300);
        let mut spheres: Vec<(DVec3, f64)> = Vec::new();
        let point = |rng: &mut SplitMix64, s: f64| {
            DVec3::new(rng.range(-s, s), rng.range(-s, s), rng.range(-s, s))
        };
        for step in 0..3000 {
            match rng.index(4) {
                0 | 1 if spheres.len() < 300 => {
                    let s = (point(&mut rng, 1.0), 10f64.powf(rng.range(-4.0, 0.5)));
                    broad.push(s.0, s.1);
                    spheres.push(s);
                }
                2 if !spheres.is_empty() => {
                    let i = rng.index(spheres.len());
                    spheres[i].0 += point(&mut rng, 0.05);
                    broad.update(i, spheres[i].0);
                }
                3 if !spheres.is_empty() && step % 3 == 0 => {
                    let i = rng.index(spheres.len());
                    spheres.swap_remove(i);
                    broad.swap_remove(i);
                }
                _ => {}
            }
            let c = point(&mut rng, 1.2);
            // Boxes from 4 cm across down to a few µm: a query whose box spans more than
            // MAX_CELLS_PER_LEVEL cells of an occupied level stands for the whole scene,
            // so the boxes must be small beside the smallest spheres' cells (0.1 mm) for
            // the precise sets to be checked with every level occupied.
            let e = point(&mut rng, 0.02).abs() * 10f64.powf(rng.range(-4.0, 0.0));
            let near = broad.query(c - e, c + e);
            let found: Vec<usize> = near.indices(spheres.len()).collect();
            assert!(found.windows(2).all(|w| w[0] < w[1]));
            for (i, &(centre, r)) in spheres.iter().enumerate() {
                let d = (centre - centre.clamp(c - e, c + e)).length();
                if d <= r {
                    assert!(found.contains(&i), "step {step}: sphere {i} missed");
                }
            }
            if near.all() {
                continue;
            }
            precise_sets += 1;
            for &i in &found {
                let (centre, r) = spheres[i];
                let h = edge(usize::from(cell_of(centre, r).level));
                let off = (centre - centre.clamp(c - e, c + e)).abs().max_element();
                assert!(
                    off <= 2.0 * h * (1.0 + 1e-6) + 1e-9,
                    "step {step}: sphere {i} ({centre}, radius {r}) is {off} m off the box, \
                     its cells are {h} m"
                );
                found_checked += 1;
            }
        }
        // Enough queries got a set, not the whole scene, for the locality check to have
        // examined something: the small boxes do (about two queries in three).
        assert!(
            precise_sets * 4 > 3000,
            "{precise_sets} of 3000 queries gave a set"
        );
        assert!(
            found_checked >= precise_sets,
            "{found_checked} found in {precise_sets} sets"
        );
    }
}
