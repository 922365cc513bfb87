//! Setting up the servo thread: FIFO priority and core pinning, as the system permits,
//! and what was obtained.

use super::options::RealtimeOptions;
use crate::servo::tick::ServoError;

/// Priority asked for the servo thread on Linux (SCHED_FIFO, 1–99): high, below the
/// kernel's own per-CPU threads (99).
#[cfg(all(unix, feature = "realtime"))]
pub const FIFO_PRIORITY: u8 = 80;

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

/// Asks for FIFO priority and pins the thread, as permitted.
#[cfg(feature = "realtime")]
pub(super) fn set_up_thread(options: &RealtimeOptions) -> RealtimeSetup {
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
pub(super) fn set_up_thread(options: &RealtimeOptions) -> RealtimeSetup {
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
