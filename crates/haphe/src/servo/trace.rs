//! What the servo loop records every tick, and the CSV form of it; reading traces back is
//! [`read`], beside it.

pub(crate) mod read;

use std::io::{self, Write};

use glam::DVec3;

use super::device::{Buttons, DeviceFault};
use crate::proxy::TickStatus;
use crate::scene::ObjectId;

/// Every name the status column can hold ([`TickRecord::status_name`]), so that a reader
/// of traces can refuse what no run writes.
pub const STATUS_NAMES: [&str; 12] = [
    "free", "contact", "sticking", "ramping", "clamped", "capped", "wedged", "rejected", "holding",
    "faulted", "fault", "held",
];

/// Where the loop is in its start-up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Phase {
    /// Safe start: the device point is inside an object, so no proxy is placed and the
    /// force is zero until it comes out.
    #[default]
    Holding,
    /// The proxy was placed; the force is ramped up from zero.
    Ramping,
    /// Normal rendering.
    Running,
    /// A fault stopped the loop; the force is zero.
    Faulted,
}

impl Phase {
    /// A short name for traces.
    pub fn name(self) -> &'static str {
        match self {
            Phase::Holding => "holding",
            Phase::Ramping => "ramping",
            Phase::Running => "running",
            Phase::Faulted => "faulted",
        }
    }
}

/// One tick as recorded: a small `Copy` value, so recording never allocates. The default
/// is tick 0 at time 0, everything at the origin, free, in the first phase (a buffer's
/// filler).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TickRecord {
    /// Tick number, from 0.
    pub tick: u64,
    /// Scheduled time of the tick, seconds since the loop started.
    pub t: f64,
    /// The device's index in its servo, in the order given (0 for a servo of one device;
    /// see [`Servo::with_devices`](crate::servo::Servo::with_devices)).
    pub device: u32,
    /// The device point (HIP), metres, world frame.
    pub hip: DVec3,
    /// Its velocity, m/s, world frame.
    pub velocity: DVec3,
    /// The proxy, metres, world frame (the HIP while holding).
    pub proxy: DVec3,
    /// The force written to the device, newtons, world frame (after the start ramp).
    pub force: DVec3,
    /// The object touched (its name), when in contact.
    pub object: Option<ObjectId>,
    /// The triangle under the proxy, when in contact: its index in the object's mesh as
    /// given, the face index of its file ([`Surface::source_triangle`](crate::mesh::Surface::source_triangle)).
    pub triangle: Option<u32>,
    /// Depth of the HIP behind the proxy along the contact normal, metres (0 when free).
    pub penetration: f64,
    /// What the proxy tick reported (all false while holding).
    pub status: TickStatus,
    /// Where the loop is in its start-up.
    pub phase: Phase,
    /// The fault that stopped the loop at this tick, if any.
    pub fault: Option<DeviceFault>,
    /// The device's buttons held at this tick (none before the device was read).
    pub buttons: Buttons,
    /// Whether the clutch was held at this tick (see
    /// [`ServoOptions::with_clutch_button`](crate::servo::ServoOptions::with_clutch_button)):
    /// the tool stayed while the device moved.
    pub clutch: bool,
}

impl TickRecord {
    /// Whether the proxy is in contact.
    pub fn in_contact(&self) -> bool {
        self.object.is_some()
    }

    /// The status column: the phase while not running, else the most important flag
    /// (`rejected`, `wedged`, `capped`, `held` — beyond the saturation depth —,
    /// `clamped`), else `sticking`, `contact` or `free`.
    pub fn status_name(&self) -> &'static str {
        let s = &self.status;
        if self.fault.is_some() {
            "fault"
        } else if self.phase == Phase::Holding || self.phase == Phase::Faulted {
            self.phase.name()
        } else if s.input_rejected {
            "rejected"
        } else if s.wedged {
            "wedged"
        } else if s.step_cap_hit || s.walk_cap_hit {
            "capped"
        } else if s.deep_hold {
            "held"
        } else if s.force_clamped {
            "clamped"
        } else if self.phase == Phase::Ramping {
            "ramping"
        } else if s.sticking {
            "sticking"
        } else if s.in_contact {
            "contact"
        } else {
            "free"
        }
    }

    /// Writes the record as one CSV line with the columns of [`CSV_HEADER`]. Numbers
    /// are written in Rust's shortest round-trip form, so the same run gives the same
    /// bytes.
    ///
    /// # Errors
    /// Those of the writer.
    pub fn write_csv(&self, w: &mut impl Write) -> io::Result<()> {
        let v = |p: DVec3| (p.x, p.y, p.z);
        let (hx, hy, hz) = v(self.hip);
        let (px, py, pz) = v(self.proxy);
        let (fx, fy, fz) = v(self.force);
        write!(
            w,
            "{},{hx},{hy},{hz},{px},{py},{pz},{fx},{fy},{fz},{},",
            self.t,
            u8::from(self.in_contact())
        )?;
        if let Some(o) = self.object {
            write!(w, "{}", o.0)?;
        }
        w.write_all(b",")?;
        if let Some(t) = self.triangle {
            write!(w, "{t}")?;
        }
        writeln!(
            w,
            ",{},{},{},{},{}",
            self.status_name(),
            self.penetration,
            u8::from(self.status.sticking),
            self.buttons.0,
            u8::from(self.clutch)
        )
    }
}

/// The header of a trace CSV, without the line end: time (s), HIP and proxy (m, world),
/// force (N, world), contact (0/1), object id and triangle (empty when free), status
/// ([`TickRecord::status_name`]), penetration (m), sticking (0/1), the buttons held (an
/// integer, bit 0 the first button) and the clutch (0/1).
pub const CSV_HEADER: &str = "t,hip_x,hip_y,hip_z,proxy_x,proxy_y,proxy_z,force_x,force_y,force_z,contact,object,triangle,status,penetration,sticking,buttons,clutch";

/// The header of traces written before the buttons and the clutch were recorded; they
/// are read with no button held.
pub(crate) const CSV_HEADER_BEFORE_BUTTONS: &str = "t,hip_x,hip_y,hip_z,proxy_x,proxy_y,proxy_z,force_x,force_y,force_z,contact,object,triangle,status,penetration,sticking";

/// Writes [`CSV_HEADER`] and a line end.
///
/// # Errors
/// Those of the writer.
pub fn write_csv_header(w: &mut impl Write) -> io::Result<()> {
    writeln!(w, "{CSV_HEADER}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_status_a_record_can_have_is_listed() {
        let base = TickRecord {
            phase: Phase::Running,
            ..TickRecord::default()
        };
        let flags: [fn(&mut TickStatus); 9] = [
            |_| {},
            |s| s.in_contact = true,
            |s| s.sticking = true,
            |s| s.force_clamped = true,
            |s| s.deep_hold = true,
            |s| s.step_cap_hit = true,
            |s| s.wedged = true,
            |s| s.input_rejected = true,
            |s| s.walk_cap_hit = true,
        ];
        let mut seen = Vec::new();
        for phase in [
            Phase::Holding,
            Phase::Ramping,
            Phase::Running,
            Phase::Faulted,
        ] {
            for set in flags {
                for fault in [None, Some(DeviceFault::Disconnected)] {
                    let mut r = TickRecord {
                        phase,
                        fault,
                        ..base
                    };
                    set(&mut r.status);
                    let name = r.status_name();
                    assert!(STATUS_NAMES.contains(&name), "{name} is not listed");
                    seen.push(name);
                }
            }
        }
        for name in STATUS_NAMES {
            assert!(seen.contains(&name), "{name} is listed but never written");
        }
    }
}
