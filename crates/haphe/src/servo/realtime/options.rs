//! The options of the servo thread: priority, core, spinning before deadlines.

use crate::scene::{Param, ParamError};

/// Longest part of a period spun before a deadline (instead of sleeping), seconds: the
/// operating system's wake-up is often late by tens of microseconds, so the last part is
/// spun. At high rates the default is `DEFAULT_SPIN_FRACTION` of the period instead.
pub const DEFAULT_SPIN_S: f64 = 200e-6;

/// Default spin at high rates, as a fraction of the period. A real-time thread that never
/// sleeps is throttled by Linux (by default 50 ms in every second, `sched_rt_runtime_us`),
/// and one that spins most of the period competes with everything else on its core;
/// measured on a loaded 2-core virtual machine at 10 kHz, spinning 30 µs of 100 µs gave
/// the fewest overruns (60–100 µs: more, and 50 ms stalls from throttling; 15 µs: wake-ups
/// late by 15 µs at the median).
pub const DEFAULT_SPIN_FRACTION: f64 = 0.3;

/// How the servo thread is scheduled, built from [`RealtimeOptions::default`] by the
/// `with_*` builders (the spin is checked against its domain, [`Param::SpinSeconds`]); the
/// fields are private, so a struct literal does not build:
///
/// ```compile_fail
/// let o = haphe::servo::RealtimeOptions { spin_seconds: Some(f64::NAN), ..Default::default() };
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RealtimeOptions {
    /// Ask for real-time (FIFO) priority; without permission the thread keeps the normal
    /// priority, quietly, and [`RealtimeSetup`] says so.
    pub(crate) realtime_priority: bool,
    /// Pin the thread to this core (`None`: the last core, where the system tends to put
    /// the least work; pinning is skipped when there is a single core).
    pub(crate) core: Option<usize>,
    /// Spin (instead of sleeping) for this last part before each deadline, seconds.
    /// `None`: [`DEFAULT_SPIN_S`], at most [`DEFAULT_SPIN_FRACTION`] of the period.
    pub(crate) spin_seconds: Option<f64>,
    /// Capacity of the record ring to the reading thread, ticks (a servo of several
    /// devices gets this many records per device); records that find it full are
    /// dropped and counted.
    pub(crate) record_capacity: usize,
    /// Run a standby thread pinned to this core, which ticks in place of the servo
    /// thread when that one has not started a tick
    /// 20 µs after its deadline (its core was taken
    /// away: host steal time on a virtual machine, or a preemption). The standby spins the
    /// whole period at normal priority, so it costs a second core; `None` (the default):
    /// no standby. A core the servo thread is pinned to gets no standby (said in
    /// [`RealtimeSetup::notes`]).
    pub(crate) standby_core: Option<usize>,
    /// Stop the run (zero force, [`StopReason::Overruns`]) once more deadlines than this
    /// were missed (overruns and skipped deadlines together, see
    /// [`TickStats::missed`](crate::servo::TickStats::missed)); `None` (the
    /// default): never. A real device should have one: a servo that keeps missing its
    /// deadlines renders unstable walls.
    pub(crate) overrun_budget: Option<u64>,
}

impl Default for RealtimeOptions {
    /// Real-time priority, the last core, the default spin, one second of records at
    /// 40 kHz, no standby thread, no overrun budget.
    fn default() -> RealtimeOptions {
        RealtimeOptions {
            realtime_priority: true,
            core: None,
            spin_seconds: None,
            record_capacity: 40_000,
            standby_core: None,
            overrun_budget: None,
        }
    }
}

impl RealtimeOptions {
    /// The same options asking (or not) for real-time priority.
    pub fn with_realtime_priority(self, realtime_priority: bool) -> RealtimeOptions {
        RealtimeOptions {
            realtime_priority,
            ..self
        }
    }

    /// The same options pinning the servo thread to `core` (`None`: the last core).
    pub fn with_core(self, core: Option<usize>) -> RealtimeOptions {
        RealtimeOptions { core, ..self }
    }

    /// The same options spinning this last part before each deadline, seconds (`None`:
    /// the default).
    ///
    /// # Errors
    /// [`ParamError`] naming `spin_seconds` outside its domain (0 to 1 s).
    pub fn with_spin_seconds(
        self,
        spin_seconds: Option<f64>,
    ) -> Result<RealtimeOptions, ParamError> {
        Ok(RealtimeOptions {
            spin_seconds: spin_seconds
                .map(|s| Param::SpinSeconds.check(s))
                .transpose()?,
            ..self
        })
    }

    /// The same options with a record ring of `record_capacity` ticks (of records per
    /// device).
    pub fn with_record_capacity(self, record_capacity: usize) -> RealtimeOptions {
        RealtimeOptions {
            record_capacity,
            ..self
        }
    }

    /// The same options with a standby thread pinned to `core` (`None`: no standby).
    pub fn with_standby_core(self, standby_core: Option<usize>) -> RealtimeOptions {
        RealtimeOptions {
            standby_core,
            ..self
        }
    }

    /// The same options stopping the run once more than `budget` deadlines were missed
    /// (`None`: never).
    pub fn with_overrun_budget(self, overrun_budget: Option<u64>) -> RealtimeOptions {
        RealtimeOptions {
            overrun_budget,
            ..self
        }
    }

    /// Whether real-time priority is asked for.
    pub fn realtime_priority(&self) -> bool {
        self.realtime_priority
    }

    /// The core the servo thread is pinned to (`None`: the last core).
    pub fn core(&self) -> Option<usize> {
        self.core
    }

    /// The spin before each deadline, seconds (`None`: the default).
    pub fn spin_seconds(&self) -> Option<f64> {
        self.spin_seconds
    }

    /// The record ring's capacity, ticks.
    pub fn record_capacity(&self) -> usize {
        self.record_capacity
    }

    /// The standby thread's core, if any.
    pub fn standby_core(&self) -> Option<usize> {
        self.standby_core
    }

    /// The overrun budget, if any.
    pub fn overrun_budget(&self) -> Option<u64> {
        self.overrun_budget
    }
}
