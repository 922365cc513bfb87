//! Tick statistics gathered on the servo thread without allocation: log-linear histograms
//! of durations and counters.

/// Linear sub-buckets per power of two, as a power of two: 32 sub-buckets, so a reported
/// quantile is within 1/64 (1.6 %) of the true value.
const SUB_BITS: u32 = 5;
const SUB: usize = 1 << SUB_BITS;
/// Buckets for every `u64`: values below `SUB` exactly, then `SUB` per power of two.
const BUCKETS: usize = SUB * (64 - SUB_BITS as usize + 1);

/// A histogram of durations in nanoseconds, from 0 to `u64::MAX`, with a relative
/// resolution of 1/64 (HDR-style log-linear buckets). Storage is allocated once, when it
/// is made; recording never allocates.
#[derive(Debug, Clone)]
pub struct Histogram {
    counts: Box<[u64]>,
    count: u64,
    max: u64,
    sum: u128,
}

impl Default for Histogram {
    fn default() -> Histogram {
        Histogram::new()
    }
}

fn bucket_of(v: u64) -> usize {
    if v < SUB as u64 {
        return v as usize;
    }
    let e = 63 - v.leading_zeros(); // ≥ SUB_BITS
    let sub = (v >> (e - SUB_BITS)) as usize - SUB;
    SUB * (e - SUB_BITS + 1) as usize + sub
}

/// The midpoint of bucket `b`, nanoseconds.
fn value_of(b: usize) -> u64 {
    if b < SUB {
        return b as u64;
    }
    let e = (b / SUB) as u32 - 1 + SUB_BITS;
    let sub = (b % SUB) as u64 + SUB as u64;
    let shift = e - SUB_BITS;
    let low = sub << shift;
    low.saturating_add((1u64 << shift) / 2)
}

impl Histogram {
    /// An empty histogram (about 15 KB, allocated and touched here).
    pub fn new() -> Histogram {
        let mut counts = vec![0u64; BUCKETS].into_boxed_slice();
        // Touch every page now, so that the first records do not fault pages in.
        for c in counts.iter_mut() {
            *c = std::hint::black_box(0);
        }
        Histogram {
            counts,
            count: 0,
            max: 0,
            sum: 0,
        }
    }

    /// Records a duration, nanoseconds.
    ///
    /// # Real-time
    /// No allocation; constant time.
    #[inline]
    pub fn record(&mut self, ns: u64) {
        if let Some(c) = self.counts.get_mut(bucket_of(ns)) {
            *c += 1;
        }
        self.count += 1;
        self.max = self.max.max(ns);
        self.sum += u128::from(ns);
    }

    /// Forgets every record.
    pub fn clear(&mut self) {
        self.counts.fill(0);
        self.count = 0;
        self.max = 0;
        self.sum = 0;
    }

    /// Number of records.
    pub fn count(&self) -> u64 {
        self.count
    }

    /// Largest record, nanoseconds (exact).
    pub fn max(&self) -> u64 {
        self.max
    }

    /// Mean, nanoseconds (0 when empty).
    pub fn mean(&self) -> f64 {
        if self.count == 0 {
            0.0
        } else {
            self.sum as f64 / self.count as f64
        }
    }

    /// The `q`-quantile (`0 ≤ q ≤ 1`), nanoseconds, within 1/64 of the true value, and
    /// never above the maximum (the largest rank is the maximum, exactly); 0 when empty.
    pub fn quantile(&self, q: f64) -> u64 {
        if self.count == 0 {
            return 0;
        }
        let q = if q.is_finite() {
            q.clamp(0.0, 1.0)
        } else {
            1.0
        };
        let rank = ((q * self.count as f64).ceil() as u64).clamp(1, self.count);
        if rank == self.count {
            return self.max;
        }
        let mut seen = 0u64;
        for (b, &c) in self.counts.iter().enumerate() {
            seen += c;
            if seen >= rank {
                return value_of(b).min(self.max);
            }
        }
        self.max
    }

    /// Number of records above `ns` nanoseconds (counted to bucket resolution).
    pub fn count_above(&self, ns: u64) -> u64 {
        let b = bucket_of(ns);
        self.counts.iter().skip(b + 1).sum()
    }
}

/// Statistics of a servo run: tick compute time, lateness against the deadlines (real-time
/// runs only), deadline misses and what the ticks reported.
#[derive(Debug, Clone, Default)]
pub struct TickStats {
    /// Time from reading the device to writing the force, per tick, nanoseconds.
    pub compute: Histogram,
    /// How late each tick started after its deadline, nanoseconds (real-time runs only).
    pub lateness: Histogram,
    /// Ticks run.
    pub ticks: u64,
    /// Ticks that finished after the next tick's deadline (real-time runs only).
    pub overruns: u64,
    /// Deadlines skipped because the loop was more than a period late (real-time runs only).
    pub skipped: u64,
    /// Ticks with the proxy in contact.
    pub contact_ticks: u64,
    /// Ticks held at zero force by the safe start (the device started inside an object).
    pub held_ticks: u64,
    /// Ticks whose force was clamped to the device's maximum.
    pub clamped_ticks: u64,
    /// Ticks whose device input was rejected (not finite).
    pub rejected_ticks: u64,
    /// Ticks that hit a step cap of the proxy or its contact walk.
    pub capped_ticks: u64,
    /// Wall-clock time of the run, seconds (set when it ends).
    pub wall_seconds: f64,
}

impl TickStats {
    /// Empty statistics, with the histograms allocated.
    pub fn new() -> TickStats {
        TickStats::default()
    }

    /// Ticks per wall-clock second (0 before the run ends).
    pub fn achieved_rate(&self) -> f64 {
        if self.wall_seconds > 0.0 {
            self.ticks as f64 / self.wall_seconds
        } else {
            0.0
        }
    }

    /// Overruns as a fraction of ticks.
    pub fn overrun_fraction(&self) -> f64 {
        if self.ticks == 0 {
            0.0
        } else {
            self.overruns as f64 / self.ticks as f64
        }
    }

    /// Deadlines whose force came late or never: the ticks that overran plus the
    /// deadlines skipped, over every deadline of the run (ticks run and skipped). What a
    /// user of the device feels as missed updates; 0 for a run on a virtual clock.
    pub fn missed_fraction(&self) -> f64 {
        let deadlines = self.deadlines();
        if deadlines == 0 {
            0.0
        } else {
            self.missed() as f64 / deadlines as f64
        }
    }

    /// Deadlines of the run: ticks run and deadlines skipped.
    pub fn deadlines(&self) -> u64 {
        self.ticks + self.skipped
    }

    /// Deadlines whose force came late or never: overruns and skipped deadlines.
    pub fn missed(&self) -> u64 {
        self.overruns + self.skipped
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn buckets_cover_every_value_in_order() {
        let mut last = 0;
        for v in (0..10_000u64).chain([u64::MAX / 3, u64::MAX]) {
            let b = bucket_of(v);
            assert!(b < BUCKETS && b >= last, "{v}");
            last = b;
            let mid = value_of(b);
            assert!(
                mid.abs_diff(v) as f64 <= 1.0 + v as f64 / 64.0,
                "{v} -> {mid}"
            );
        }
    }

    #[test]
    fn missed_deadlines_count_overruns_and_skipped_deadlines() {
        let stats = TickStats {
            ticks: 9_990,
            overruns: 5,
            skipped: 10,
            ..TickStats::default()
        };
        assert!((stats.overrun_fraction() - 5.0 / 9_990.0).abs() < 1e-15);
        assert!((stats.missed_fraction() - 15.0 / 10_000.0).abs() < 1e-15);
        assert_eq!(TickStats::default().missed_fraction(), 0.0);
    }

    #[test]
    fn quantiles_are_close() {
        let mut h = Histogram::new();
        for v in 1..=100_000u64 {
            h.record(v);
        }
        for (q, want) in [(0.5, 50_000.0), (0.99, 99_000.0), (0.999, 99_900.0)] {
            let got = h.quantile(q) as f64;
            assert!((got - want).abs() / want < 1.0 / 60.0, "{q}: {got}");
        }
        assert_eq!(h.quantile(1.0), 100_000);
        assert_eq!(h.max(), 100_000);
        assert!((h.mean() - 50_000.5).abs() < 1e-6);
        assert!(h.count_above(50_000) > 45_000);
        h.clear();
        assert_eq!((h.count(), h.quantile(0.5)), (0, 0));
    }
}
