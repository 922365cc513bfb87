//! The network device (`udp:HOST:PORT`): another process or machine sends the device
//! point in one small datagram, haphe answers with the force in another
//! ([`datagram`]). haphe listens on HOST:PORT and answers the address the latest
//! position came from.
//!
//! On the servo path the socket is read without blocking into a fixed buffer: every
//! datagram waiting is taken (at most [`MAX_DATAGRAMS_PER_TICK`]), the newest valid one
//! is used. A datagram that is not a position datagram is counted as malformed; one whose
//! sequence number is not above the last used one (reordered, repeated) is dropped and
//! counted; gaps in the sequence are counted as lost. A tick with nothing new holds the
//! last position (counted as late). When no new position came for
//! [`UdpOptions::timeout_s`], the device faults: a zero force datagram with status
//! [`Status::Timeout`] is sent and the servo stops. A position datagram with the stop
//! flag ([`datagram::FLAG_STOP`]) ends the run cleanly: a zero force datagram with status
//! [`Status::Stopped`], and the device reports [`DeviceFault::Ended`] as a replay that
//! ended does.

pub mod datagram;

use std::io::ErrorKind;
use std::net::{SocketAddr, ToSocketAddrs, UdpSocket};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use glam::DVec3;
use haphe::servo::{Buttons, Device, DeviceError, DeviceFault, DeviceSpec, DeviceState};

use self::datagram::{FORCE_LEN, ForceDatagram, PositionDatagram, Status};

/// Datagrams taken from the socket in one tick at most (the rest wait for the next).
pub const MAX_DATAGRAMS_PER_TICK: usize = 64;

/// Default [`UdpOptions::timeout_s`]: 50 ms, 50 ticks at 1 kHz. Longer, and a lost peer
/// leaves the user pressing on a stale wall; shorter, and an ordinary network hiccup
/// stops the run.
pub const UDP_TIMEOUT_S: f64 = 0.05;

/// Default [`UdpOptions::first_timeout_s`]: how long opening waits for the peer.
pub const UDP_FIRST_TIMEOUT_S: f64 = 10.0;

/// Settings of a [`UdpDevice`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UdpOptions {
    /// Seconds without a new position after which the device faults.
    pub timeout_s: f64,
    /// Seconds [`Device::open`] waits for the first position.
    pub first_timeout_s: f64,
    /// Workspace of the peer's device, metres, device frame (for the default mapping).
    pub workspace: (DVec3, DVec3),
    /// Largest force sent, newtons.
    pub max_force: f64,
}

impl Default for UdpOptions {
    /// The default timeouts, a 0.2 m cube workspace centred on the origin,
    /// [`DEFAULT_MAX_FORCE_N`](haphe::scene::DEFAULT_MAX_FORCE_N).
    fn default() -> UdpOptions {
        UdpOptions {
            timeout_s: UDP_TIMEOUT_S,
            first_timeout_s: UDP_FIRST_TIMEOUT_S,
            workspace: (DVec3::splat(-0.1), DVec3::splat(0.1)),
            max_force: haphe::scene::DEFAULT_MAX_FORCE_N,
        }
    }
}

/// What the UDP device counted, readable from another thread during and after a run.
#[derive(Debug, Default)]
pub struct UdpCounters {
    /// Position datagrams used.
    pub received: AtomicU64,
    /// Sequence numbers skipped (datagrams lost, or still to come out of order).
    pub lost: AtomicU64,
    /// Datagrams dropped for a sequence number not above the last used one.
    pub reordered: AtomicU64,
    /// Datagrams that were not position datagrams.
    pub malformed: AtomicU64,
    /// Ticks that found no new position and held the last one.
    pub late_ticks: AtomicU64,
    /// Force datagrams sent.
    pub sent: AtomicU64,
    /// Force datagrams the socket refused (a full send buffer).
    pub send_failed: AtomicU64,
    /// 1 once the device faulted for want of positions.
    pub timed_out: AtomicU64,
    /// 1 once the peer sent the stop flag.
    pub stopped_by_peer: AtomicU64,
}

impl UdpCounters {
    /// One line for reports.
    pub fn summary(&self) -> String {
        let g = |a: &AtomicU64| a.load(Ordering::Relaxed);
        format!(
            "udp: {} positions used, {} lost, {} reordered or repeated (dropped), {} malformed, \
             {} ticks without a new position, {} forces sent ({} refused){}",
            g(&self.received),
            g(&self.lost),
            g(&self.reordered),
            g(&self.malformed),
            g(&self.late_ticks),
            g(&self.sent),
            g(&self.send_failed),
            if g(&self.timed_out) > 0 {
                "; timed out: no position within the timeout"
            } else if g(&self.stopped_by_peer) > 0 {
                "; the peer sent stop"
            } else {
                ""
            }
        )
    }
}

/// The network device (see the module documentation).
///
/// # Real-time
/// `read` and `write_force` use fixed buffers and non-blocking socket calls: no
/// allocation, no lock, no wait.
pub struct UdpDevice {
    listen: SocketAddr,
    options: UdpOptions,
    socket: Option<UdpSocket>,
    peer: Option<SocketAddr>,
    buffer: [u8; 256],
    last: Option<PositionDatagram>,
    last_at: Instant,
    velocity: DVec3,
    sent: u64,
    faulted: bool,
    stopped: bool,
    counters: Arc<UdpCounters>,
}

impl UdpDevice {
    /// A device listening on `address` (`HOST:PORT`), not yet open.
    ///
    /// # Errors
    /// When the address does not resolve.
    pub fn new(address: &str, options: UdpOptions) -> Result<UdpDevice, DeviceError> {
        let listen = address
            .to_socket_addrs()
            .map_err(|e| DeviceError::Open(format!("udp:{address}: {e}")))?
            .next()
            .ok_or_else(|| DeviceError::Open(format!("udp:{address}: no address")))?;
        Ok(UdpDevice {
            listen,
            options,
            socket: None,
            peer: None,
            buffer: [0; 256],
            last: None,
            last_at: Instant::now(),
            velocity: DVec3::ZERO,
            sent: 0,
            faulted: false,
            stopped: false,
            counters: Arc::new(UdpCounters::default()),
        })
    }

    /// The counters, shared.
    pub fn counters(&self) -> Arc<UdpCounters> {
        Arc::clone(&self.counters)
    }

    /// The address listened on (with the port chosen, once open, when 0 was asked).
    pub fn local_addr(&self) -> SocketAddr {
        self.socket
            .as_ref()
            .and_then(|s| s.local_addr().ok())
            .unwrap_or(self.listen)
    }

    /// Binds the socket without waiting for the peer (for tests and callers that start
    /// their peer after binding); [`Device::open`] then waits for the first position.
    ///
    /// # Errors
    /// When the address cannot be bound.
    pub fn bind(&mut self) -> Result<SocketAddr, DeviceError> {
        if self.socket.is_none() {
            let s = UdpSocket::bind(self.listen).map_err(|e| {
                DeviceError::Open(format!("cannot listen on udp:{}: {e}", self.listen))
            })?;
            self.socket = Some(s);
        }
        Ok(self.local_addr())
    }

    /// Takes what waits on the socket; whether a new position was taken.
    fn drain(&mut self) -> bool {
        let Some(socket) = self.socket.as_ref() else {
            return false;
        };
        let mut fresh = false;
        for _ in 0..MAX_DATAGRAMS_PER_TICK {
            let (n, from) = match socket.recv_from(&mut self.buffer) {
                Ok(x) => x,
                Err(e) if e.kind() == ErrorKind::WouldBlock => break,
                // An ICMP "port unreachable" for an earlier force datagram, and the like.
                Err(_) => continue,
            };
            let Some(d) = PositionDatagram::decode(&self.buffer[..n]) else {
                self.counters.malformed.fetch_add(1, Ordering::Relaxed);
                continue;
            };
            if let Some(last) = self.last {
                if d.sequence <= last.sequence {
                    self.counters.reordered.fetch_add(1, Ordering::Relaxed);
                    continue;
                }
                self.counters
                    .lost
                    .fetch_add(d.sequence - last.sequence - 1, Ordering::Relaxed);
                let dt = d.timestamp_us.saturating_sub(last.timestamp_us) as f64 * 1e-6;
                self.velocity = if dt > 0.0 && dt <= self.options.timeout_s {
                    (d.position - last.position) / dt
                } else {
                    DVec3::ZERO
                };
            }
            self.counters.received.fetch_add(1, Ordering::Relaxed);
            if d.stop {
                self.stopped = true;
                self.counters.stopped_by_peer.store(1, Ordering::Relaxed);
            }
            self.last = Some(d);
            self.peer = Some(from);
            fresh = true;
        }
        fresh
    }

    fn send(&mut self, status: Status, force: DVec3) {
        let (Some(socket), Some(peer)) = (self.socket.as_ref(), self.peer) else {
            return;
        };
        self.sent += 1;
        let bytes = ForceDatagram {
            status,
            sequence: self.sent,
            position_sequence: self.last.map_or(0, |d| d.sequence),
            force,
        }
        .encode();
        let c = &self.counters;
        match socket.send_to(&bytes[..FORCE_LEN], peer) {
            Ok(_) => c.sent.fetch_add(1, Ordering::Relaxed),
            Err(_) => c.send_failed.fetch_add(1, Ordering::Relaxed),
        };
    }
}

impl Device for UdpDevice {
    fn spec(&self) -> DeviceSpec {
        DeviceSpec {
            name: "udp",
            max_force: self.options.max_force,
            max_stiffness: f64::INFINITY,
            workspace_min: self.options.workspace.0,
            workspace_max: self.options.workspace.1,
        }
    }

    fn open(&mut self) -> Result<(), DeviceError> {
        if self.last.is_some() {
            return Ok(());
        }
        self.bind()?;
        let Some(socket) = self.socket.as_ref() else {
            return Err(DeviceError::Open("the socket is not bound".into()));
        };
        let wait = Duration::from_secs_f64(self.options.first_timeout_s.max(0.001));
        let limit = Instant::now() + wait;
        socket
            .set_nonblocking(true)
            .map_err(|e| DeviceError::Open(format!("udp:{}: {e}", self.listen)))?;
        while Instant::now() < limit {
            if self.drain() {
                self.last_at = Instant::now();
                return Ok(());
            }
            std::thread::sleep(Duration::from_millis(1));
        }
        Err(DeviceError::Open(format!(
            "no position datagram reached udp:{} within {:.1} s ({}); is the peer sending to \
             this address? (docs/devices.md)",
            self.local_addr(),
            wait.as_secs_f64(),
            self.counters.summary()
        )))
    }

    fn read(&mut self, _t: f64) -> Result<DeviceState, DeviceFault> {
        if self.faulted {
            return Err(DeviceFault::Disconnected);
        }
        if self.stopped {
            self.send(Status::Stopped, DVec3::ZERO);
            return Err(DeviceFault::Ended);
        }
        let Some(_) = self.socket else {
            return Err(DeviceFault::NotOpen);
        };
        let now = Instant::now();
        if self.drain() {
            self.last_at = now;
            if self.stopped {
                self.send(Status::Stopped, DVec3::ZERO);
                return Err(DeviceFault::Ended);
            }
        } else {
            self.counters.late_ticks.fetch_add(1, Ordering::Relaxed);
            if now.saturating_duration_since(self.last_at).as_secs_f64() > self.options.timeout_s {
                self.faulted = true;
                self.counters.timed_out.store(1, Ordering::Relaxed);
                self.send(Status::Timeout, DVec3::ZERO);
                return Err(DeviceFault::Disconnected);
            }
        }
        let Some(d) = self.last else {
            return Err(DeviceFault::NotOpen);
        };
        Ok(DeviceState {
            position: d.position,
            velocity: self.velocity,
            buttons: Buttons(d.buttons),
        })
    }

    fn write_force(&mut self, force: DVec3) -> Result<(), DeviceFault> {
        if self.stopped {
            self.send(Status::Stopped, DVec3::ZERO);
            return Ok(());
        }
        if self.faulted {
            self.send(Status::Timeout, DVec3::ZERO);
            return Ok(());
        }
        let f = if force.is_finite() {
            force
        } else {
            DVec3::ZERO
        };
        self.send(Status::Running, f);
        Ok(())
    }

    fn close(&mut self) {
        if self.socket.is_some() {
            self.send(Status::Stopped, DVec3::ZERO);
            self.socket = None;
        }
    }
}
