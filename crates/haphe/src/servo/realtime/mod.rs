//! [`ServoLoop`]: the servo on a dedicated thread, ticking on absolute deadlines of the
//! wall clock, with real-time priority and core pinning where the system permits.

mod external;
mod interference;
mod standby;

pub use external::DeviceClock;
pub use interference::Interference;
pub use standby::StandbyReport;

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use rtrb::{Consumer, RingBuffer};

use crate::scene::{Param, ParamError};
use crate::servo::device::Device;
use crate::servo::tick::{Servo, ServoError, StopReason};
use crate::servo::trace::TickRecord;
use interference::Counters;
use standby::with_standby;

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

/// Priority asked for the servo thread on Linux (SCHED_FIFO, 1–99): high, below the
/// kernel's own per-CPU threads (99).
#[cfg(all(unix, feature = "realtime"))]
pub const FIFO_PRIORITY: u8 = 80;

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
    /// Capacity of the record ring to the reading thread, ticks; records that find it
    /// full are dropped and counted.
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
    /// [`TickStats::missed`](super::TickStats::missed)); `None` (the
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

    /// The same options with a record ring of `record_capacity` ticks.
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

/// What the system granted the servo thread.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct RealtimeSetup {
    /// The thread runs with FIFO real-time priority.
    pub realtime_priority: bool,
    /// The core the thread is pinned to.
    pub pinned_core: Option<usize>,
    /// Why a request was not granted, for the report.
    pub notes: Vec<String>,
}

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
/// [`TickStats`](super::TickStats) (preallocated histograms). A tick that ends after
/// the next deadline is an **overrun**; when the loop falls more than a period behind, it
/// skips the deadlines already past (counted as `skipped`) instead of racing to catch up.
/// Each tick's [`TickRecord`] goes to the reading thread through a wait-free ring
/// ([`ServoLoop::drain`]).
///
/// The simulated devices take the scheduled time of a tick as their clock, so what they
/// do does not depend on the lateness of the loop.
#[derive(Debug)]
pub struct ServoLoop<D: Device + 'static> {
    stop: Arc<AtomicBool>,
    records: Consumer<TickRecord>,
    handle: JoinHandle<RealtimeRun<D>>,
}

/// Checks that this process may run on `core` (for [`RealtimeOptions::standby_core`]).
///
/// # Errors
/// [`ServoError::NoSuchCore`], with the cores it may run on.
pub fn check_core(core: usize) -> Result<(), ServoError> {
    #[cfg(feature = "realtime")]
    let cores: Vec<usize> = core_affinity::get_core_ids()
        .unwrap_or_default()
        .iter()
        .map(|c| c.id)
        .collect();
    // Without the OS calls, the cores the standard library counts.
    #[cfg(not(feature = "realtime"))]
    let cores: Vec<usize> =
        (0..std::thread::available_parallelism().map_or(1, |n| n.get())).collect();
    if cores.contains(&core) {
        Ok(())
    } else {
        Err(ServoError::NoSuchCore { core, cores })
    }
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
        let (producer, consumer) = RingBuffer::new(options.record_capacity.max(1));
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

/// Asks for FIFO priority and pins the thread, as permitted.
#[cfg(feature = "realtime")]
fn set_up_thread(options: &RealtimeOptions) -> RealtimeSetup {
    let mut setup = RealtimeSetup::default();
    if options.realtime_priority {
        match fifo_priority() {
            Ok(()) => setup.realtime_priority = true,
            Err(why) => setup
                .notes
                .push(format!("real-time priority not granted ({why})")),
        }
    }
    match core_affinity::get_core_ids() {
        Some(cores) if cores.len() > 1 || options.core.is_some() => {
            let wanted = options.core.unwrap_or(cores.len() - 1);
            match cores.iter().find(|c| c.id == wanted) {
                Some(&core) if core_affinity::set_for_current(core) => {
                    setup.pinned_core = Some(core.id);
                }
                Some(_) => setup
                    .notes
                    .push(format!("pinning to core {wanted} refused")),
                None => setup.notes.push(format!("no core {wanted} to pin to")),
            }
        }
        Some(_) => setup.notes.push("one core: not pinned".into()),
        None => setup.notes.push("core pinning unsupported here".into()),
    }
    setup
}

/// Without the `realtime` feature: normal priority, not pinned, as the notes say.
#[cfg(not(feature = "realtime"))]
fn set_up_thread(options: &RealtimeOptions) -> RealtimeSetup {
    let mut setup = RealtimeSetup::default();
    if options.realtime_priority || options.core.is_some() {
        setup
            .notes
            .push("real-time priority and core pinning not built (feature 'realtime')".into());
    }
    setup
}

#[cfg(all(unix, feature = "realtime"))]
fn fifo_priority() -> Result<(), String> {
    use thread_priority::{
        RealtimeThreadSchedulePolicy, ThreadPriority, ThreadPriorityValue, ThreadSchedulePolicy,
        set_thread_priority_and_policy, thread_native_id,
    };
    let value = ThreadPriorityValue::try_from(FIFO_PRIORITY).map_err(|e| e.to_string())?;
    set_thread_priority_and_policy(
        thread_native_id(),
        ThreadPriority::Crossplatform(value),
        ThreadSchedulePolicy::Realtime(RealtimeThreadSchedulePolicy::Fifo),
    )
    .map_err(|e| format!("{e:?}"))
}

#[cfg(all(not(unix), feature = "realtime"))]
fn fifo_priority() -> Result<(), String> {
    thread_priority::set_current_thread_priority(thread_priority::ThreadPriority::Max)
        .map_err(|e| format!("{e:?}"))
}

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

fn nanos(d: Duration) -> u64 {
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
    /// the next deadline), hands its record on, notes a fault. Returns when it ended.
    /// Shared by haphe's own clock and a device's ([`DeviceClock`]).
    pub(super) fn timed_tick(
        &mut self,
        deadline: Instant,
        offset: Duration,
        period_ns: u64,
    ) -> Instant {
        let began = Instant::now();
        let record = self.servo.tick_at(offset.as_secs_f64());
        let done = Instant::now();
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
        if self.producer.push(record).is_err() {
            self.dropped += 1;
        }
        if let Some(f) = record.fault {
            self.stop = Some(StopReason::Fault(f));
        }
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

/// The servo thread.
fn run_thread<D: Device>(
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
