//! Objects whose shape changes while the view runs: each version, published by the thread
//! that makes it (the latest version only, never waiting for a page), is sent to each page
//! as a binary WebSocket message at most [`SHAPE_RATE_HZ`] times a second, when the version
//! changed. Two messages: a deformation moves the vertices and keeps the triangles
//! ([`VERTICES_MAGIC`], the vertices alone); a cut makes another mesh
//! ([`REMESH_MAGIC`], the whole mesh). The page redraws the object from either.

use std::sync::Arc;

use glam::DVec3;
use tokio::sync::watch;

/// Most shape messages a page receives a second, per changing object.
pub const SHAPE_RATE_HZ: f64 = 30.0;

/// Magic number at the start of a vertex message: `HPD1`, little-endian.
pub const VERTICES_MAGIC: u32 = u32::from_le_bytes(*b"HPD1");

/// Magic number at the start of a mesh message: `HPM1`, little-endian.
pub const REMESH_MAGIC: u32 = u32::from_le_bytes(*b"HPM1");

/// Bytes before the positions of a vertex message: magic, id, version, vertex count.
const VERTICES_HEAD: usize = 20;

/// Bytes before the positions of a mesh message: magic, id, version, vertex count,
/// triangle count.
const REMESH_HEAD: usize = 24;

/// The changing thread's end: publishes each version of one object's shape (object
/// frame).
#[derive(Debug)]
pub struct ShapePublisher {
    tx: watch::Sender<Option<Arc<[u8]>>>,
}

/// The view's end, given to the [`Model`](crate::Model) ([`Model::with_shape_feed`](crate::Model::with_shape_feed)).
#[derive(Debug, Clone)]
pub struct ShapeFeed {
    pub(crate) rx: watch::Receiver<Option<Arc<[u8]>>>,
}

/// A publisher and its feed.
pub fn shape_channel() -> (ShapePublisher, ShapeFeed) {
    let (tx, rx) = watch::channel(None);
    (ShapePublisher { tx }, ShapeFeed { rx })
}

impl ShapePublisher {
    /// Publishes version `version` of object `id`'s vertices, moved, in the order of the
    /// mesh the page has (a deformation), replacing any version not yet sent. The message
    /// is [`encode_vertices`]'s.
    pub fn publish_vertices(&self, id: u32, version: u64, positions: &[DVec3]) {
        self.tx
            .send_replace(Some(encode_vertices(id, version, positions)));
    }

    /// Publishes version `version` of object `id`'s whole mesh (a cut: other vertices and
    /// other triangles), replacing any version not yet sent. The message is
    /// [`encode_mesh`]'s.
    pub fn publish_mesh(&self, id: u32, version: u64, mesh: MeshParts<'_>) {
        self.tx.send_replace(Some(encode_mesh(id, version, mesh)));
    }
}

/// The arrays of a mesh message: positions (object frame), triangles (counter-clockwise
/// seen from outside) and, per triangle, the face index that ticks name it by
/// ([`Surface::source_triangles`](haphe::mesh::Surface::source_triangles)).
#[derive(Debug, Clone, Copy)]
pub struct MeshParts<'a> {
    /// Vertex positions, metres, object frame.
    pub positions: &'a [DVec3],
    /// Triangles, three vertex indices each.
    pub triangles: &'a [[u32; 3]],
    /// The face index of each triangle (one per triangle).
    pub source: &'a [u32],
}

/// The vertex message, little-endian: `HPD1`, id (u32), version (u64), vertex count
/// (u32), positions (3 f32 per vertex).
pub fn encode_vertices(id: u32, version: u64, positions: &[DVec3]) -> Arc<[u8]> {
    let mut out = Vec::with_capacity(VERTICES_HEAD + 12 * positions.len());
    out.extend_from_slice(&VERTICES_MAGIC.to_le_bytes());
    out.extend_from_slice(&id.to_le_bytes());
    out.extend_from_slice(&version.to_le_bytes());
    out.extend_from_slice(&(positions.len() as u32).to_le_bytes());
    push_positions(&mut out, positions);
    Arc::from(out)
}

/// The mesh message, little-endian: `HPM1`, id (u32), version (u64), vertex count (u32),
/// triangle count (u32), positions (3 f32 per vertex), triangles (3 u32 each), source
/// face indices (u32 per triangle). A `source` of another length than `triangles` is
/// sent as each triangle's own index.
pub fn encode_mesh(id: u32, version: u64, mesh: MeshParts<'_>) -> Arc<[u8]> {
    let (positions, triangles) = (mesh.positions, mesh.triangles);
    let mut out = Vec::with_capacity(REMESH_HEAD + 12 * positions.len() + 16 * triangles.len());
    out.extend_from_slice(&REMESH_MAGIC.to_le_bytes());
    out.extend_from_slice(&id.to_le_bytes());
    out.extend_from_slice(&version.to_le_bytes());
    out.extend_from_slice(&(positions.len() as u32).to_le_bytes());
    out.extend_from_slice(&(triangles.len() as u32).to_le_bytes());
    push_positions(&mut out, positions);
    for v in triangles.iter().flatten() {
        out.extend_from_slice(&v.to_le_bytes());
    }
    for t in 0..triangles.len() {
        let s = if mesh.source.len() == triangles.len() {
            mesh.source[t]
        } else {
            t as u32
        };
        out.extend_from_slice(&s.to_le_bytes());
    }
    Arc::from(out)
}

fn push_positions(out: &mut Vec<u8>, positions: &[DVec3]) {
    for p in positions {
        for v in p.to_array() {
            out.extend_from_slice(&(v as f32).to_le_bytes());
        }
    }
}

/// A shape message read back, as the page reads it: a deformation's vertices (the
/// triangles stay the page's), or a cut's whole mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct ShapeMessage {
    /// The object's id.
    pub id: u32,
    /// The shape's version.
    pub version: u64,
    /// Vertex positions, metres, object frame.
    pub positions: Vec<[f32; 3]>,
    /// Triangles, in a mesh message; empty in a vertex message.
    pub triangles: Vec<[u32; 3]>,
    /// Each triangle's face index, in a mesh message; empty in a vertex message.
    pub source: Vec<u32>,
    /// A mesh message (`HPM1`) rather than a vertex message (`HPD1`).
    pub remesh: bool,
}

/// Reads a message of [`encode_vertices`] or [`encode_mesh`]; `None` for anything else
/// (another magic, a count the length does not hold).
pub fn decode_shape(bytes: &[u8]) -> Option<ShapeMessage> {
    let u32_at = |i: usize| Some(u32::from_le_bytes(bytes.get(i..i + 4)?.try_into().ok()?));
    let magic = u32_at(0)?;
    let id = u32_at(4)?;
    let version = u64::from_le_bytes(bytes.get(8..16)?.try_into().ok()?);
    let nv = u32_at(16)? as usize;
    let (remesh, nt, head) = match magic {
        VERTICES_MAGIC => (false, 0, VERTICES_HEAD),
        REMESH_MAGIC => (true, u32_at(20)? as usize, REMESH_HEAD),
        _ => return None,
    };
    let length = nv
        .checked_mul(12)?
        .checked_add(nt.checked_mul(16)?)?
        .checked_add(head)?;
    if bytes.len() != length {
        return None;
    }
    let words = |from: usize, n: usize| -> Vec<u32> {
        (0..n).filter_map(|k| u32_at(from + 4 * k)).collect()
    };
    let positions = words(head, 3 * nv)
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]].map(f32::from_bits))
        .collect();
    let at = head + 12 * nv;
    let triangles = words(at, 3 * nt)
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    let source = words(at + 12 * nt, nt);
    Some(ShapeMessage {
        id,
        version,
        positions,
        triangles,
        source,
        remesh,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_latest_version_is_what_the_feed_holds() {
        let (publisher, feed) = shape_channel();
        assert!(feed.rx.borrow().is_none());
        publisher.publish_vertices(3, 1, &[DVec3::X]);
        publisher.publish_vertices(3, 2, &[DVec3::new(0.5, -1.0, 2.0)]);
        let bytes = feed.rx.borrow().clone().expect("a version");
        assert_eq!(bytes.len(), 20 + 12);
        assert_eq!(&bytes[..4], b"HPD1");
        assert_eq!(u32::from_le_bytes(bytes[4..8].try_into().expect("4")), 3);
        assert_eq!(u64::from_le_bytes(bytes[8..16].try_into().expect("8")), 2);
        assert_eq!(u32::from_le_bytes(bytes[16..20].try_into().expect("4")), 1);
        assert_eq!(
            f32::from_le_bytes(bytes[24..28].try_into().expect("4")),
            -1.0
        );
        let back = decode_shape(&bytes).expect("it reads");
        assert_eq!((back.id, back.version, back.remesh), (3, 2, false));
        assert_eq!(back.positions, vec![[0.5, -1.0, 2.0]]);
        assert!(back.triangles.is_empty() && back.source.is_empty());
    }

    /// A mesh message reads back as it was written: the counts, every position (in f32),
    /// every triangle and face index; a mesh replaces a vertex message in the feed.
    #[test]
    fn a_mesh_message_round_trips() {
        let positions = [
            DVec3::ZERO,
            DVec3::new(0.001, 0.0, 0.0),
            DVec3::new(0.0, 0.002, 0.0),
            DVec3::new(0.0, 0.0, -0.003),
        ];
        let triangles = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
        let source = [3, 0, 2, 1];
        let (publisher, feed) = shape_channel();
        publisher.publish_vertices(7, 4, &positions);
        let mesh = MeshParts {
            positions: &positions,
            triangles: &triangles,
            source: &source,
        };
        publisher.publish_mesh(7, u64::MAX - 1, mesh);
        let bytes = feed.rx.borrow().clone().expect("a version");
        assert_eq!(&bytes[..4], b"HPM1");
        assert_eq!(bytes.len(), 24 + 12 * 4 + 16 * 4);
        let back = decode_shape(&bytes).expect("it reads");
        assert_eq!(
            (back.id, back.version, back.remesh),
            (7, u64::MAX - 1, true)
        );
        let expected: Vec<[f32; 3]> = positions
            .iter()
            .map(|p| p.to_array().map(|v| v as f32))
            .collect();
        assert_eq!(back.positions, expected);
        assert_eq!(back.triangles, triangles);
        assert_eq!(back.source, source);
        // Without face indices, each triangle is its own.
        let plain = encode_mesh(
            7,
            1,
            MeshParts {
                source: &[],
                ..mesh
            },
        );
        assert_eq!(decode_shape(&plain).expect("it reads").source, [0, 1, 2, 3]);
        // Cut short, or another magic: not a shape message.
        assert_eq!(decode_shape(&bytes[..bytes.len() - 4]), None);
        let mut other = bytes.to_vec();
        other[3] = b'9';
        assert_eq!(decode_shape(&other), None);
        assert_eq!(decode_shape(&[]), None);
    }
}
