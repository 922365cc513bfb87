//! The two datagrams of the UDP device, little-endian, fixed size (see docs/devices.md).
//!
//! Position, peer → haphe, [`POSITION_LEN`] bytes:
//!
//! | offset | type | field |
//! | --- | --- | --- |
//! | 0 | 4 bytes | magic `HPHP` |
//! | 4 | u16 | version, [`VERSION`] |
//! | 6 | u16 | flags: bit 0 [`FLAG_STOP`] (the peer is done: the run ends cleanly); the other bits 0 |
//! | 8 | u64 | sequence number, increasing by one per datagram |
//! | 16 | u64 | timestamp, microseconds of the sender's clock |
//! | 24 | 3 × f64 | position x, y, z, metres, device frame |
//! | 48 | u32 | buttons held, bit 0 the first |
//! | 52 | u32 | reserved, 0 |
//!
//! Force, haphe → peer, [`FORCE_LEN`] bytes:
//!
//! | offset | type | field |
//! | --- | --- | --- |
//! | 0 | 4 bytes | magic `HPHF` |
//! | 4 | u16 | version, [`VERSION`] |
//! | 6 | u16 | status, [`Status`] |
//! | 8 | u64 | sequence number of this force datagram |
//! | 16 | u64 | sequence number of the latest position datagram used |
//! | 24 | 3 × f64 | force x, y, z, newtons, device frame |

use glam::DVec3;

/// Magic of a position datagram.
pub const POSITION_MAGIC: [u8; 4] = *b"HPHP";
/// Magic of a force datagram.
pub const FORCE_MAGIC: [u8; 4] = *b"HPHF";
/// Version of both datagrams.
pub const VERSION: u16 = 1;
/// Bit of a position datagram's flags (offset 6, once reserved and always 0, so a peer
/// that never sets it is unchanged): the peer is done. haphe uses the datagram's position
/// as any other, answers with a zero force of status [`Status::Stopped`] and ends the run
/// as a replay ends ([`haphe::servo::DeviceFault::Ended`]): a clean stop, exit code 0.
pub const FLAG_STOP: u16 = 1;
/// Bytes of a position datagram.
pub const POSITION_LEN: usize = 56;
/// Bytes of a force datagram.
pub const FORCE_LEN: usize = 48;

/// What a force datagram says about the rendering.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u16)]
pub enum Status {
    /// The force is the rendered force.
    Running = 0,
    /// No position came within the timeout: the force is zero and the run stops.
    Timeout = 1,
    /// haphe stopped (end of the run, Ctrl-C, a fault): the force is zero.
    Stopped = 2,
}

/// A position datagram.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PositionDatagram {
    /// Increasing by one per datagram.
    pub sequence: u64,
    /// Microseconds of the sender's clock.
    pub timestamp_us: u64,
    /// Metres, device frame.
    pub position: DVec3,
    /// Buttons held, bit 0 the first.
    pub buttons: u32,
    /// The peer is done ([`FLAG_STOP`]).
    pub stop: bool,
}

/// A force datagram.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceDatagram {
    /// What the force means.
    pub status: Status,
    /// Sequence number of this datagram.
    pub sequence: u64,
    /// Sequence number of the latest position datagram used.
    pub position_sequence: u64,
    /// Newtons, device frame.
    pub force: DVec3,
}

fn u16_at(b: &[u8], i: usize) -> u16 {
    u16::from_le_bytes([b[i], b[i + 1]])
}

fn u32_at(b: &[u8], i: usize) -> u32 {
    u32::from_le_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]])
}

fn u64_at(b: &[u8], i: usize) -> u64 {
    let mut a = [0u8; 8];
    a.copy_from_slice(&b[i..i + 8]);
    u64::from_le_bytes(a)
}

fn vec_at(b: &[u8], i: usize) -> DVec3 {
    let f = |j: usize| f64::from_bits(u64_at(b, i + 8 * j));
    DVec3::new(f(0), f(1), f(2))
}

fn put_vec(b: &mut [u8], i: usize, v: DVec3) {
    for (j, x) in v.to_array().into_iter().enumerate() {
        b[i + 8 * j..i + 8 * j + 8].copy_from_slice(&x.to_le_bytes());
    }
}

impl PositionDatagram {
    /// The bytes of the datagram.
    pub fn encode(&self) -> [u8; POSITION_LEN] {
        let mut b = [0u8; POSITION_LEN];
        b[0..4].copy_from_slice(&POSITION_MAGIC);
        b[4..6].copy_from_slice(&VERSION.to_le_bytes());
        let flags = if self.stop { FLAG_STOP } else { 0 };
        b[6..8].copy_from_slice(&flags.to_le_bytes());
        b[8..16].copy_from_slice(&self.sequence.to_le_bytes());
        b[16..24].copy_from_slice(&self.timestamp_us.to_le_bytes());
        put_vec(&mut b, 24, self.position);
        b[48..52].copy_from_slice(&self.buttons.to_le_bytes());
        b
    }

    /// The datagram in `bytes`; `None` when it is not one (size, magic, version, a
    /// non-finite position).
    ///
    /// # Real-time
    /// No allocation.
    pub fn decode(bytes: &[u8]) -> Option<PositionDatagram> {
        if bytes.len() != POSITION_LEN
            || bytes[0..4] != POSITION_MAGIC
            || u16_at(bytes, 4) != VERSION
        {
            return None;
        }
        let position = vec_at(bytes, 24);
        position.is_finite().then(|| PositionDatagram {
            sequence: u64_at(bytes, 8),
            timestamp_us: u64_at(bytes, 16),
            position,
            buttons: u32_at(bytes, 48),
            stop: u16_at(bytes, 6) & FLAG_STOP != 0,
        })
    }
}

impl ForceDatagram {
    /// The bytes of the datagram.
    ///
    /// # Real-time
    /// No allocation.
    pub fn encode(&self) -> [u8; FORCE_LEN] {
        let mut b = [0u8; FORCE_LEN];
        b[0..4].copy_from_slice(&FORCE_MAGIC);
        b[4..6].copy_from_slice(&VERSION.to_le_bytes());
        b[6..8].copy_from_slice(&(self.status as u16).to_le_bytes());
        b[8..16].copy_from_slice(&self.sequence.to_le_bytes());
        b[16..24].copy_from_slice(&self.position_sequence.to_le_bytes());
        put_vec(&mut b, 24, self.force);
        b
    }

    /// The datagram in `bytes`; `None` when it is not one.
    pub fn decode(bytes: &[u8]) -> Option<ForceDatagram> {
        if bytes.len() != FORCE_LEN || bytes[0..4] != FORCE_MAGIC || u16_at(bytes, 4) != VERSION {
            return None;
        }
        let status = match u16_at(bytes, 6) {
            0 => Status::Running,
            1 => Status::Timeout,
            2 => Status::Stopped,
            _ => return None,
        };
        Some(ForceDatagram {
            status,
            sequence: u64_at(bytes, 8),
            position_sequence: u64_at(bytes, 16),
            force: vec_at(bytes, 24),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_and_rejects() {
        let p = PositionDatagram {
            sequence: 7,
            timestamp_us: 123_456,
            position: DVec3::new(0.01, -0.02, 0.03),
            buttons: 0b101,
            stop: false,
        };
        let b = p.encode();
        assert_eq!(PositionDatagram::decode(&b), Some(p));
        assert_eq!(
            &b[6..8],
            &[0, 0],
            "no flag: the bytes of a peer that never stops"
        );
        let last = PositionDatagram { stop: true, ..p };
        assert_eq!(&last.encode()[6..8], &FLAG_STOP.to_le_bytes());
        assert_eq!(PositionDatagram::decode(&last.encode()), Some(last));
        assert_eq!(&b[0..4], b"HPHP");
        assert_eq!(u64::from_le_bytes(b[8..16].try_into().expect("8")), 7);
        assert!(PositionDatagram::decode(&b[..55]).is_none());
        let mut bad = b;
        bad[4] = 2;
        assert!(PositionDatagram::decode(&bad).is_none());
        let mut nan = b;
        nan[24..32].copy_from_slice(&f64::NAN.to_le_bytes());
        assert!(PositionDatagram::decode(&nan).is_none());
        let f = ForceDatagram {
            status: Status::Timeout,
            sequence: 3,
            position_sequence: 7,
            force: DVec3::new(1.0, 2.0, -3.0),
        };
        assert_eq!(ForceDatagram::decode(&f.encode()), Some(f));
        assert!(ForceDatagram::decode(&b).is_none());
    }
}
