//! Deforming objects: the vertices of an object whose shape another thread deforms,
//! published by that thread (the latest version only, never waiting for a page) and sent
//! to each page as a binary WebSocket message at most [`VERTEX_RATE_HZ`] times a second,
//! when the version changed; the page redraws the mesh from them.

use std::sync::Arc;

use glam::DVec3;
use tokio::sync::watch;

/// Most vertex messages a page receives a second, per deforming object.
pub const VERTEX_RATE_HZ: f64 = 30.0;

/// Magic number at the start of a vertex message: `HPD1`, little-endian.
pub const VERTICES_MAGIC: u32 = u32::from_le_bytes(*b"HPD1");

/// The deforming thread's end: publishes each version's vertices (object frame, in the
/// order of the mesh the page was sent).
#[derive(Debug)]
pub struct VertexPublisher {
    tx: watch::Sender<Option<Arc<[u8]>>>,
}

/// The view's end, given to the [`Model`](crate::Model) ([`Model::with_deforming`](crate::Model::with_deforming)).
#[derive(Debug, Clone)]
pub struct VertexFeed {
    pub(crate) rx: watch::Receiver<Option<Arc<[u8]>>>,
}

/// A publisher and its feed.
pub fn vertex_channel() -> (VertexPublisher, VertexFeed) {
    let (tx, rx) = watch::channel(None);
    (VertexPublisher { tx }, VertexFeed { rx })
}

impl VertexPublisher {
    /// Publishes version `version` of object `id`'s vertices, replacing any version not
    /// yet sent. The message, little-endian: `HPD1`, id (u32), version (u64), vertex count
    /// (u32), positions (3 f32 per vertex).
    pub fn publish(&self, id: u32, version: u64, positions: &[DVec3]) {
        self.tx
            .send_replace(Some(encode_vertices(id, version, positions)));
    }
}

/// The vertex message of `positions` (see [`VertexPublisher::publish`]).
pub fn encode_vertices(id: u32, version: u64, positions: &[DVec3]) -> Arc<[u8]> {
    let mut out = Vec::with_capacity(20 + 12 * positions.len());
    out.extend_from_slice(&VERTICES_MAGIC.to_le_bytes());
    out.extend_from_slice(&id.to_le_bytes());
    out.extend_from_slice(&version.to_le_bytes());
    out.extend_from_slice(&(positions.len() as u32).to_le_bytes());
    for p in positions {
        for v in p.to_array() {
            out.extend_from_slice(&(v as f32).to_le_bytes());
        }
    }
    Arc::from(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_latest_version_is_what_the_feed_holds() {
        let (publisher, feed) = vertex_channel();
        assert!(feed.rx.borrow().is_none());
        publisher.publish(3, 1, &[DVec3::X]);
        publisher.publish(3, 2, &[DVec3::new(0.5, -1.0, 2.0)]);
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
    }
}
