//! What changes the first object's shape while a live view runs (`--deform`, `--cut`):
//! the deformer thread, or the cutting on a thread of its own that follows the records
//! the view's pump hands it; each version they send to the servo is published to the page
//! (a deformation's vertices, a cut's whole mesh), and their summary printed at the end.

use std::thread::JoinHandle;

use anyhow::anyhow;
use haphe::scene::{Scene, SceneEditor, Shape};
use haphe_view::{MeshParts, Model, RecordHook};

use super::super::cut::{self, Cutting};
use super::super::deform::{self, Clock, Deformer, Plan};
use crate::args::cut::CutSetup;
use crate::args::deform::Deform;

/// What changes the first object's shape in a live view, before it starts: its
/// deformation, or its volume's cutting (or the volume kept to be saved).
pub struct Changes {
    plan: Option<Plan>,
    cutting: Option<Cutting>,
}

/// What changes it while the view runs: the deformer, or the cutting thread (with the
/// hook the view's pump hands each record to) or the volume kept.
pub struct Changing {
    deformer: Option<Deformer>,
    /// Handed to the view's source.
    pub on_record: Option<RecordHook>,
    volume: Option<LiveVolume>,
}

impl Changes {
    /// The deformation of `deform` or the cutting of `cut` of `scene`'s first object
    /// (named `first`), through the scene's `editor`, by a tool of `tool_radius` on a
    /// servo of `rate_hz`; says so when it cuts.
    pub fn plan(
        scene: &Scene,
        editor: Option<SceneEditor>,
        first: &str,
        (deform, cut): (Option<Deform>, Option<CutSetup>),
        (tool_radius, rate_hz): (f64, f64),
    ) -> anyhow::Result<Changes> {
        let (plan, cut_editor) = match (deform, editor) {
            (Some(d), Some(e)) => (Some(Plan::new(scene, e, first, d)?), None),
            (_, editor) => (None, editor),
        };
        let placed = scene.objects().first().map(|o| (o.id, o.pose));
        let cutting = cut::start(
            &mut std::io::stdout(),
            cut,
            (cut_editor, placed),
            (tool_radius, rate_hz),
        )?;
        Ok(Changes { plan, cutting })
    }

    /// Starts the deformer or the cutting thread, each version they send published to the
    /// page through `model`.
    pub fn start(self, model: Model) -> anyhow::Result<(Changing, Model)> {
        let (deformer, model) = start_deformer(self.plan, model)?;
        let (on_record, volume, model) = start_cutting(self.cutting, model)?;
        let changing = Changing {
            deformer,
            on_record,
            volume,
        };
        Ok((changing, model))
    }
}

impl Changing {
    /// Once the view has stopped: the deformer's or the cutting's summary block, and the
    /// volume saved.
    pub fn finish(self) -> anyhow::Result<()> {
        if let Some(deformer) = self.deformer {
            deform::print(&mut std::io::stdout(), &deformer.finish()?, None, None)?;
        }
        if let Some(volume) = self.volume {
            volume.finish()?;
        }
        Ok(())
    }
}

/// Starts the deformer of `plan`, if any, on the wall clock, publishing each version it
/// sends to the page (its vertices) through `model`, and says so.
fn start_deformer(plan: Option<Plan>, model: Model) -> anyhow::Result<(Option<Deformer>, Model)> {
    let Some(plan) = plan else {
        return Ok((None, model));
    };
    let (publisher, feed) = haphe_view::shape_channel();
    let id = plan.id().0;
    println!("{}", plan.describe(Clock::Wall));
    let deformer = plan.spawn(
        Clock::Wall,
        Some(Box::new(move |shape: &Shape| {
            publisher.publish_vertices(id, shape.version(), shape.surface().vertices());
        })),
    )?;
    Ok((Some(deformer), model.with_shape_feed(feed)))
}

/// The volume of a live view: cut on a thread of its own, which hands it back when the
/// view stops, or kept as it is to be saved (`--save-volume` without `--cut`).
enum LiveVolume {
    Cut(JoinHandle<Cutting>),
    Kept(Box<Cutting>),
}

impl LiveVolume {
    /// The cutting's summary block and the volume saved, as `simulate` prints them.
    fn finish(self) -> anyhow::Result<()> {
        let cutting = match self {
            LiveVolume::Cut(thread) => thread
                .join()
                .map_err(|_| anyhow!("the cutting thread panicked"))?,
            LiveVolume::Kept(cutting) => *cutting,
        };
        cutting.finish(&mut std::io::stdout())
    }
}

/// Starts `cutting`, when it cuts, on a thread of its own, publishing each version it
/// sends to the page (its whole mesh) through `model`; the hook the view's pump hands
/// each record to.
fn start_cutting(
    cutting: Option<Cutting>,
    model: Model,
) -> anyhow::Result<(Option<RecordHook>, Option<LiveVolume>, Model)> {
    let cutting = match cutting {
        Some(c) if c.cuts() => c,
        kept => return Ok((None, kept.map(|c| LiveVolume::Kept(Box::new(c))), model)),
    };
    let (publisher, feed) = haphe_view::shape_channel();
    let id = cutting.object().0;
    let cutting = cutting.publishing(Box::new(move |shape: &Shape| {
        let s = shape.surface();
        let parts = MeshParts {
            positions: s.vertices(),
            triangles: s.triangles(),
            source: s.source_triangles(),
        };
        publisher.publish_mesh(id, shape.version(), parts);
    }));
    let (hook, thread) = cutting.follow_on_thread()?;
    Ok((
        Some(hook),
        Some(LiveVolume::Cut(thread)),
        model.with_shape_feed(feed),
    ))
}
