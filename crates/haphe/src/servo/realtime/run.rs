//! What the ticking thread holds and its schedule: the servo, the absolute deadlines, and
//! the wait until each.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crate::servo::device::Device;
use crate::servo::tick::{Servo, StopReason};
use crate::servo::trace::TickRecord;

/// Sleeps until `spin` before `deadline`, then spins to it.
#[inline]
pub(super) fn wait_until(deadline: Instant, spin: Duration) {
    loop {
        let now = Instant::now();
        if now >= deadline {
            return;
        }
        let left = deadline - now;
        if left > spin {
            std::thread::sleep(left - spin);
        } else {
            std::hint::spin_loop();
        }
    }
}

pub(super) fn nanos(d: Duration) -> u64 {
    u64::try_from(d.as_nanos()).unwrap_or(u64::MAX)
}

/// What the thread that ticks holds: the servo and the loop's own counters.
pub(super) struct Run<D: Device> {
    pub(super) servo: Servo<D>,
    pub(super) producer: rtrb::Producer<TickRecord>,
    /// The next tick to run; its deadline is `start + k · period`.
    pub(super) k: u64,
    pub(super) dropped: u64,
    /// Why the run ended, once it has.
    pub(super) stop: Option<StopReason>,
    /// See [`RealtimeOptions::overrun_budget`].
    pub(super) overrun_budget: Option<u64>,
}

/// The deadlines of a run.
#[derive(Debug, Clone, Copy)]
pub(super) struct Schedule {
    pub(super) start: Instant,
    pub(super) period_ns: u64,
    pub(super) max_ticks: Option<u64>,
}

impl Schedule {
    /// The deadline of tick `k`, and its time since the start.
    pub(super) fn deadline(&self, k: u64) -> (Instant, Duration) {
        let offset = Duration::from_nanos(k.saturating_mul(self.period_ns));
        (self.start + offset, offset)
    }
}

/// The period of a run at `rate` Hz, nanoseconds (at least 1), and its number of ticks
/// when it lasts `seconds` (`None`, negative or not finite: until stopped).
pub(super) fn period_and_ticks(rate: f64, seconds: Option<f64>) -> (u64, Option<u64>) {
    let period_ns = ((1e9 / rate).round() as u64).max(1);
    let max_ticks = seconds
        .filter(|s| s.is_finite() && *s >= 0.0)
        .map(|s| (s * rate).round() as u64);
    (period_ns, max_ticks)
}

impl<D: Device> Run<D> {
    /// A run of `servo`, not started, recording into `producer`.
    pub(super) fn new(
        servo: Servo<D>,
        producer: rtrb::Producer<TickRecord>,
        overrun_budget: Option<u64>,
    ) -> Run<D> {
        Run {
            servo,
            producer,
            k: 0,
            dropped: 0,
            stop: None,
            overrun_budget,
        }
    }

    /// Whether the run has ended; decides it (the time is up, or a stop was asked) when
    /// it has not yet.
    pub(super) fn ended(&mut self, schedule: &Schedule, stop_flag: &AtomicBool) -> bool {
        if self.stop.is_none() {
            if schedule.max_ticks.is_some_and(|m| self.k >= m) {
                self.stop = Some(StopReason::Finished);
            } else if stop_flag.load(Ordering::Relaxed) {
                self.stop = Some(StopReason::Requested);
            }
        }
        self.stop.is_some()
    }

    /// Runs tick `k` (its deadline has come), records its lateness and compute time,
    /// hands its record on, and moves on to the next deadline not yet past.
    pub(super) fn tick(&mut self, schedule: &Schedule) {
        let (deadline, offset) = schedule.deadline(self.k);
        let done = self.timed_tick(deadline, offset, schedule.period_ns);
        // More than a period behind: skip the deadlines already past.
        let behind = nanos(done.saturating_duration_since(schedule.start)) / schedule.period_ns;
        if behind > self.k {
            self.servo.stats_mut().skipped += behind + 1 - self.k;
            self.k = behind + 1;
        }
        self.check_budget();
    }

    /// Runs tick `k` at the time `offset` since the start, its deadline having been
    /// `deadline`: records lateness, compute time and an overrun (the tick ended after
    /// the next deadline), hands its records on (one per device), notes a fault. Returns when it ended.
    /// Shared by haphe's own clock and a device's ([`DeviceClock`]).
    pub(super) fn timed_tick(
        &mut self,
        deadline: Instant,
        offset: Duration,
        period_ns: u64,
    ) -> Instant {
        let began = Instant::now();
        let records = self.servo.tick_devices(offset.as_secs_f64());
        let done = Instant::now();
        for &record in records {
            if self.producer.push(record).is_err() {
                self.dropped += 1;
            }
            if let Some(f) = record.fault {
                self.stop = Some(StopReason::Fault(f));
            }
        }
        let stats = self.servo.stats_mut();
        stats
            .lateness
            .record(nanos(began.saturating_duration_since(deadline)));
        stats
            .compute
            .record(nanos(done.saturating_duration_since(began)));
        if done > deadline + Duration::from_nanos(period_ns) {
            stats.overruns += 1;
        }
        self.k += 1;
        done
    }

    /// Ends the run with zero force when more deadlines were missed than the budget.
    pub(super) fn check_budget(&mut self) {
        if self.stop.is_none()
            && self
                .overrun_budget
                .is_some_and(|b| self.servo.stats().missed() > b)
        {
            self.servo.zero_force();
            self.stop = Some(StopReason::Overruns);
        }
    }
}
