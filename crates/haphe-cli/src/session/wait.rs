//! Waiting for a real-time run: Ctrl-C and SIGTERM, and the records handed over until
//! the run ends.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use anyhow::Context;
use haphe::servo::{Device, RealtimeRun, ServoLoop, TickRecord};

/// Set by Ctrl-C.
static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// Set once the servo thread is about to start: from then on Ctrl-C asks it to stop
/// (with zero force); before, Ctrl-C ends the process at once (no force is being
/// rendered while the scene is built or a device is opened).
static SERVO_RUNNING: AtomicBool = AtomicBool::new(false);

/// Called just before the servo thread starts.
pub fn servo_starting() {
    SERVO_RUNNING.store(true, Ordering::SeqCst);
}

/// Whether Ctrl-C was pressed.
pub fn interrupted() -> bool {
    INTERRUPTED.load(Ordering::Relaxed)
}

/// Installs the handler of Ctrl-C (SIGINT) and SIGTERM: before [`servo_starting`] they
/// end the process at once (exit code 130); after, they set [`interrupted`], and the
/// caller stops the servo, which writes zero force before the process exits.
pub fn catch_interrupts() -> anyhow::Result<()> {
    ctrlc::set_handler(|| {
        if SERVO_RUNNING.load(Ordering::SeqCst) {
            INTERRUPTED.store(true, Ordering::Relaxed);
        } else {
            std::process::exit(130);
        }
    })
    .context("cannot install the Ctrl-C handler")
}

/// Hands records to `f` until the run ends by itself or Ctrl-C stops it (then zero
/// force is written by the servo as it stops).
pub fn wait<D: Device + 'static>(
    mut running: ServoLoop<D>,
    mut f: impl FnMut(&TickRecord),
) -> anyhow::Result<RealtimeRun<D>> {
    while !running.is_finished() && !interrupted() {
        if running.drain(&mut f) == 0 {
            std::thread::sleep(Duration::from_millis(2));
        }
    }
    Ok(running.stop(f)?)
}
