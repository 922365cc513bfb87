//! A small deterministic random generator for reproducible samples in tests, benchmarks,
//! verification and procedural shapes: the same seed gives the same numbers on every
//! machine and in every version of haphe. Public with the `testing` feature.
#![cfg_attr(not(feature = "testing"), allow(dead_code))]

use glam::DVec3;

/// Steele, Lea and Flood's `splitmix64`: tiny, fast, good statistics, fully specified.
#[derive(Debug, Clone)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator starting from `seed`.
    pub fn new(seed: u64) -> SplitMix64 {
        SplitMix64(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A uniform number in `[0, 1)` with 53 random bits.
    pub fn next_unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// A uniform number in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_unit()
    }

    /// A uniform index in `0..n` (`0` when `n` is 0).
    pub fn index(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.next_u64() % n as u64) as usize
        }
    }

    /// A uniform point in the box `[lo, hi)`.
    pub fn point_in(&mut self, lo: DVec3, hi: DVec3) -> DVec3 {
        DVec3::new(
            self.range(lo.x, hi.x),
            self.range(lo.y, hi.y),
            self.range(lo.z, hi.z),
        )
    }

    /// A uniformly distributed unit vector.
    pub fn unit_vector(&mut self) -> DVec3 {
        loop {
            let v = self.point_in(DVec3::splat(-1.0), DVec3::splat(1.0));
            let l2 = v.length_squared();
            if l2 > 1e-6 && l2 <= 1.0 {
                return v / l2.sqrt();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_reference_sequence() {
        // The first outputs of the reference implementation seeded with 0.
        let mut random = SplitMix64::new(0);
        assert_eq!(random.next_u64(), 0xE220_A839_7B1D_CDAF);
        assert_eq!(random.next_u64(), 0x6E78_9E6A_A1B9_65F4);
        assert_eq!(random.next_u64(), 0x06C4_5D18_8009_454F);
    }

    #[test]
    fn samples_stay_in_range() {
        let mut random = SplitMix64::new(7);
        for _ in 0..1000 {
            let x = random.range(-2.0, 3.0);
            assert!((-2.0..3.0).contains(&x));
            assert!((random.unit_vector().length() - 1.0).abs() < 1e-12);
            assert!(random.index(5) < 5);
        }
    }
}
