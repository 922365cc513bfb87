//! The live side: the servo loop on its real-time thread, and a pump thread that takes its
//! records and tick timings (both through wait-free rings), thins them to display rate and
//! publishes one [`Frame`] per display frame for the WebSockets.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use glam::DVec3;
use haphe::scene::Scene;
use haphe::servo::{
    Device, DeviceClock, Histogram, ObjectMotion, RealtimeOptions, RealtimeRun, Servo, ServoError,
    ServoLoop, ServoOptions, TickRecord,
};
use serde::Serialize;
use tokio::sync::watch;

use crate::poses::{ObjectPose, poses_at};
use crate::timing::Timed;

/// Display rate of the stream, frames per second.
pub const FRAME_RATE_HZ: f64 = 60.0;

/// Window of the live tick statistics (rate, compute-time quantiles), seconds.
pub const STATS_WINDOW_S: f64 = 1.0;

/// What the page receives once per display frame: the last tick of the frame, the
/// largest force and penetration over all of the frame's ticks, and the tick statistics of
/// the last full window.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Frame {
    /// Tick number of the last tick.
    pub tick: u64,
    /// Its scheduled time, seconds.
    pub t: f64,
    /// Device point, metres, world frame.
    pub hip: [f64; 3],
    /// Proxy, metres, world frame.
    pub proxy: [f64; 3],
    /// Force, newtons, world frame.
    pub force: [f64; 3],
    /// The object in contact.
    pub object: Option<u32>,
    /// The triangle in contact (face index of the object's file).
    pub triangle: Option<u32>,
    /// Penetration, metres.
    pub penetration: f64,
    /// Friction is sticking.
    pub sticking: bool,
    /// The tick's status ([`TickRecord::status_name`]).
    pub status: &'static str,
    /// Ticks since the previous frame.
    pub ticks: u64,
    /// Largest force magnitude over those ticks, newtons.
    pub max_force: f64,
    /// Largest penetration over those ticks, metres.
    pub max_penetration: f64,
    /// Ticks per second over the last full window.
    pub rate_hz: f64,
    /// Compute time of a tick (device read to force write) over the last full window:
    /// median, 99th and 99.9th percentile and maximum, microseconds.
    pub compute_us: [f64; 4],
    /// The servo loop has ended (its device ended or faulted).
    pub ended: bool,
    /// The poses of the objects moved by script at the last tick's time (empty without
    /// motions).
    pub poses: Vec<ObjectPose>,
    /// The other devices of a run of several (two hands), at the last tick: each one's
    /// tool, drawn beside the first device's.
    pub others: Vec<OtherTool>,
}

/// Another device's tool in a [`Frame`]: where its device point, proxy and force are at
/// the frame's last tick.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct OtherTool {
    /// Device point, metres, world frame.
    pub hip: [f64; 3],
    /// Proxy (the tool's centre), metres, world frame.
    pub proxy: [f64; 3],
    /// Force, newtons, world frame.
    pub force: [f64; 3],
    /// The tool's radius, metres (0: a point).
    pub tool_radius: f64,
    /// In contact with an object.
    pub contact: bool,
}

impl Frame {
    fn from_record(r: &TickRecord) -> Frame {
        Frame {
            tick: r.tick,
            t: r.t,
            hip: r.hip.to_array(),
            proxy: r.proxy.to_array(),
            force: r.force.to_array(),
            object: r.object.map(|o| o.0),
            triangle: r.triangle,
            penetration: r.penetration,
            sticking: r.status.sticking,
            status: r.status_name(),
            ticks: 0,
            max_force: 0.0,
            max_penetration: 0.0,
            rate_hz: 0.0,
            compute_us: [0.0; 4],
            ended: false,
            poses: Vec::new(),
            others: Vec::new(),
        }
    }

    /// The force as a vector.
    pub fn force(&self) -> DVec3 {
        DVec3::from_array(self.force)
    }
}

/// The latest frame and its JSON, as published.
#[derive(Debug, Clone)]
pub struct Published {
    /// The frame.
    pub frame: Frame,
    /// Its JSON text.
    pub json: Arc<str>,
}

/// Called on the pump thread with each record it takes from the servo (every device's,
/// in tick order; records the ring dropped are missing): how a program follows the run
/// beside the view, a cutter the tool's presses. The frames wait while it runs: keep it
/// short, and hand long work to a thread of its own.
pub type RecordHook = Box<dyn FnMut(&TickRecord) + Send>;

/// What a live view runs: any device (the mouse, the simulated hand, a real device) on a
/// scene.
pub struct LiveSource {
    /// The device; its workspace is mapped to the world by `options.mapping`.
    pub device: Box<dyn Device>,
    /// The scene (the same objects as the view's [`Model`](crate::Model)).
    pub scene: Scene,
    /// Rate, proxy and mapping.
    pub options: ServoOptions,
    /// Objects moved by script (each frame carries their poses at its tick's time).
    pub motions: Vec<ObjectMotion>,
    /// Length of the run, seconds (`None`: until the view stops).
    pub seconds: Option<f64>,
    /// How the servo thread is scheduled.
    pub realtime: RealtimeOptions,
    /// The device's own servo clock, when it has one (OpenHaptics' scheduler): the tick
    /// then runs on the vendor's thread
    /// ([`ServoLoop::spawn_clocked`](haphe::servo::ServoLoop::spawn_clocked)).
    pub clock: Option<Box<dyn DeviceClock>>,
    /// Further devices on the same servo (two hands), each with its own options
    /// (mapping, tool): every frame carries their tools ([`Frame::others`]).
    pub others: Vec<(Box<dyn Device>, ServoOptions)>,
    /// Called with each record, on the pump thread ([`RecordHook`]); dropped when the
    /// servo loop has stopped and its last records were handed over.
    pub on_record: Option<RecordHook>,
}

/// How a live view's servo ran: its device is the view's timed wrapper around the one
/// given.
pub type LiveRun = RealtimeRun<Timed<Box<dyn Device>>>;

/// The servo and pump threads of a live view.
pub(crate) struct Live {
    stop: Arc<AtomicBool>,
    pump: JoinHandle<Result<LiveRun, ServoError>>,
}

impl Live {
    /// Opens the device, starts the servo on its real-time thread and the pump that
    /// publishes to `frames`.
    pub(crate) fn start(
        source: LiveSource,
        frames: watch::Sender<Option<Published>>,
    ) -> Result<Live, ServoError> {
        let (device, timings) = Timed::new(source.device);
        let radii: Vec<f64> = source
            .others
            .iter()
            .map(|(_, o)| o.proxy().tool_radius())
            .collect();
        let mut servo = if source.others.is_empty() {
            Servo::new(device, source.scene, source.options)?
        } else {
            // The first device's read-to-write time spans the whole tick of every device.
            let mut devices = vec![(device, source.options)];
            for (d, options) in source.others {
                devices.push((Timed::new(d).0, options));
            }
            Servo::with_devices(devices, source.scene)?
        };
        // The pump computes the poses each frame from the same motions: nothing more
        // leaves the servo thread.
        let motions = source.motions.clone();
        servo.set_motions(source.motions);
        let on_record = source.on_record;
        let mut running = match source.clock {
            Some(clock) => ServoLoop::spawn_clocked(servo, clock, source.seconds, source.realtime)?,
            None => ServoLoop::spawn(servo, source.seconds, source.realtime)?,
        };
        let stop = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&stop);
        let pump = std::thread::Builder::new()
            .name("haphe-view-pump".into())
            .spawn(move || {
                let mut timings = timings;
                let mut pump = Pump::new(motions, radii);
                pump.on_record = on_record;
                let frame = Duration::from_secs_f64(1.0 / FRAME_RATE_HZ);
                let mut next = Instant::now() + frame;
                while !flag.load(Ordering::Relaxed) {
                    std::thread::sleep(next.saturating_duration_since(Instant::now()));
                    next += frame;
                    running.drain(|r| pump.add(r));
                    while let Ok(ns) = timings.pop() {
                        pump.compute.record(u64::from(ns));
                    }
                    let ended = running.is_finished();
                    pump.publish(&frames, ended);
                    if ended {
                        break;
                    }
                }
                let run = running.stop(|r| pump.add(r))?;
                pump.publish(&frames, true);
                Ok(run)
            })
            .map_err(ServoError::Spawn)?;
        Ok(Live { stop, pump })
    }

    /// Stops the servo loop (zero force written, device closed) and hands its run back.
    pub(crate) fn stop(self) -> Result<LiveRun, ServoError> {
        self.stop.store(true, Ordering::Relaxed);
        let mut run = self.pump.join().map_err(|_| ServoError::Panicked)??;
        run.servo.close();
        Ok(run)
    }
}

/// Thinning state of the pump thread.
struct Pump {
    last: Option<TickRecord>,
    /// The other devices' last records, and their tools' radii.
    others: Vec<Option<TickRecord>>,
    radii: Vec<f64>,
    ticks: u64,
    max_force: f64,
    max_penetration: f64,
    compute: Histogram,
    window_start: Instant,
    window_ticks: u64,
    rate_hz: f64,
    compute_us: [f64; 4],
    motions: Vec<ObjectMotion>,
    on_record: Option<RecordHook>,
}

impl Pump {
    fn new(motions: Vec<ObjectMotion>, radii: Vec<f64>) -> Pump {
        Pump {
            motions,
            last: None,
            others: vec![None; radii.len()],
            radii,
            ticks: 0,
            max_force: 0.0,
            max_penetration: 0.0,
            compute: Histogram::new(),
            window_start: Instant::now(),
            window_ticks: 0,
            rate_hz: 0.0,
            compute_us: [0.0; 4],
            on_record: None,
        }
    }

    fn add(&mut self, r: &TickRecord) {
        if let Some(hook) = self.on_record.as_mut() {
            hook(r);
        }
        if r.device > 0 {
            if let Some(o) = self.others.get_mut(r.device as usize - 1) {
                *o = Some(*r);
            }
            return;
        }
        self.last = Some(*r);
        self.ticks += 1;
        self.window_ticks += 1;
        self.max_force = self.max_force.max(r.force.length());
        self.max_penetration = self.max_penetration.max(r.penetration);
    }

    fn publish(&mut self, frames: &watch::Sender<Option<Published>>, ended: bool) {
        let elapsed = self.window_start.elapsed().as_secs_f64();
        if elapsed >= STATS_WINDOW_S {
            self.rate_hz = self.window_ticks as f64 / elapsed;
            let us = |ns: u64| ns as f64 * 1e-3;
            self.compute_us = [
                us(self.compute.quantile(0.5)),
                us(self.compute.quantile(0.99)),
                us(self.compute.quantile(0.999)),
                us(self.compute.max()),
            ];
            self.compute.clear();
            self.window_ticks = 0;
            self.window_start = Instant::now();
        }
        let Some(last) = self.last else { return };
        let mut frame = Frame::from_record(&last);
        frame.ticks = self.ticks;
        frame.max_force = self.max_force;
        frame.max_penetration = self.max_penetration;
        frame.rate_hz = self.rate_hz;
        frame.compute_us = self.compute_us;
        frame.ended = ended;
        frame.poses = poses_at(&self.motions, last.t);
        frame.others = self
            .others
            .iter()
            .zip(&self.radii)
            .filter_map(|(r, &tool_radius)| {
                r.map(|r| OtherTool {
                    hip: r.hip.to_array(),
                    proxy: r.proxy.to_array(),
                    force: r.force.to_array(),
                    tool_radius,
                    contact: r.in_contact(),
                })
            })
            .collect();
        self.ticks = 0;
        self.max_force = 0.0;
        self.max_penetration = 0.0;
        let json = serde_json::to_string(&frame).map_or_else(|_| Arc::from("{}"), Arc::from);
        frames.send_replace(Some(Published { frame, json }));
    }
}

#[cfg(test)]
mod tests {
    use haphe::scene::Material;
    use haphe::servo::{ScriptedDevice, Trajectory};

    use super::*;

    /// A live view of two devices publishes the first one's frame and the other's tool,
    /// each where its own device holds it, with its own tool radius.
    #[test]
    fn frames_carry_every_devices_tool() {
        let scene = haphe::verify::sphere_scene(500, Material::default()).expect("a scene");
        let (a, b) = (DVec3::new(0.0, 0.0, 0.3), DVec3::new(0.3, 0.0, 0.0));
        let tool = ServoOptions::default().with_proxy(
            ServoOptions::default()
                .proxy()
                .with_tool_radius(0.01)
                .expect("a radius"),
        );
        let source = LiveSource {
            device: Box::new(ScriptedDevice::new(Trajectory::still(a))),
            scene,
            options: ServoOptions::default(),
            motions: Vec::new(),
            seconds: Some(2.0),
            realtime: RealtimeOptions::default().with_realtime_priority(false),
            clock: None,
            others: vec![(Box::new(ScriptedDevice::new(Trajectory::still(b))), tool)],
            on_record: None,
        };
        let (frames, mut seen) = watch::channel(None);
        let live = Live::start(source, frames).expect("a live view");
        let deadline = Instant::now() + Duration::from_secs(10);
        let frame = loop {
            let published = seen.borrow_and_update().clone();
            if let Some(p) = published
                && !p.frame.others.is_empty()
            {
                break p;
            }
            assert!(Instant::now() < deadline, "no frame with the other device");
            std::thread::sleep(Duration::from_millis(10));
        };
        let run = live.stop().expect("stops");
        assert_eq!(run.servo.devices(), 2);
        assert_eq!(frame.frame.hip, a.to_array());
        let other = frame.frame.others[0];
        assert_eq!((other.hip, other.proxy), (b.to_array(), b.to_array()));
        assert_eq!(other.tool_radius, 0.01);
        assert!(
            frame.json.contains("\"others\":[{\"hip\":[0.3,0.0,0.0]"),
            "{}",
            frame.json
        );
    }
}
