//! [`ServoLoop`]: the handle of the servo thread, and the thread's body.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use rtrb::{Consumer, RingBuffer};

use super::interference::{Counters, Interference};
use super::options::{DEFAULT_SPIN_FRACTION, DEFAULT_SPIN_S, RealtimeOptions};
use super::run::{Run, Schedule, period_and_ticks, wait_until};
use super::standby::{StandbyReport, with_standby};
use super::thread::{RealtimeSetup, check_core, set_up_thread};
use crate::servo::device::Device;
use crate::servo::tick::{Servo, ServoError, StopReason};
use crate::servo::trace::TickRecord;

/// How a real-time run went.
#[derive(Debug)]
pub struct RealtimeRun<D: Device> {
    /// The servo, with its statistics (and zero force written).
    pub servo: Servo<D>,
    /// What the system granted.
    pub setup: RealtimeSetup,
    /// Why the run ended.
    pub stop: StopReason,
    /// Records dropped because the reading thread fell behind.
    pub dropped_records: u64,
    /// What ran instead of the servo thread during the run (steal time of its core,
    /// preemptions): what to look at when there were overruns.
    pub interference: Interference,
    /// What the standby thread did, when there was one.
    pub standby: Option<StandbyReport>,
}

/// A [`Servo`] running on its own thread at its rate on the wall clock.
///
/// Tick `k` has the absolute deadline `start + k · period`. The thread sleeps until
/// shortly before it and spins the rest, reads the clock (lateness = now − deadline),
/// runs the tick, and records compute time and lateness in the servo's
/// [`TickStats`](crate::servo::TickStats) (preallocated histograms). A tick that ends after
/// the next deadline is an **overrun**; when the loop falls more than a period behind, it
/// skips the deadlines already past (counted as `skipped`) instead of racing to catch up.
/// Each tick's [`TickRecord`] goes to the reading thread through a wait-free ring
/// ([`ServoLoop::drain`]).
///
/// The simulated devices take the scheduled time of a tick as their clock, so what they
/// do does not depend on the lateness of the loop.
#[derive(Debug)]
pub struct ServoLoop<D: Device + 'static> {
    pub(super) stop: Arc<AtomicBool>,
    pub(super) records: Consumer<TickRecord>,
    pub(super) handle: JoinHandle<RealtimeRun<D>>,
}

impl<D: Device + 'static> ServoLoop<D> {
    /// Starts `servo` on a new thread for `seconds` (`None`: until [`stop`](Self::stop)).
    ///
    /// # Errors
    /// [`ServoError::NoSuchCore`] when [`RealtimeOptions::standby_core`] names a core this
    /// process may not run on; [`ServoError::Spawn`] when the thread cannot be started.
    pub fn spawn(
        servo: Servo<D>,
        seconds: Option<f64>,
        options: RealtimeOptions,
    ) -> Result<ServoLoop<D>, ServoError> {
        if let Some(core) = options.standby_core {
            check_core(core)?;
        }
        let (producer, consumer) = RingBuffer::new(
            options
                .record_capacity
                .max(1)
                .saturating_mul(servo.devices()),
        );
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        let handle = std::thread::Builder::new()
            .name("haphe-servo".into())
            .spawn(move || run_thread(servo, seconds, options, &flag, producer))
            .map_err(ServoError::Spawn)?;
        Ok(ServoLoop {
            stop,
            records: consumer,
            handle,
        })
    }

    /// Takes the records waiting in the ring, oldest first. Call it often (every few
    /// milliseconds) so that none are dropped.
    pub fn drain(&mut self, mut f: impl FnMut(&TickRecord)) -> usize {
        let mut n = 0;
        while let Ok(r) = self.records.pop() {
            f(&r);
            n += 1;
        }
        n
    }

    /// Whether the thread has ended (its time ran out, or a fault).
    pub fn is_finished(&self) -> bool {
        self.handle.is_finished()
    }

    /// Asks the thread to stop, waits for it, and hands the run back. Every record not yet
    /// drained goes to `f`.
    ///
    /// # Errors
    /// [`ServoError::Panicked`] if the servo thread panicked.
    pub fn stop(mut self, mut f: impl FnMut(&TickRecord)) -> Result<RealtimeRun<D>, ServoError> {
        self.stop.store(true, Ordering::Relaxed);
        while !self.handle.is_finished() {
            self.drain(&mut f);
            std::thread::sleep(Duration::from_millis(1));
        }
        let run = self.handle.join().map_err(|_| ServoError::Panicked)?;
        while let Ok(r) = self.records.pop() {
            f(&r);
        }
        Ok(run)
    }

    /// Waits until the thread ends by itself (its time ran out, or a fault), handing
    /// the records to `f` as they come, then hands the run back.
    ///
    /// # Errors
    /// [`ServoError::Panicked`] if the servo thread panicked.
    pub fn wait(mut self, mut f: impl FnMut(&TickRecord)) -> Result<RealtimeRun<D>, ServoError> {
        while !self.handle.is_finished() {
            if self.drain(&mut f) == 0 {
                std::thread::sleep(Duration::from_millis(2));
            }
        }
        self.stop(f)
    }
}

/// The servo thread.
pub(super) fn run_thread<D: Device>(
    servo: Servo<D>,
    seconds: Option<f64>,
    options: RealtimeOptions,
    stop_flag: &AtomicBool,
    producer: rtrb::Producer<TickRecord>,
) -> RealtimeRun<D> {
    let mut setup = set_up_thread(&options);
    // A standby on the servo thread's own core could only take turns with it.
    let standby_core = match options.standby_core {
        Some(c) if setup.pinned_core == Some(c) => {
            setup
                .notes
                .push(format!("no standby: core {c} is the servo thread's own"));
            None
        }
        other => other,
    };
    let rate = servo.options().rate_hz();
    let (period_ns, max_ticks) = period_and_ticks(rate, seconds);
    let spin_s = options
        .spin_seconds
        .filter(|s| s.is_finite() && *s >= 0.0)
        .unwrap_or_else(|| DEFAULT_SPIN_S.min(DEFAULT_SPIN_FRACTION / rate));
    let spin = Duration::from_secs_f64(spin_s);
    let mut run = Run::new(servo, producer, options.overrun_budget);
    let counters = Counters::read(setup.pinned_core);
    let (mut run, standby) = match standby_core {
        None => {
            // Everything above may allocate; nothing below does.
            let schedule = Schedule {
                start: Instant::now(),
                period_ns,
                max_ticks,
            };
            while !run.ended(&schedule, stop_flag) {
                wait_until(schedule.deadline(run.k).0, spin);
                run.tick(&schedule);
            }
            run.servo.stats_mut().wall_seconds += schedule.start.elapsed().as_secs_f64();
            (run, None)
        }
        Some(core) => with_standby(run, core, (period_ns, max_ticks), spin, stop_flag),
    };
    run.servo.zero_force();
    let interference = counters.since(Counters::read(setup.pinned_core));
    RealtimeRun {
        servo: run.servo,
        setup,
        stop: run.stop.unwrap_or(StopReason::Finished),
        dropped_records: run.dropped,
        interference,
        standby,
    }
}
