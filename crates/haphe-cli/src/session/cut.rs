//! Cutting in a session (`--cut`): the tool removes the material of the volume object it
//! presses on. The cutter follows the servo's records (on the simulated clock, after each
//! tick on the servo's own thread, so runs repeat; on the wall clock, on the thread that
//! receives the records), and every refresh period makes the cut volume's next shape
//! ([`Cutter::refresh`]) and hands it to the servo wait-free through the scene's editor
//! ([`Edit::SetShape`]); the versions the servo no longer uses come back and are dropped
//! here, never on the servo thread. In the live view the records reach it on a thread of
//! its own ([`Cutting::follow_on_thread`]), and each version sent is published to the
//! page.

use std::io::Write;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use anyhow::{anyhow, bail};
use haphe::scene::{Edit, ObjectId, Pose, Returned, SceneEditor};
use haphe::servo::{Histogram, TickRecord};
use haphe::volume::{CutOptions, Cutter};

use super::publish::Publish;
use super::summary::us as time;
use crate::args::cut::CutSetup;
use crate::input::volume::write_volume;

/// The volume of a run and its cutting: the cutter, the object it cuts, the scene's
/// editor (when it cuts), where to save the volume, and what it did.
pub struct Cutting {
    cutter: Cutter,
    /// The editor, when it cuts (`--cut`).
    editor: Option<SceneEditor>,
    save: Option<PathBuf>,
    id: ObjectId,
    pose: Pose,
    dt: f64,
    /// Ticks between refreshes.
    every: u64,
    /// The tick from which the next refresh is due.
    due: u64,
    refresh_hz: f64,
    times: Histogram,
    sent: u64,
    busy: u64,
    handed_back: u64,
    error: Option<String>,
    /// Called with each version sent (the view's page draws it).
    publish: Option<Publish>,
    /// Records its thread never saw: the queue from the view's pump was full.
    dropped_records: u64,
}

/// The volume of `setup` as the first object of the run, `first` (its id and pose), cut
/// through `editor` when `setup` says so, by a tool of `tool_radius` on a servo of
/// `rate_hz`; says so on `out` (the line under the scene's) when it cuts.
///
/// # Errors
/// The tool's radius or the cut force out of their domains; the output failed.
pub fn start(
    out: &mut impl Write,
    setup: Option<CutSetup>,
    (editor, first): (Option<SceneEditor>, Option<(ObjectId, Pose)>),
    (tool_radius, rate_hz): (f64, f64),
) -> anyhow::Result<Option<Cutting>> {
    let cutting = make(setup, editor, first, (tool_radius, rate_hz))?;
    if let Some(line) = cutting.as_ref().and_then(Cutting::describe) {
        writeln!(out, "{line}")?;
    }
    Ok(cutting)
}

/// [`start`] before the line is written.
fn make(
    setup: Option<CutSetup>,
    editor: Option<SceneEditor>,
    first: Option<(ObjectId, Pose)>,
    (tool_radius, rate_hz): (f64, f64),
) -> anyhow::Result<Option<Cutting>> {
    let (Some(setup), Some((id, pose))) = (setup, first) else {
        return Ok(None);
    };
    let CutSetup {
        mut cutter,
        cut,
        save,
    } = setup;
    let cut_force = cut.map_or(CutOptions::DEFAULT_CUT_FORCE, |c| c.cut_force);
    // The layers the volume was loaded with stay.
    let layers = cutter.options().layers().to_vec();
    let options = CutOptions::new(tool_radius, cut_force)
        .map_err(|e| anyhow!("--cut-force: {e}"))?
        .with_layers(layers);
    cutter.set_options(options)?;
    let refresh_hz = cut.map_or(1.0, |c| c.refresh_hz);
    Ok(Some(Cutting {
        cutter,
        editor: editor.filter(|_| cut.is_some()),
        save,
        id,
        pose,
        dt: 1.0 / rate_hz,
        every: (rate_hz / refresh_hz).round().max(1.0) as u64,
        due: 0,
        refresh_hz,
        times: Histogram::new(),
        sent: 0,
        busy: 0,
        handed_back: 0,
        error: None,
        publish: None,
        dropped_records: 0,
    }))
}

impl Cutting {
    /// The line under the scene's, when it cuts.
    fn describe(&self) -> Option<String> {
        self.editor.as_ref()?;
        let o = self.cutter.options();
        Some(format!(
            "cutting: a tool of radius {:.2} mm removes the material it presses on with {} N or more; the shape is made again at up to {} Hz off the servo's thread",
            o.tool_radius() * 1e3,
            o.cut_force(),
            self.refresh_hz
        ))
    }

    /// One tick's record: the tool's press on the object, and at each refresh period the
    /// next shape sent.
    pub fn on_record(&mut self, r: &TickRecord) {
        if self.error.is_some() || self.editor.is_none() {
            return;
        }
        if r.object == Some(self.id) {
            let centre = self.pose.to_object(r.proxy);
            self.cutter.press(centre, r.force.length(), self.dt);
        }
        // Records may be dropped on the wall clock: the next refresh is due by tick count.
        if r.tick >= self.due {
            self.due = r.tick + self.every;
            self.refresh();
        }
    }

    /// Makes the next shape, if anything changed, and sends it.
    fn refresh(&mut self) {
        let Some(editor) = self.editor.as_mut() else {
            return;
        };
        for back in editor.collect() {
            if let Returned::Replaced(..) = back {
                self.handed_back += 1;
            }
        }
        let began = Instant::now();
        match self.cutter.refresh() {
            Ok(Some(shape)) => {
                let ns = began.elapsed().as_nanos();
                self.times.record(u64::try_from(ns).unwrap_or(u64::MAX));
                match editor.send(Edit::SetShape(self.id, Arc::clone(&shape))) {
                    Ok(()) => {
                        self.sent += 1;
                        if let Some(publish) = &mut self.publish {
                            publish(&shape);
                        }
                    }
                    Err(_) => self.busy += 1,
                }
            }
            Ok(None) => {}
            Err(e) => self.error = Some(e.to_string()),
        }
    }

    /// The summary's block (when it cut), then the volume saved (`--save-volume`).
    ///
    /// # Errors
    /// The cutter stopped (all material cut away), the volume could not be written, or
    /// the output failed.
    pub fn finish(&self, out: &mut impl Write) -> anyhow::Result<()> {
        if self.editor.is_some() {
            self.print(out)?;
        }
        if let Some(path) = &self.save {
            write_volume(path, self.cutter.volume())?;
            writeln!(out, "volume written to {}", path.display())?;
        }
        Ok(())
    }

    /// The summary's block.
    fn print(&self, out: &mut impl Write) -> anyhow::Result<()> {
        writeln!(out, "\ncutting:")?;
        let o = self.cutter.options();
        writeln!(
            out,
            "  tool              radius {:.2} mm, cutting from {} N",
            o.tool_radius() * 1e3,
            o.cut_force()
        )?;
        writeln!(out, "  removed           {} voxels", self.cutter.removed())?;
        if self.dropped_records > 0 {
            writeln!(
                out,
                "  presses lost      {} ticks' records (the cutting thread fell behind)",
                self.dropped_records
            )?;
        }
        let mut versions = format!(
            "{} sent to the servo through the scene's editor (at most {} Hz)",
            self.sent, self.refresh_hz
        );
        if self.busy > 0 {
            versions += &format!(", {} dropped (the edit ring was full)", self.busy);
        }
        writeln!(out, "  versions          {versions}")?;
        let t = &self.times;
        if t.count() > 0 {
            writeln!(
                out,
                "  refresh time      p50 {}  p99 {}  max {} (the changed chunks extracted again, then the shape built)",
                time(t.quantile(0.5)),
                time(t.quantile(0.99)),
                time(t.max())
            )?;
        }
        writeln!(
            out,
            "  surface now       {} triangles",
            self.cutter.shape().surface().triangle_count()
        )?;
        if let Some(e) = &self.error {
            bail!("--cut: the cutter stopped: {e}");
        }
        Ok(())
    }
}

/// Records the live view's pump hands the cutting thread; past them, a record is dropped
/// rather than wait (the thread is remaking a shape), as records are on the wall clock.
#[cfg(feature = "view")]
const RECORD_QUEUE: usize = 8192;

#[cfg(feature = "view")]
impl Cutting {
    /// Whether it cuts (`--cut`): otherwise it only saves the volume, if asked.
    pub fn cuts(&self) -> bool {
        self.editor.is_some()
    }

    /// The object it cuts.
    pub fn object(&self) -> ObjectId {
        self.id
    }

    /// The cutting with `publish` called with each version it sends.
    pub fn publishing(mut self, publish: Publish) -> Cutting {
        self.publish = Some(publish);
        self
    }

    /// The cutting on a thread of its own, following the records handed to the function
    /// returned, which never waits (a record that finds [`RECORD_QUEUE`] records queued is
    /// dropped, and counted in the summary); the thread hands the cutting back once that function is dropped and the
    /// records queued are followed.
    ///
    /// # Errors
    /// The thread cannot start.
    pub fn follow_on_thread(
        self,
    ) -> anyhow::Result<(haphe_view::RecordHook, std::thread::JoinHandle<Cutting>)> {
        use std::sync::atomic::{AtomicU64, Ordering};
        let (tx, rx) = std::sync::mpsc::sync_channel::<TickRecord>(RECORD_QUEUE);
        let dropped = Arc::new(AtomicU64::new(0));
        let counted = Arc::clone(&dropped);
        let thread = std::thread::Builder::new()
            .name("haphe-cut".into())
            .spawn(move || {
                let mut cutting = self;
                for r in rx {
                    cutting.on_record(&r);
                }
                cutting.dropped_records = counted.load(Ordering::Relaxed);
                cutting
            })
            .map_err(|e| anyhow!("cannot start the cutting thread: {e}"))?;
        let hook = move |r: &TickRecord| {
            if tx.try_send(*r).is_err() {
                dropped.fetch_add(1, Ordering::Relaxed);
            }
        };
        Ok((Box::new(hook), thread))
    }
}
