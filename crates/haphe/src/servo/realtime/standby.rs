//! The standby servo thread (see
//! [`RealtimeOptions::standby_core`](super::RealtimeOptions::standby_core)): a second
//! thread, pinned to another core, that runs a tick in place of the servo thread when that
//! one has not started it 20 µs (`STANDBY_GRACE_S`) after its deadline. On a shared machine the servo
//! thread's core is sometimes taken away for a while (host steal time on a virtual
//! machine, a preemption); the other core is seldom taken at the same moment.
//!
//! Both threads wait for the next deadline; whichever claims the run first (a
//! non-blocking `try_lock`: one compare-and-swap, neither thread ever waits for the other)
//! runs the tick and publishes the next deadline. The servo thread claims at the deadline,
//! the standby only after the grace, so it ticks only when the servo thread is late.

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use super::interference::{Counters, Interference};
use super::run::{Run, Schedule, wait_until};
use crate::servo::device::Device;

/// How late a tick may start before the standby thread (see
/// [`RealtimeOptions::standby_core`](super::RealtimeOptions::standby_core)) takes it,
/// seconds: far above the servo thread's own lateness when it runs (under a microsecond at
/// the median when it spins), far below a period at 10 kHz.
const STANDBY_GRACE_S: f64 = 20e-6;

/// What the standby thread of a run did (see
/// [`RealtimeOptions::standby_core`](super::RealtimeOptions::standby_core)).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StandbyReport {
    /// The core it was pinned to (`None` when pinning was refused).
    pub pinned_core: Option<usize>,
    /// Ticks it ran in place of the servo thread.
    pub ticks: u64,
    /// What ran instead of it on its core.
    pub interference: Interference,
}

/// [`Shared::next`] once the run has ended.
const ENDED: u64 = u64::MAX;

/// A run that two threads may tick: whichever claims it first for a deadline.
struct Shared<D: Device> {
    run: Mutex<Run<D>>,
    /// The next tick to run (`run.k`, published for the thread that waits), or [`ENDED`].
    next: AtomicU64,
}

impl<D: Device> Shared<D> {
    /// Claims the run for tick `k` without waiting (one compare-and-swap of the mutex's
    /// state, `try_lock`) and runs the tick when it is still due; whether it ran it. Not
    /// when the other thread holds the run or has run tick `k`, nor once the run has
    /// ended ([`Shared::next`] then says [`ENDED`]).
    fn serve(&self, k: u64, schedule: &Schedule, stop_flag: &AtomicBool) -> bool {
        let mut run = match self.run.try_lock() {
            Ok(run) => run,
            Err(std::sync::TryLockError::WouldBlock) => return false,
            // The other thread panicked while ticking: `thread::scope` passes the panic on.
            Err(std::sync::TryLockError::Poisoned(_)) => {
                self.next.store(ENDED, Ordering::Release);
                return false;
            }
        };
        if run.k != k {
            return false;
        }
        let ticked = !run.ended(schedule, stop_flag);
        if ticked {
            run.tick(schedule);
        }
        let next = if run.ended(schedule, stop_flag) {
            ENDED
        } else {
            run.k
        };
        self.next.store(next, Ordering::Release);
        ticked
    }
}

/// The loop of the servo thread and of a standby thread pinned to `core` that ticks in
/// its place when it is late by 20 µs (`STANDBY_GRACE_S`). Returns the run and what the
/// standby did.
pub(super) fn with_standby<D: Device>(
    run: Run<D>,
    core: usize,
    (period_ns, max_ticks): (u64, Option<u64>),
    spin: Duration,
    stop_flag: &AtomicBool,
) -> (Run<D>, Option<StandbyReport>) {
    let shared = Shared {
        next: AtomicU64::new(run.k),
        run: Mutex::new(run),
    };
    let schedule = Schedule {
        start: Instant::now(),
        period_ns,
        max_ticks,
    };
    let grace = Duration::from_secs_f64(STANDBY_GRACE_S);
    let report = std::thread::scope(|scope| {
        let standby = std::thread::Builder::new()
            .name("haphe-standby".into())
            .spawn_scoped(scope, || {
                // Not looked up among the cores this thread may use: it starts with the
                // servo thread's affinity, that one core.
                let pinned_core = pin_to(core);
                let counters = Counters::read(pinned_core);
                let mut ticks = 0u64;
                // Nothing below allocates.
                loop {
                    let k = shared.next.load(Ordering::Acquire);
                    if k == ENDED {
                        break;
                    }
                    // Spin (never sleep: a late wake-up would defeat the standby) until
                    // the grace after the deadline, or until the servo thread ticks.
                    let due = schedule.deadline(k).0 + grace;
                    while Instant::now() < due && shared.next.load(Ordering::Acquire) == k {
                        std::hint::spin_loop();
                    }
                    if shared.next.load(Ordering::Acquire) != k {
                        continue;
                    }
                    if shared.serve(k, &schedule, stop_flag) {
                        ticks += 1;
                    } else {
                        std::hint::spin_loop();
                    }
                }
                StandbyReport {
                    pinned_core,
                    ticks,
                    interference: counters.since(Counters::read(pinned_core)),
                }
            });
        // Nothing below allocates.
        loop {
            let k = shared.next.load(Ordering::Acquire);
            if k == ENDED {
                break;
            }
            wait_until(schedule.deadline(k).0, spin);
            if !shared.serve(k, &schedule, stop_flag) {
                std::hint::spin_loop();
            }
        }
        shared.next.store(ENDED, Ordering::Release);
        // A standby that could not be started leaves every tick to this thread.
        standby.ok().map(|handle| {
            handle
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
        })
    });
    let mut run = shared
        .run
        .into_inner()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    run.servo.stats_mut().wall_seconds += schedule.start.elapsed().as_secs_f64();
    (run, report)
}

/// Pins the current thread to `core`; its index when that worked.
#[cfg(feature = "realtime")]
fn pin_to(core: usize) -> Option<usize> {
    core_affinity::set_for_current(core_affinity::CoreId { id: core }).then_some(core)
}

/// Without the `realtime` feature threads are not pinned.
#[cfg(not(feature = "realtime"))]
fn pin_to(_core: usize) -> Option<usize> {
    None
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use rtrb::{Consumer, RingBuffer};

    use super::*;
    use crate::scene::Scene;
    use crate::servo::{ScriptedDevice, Servo, ServoOptions, StopReason, TickRecord, Trajectory};

    /// A run of a device held still in an empty scene at 1 kHz, its deadlines far in the
    /// future so that no tick is late and none is skipped.
    fn new_run(max_ticks: u64) -> (Shared<ScriptedDevice>, Schedule, Consumer<TickRecord>) {
        let device = ScriptedDevice::new(Trajectory::still(DVec3::new(0.0, 0.0, 1.0)));
        let servo = Servo::new(device, Scene::local(1), ServoOptions::default()).expect("a servo");
        let (producer, consumer) = RingBuffer::new(1024);
        let run = Run::new(servo, producer, None);
        let schedule = Schedule {
            start: Instant::now() + Duration::from_secs(3600),
            period_ns: 1_000_000,
            max_ticks: Some(max_ticks),
        };
        let shared = Shared {
            next: AtomicU64::new(0),
            run: Mutex::new(run),
        };
        (shared, schedule, consumer)
    }

    /// Two threads claiming the same deadlines in turn (here one thread playing both, in
    /// the orders a race can produce): each tick runs once, in order, the second claim of
    /// a deadline finds it done, a claim while the other holds the run finds it busy, and
    /// the hand-off allocates nothing.
    #[test]
    fn each_deadline_is_ticked_once_by_whichever_claims_it_first() {
        let (shared, schedule, mut records) = new_run(300);
        let stop = AtomicBool::new(false);
        let allocations = allocation_counter::measure(|| {
            for k in 0..300 {
                assert_eq!(shared.next.load(Ordering::Acquire), k);
                // The first claim runs the tick; a late one for the same deadline does not.
                let (first, second) = if k % 3 == 0 {
                    ("standby", "servo")
                } else {
                    ("servo", "standby")
                };
                assert!(shared.serve(k, &schedule, &stop), "{first}, tick {k}");
                assert!(!shared.serve(k, &schedule, &stop), "{second}, tick {k}");
            }
        });
        assert_eq!(allocations.count_total, 0);
        assert_eq!(shared.next.load(Ordering::Acquire), ENDED);
        assert!(!shared.serve(300, &schedule, &stop));
        // While one thread holds the run, the other's claim returns at once.
        let (busy, schedule, _) = new_run(10);
        let held = busy.run.lock().expect("not poisoned");
        assert!(!busy.serve(0, &schedule, &stop));
        drop(held);
        assert!(busy.serve(0, &schedule, &stop));
        // Every record once, in order of deadline.
        let mut t = Vec::new();
        while let Ok(r) = records.pop() {
            t.push((r.tick, r.t));
        }
        assert_eq!(t.len(), 300);
        assert!(
            t.iter()
                .enumerate()
                .all(|(i, &(tick, at))| tick == i as u64 && (at - i as f64 * 1e-3).abs() < 1e-12)
        );
    }

    /// A stop asked between deadlines ends the run at the next claim, whoever makes it.
    #[test]
    fn a_stop_ends_the_run_at_the_next_claim() {
        let (shared, schedule, _) = new_run(100);
        let stop = AtomicBool::new(false);
        assert!(shared.serve(0, &schedule, &stop));
        stop.store(true, Ordering::Relaxed);
        assert!(!shared.serve(1, &schedule, &stop));
        assert_eq!(shared.next.load(Ordering::Acquire), ENDED);
        let run = shared.run.into_inner().expect("not poisoned");
        assert_eq!((run.k, run.stop), (1, Some(StopReason::Requested)));
    }
}
