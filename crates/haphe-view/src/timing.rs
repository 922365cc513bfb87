//! Live tick timing for the view: a device wrapper that measures, on the servo thread,
//! the time from reading the device to writing its force (the tick's work: scene, proxy,
//! force) and hands each duration out through a wait-free ring.

use std::time::Instant;

use glam::DVec3;
use haphe::servo::{Device, DeviceError, DeviceFault, DeviceSpec, DeviceState};
use rtrb::{Consumer, Producer, RingBuffer};

/// Capacity of the timing ring, ticks: a quarter second at the highest rate (40 kHz); the
/// view drains it every display frame. Durations that find it full are dropped.
pub const TIMING_CAPACITY: usize = 10_000;

/// `D`, with the time from each [`read`](Device::read) to the following
/// [`write_force`](Device::write_force) sent out, nanoseconds.
///
/// # Real-time
/// Two clock reads and one wait-free push per tick; no allocation, lock or panic.
#[derive(Debug)]
pub struct Timed<D> {
    inner: D,
    began: Option<Instant>,
    out: Producer<u32>,
}

impl<D: Device> Timed<D> {
    /// Wraps `inner`; the durations come out of the returned consumer.
    pub fn new(inner: D) -> (Timed<D>, Consumer<u32>) {
        let (out, consumer) = RingBuffer::new(TIMING_CAPACITY);
        (
            Timed {
                inner,
                began: None,
                out,
            },
            consumer,
        )
    }
}

impl<D: Device> Device for Timed<D> {
    fn spec(&self) -> DeviceSpec {
        self.inner.spec()
    }
    fn open(&mut self) -> Result<(), DeviceError> {
        self.inner.open()
    }
    fn calibrate(&mut self) -> Result<(), DeviceError> {
        self.inner.calibrate()
    }
    fn read(&mut self, t: f64) -> Result<DeviceState, DeviceFault> {
        self.began = Some(Instant::now());
        self.inner.read(t)
    }
    fn write_force(&mut self, force: DVec3) -> Result<(), DeviceFault> {
        let result = self.inner.write_force(force);
        if let Some(began) = self.began.take() {
            let ns = u32::try_from(began.elapsed().as_nanos()).unwrap_or(u32::MAX);
            // A full ring means the view is behind: the duration is dropped, never waited on.
            let _ = self.out.push(ns);
        }
        result
    }
    fn close(&mut self) {
        self.inner.close();
    }
}
