//! Timing one query at a time, and summarising the times.
//!
//! [`time_each`] reads the monotonic clock ([`Instant`]) just before and just after each
//! query, with the input and the answer passed through [`black_box`] so the compiler can
//! neither hoist the query out of the timed region nor drop it. What it records is the
//! query plus the cost of reading the clock. That cost is measured the same way, with an
//! empty query ([`time_empty`]), interleaved with the real methods in every round, and
//! [`Summary::of`] subtracts its median from every percentile and its mean from the mean.
//!
//! On Linux with a TSC clock source `Instant::now` is a vDSO call of a few tens of
//! nanoseconds that orders itself with the surrounding instructions. The percentiles
//! carry the clock's granularity: where the counter ticks in steps (some processors and
//! virtual machines advance it every few nanoseconds), every time is a whole number of
//! steps. The mean does not: a query starts at a random phase of the step, so the
//! quantisation averages out over many queries, and the mean resolves costs finer than a
//! step. It is the mean of the fastest 99 % of the queries ([`TRIMMED_FRACTION`]), so that
//! the rare query that the operating system interrupts for milliseconds on a shared
//! machine does not swamp it; the percentiles show the tail.

use std::hint::black_box;
use std::time::{Duration, Instant};

use haphe::DVec3;

/// Runs chunk `c` of a stream, appending one raw time per query.
pub type Run<'a> = Box<dyn FnMut(usize, &mut Vec<u32>) + 'a>;

/// Times `query` on each input, appending one raw time per input to `out` (nanoseconds,
/// clock overhead included, saturated at `u32::MAX`).
#[inline(always)]
pub fn time_each<T, R>(
    inputs: impl IntoIterator<Item = T>,
    mut query: impl FnMut(T) -> R,
    out: &mut Vec<u32>,
) {
    for input in inputs {
        let start = Instant::now();
        let answer = query(black_box(input));
        black_box(answer);
        out.push(nanos(start.elapsed()));
    }
}

/// Times `count` empty queries exactly as [`time_each`] times real ones, on a point as
/// input: the clock overhead.
pub fn time_empty(count: usize, out: &mut Vec<u32>) {
    time_each(std::iter::repeat_n(DVec3::ZERO, count), |p| p, out);
}

/// A duration in whole nanoseconds, saturated at `u32::MAX` (4.3 s).
fn nanos(d: Duration) -> u32 {
    u32::try_from(d.as_nanos()).unwrap_or(u32::MAX)
}

/// The fraction of the fastest queries that [`Summary::trimmed_mean`] averages.
pub const TRIMMED_FRACTION: f64 = 0.99;

/// Percentiles of a set of per-query times, nanoseconds, clock overhead subtracted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summary {
    /// Number of timed queries.
    pub samples: usize,
    /// Median.
    pub p50: f64,
    /// 99th percentile.
    pub p99: f64,
    /// 99.9th percentile.
    pub p999: f64,
    /// Slowest query.
    pub max: f64,
    /// Mean of the fastest [`TRIMMED_FRACTION`] of the queries.
    pub trimmed_mean: f64,
}

/// What reading the clock around a query costs: the median and the mean of empty timings,
/// nanoseconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Overhead {
    /// Subtracted from percentiles.
    pub median: f64,
    /// Subtracted from the trimmed mean.
    pub trimmed_mean: f64,
}

impl Overhead {
    /// Nothing to subtract.
    pub const NONE: Overhead = Overhead {
        median: 0.0,
        trimmed_mean: 0.0,
    };

    /// The overhead measured by empty timings (summarised with [`Overhead::NONE`]).
    pub fn of(clock: &Summary) -> Overhead {
        Overhead {
            median: clock.p50,
            trimmed_mean: clock.trimmed_mean,
        }
    }
}

impl Summary {
    /// Summarises raw times (sorted in place), subtracting the overhead (never going
    /// below zero). Percentiles are nearest-rank: the smallest time with at least that
    /// fraction of the samples at or below it.
    pub fn of(raw: &mut [u32], overhead: Overhead) -> Summary {
        raw.sort_unstable();
        Summary::of_sorted(raw.len(), |i| f64::from(raw[i]), overhead)
    }

    /// Summarises a few whole-operation times (builds, decodes), nothing subtracted.
    pub fn of_durations(times: &[Duration]) -> Summary {
        let mut ns: Vec<f64> = times.iter().map(|d| d.as_secs_f64() * 1e9).collect();
        ns.sort_unstable_by(f64::total_cmp);
        Summary::of_sorted(ns.len(), |i| ns[i], Overhead::NONE)
    }

    /// Nearest-rank percentiles of `n` sorted times given by `at`.
    fn of_sorted(n: usize, at: impl Fn(usize) -> f64, overhead: Overhead) -> Summary {
        let rank = |q: f64| -> f64 {
            if n == 0 {
                return f64::NAN;
            }
            let i = ((q * n as f64).ceil() as usize).clamp(1, n) - 1;
            (at(i) - overhead.median).max(0.0)
        };
        let kept = ((TRIMMED_FRACTION * n as f64).ceil() as usize).clamp(1, n.max(1));
        let trimmed_mean = if n == 0 {
            f64::NAN
        } else {
            ((0..kept).map(&at).sum::<f64>() / kept as f64 - overhead.trimmed_mean).max(0.0)
        };
        Summary {
            samples: n,
            p50: rank(0.5),
            p99: rank(0.99),
            p999: rank(0.999),
            max: rank(1.0),
            trimmed_mean,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_are_nearest_rank_with_the_overhead_subtracted() {
        let mut raw: Vec<u32> = (1..=1000).rev().collect();
        let overhead = Overhead {
            median: 10.0,
            trimmed_mean: 20.0,
        };
        let s = Summary::of(&mut raw, overhead);
        assert_eq!(s.samples, 1000);
        assert_eq!(s.p50, 490.0);
        assert_eq!(s.p99, 980.0);
        assert_eq!(s.p999, 989.0);
        assert_eq!(s.max, 990.0);
        assert_eq!(s.trimmed_mean, 475.5, "the mean of 1..=990, less 20");
        let mut few = vec![3, 1, 2];
        let s = Summary::of(
            &mut few,
            Overhead {
                median: 5.0,
                trimmed_mean: 5.0,
            },
        );
        assert_eq!((s.p50, s.max), (0.0, 0.0), "never below zero");
    }
}
