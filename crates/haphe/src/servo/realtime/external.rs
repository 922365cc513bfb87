//! A servo clocked by its device: some vendor SDKs own the servo thread and call the
//! application back once per period (OpenHaptics' scheduler at 1 kHz). A [`DeviceClock`]
//! runs [`ServoLoop::spawn_clocked`]'s tick on that thread, one tick per callback, with
//! the same tick, statistics, record ring, overrun budget and stop rules as haphe's own
//! fixed-rate thread.

use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use rtrb::RingBuffer;

use super::interference::Counters;
use super::options::RealtimeOptions;
use super::run::{Run, Schedule, nanos, period_and_ticks};
use super::servo_loop::{RealtimeRun, ServoLoop};
use super::thread::RealtimeSetup;
use crate::servo::device::{Device, DeviceFault};
use crate::servo::tick::{Servo, ServoError, StopReason};
use crate::servo::trace::TickRecord;

/// A device's own servo clock: it calls a tick once per period from the thread the
/// vendor's SDK runs, until the tick says to stop.
///
/// The servo's rate ([`ServoOptions::rate_hz`](crate::servo::ServoOptions::rate_hz))
/// should be the rate of the callbacks: tick `k` is run for the time `k / rate`, and
/// lateness is measured against one period after the previous callback.
pub trait DeviceClock: Send {
    /// Calls `tick` once per period from the device's servo thread until it returns
    /// `false`, then stops the callbacks and returns. Blocks the calling thread meanwhile.
    ///
    /// # Errors
    /// A [`DeviceFault`] when the clock could not be started or stopped calling back
    /// (the device is gone); the run then ends with zero force written.
    fn run(&mut self, tick: &mut (dyn FnMut() -> bool + Send)) -> Result<(), DeviceFault>;
}

impl<D: Device + 'static> ServoLoop<D> {
    /// Starts `servo` clocked by its device's own servo thread (`clock`) for `seconds`
    /// (`None`: until [`stop`](Self::stop)): one tick per callback. The options' priority,
    /// pinning, spin and standby do not apply (the vendor's thread is the vendor's); the
    /// record ring and the overrun budget do.
    ///
    /// # Errors
    /// [`ServoError::Spawn`] when the thread that waits on the clock cannot be started.
    pub fn spawn_clocked(
        servo: Servo<D>,
        clock: Box<dyn DeviceClock>,
        seconds: Option<f64>,
        options: RealtimeOptions,
    ) -> Result<ServoLoop<D>, ServoError> {
        let (producer, consumer) = RingBuffer::new(
            options
                .record_capacity
                .max(1)
                .saturating_mul(servo.devices()),
        );
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        let handle = std::thread::Builder::new()
            .name("haphe-clocked".into())
            .spawn(move || run_clocked(servo, clock, seconds, options, &flag, producer))
            .map_err(ServoError::Spawn)?;
        Ok(ServoLoop {
            stop,
            records: consumer,
            handle,
        })
    }
}

/// The thread that hands the tick to the device's clock and waits for it.
fn run_clocked<D: Device>(
    servo: Servo<D>,
    mut clock: Box<dyn DeviceClock>,
    seconds: Option<f64>,
    options: RealtimeOptions,
    stop_flag: &AtomicBool,
    producer: rtrb::Producer<TickRecord>,
) -> RealtimeRun<D> {
    let (period_ns, max_ticks) = period_and_ticks(servo.options().rate_hz(), seconds);
    let period = Duration::from_nanos(period_ns);
    let mut run = Run::new(servo, producer, options.overrun_budget);
    let counters = Counters::read(None);
    let schedule = Schedule {
        start: Instant::now(),
        period_ns,
        max_ticks,
    };
    let mut expected: Option<Instant> = None;
    // Nothing in the tick below allocates.
    let mut tick = || {
        if run.ended(&schedule, stop_flag) {
            // The last callback: the force it leaves behind is zero.
            run.servo.zero_force();
            return false;
        }
        let now = Instant::now();
        let mut deadline = expected.unwrap_or(now);
        // A callback more than a period late: the vendor's thread skipped deadlines.
        let late = nanos(now.saturating_duration_since(deadline));
        if late >= period_ns {
            run.servo.stats_mut().skipped += late / period_ns;
            deadline += Duration::from_nanos(late / period_ns * period_ns);
        }
        let offset = Duration::from_nanos(run.k.saturating_mul(period_ns));
        run.timed_tick(deadline, offset, period_ns);
        expected = Some(deadline + period);
        run.check_budget();
        if run.ended(&schedule, stop_flag) {
            run.servo.zero_force();
            return false;
        }
        true
    };
    let outcome = clock.run(&mut tick);
    if let Err(f) = outcome
        && run.stop.is_none()
    {
        run.stop = Some(StopReason::Fault(f));
    }
    if run.stop.is_none() {
        // The clock returned without being told to: its device stopped calling back.
        run.stop = Some(StopReason::Fault(DeviceFault::Disconnected));
    }
    run.servo.stats_mut().wall_seconds += schedule.start.elapsed().as_secs_f64();
    run.servo.zero_force();
    RealtimeRun {
        stop: run.stop.unwrap_or(StopReason::Finished),
        dropped_records: run.dropped,
        interference: counters.since(Counters::read(None)),
        setup: RealtimeSetup {
            notes: vec!["clocked by the device's own servo thread".into()],
            ..RealtimeSetup::default()
        },
        standby: None,
        servo: run.servo,
    }
}
