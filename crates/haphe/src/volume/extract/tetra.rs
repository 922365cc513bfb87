//! Marching tetrahedra on the Kuhn (Freudenthal) decomposition: every cube of eight voxels
//! split into the same six tetrahedra around its main diagonal, so that a face two cubes
//! share is split the same way in both and the surface has neither ambiguous cases nor
//! cracks.
//!
//! A cube's corners are numbered by their offset bits, `x + 2y + 4z`. Every edge of the
//! decomposition joins a corner to one whose offset bits include it (the tetrahedra are
//! chains from corner 0 to corner 7), so an edge is its lower voxel and a direction in
//! `{0, 1}³` (1 to 7, the corners' bits XOR'd): a cube edge, a face diagonal or the main
//! diagonal.

/// The six tetrahedra of a cube as corner numbers, one per order of the axes (corner 0,
/// a step along the first axis, then the second, then corner 7), each listed so that it
/// is positively oriented in voxel indices: `det(v1 − v0, v2 − v0, v3 − v0) > 0`.
pub(super) const TETRAHEDRA: [[u8; 4]; 6] = [
    [0, 1, 3, 7], // x, y, z
    [0, 5, 1, 7], // x, z, y (an odd order: two corners swapped)
    [0, 3, 2, 7], // y, x, z (odd)
    [0, 2, 6, 7], // y, z, x
    [0, 4, 5, 7], // z, x, y
    [0, 6, 4, 7], // z, y, x (odd)
];

/// The crossing of an edge lies at least this fraction of its length from either end
/// voxel: a value exactly at iso, or an infinite one, would otherwise put the vertex on
/// the voxel, where the vertices of the voxel's other edges also lie (zero-area triangles,
/// coincident vertices of different edges). 1/64 is exact in binary, so the clamp adds no
/// rounding, and moves a vertex by at most 1.6 % of a voxel.
pub(super) const CROSSING_CLAMP: f64 = 1.0 / 64.0;

/// The triangles of one case: up to two, each three edges of the tetrahedron as pairs of
/// its vertex numbers (0 to 3).
#[derive(Debug, Clone, Copy)]
pub(super) struct Case {
    /// How many of `triangles` are used.
    pub(super) count: u8,
    /// The triangles' edges, counter-clockwise seen from the air side for a positively
    /// oriented tetrahedron.
    pub(super) triangles: [[[u8; 2]; 3]; 2],
}

/// The twelve even permutations of a tetrahedron's vertices: each keeps its orientation.
const EVEN: [[u8; 4]; 12] = [
    [0, 1, 2, 3],
    [0, 2, 3, 1],
    [0, 3, 1, 2],
    [1, 0, 3, 2],
    [1, 2, 0, 3],
    [1, 3, 2, 0],
    [2, 0, 1, 3],
    [2, 1, 3, 0],
    [2, 3, 0, 1],
    [3, 0, 2, 1],
    [3, 1, 0, 2],
    [3, 2, 1, 0],
];

/// The triangles of every case, indexed by the material mask (bit `v` set when vertex `v`
/// of the tetrahedron is material).
pub(super) const CASES: [Case; 16] = cases();

/// Whether vertex `v` is material in `mask`.
const fn material(mask: usize, v: u8) -> bool {
    mask & (1 << v) != 0
}

/// An even permutation `[a, b, c, d]` whose first `lead` vertices are material and the
/// others air (for three material vertices, `lead = 1` with the roles swapped: its first
/// vertex is the only air one).
const fn ordered(mask: usize, lead: usize, first_is_material: bool) -> [u8; 4] {
    let mut p = 0;
    while p < EVEN.len() {
        let order = EVEN[p];
        let mut ok = true;
        let mut i = 0;
        while i < 4 {
            ok &= material(mask, order[i]) == ((i < lead) == first_is_material);
            i += 1;
        }
        if ok {
            return order;
        }
        p += 1;
    }
    [0, 1, 2, 3]
}

/// Builds [`CASES`]. With `[a, b, c, d]` an even permutation (so positively oriented) and
/// `a` alone material, the triangle on edges `ab, ac, ad` faces away from `a`, into the
/// air; with `a` alone air, the reverse; with `a, b` material, the quad `ac, ad, bd, bc`
/// faces `c, d`.
const fn cases() -> [Case; 16] {
    let empty = Case {
        count: 0,
        triangles: [[[0; 2]; 3]; 2],
    };
    let mut table = [empty; 16];
    let mut mask: usize = 1;
    while mask < 15 {
        let count = mask.count_ones();
        let case = &mut table[mask];
        if count == 1 || count == 3 {
            let [a, b, c, d] = ordered(mask, 1, count == 1);
            case.count = 1;
            case.triangles[0] = if count == 1 {
                [[a, b], [a, c], [a, d]]
            } else {
                [[a, b], [a, d], [a, c]]
            };
        } else {
            let [a, b, c, d] = ordered(mask, 2, true);
            case.count = 2;
            case.triangles[0] = [[a, c], [a, d], [b, d]];
            case.triangles[1] = [[a, c], [b, d], [b, c]];
        }
        mask += 1;
    }
    table
}

/// Where an edge's iso crossing lies, as the fraction of the way from its lower voxel
/// (value `v_lo`) to its upper one (`v_hi`), exactly one of which is material (value at
/// least `iso`).
///
/// From the material end `a` to the air end `b`, `t = (iso − v_a) / (v_b − v_a)` (in
/// `f64`), clamped into [`CROSSING_CLAMP`]`..=1 − CROSSING_CLAMP`; an infinite end puts
/// `t` at a clamp (air at `−∞`: next to the material end; material at `+∞`: next to the
/// air end; both: the middle). A function of the two values only, so that every chunk
/// computes the same bits for the same edge.
#[inline]
pub(super) fn crossing(v_lo: f32, v_hi: f32, iso: f32) -> f64 {
    let lo_is_material = v_lo >= iso;
    let (a, b) = if lo_is_material {
        (f64::from(v_lo), f64::from(v_hi))
    } else {
        (f64::from(v_hi), f64::from(v_lo))
    };
    let t = match (a == f64::INFINITY, b == f64::NEG_INFINITY) {
        (true, true) => 0.5,
        (true, false) => 1.0,
        (false, true) => 0.0,
        (false, false) => (f64::from(iso) - a) / (b - a),
    };
    let t = t.clamp(CROSSING_CLAMP, 1.0 - CROSSING_CLAMP);
    if lo_is_material { t } else { 1.0 - t }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The offset of corner `c`.
    fn offset(c: u8) -> [i32; 3] {
        [
            i32::from(c & 1),
            i32::from((c >> 1) & 1),
            i32::from((c >> 2) & 1),
        ]
    }

    #[test]
    fn every_tetrahedron_is_positive_and_a_chain() {
        for tet in TETRAHEDRA {
            let [o, a, b, c] = tet.map(offset);
            let d = |p: [i32; 3]| [p[0] - o[0], p[1] - o[1], p[2] - o[2]];
            let (a, b, c) = (d(a), d(b), d(c));
            let det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]);
            assert_eq!(det, 1, "{tet:?}");
            for i in 0..4 {
                for j in i + 1..4 {
                    let (lo, hi) = (tet[i].min(tet[j]), tet[i].max(tet[j]));
                    assert_eq!(lo & hi, lo, "{tet:?}: {lo} and {hi} are not a chain");
                }
            }
        }
    }

    #[test]
    fn every_case_cuts_only_edges_between_material_and_air() {
        for (mask, case) in CASES.iter().enumerate() {
            let expected = match mask.count_ones() {
                0 | 4 => 0,
                1 | 3 => 1,
                _ => 2,
            };
            assert_eq!(case.count, expected, "mask {mask}");
            for tri in &case.triangles[..usize::from(case.count)] {
                for [a, b] in tri {
                    assert_ne!(material(mask, *a), material(mask, *b), "mask {mask}");
                }
            }
        }
    }

    #[test]
    fn crossings_stay_off_the_voxels() {
        let clamp = CROSSING_CLAMP;
        assert_eq!(crossing(1.0, -1.0, 0.0), 0.5);
        assert_eq!(crossing(-1.0, 3.0, 0.0), 0.25);
        assert_eq!(crossing(0.0, -1.0, 0.0), clamp);
        assert_eq!(crossing(-1.0, 0.0, 0.0), 1.0 - clamp);
        assert_eq!(crossing(1.0, f32::NEG_INFINITY, 0.0), clamp);
        assert_eq!(crossing(f32::NEG_INFINITY, 1.0, 0.0), 1.0 - clamp);
        assert_eq!(crossing(f32::INFINITY, -1.0, 0.0), 1.0 - clamp);
        assert_eq!(crossing(f32::NEG_INFINITY, f32::INFINITY, 0.0), 0.5);
    }
}
