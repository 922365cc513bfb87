//! [`Interference`]: what ran instead of the servo thread during a real-time run, as the
//! operating system counts it. On a virtual machine, a deadline is missed mostly when the
//! host takes the virtual CPU away (steal time); on any machine, when another thread is
//! scheduled on the servo's core (a preemption). Knowing which tells a user whether to
//! change the schedule, the machine or nothing.

/// Clock ticks per second of the counters in `/proc/stat` (`USER_HZ`: 100 on every Linux
/// architecture in use; the kernel converts its own tick rate to it).
const USER_HZ: f64 = 100.0;

/// What else ran on the servo thread's CPU during a run, read before the first deadline
/// and after the last (Linux; every field is `None` where the system does not say).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Interference {
    /// Time the hypervisor ran something else while the servo thread's virtual CPU was
    /// ready (the steal time of the core the thread is pinned to, from `/proc/stat`),
    /// seconds, in steps of 10 ms. `None` when the thread is not pinned or off Linux;
    /// zero on a machine that is not virtual.
    pub steal_seconds: Option<f64>,
    /// Times the servo thread was preempted: taken off its CPU while it could run
    /// (`nonvoluntary_ctxt_switches` of the thread).
    pub preemptions: Option<u64>,
    /// Times the servo thread gave up its CPU itself, by sleeping before a deadline
    /// (`voluntary_ctxt_switches`).
    pub sleeps: Option<u64>,
}

/// The counters at one moment, on the servo thread.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Counters {
    steal_ticks: Option<u64>,
    preemptions: Option<u64>,
    sleeps: Option<u64>,
}

impl Counters {
    /// Reads the counters of the calling thread and of `core` (may allocate: call it
    /// outside the loop).
    pub(super) fn read(core: Option<usize>) -> Counters {
        let status = std::fs::read_to_string("/proc/thread-self/status").unwrap_or_default();
        let steal_ticks = core.and_then(|c| {
            std::fs::read_to_string("/proc/stat")
                .ok()
                .and_then(|stat| steal_of_core(&stat, c))
        });
        Counters {
            steal_ticks,
            preemptions: status_field(&status, "nonvoluntary_ctxt_switches:"),
            sleeps: status_field(&status, "voluntary_ctxt_switches:"),
        }
    }

    /// What happened between `self` (before) and `after`.
    pub(super) fn since(self, after: Counters) -> Interference {
        let delta = |a: Option<u64>, b: Option<u64>| Some(b?.saturating_sub(a?));
        Interference {
            steal_seconds: delta(self.steal_ticks, after.steal_ticks).map(|t| t as f64 / USER_HZ),
            preemptions: delta(self.preemptions, after.preemptions),
            sleeps: delta(self.sleeps, after.sleeps),
        }
    }
}

/// The steal counter (clock ticks) of `cpu{core}` in the text of `/proc/stat`: the eighth
/// number after the name (`user nice system idle iowait irq softirq steal ...`).
fn steal_of_core(stat: &str, core: usize) -> Option<u64> {
    let name = format!("cpu{core}");
    let line = stat
        .lines()
        .find(|l| l.split_whitespace().next() == Some(name.as_str()))?;
    line.split_whitespace().nth(8)?.parse().ok()
}

/// The number after `key` on its line of a `/proc/.../status` text (`key` at the start of
/// the line, so `voluntary_ctxt_switches:` does not match `nonvoluntary_...`).
fn status_field(status: &str, key: &str) -> Option<u64> {
    status
        .lines()
        .find_map(|l| l.strip_prefix(key))
        .and_then(|rest| rest.trim().parse().ok())
}

#[cfg(test)]
mod tests {
    use super::*;

    const STAT: &str = "cpu  6467 1537 547 1683 127 0 53 876 0 0\n\
                        cpu0 3080869 954419 232492 848429 3533 0 272 43608 0 0\n\
                        cpu1 3375123 583099 315249 829138 9170 0 5059 43795 0 0\n\
                        intr 1 2 3\n";

    const STATUS: &str = "Name:\thaphe-servo\nState:\tR (running)\n\
                          voluntary_ctxt_switches:\t3\n\
                          nonvoluntary_ctxt_switches:\t65\n";

    #[test]
    fn steal_is_the_eighth_counter_of_the_core() {
        assert_eq!(steal_of_core(STAT, 0), Some(43608));
        assert_eq!(steal_of_core(STAT, 1), Some(43795));
        assert_eq!(steal_of_core(STAT, 2), None);
        assert_eq!(steal_of_core("cpu1 1 2\n", 1), None);
    }

    #[test]
    fn voluntary_and_nonvoluntary_switches_are_told_apart() {
        assert_eq!(status_field(STATUS, "voluntary_ctxt_switches:"), Some(3));
        assert_eq!(
            status_field(STATUS, "nonvoluntary_ctxt_switches:"),
            Some(65)
        );
        assert_eq!(status_field("", "voluntary_ctxt_switches:"), None);
    }

    #[test]
    fn differences_of_the_counters() {
        let before = Counters {
            steal_ticks: Some(43795),
            preemptions: Some(8),
            sleeps: None,
        };
        let after = Counters {
            steal_ticks: Some(43827),
            preemptions: Some(65),
            sleeps: Some(4),
        };
        let i = before.since(after);
        assert!((i.steal_seconds.unwrap() - 0.32).abs() < 1e-12);
        assert_eq!(i.preemptions, Some(57));
        assert_eq!(i.sleeps, None);
    }
}
