//! A deforming object in a session (`--deform KIND --deform-rate HZ`), built as a user's
//! application would be: a deformer thread makes each new version of the object's shape
//! off the servo thread ([`Shape::deformed`] of its own latest version) and hands it over
//! wait-free through the scene's editor ([`Edit::SetShape`]); the versions the servo no
//! longer uses come back through the editor and are dropped on the deformer thread, never
//! on the servo's.
//!
//! Two clocks. On the wall clock (`haphe run`, `haphe view`, `simulate --realtime`) the
//! deformer refreshes at its rate on its own, as a physics or animation thread would. On
//! the simulated clock (`haphe simulate`) it follows the servo's virtual time instead, in
//! lockstep: see [`run_lockstep`] for why.

use std::io::Write;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use anyhow::{anyhow, bail};
use haphe::DVec3;
use haphe::scene::{Edit, ObjectId, Returned, Scene, SceneEditor, Shape};
use haphe::servo::{Device, Histogram, Servo, StopReason, TickRecord};
use haphe::verify::Deformation;

use super::publish::Publish;
use crate::args::deform::Deform;

/// How long the wall-clock deformer sleeps at most before it looks at its stop flag.
const STOP_POLL: Duration = Duration::from_millis(20);

/// Which clock the deformer follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Clock {
    /// The servo's virtual clock: a refresh when [`Deformer::refresh_at`] asks for one.
    Simulated,
    /// The wall clock: a refresh every period from when the thread starts, until stopped.
    Wall,
}

impl Clock {
    /// The wall clock for a real-time run, else the simulated clock.
    pub fn of(realtime: bool) -> Clock {
        if realtime {
            Clock::Wall
        } else {
            Clock::Simulated
        }
    }
}

/// What the deformer did, for the summary.
#[derive(Debug, Clone)]
pub struct Refreshes {
    pub kind: Deformation,
    pub rate_hz: f64,
    /// Refreshes made (each a new shape).
    pub made: u64,
    /// Of those, sent to the servo; the others found the edit ring full and were dropped.
    pub sent: u64,
    pub busy: u64,
    /// Wall clock: refreshes skipped because the one before ended after their time.
    pub skipped: u64,
    /// Versions the servo handed back (no longer used), dropped on the deformer thread.
    pub handed_back: u64,
    /// Shapes the scene refused, and why.
    pub refused: Vec<String>,
    /// Time per refresh (the vertices at their time, then [`Shape::deformed`]), ns.
    pub times: Histogram,
    /// The version of the last shape sent (the shape's version before any was sent).
    pub last_sent: u64,
    /// Why the deformer stopped early (a deformation the map cannot hold).
    pub error: Option<String>,
}

/// The deformer thread's state: the scene's editor, the object's rest vertices and the
/// latest version it made.
struct Refresher {
    editor: SceneEditor,
    id: ObjectId,
    rest: Vec<DVec3>,
    latest: Arc<Shape>,
    publish: Option<Publish>,
    report: Refreshes,
}

impl Refresher {
    /// Makes the shape at time `t` (seconds) from the latest version and sends it; the
    /// version the object is given (the latest one's again when the ring was full).
    fn refresh(&mut self, t: f64) -> Result<u64, haphe::scene::DeformError> {
        self.collect();
        let began = Instant::now();
        let vertices = self.report.kind.vertices_at(&self.rest, t);
        let shape = Arc::new(self.latest.deformed(&vertices)?);
        let ns = began.elapsed().as_nanos();
        self.report
            .times
            .record(u64::try_from(ns).unwrap_or(u64::MAX));
        self.report.made += 1;
        match self
            .editor
            .send(Edit::SetShape(self.id, Arc::clone(&shape)))
        {
            Ok(()) => {
                self.report.sent += 1;
                self.report.last_sent = shape.version();
                if let Some(publish) = &mut self.publish {
                    publish(&shape);
                }
                self.latest = shape;
            }
            // The ring is full (the servo is not ticking): this version is dropped here,
            // and the next one is made from the latest version sent.
            Err(_) => self.report.busy += 1,
        }
        Ok(self.latest.version())
    }

    /// Takes back what the servo handed back, dropping it on this thread.
    fn collect(&mut self) {
        for back in self.editor.collect() {
            match back {
                Returned::Replaced(..) => self.report.handed_back += 1,
                Returned::RefusedShape(_, shape, why) => self
                    .report
                    .refused
                    .push(format!("version {}: {why}", shape.version())),
                _ => {}
            }
        }
    }
}

/// A deformation about to start: the object (the scene's first), its rest shape, the
/// scene's editor and the flags.
pub struct Plan {
    id: ObjectId,
    name: String,
    shape: Arc<Shape>,
    editor: SceneEditor,
    deform: Deform,
}

impl Plan {
    /// The deformation of the first object of `scene` (named `name`) by `deform`, through
    /// `editor`, `scene`'s editor; its vertices now are the rest shape.
    ///
    /// # Errors
    /// An empty scene.
    pub fn new(
        scene: &Scene,
        editor: SceneEditor,
        name: &str,
        deform: Deform,
    ) -> anyhow::Result<Plan> {
        let first = scene
            .objects()
            .first()
            .ok_or_else(|| anyhow!("--deform: the scene has no object to deform"))?;
        Ok(Plan {
            id: first.id,
            name: name.to_string(),
            shape: Arc::clone(&first.shape),
            editor,
            deform,
        })
    }

    /// The object it deforms (the view's live vertices name it).
    #[cfg(feature = "view")]
    pub fn id(&self) -> ObjectId {
        self.id
    }

    /// The line under the scene's: what deforms, how often, on which clock.
    pub fn describe(&self, clock: Clock) -> String {
        let follows = match clock {
            Clock::Simulated => "following the simulated clock",
            Clock::Wall => "on the wall clock",
        };
        format!(
            "deformation: {} of {} (id {}, {} triangles) at {} Hz, each version made by a deformer thread {follows}",
            self.deform.kind.name(),
            self.name,
            self.id.0,
            self.shape.surface().triangle_count(),
            self.deform.rate_hz
        )
    }

    /// Starts the deformer thread on `clock` (on the wall clock it refreshes from now on),
    /// calling `publish` with each version it sends.
    ///
    /// # Errors
    /// A thread that cannot start.
    pub fn spawn(self, clock: Clock, publish: Option<Publish>) -> anyhow::Result<Deformer> {
        let Plan {
            id,
            shape,
            editor,
            deform,
            ..
        } = self;
        let refresher = Refresher {
            editor,
            id,
            rest: shape.surface().vertices().to_vec(),
            report: Refreshes {
                kind: deform.kind,
                rate_hz: deform.rate_hz,
                made: 0,
                sent: 0,
                busy: 0,
                skipped: 0,
                handed_back: 0,
                refused: Vec::new(),
                times: Histogram::new(),
                last_sent: shape.version(),
                error: None,
            },
            latest: shape,
            publish,
        };
        let (requests, asked) = mpsc::channel();
        let (answer, replies) = mpsc::channel();
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        let thread = std::thread::Builder::new()
            .name("haphe-deformer".into())
            .spawn(move || match clock {
                Clock::Simulated => lockstep(refresher, &asked, &answer),
                Clock::Wall => on_the_wall_clock(refresher, &flag),
            })
            .map_err(|e| anyhow!("cannot start the deformer thread: {e}"))?;
        Ok(Deformer {
            id,
            deform,
            requests: Some(requests),
            replies,
            stop,
            thread: Some(thread),
        })
    }
}

/// The deformer thread and its controls; dropping it stops the thread.
pub struct Deformer {
    /// The object it deforms.
    pub id: ObjectId,
    deform: Deform,
    /// Simulated clock: the time of each refresh asked for, and the version sent back.
    requests: Option<mpsc::Sender<f64>>,
    replies: mpsc::Receiver<Result<u64, String>>,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<Refreshes>>,
}

impl Drop for Deformer {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
    }
}

impl Deformer {
    /// Simulated clock: has the deformer make and send the shape at time `t` (seconds);
    /// returns once it is sent, with its version.
    ///
    /// # Errors
    /// The deformation refused (a surface the map cannot hold), or the thread gone.
    pub fn refresh_at(&mut self, t: f64) -> anyhow::Result<u64> {
        let gone = || anyhow!("the deformer thread stopped");
        self.requests
            .as_ref()
            .ok_or_else(gone)?
            .send(t)
            .map_err(|_| gone())?;
        self.replies
            .recv()
            .map_err(|_| gone())?
            .map_err(|e| anyhow!("--deform {}: {e}", self.deform.kind.name()))
    }

    /// Stops the thread and returns what it did.
    ///
    /// # Errors
    /// The thread panicked.
    pub fn finish(mut self) -> anyhow::Result<Refreshes> {
        self.stop.store(true, Ordering::Relaxed);
        self.requests = None;
        self.thread
            .take()
            .ok_or_else(|| anyhow!("the deformer thread stopped"))?
            .join()
            .map_err(|_| anyhow!("the deformer thread panicked"))
    }
}

/// The simulated clock's thread: a refresh for each time asked for, answered with the
/// version sent, until the asking side hangs up.
fn lockstep(
    mut r: Refresher,
    asked: &mpsc::Receiver<f64>,
    answer: &mpsc::Sender<Result<u64, String>>,
) -> Refreshes {
    while let Ok(t) = asked.recv() {
        let version = r.refresh(t).map_err(|e| e.to_string());
        let failed = version.is_err();
        if answer.send(version).is_err() || failed {
            break;
        }
    }
    r.collect();
    r.report
}

/// The wall clock's thread: refresh `k` at `k / rate` seconds after the start (the
/// deformation at that time), until stopped; a refresh that ends after the next one's
/// time skips the refreshes it overran.
fn on_the_wall_clock(mut r: Refresher, stop: &AtomicBool) -> Refreshes {
    let start = Instant::now();
    let period = 1.0 / r.report.rate_hz;
    let mut k: u64 = 0;
    'refreshes: loop {
        let due = start + Duration::from_secs_f64(k as f64 * period);
        loop {
            if stop.load(Ordering::Relaxed) {
                break 'refreshes;
            }
            let now = Instant::now();
            if now >= due {
                break;
            }
            std::thread::sleep((due - now).min(STOP_POLL));
        }
        if let Err(e) = r.refresh(k as f64 * period) {
            r.report.error = Some(e.to_string());
            break;
        }
        let next = (start.elapsed().as_secs_f64() / period).floor() as u64 + 1;
        r.report.skipped += next.saturating_sub(k + 1);
        k = next.max(k + 1);
    }
    r.collect();
    r.report
}

/// The versions the ticks of a lockstep run used: (version, ticks it was in force), in
/// order.
#[derive(Debug, Default, Clone)]
pub struct Versions(pub Vec<(u64, u64)>);

/// Runs `ticks` ticks of `servo` on the simulated clock while the deformer refreshes the
/// object in lockstep with it: refresh `j`, the deformation at `t_j = j / deform rate`, is
/// made on the deformer thread and sent through the editor before tick
/// `ceil(t_j · servo rate)`, the first tick at or after `t_j`, which applies it; the ticks
/// until the next refresh run against it. This is where a deformer that keeps up with a
/// real clock would put its versions, but here the same input gives the same ticks
/// against the same versions, run after run, byte for byte: a deformer left to run free
/// beside a servo ticking as fast as the machine goes would land its versions at ticks
/// the operating system's scheduling decides. After each stretch the servo's scene is
/// checked to hold the version sent; hands every record to `on_tick`.
///
/// # Errors
/// A deformation refused, the deformer gone, or a scene that does not hold the version
/// sent.
pub fn run_lockstep<D: Device>(
    servo: &mut Servo<D>,
    deformer: &mut Deformer,
    ticks: u64,
    mut on_tick: impl FnMut(&TickRecord),
) -> anyhow::Result<(StopReason, Versions)> {
    let ratio = servo.options().rate_hz() / deformer.deform.rate_hz;
    // The first tick at or after refresh j's time (the tolerance keeps an exact multiple
    // from rounding up).
    let first_tick = |j: u64| ((j as f64 * ratio) - 1e-9).ceil().max(0.0) as u64;
    let mut versions = Versions::default();
    let (mut j, mut k) = (0u64, 0u64);
    let mut stop = StopReason::Finished;
    while k < ticks {
        let version = deformer.refresh_at(j as f64 / deformer.deform.rate_hz)?;
        let until = first_tick(j + 1).clamp(k + 1, ticks);
        let before = servo.stats().ticks;
        stop = servo.run_simulated(until - k, &mut on_tick);
        let ran = servo.stats().ticks - before;
        if stop == StopReason::Finished {
            let held = servo
                .scene()
                .index_of(deformer.id)
                .map(|i| servo.scene().objects()[i].shape.version());
            if held != Some(version) {
                bail!(
                    "the servo's scene holds version {held:?} of the deforming object, not version {version}, which the deformer sent"
                );
            }
        }
        versions.0.push((version, ran));
        if stop != StopReason::Finished {
            break;
        }
        (j, k) = (j + 1, until);
    }
    Ok((stop, versions))
}

/// Formats nanoseconds as µs or ms.
fn time(ns: u64) -> String {
    super::summary::us(ns)
}

/// Prints what the deformation did: its refreshes and their times, and the versions the
/// ticks used (`versions`, of a lockstep run), or, on the wall clock, the version in force
/// when the run ended (`last`).
pub fn print(
    out: &mut impl Write,
    r: &Refreshes,
    versions: Option<&Versions>,
    last: Option<u64>,
) -> anyhow::Result<()> {
    writeln!(out, "\ndeformation:")?;
    writeln!(
        out,
        "  kind              {} at {} Hz",
        r.kind.name(),
        r.rate_hz
    )?;
    let mut refreshes = format!(
        "{} made, {} sent to the servo through the scene's editor",
        r.made, r.sent
    );
    if r.busy > 0 {
        refreshes += &format!(", {} dropped (the edit ring was full)", r.busy);
    }
    if r.skipped > 0 {
        refreshes += &format!(
            ", {} skipped (the one before overran its period)",
            r.skipped
        );
    }
    writeln!(out, "  refreshes         {refreshes}")?;
    let t = &r.times;
    writeln!(
        out,
        "  refresh time      p50 {}  p99 {}  max {} (the vertices, then Shape::deformed, on the deformer thread)",
        time(t.quantile(0.5)),
        time(t.quantile(0.99)),
        time(t.max())
    )?;
    match (versions, last) {
        (Some(v), _) => writeln!(out, "  versions          {}", describe_versions(v))?,
        (None, Some(last)) => writeln!(
            out,
            "  versions          the ticks used versions up to {last}, the one in force when the run ended (the last sent: {})",
            r.last_sent
        )?,
        (None, None) => {}
    }
    writeln!(
        out,
        "  handed back       {} version(s) no longer used, dropped on the deformer thread",
        r.handed_back
    )?;
    if !r.refused.is_empty() {
        writeln!(out, "  refused           {}", r.refused.join("; "))?;
    }
    if let Some(e) = &r.error {
        bail!("--deform {}: the deformer stopped: {e}", r.kind.name());
    }
    Ok(())
}

/// The versions of a lockstep run in a few words: their range and how many ticks each
/// was in force.
fn describe_versions(v: &Versions) -> String {
    let (Some(first), Some(last)) = (v.0.first(), v.0.last()) else {
        return "no tick ran".into();
    };
    let lo = v.0.iter().map(|&(_, n)| n).min().unwrap_or(0);
    let hi = v.0.iter().map(|&(_, n)| n).max().unwrap_or(0);
    let each = if lo == hi {
        format!("{lo}")
    } else {
        format!("{lo} to {hi}")
    };
    format!(
        "the ticks used versions {} to {}, each in force for {each} ticks (checked on the servo's scene)",
        first.0, last.0
    )
}
