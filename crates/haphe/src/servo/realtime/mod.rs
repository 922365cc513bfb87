//! [`ServoLoop`]: the servo on a dedicated thread, ticking on absolute deadlines of the
//! wall clock, with real-time priority and core pinning where the system permits.

mod external;
mod interference;
mod options;
mod run;
mod servo_loop;
mod standby;
mod thread;

pub use external::DeviceClock;
pub use interference::Interference;
pub use options::RealtimeOptions;
pub use servo_loop::{RealtimeRun, ServoLoop};
pub use standby::StandbyReport;
pub use thread::{RealtimeSetup, check_core};
