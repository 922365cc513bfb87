//! What a haptics user wants to know about a run, gathered record by record, and the
//! samples kept for the plot.

use std::io::Write;

use haphe::DVec3;
use haphe::servo::{
    Histogram, Interference, Phase, RealtimeSetup, StandbyReport, StopReason, TickRecord, TickStats,
};

/// The fastest a hand moves a haptic device's handle, metres per second of the device
/// (world speed over the mapping's scale). The fastest human arm movements short of
/// throwing peak at about 3 to 5 m/s at the hand, and desktop devices are built for
/// much less (their handles' rated speeds are around 1 m/s); a faster run is not a
/// hand's, most often a model in the wrong unit that the simulated hand's path scaled up.
pub const MAX_HAND_SPEED_M_S: f64 = 5.0;

/// The deepest a hand can press into an object, metres of the device (world depth over
/// the mapping's scale): the largest desktop workspaces are about 0.4 m across, and a
/// hand pressing against even the lowest force limit is stopped within a fraction of it;
/// 0.1 m is beyond any device. Deeper is, again, most often a model in the wrong unit.
pub const MAX_PENETRATION_M: f64 = 0.1;

/// Most samples kept for the plot; longer runs are decimated evenly.
pub const PLOT_SAMPLES: usize = 20_000;

/// One plotted sample.
#[derive(Debug, Clone, Copy)]
pub struct PlotPoint {
    pub t: f64,
    pub hip: DVec3,
    pub proxy: DVec3,
    pub force: DVec3,
    pub penetration: f64,
    pub contact: bool,
}

/// Figures accumulated over the records of a run.
#[derive(Debug, Default)]
pub struct Summary {
    pub ticks: u64,
    pub contact_ticks: u64,
    pub touches: u64,
    pub sticking_ticks: u64,
    pub clamped_ticks: u64,
    pub held_ticks: u64,
    /// Ticks that placed a proxy (ramping or running): the device was out of every
    /// object.
    pub free_ticks: u64,
    /// Ticks with the clutch held, and how many times it was pressed.
    pub clutch_ticks: u64,
    pub clutch_presses: u64,
    pub max_penetration: f64,
    pub penetration_sum: f64,
    pub max_force: f64,
    pub max_speed: f64,
    pub last_t: f64,
    /// Contact ticks per object id.
    pub per_object: Vec<(u32, u64)>,
    was_in_contact: bool,
    was_clutched: bool,
    every: u64,
    pub plot: Vec<PlotPoint>,
}

impl Summary {
    /// A summary that keeps about [`PLOT_SAMPLES`] plot samples of `expected_ticks`.
    pub fn new(expected_ticks: u64) -> Summary {
        Summary {
            every: (expected_ticks / PLOT_SAMPLES as u64).max(1),
            plot: Vec::with_capacity(PLOT_SAMPLES + 1),
            ..Summary::default()
        }
    }

    /// Adds one record.
    pub fn add(&mut self, r: &TickRecord) {
        self.ticks += 1;
        self.last_t = r.t;
        let contact = r.in_contact();
        if let Some(id) = r.object {
            self.contact_ticks += 1;
            self.penetration_sum += r.penetration;
            match self.per_object.iter_mut().find(|(o, _)| *o == id.0) {
                Some((_, n)) => *n += 1,
                None => self.per_object.push((id.0, 1)),
            }
        }
        self.touches += u64::from(contact && !self.was_in_contact);
        self.was_in_contact = contact;
        self.sticking_ticks += u64::from(r.status.sticking);
        self.clamped_ticks += u64::from(r.status.force_clamped);
        self.held_ticks += u64::from(r.phase == Phase::Holding);
        self.free_ticks += u64::from(matches!(r.phase, Phase::Ramping | Phase::Running));
        self.clutch_ticks += u64::from(r.clutch);
        self.clutch_presses += u64::from(r.clutch && !self.was_clutched);
        self.was_clutched = r.clutch;
        self.max_penetration = self.max_penetration.max(r.penetration);
        self.max_force = self.max_force.max(r.force.length());
        self.max_speed = self.max_speed.max(r.velocity.length());
        if r.tick.is_multiple_of(self.every) {
            // A run longer than expected (a realtime run's extra ticks) keeps the plot
            // bounded: every other sample is dropped and the spacing doubled.
            if self.plot.len() >= 2 * PLOT_SAMPLES {
                let mut keep = false;
                self.plot.retain(|_| {
                    keep = !keep;
                    keep
                });
                self.every *= 2;
                if !r.tick.is_multiple_of(self.every) {
                    return;
                }
            }
            self.plot.push(PlotPoint {
                t: r.t,
                hip: r.hip,
                proxy: r.proxy,
                force: r.force,
                penetration: r.penetration,
                contact,
            });
        }
    }
}

/// Formats nanoseconds as µs with a sensible precision.
pub fn us(ns: u64) -> String {
    let v = ns as f64 / 1e3;
    if v < 10.0 {
        format!("{v:.2} µs")
    } else if v < 1000.0 {
        format!("{v:.1} µs")
    } else {
        format!("{:.2} ms", v / 1e3)
    }
}

/// The median, p99, p99.9 and largest of `h` (nanoseconds), as µs.
fn quantiles(h: &Histogram) -> String {
    format!(
        "p50 {}  p99 {}  p99.9 {}  max {}",
        us(h.quantile(0.5)),
        us(h.quantile(0.99)),
        us(h.quantile(0.999)),
        us(h.max())
    )
}

/// How a run was made, for the report (of one device: its scale, maximum force and
/// clutch; the rest is the run's).
#[derive(Clone)]
pub struct RunInfo<'a> {
    pub rate_hz: f64,
    /// World metres per device metre (1 for the simulated devices).
    pub scale: f64,
    pub realtime: bool,
    pub max_force: f64,
    pub stop: StopReason,
    pub setup: Option<&'a RealtimeSetup>,
    pub interference: Option<Interference>,
    /// What the standby thread did, when there was one.
    pub standby: Option<StandbyReport>,
    pub dropped_records: u64,
    /// The clutch's button, and how far its use moved the device's origin in the world,
    /// metres.
    pub clutch: Option<(u32, DVec3)>,
}

/// What else ran on the servo's CPU, when the system says: the host's steal time of the
/// pinned core (a virtual machine's CPU taken away) and the thread's preemptions.
fn print_interference(
    out: &mut impl Write,
    i: &Interference,
    core: Option<usize>,
) -> std::io::Result<()> {
    let mut parts = Vec::new();
    if let (Some(steal), Some(core)) = (i.steal_seconds, core) {
        parts.push(format!(
            "host steal {:.2} s on core {core} (the virtual CPU taken away)",
            steal
        ));
    }
    if let Some(n) = i.preemptions {
        parts.push(format!("thread preempted {n} time(s)"));
    }
    if let Some(n) = i.sleeps {
        parts.push(format!("slept {n} time(s)"));
    }
    if !parts.is_empty() {
        writeln!(out, "  interference      {}", parts.join(", "))?;
    }
    Ok(())
}

/// The flag of a figure no real hand on a device reaches: `value` (SI, at the device)
/// above `limit` (in the unit shown, `per_si` of it per SI unit).
fn impossible(value: f64, limit: f64, per_si: f64, unit: &str) -> String {
    if value * per_si > limit {
        format!(
            " (impossible for a hand on a device, over {limit} {unit}: is the model in the wrong unit?)"
        )
    } else {
        String::new()
    }
}

/// How the run stopped, after its ticks: nothing when it finished.
fn stop_note(stop: StopReason) -> String {
    match stop {
        StopReason::Finished => String::new(),
        StopReason::Requested => " (stopped)".into(),
        StopReason::Overruns => {
            " (stopped: the overrun budget was exceeded, zero force written)".into()
        }
        StopReason::Fault(haphe::servo::DeviceFault::Ended) => {
            " (ended by the device: its trace or path ended, or its peer sent stop)".into()
        }
        StopReason::Fault(f) => format!(" (stopped by a device fault: {f}; zero force written)"),
    }
}

/// The contact time of each object touched, after the contact line: nothing when none was.
fn per_object(s: &Summary, period: f64) -> String {
    let objects: Vec<String> = s
        .per_object
        .iter()
        .map(|(id, n)| format!("object {id}: {:.3} s", *n as f64 * period))
        .collect();
    if objects.is_empty() {
        String::new()
    } else {
        format!("; {}", objects.join(", "))
    }
}

/// Prints the summary of a run: its ticks, then what each device did (a block per
/// device, under its name, when there are several; `devices` holds each one's name,
/// summary and figures), then the servo's timing.
pub fn print_devices(
    out: &mut impl Write,
    devices: &[(String, &Summary, RunInfo<'_>)],
    stats: &TickStats,
) -> std::io::Result<()> {
    let Some((_, first, info)) = devices.first() else {
        return Ok(());
    };
    let clock = if info.realtime {
        "wall clock"
    } else {
        "simulated time"
    };
    writeln!(
        out,
        "  ticks             {} at {} Hz = {:.3} s of {clock}{}",
        first.ticks,
        info.rate_hz,
        first.ticks as f64 / info.rate_hz,
        stop_note(info.stop)
    )?;
    for (name, s, info) in devices {
        if devices.len() > 1 {
            writeln!(out, "  {name}:")?;
        }
        print_device(out, s, info)?;
    }
    writeln!(out, "  tick time         {}", quantiles(&stats.compute))?;
    if info.realtime {
        print_realtime(out, stats, info)?;
    } else {
        writeln!(
            out,
            "  achieved rate     {:.0} ticks/s as fast as possible ({:.3} s of compute; {:.0}x the asked rate)",
            stats.achieved_rate(),
            stats.wall_seconds,
            stats.achieved_rate() / info.rate_hz
        )?;
    }
    Ok(())
}

/// Prints what one device did: contact, penetration, force, friction, speed, safe start
/// and clutch.
fn print_device(out: &mut impl Write, s: &Summary, info: &RunInfo<'_>) -> std::io::Result<()> {
    let period = 1.0 / info.rate_hz;
    let pct = |n: u64| {
        if s.ticks == 0 {
            0.0
        } else {
            100.0 * n as f64 / s.ticks as f64
        }
    };
    writeln!(
        out,
        "  contact           {:.3} s ({:.1} % of ticks), {} touch(es){}",
        s.contact_ticks as f64 * period,
        pct(s.contact_ticks),
        s.touches,
        per_object(s, period)
    )?;
    let mean = if s.contact_ticks > 0 {
        s.penetration_sum / s.contact_ticks as f64
    } else {
        0.0
    };
    writeln!(
        out,
        "  max penetration   {:.3} mm (mean in contact {:.3} mm){}",
        s.max_penetration * 1e3,
        mean * 1e3,
        impossible(
            s.max_penetration / info.scale,
            MAX_PENETRATION_M * 1e3,
            1e3,
            "mm deep"
        )
    )?;
    writeln!(
        out,
        "  max force         {:.3} N (device maximum {} N; clamped on {} ticks)",
        s.max_force, info.max_force, s.clamped_ticks
    )?;
    writeln!(
        out,
        "  friction          sticking on {} ticks ({:.1} % of contact)",
        s.sticking_ticks,
        if s.contact_ticks > 0 {
            100.0 * s.sticking_ticks as f64 / s.contact_ticks as f64
        } else {
            0.0
        }
    )?;
    writeln!(
        out,
        "  fastest hand      {:.3} m/s{}",
        s.max_speed,
        impossible(s.max_speed / info.scale, MAX_HAND_SPEED_M_S, 1.0, "m/s")
    )?;
    print_start_and_clutch(out, s, info, period)
}

/// The summary's lines on the safe start and the clutch.
fn print_start_and_clutch(
    out: &mut impl Write,
    s: &Summary,
    info: &RunInfo<'_>,
    period: f64,
) -> std::io::Result<()> {
    if s.held_ticks > 0 {
        writeln!(
            out,
            "  safe start        held {} tick(s) at zero force (device inside an object)",
            s.held_ticks
        )?;
    } else {
        writeln!(
            out,
            "  safe start        not needed (the device began outside every object)"
        )?;
    }
    if let Some((button, moved)) = info.clutch {
        writeln!(
            out,
            "  clutch            button {button} held {} time(s), {:.3} s; the device's origin moved by ({:.1}, {:.1}, {:.1}) mm in the world",
            s.clutch_presses,
            s.clutch_ticks as f64 * period,
            // `+ 0.0`: no "-0.0" for an axis it did not move along.
            moved.x * 1e3 + 0.0,
            moved.y * 1e3 + 0.0,
            moved.z * 1e3 + 0.0
        )?;
    }
    Ok(())
}

/// The real-time part of the summary: lateness, overruns, the rate achieved, the threads
/// and what else ran on their cores.
fn print_realtime(
    out: &mut impl Write,
    stats: &TickStats,
    info: &RunInfo<'_>,
) -> std::io::Result<()> {
    writeln!(out, "  lateness          {}", quantiles(&stats.lateness))?;
    writeln!(
        out,
        "  overruns          {} ({:.4} % of ticks; a tick that ended after the next deadline), {} deadline(s) skipped",
        stats.overruns,
        100.0 * stats.overrun_fraction(),
        stats.skipped
    )?;
    writeln!(
        out,
        "  missed deadlines  {} ({:.4} % of {} deadlines: overruns and skipped together)",
        stats.missed(),
        100.0 * stats.missed_fraction(),
        stats.deadlines()
    )?;
    writeln!(
        out,
        "  achieved rate     {:.1} Hz (asked {} Hz)",
        stats.achieved_rate(),
        info.rate_hz
    )?;
    if let Some(setup) = info.setup {
        let mut how = vec![if setup.realtime_priority {
            "FIFO real-time priority".to_string()
        } else {
            "normal priority".to_string()
        }];
        if let Some(core) = setup.pinned_core {
            how.push(format!("pinned to core {core}"));
        }
        how.extend(setup.notes.iter().cloned());
        writeln!(out, "  servo thread      {}", how.join("; "))?;
        if let Some(i) = info.interference {
            print_interference(out, &i, setup.pinned_core)?;
        }
    }
    if let Some(standby) = &info.standby {
        let core = standby
            .pinned_core
            .map_or("not pinned".to_string(), |c| format!("pinned to core {c}"));
        writeln!(
            out,
            "  standby thread    {core}; ran {} tick(s) ({:.4} % of ticks) when the servo thread was late",
            standby.ticks,
            100.0 * standby.ticks as f64 / stats.ticks.max(1) as f64
        )?;
        print_interference(out, &standby.interference, standby.pinned_core)?;
    }
    if info.dropped_records > 0 {
        writeln!(
            out,
            "  records dropped   {} (the writer fell behind)",
            info.dropped_records
        )?;
    }
    Ok(())
}
