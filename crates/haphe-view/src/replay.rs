//! Trace replay: a per-tick CSV as `haphe simulate --out` writes it (columns of
//! [`CSV_HEADER`](haphe::servo::CSV_HEADER), read by the library's [`Trace::read`]), read once and sent to the page, which plays it with play, pause, speed
//! and a scrubber.

/// A trace read from CSV ([`TickTrace`](haphe::servo::TickTrace)), its rows and errors.
pub use haphe::servo::{TickTrace as Trace, TraceError, TraceRow};

/// The status names of a trace, in the order of their codes in [`encode_trace`].
pub use haphe::servo::STATUS_NAMES;

/// Values per row in [`encode_trace`].
pub const ROW_VALUES: usize = 15;

/// The rows as little-endian f32, [`ROW_VALUES`] per row: t, HIP xyz, proxy xyz,
/// force xyz, object (−1 when free), triangle (−1 when free), status code,
/// penetration, sticking (0/1).
pub fn encode_trace(trace: &Trace) -> Vec<u8> {
    let mut out = Vec::with_capacity(trace.rows.len() * ROW_VALUES * 4);
    for r in &trace.rows {
        let id = |v: Option<u32>| v.map_or(-1.0, |v| v as f64);
        let values = [
            r.t,
            r.hip[0],
            r.hip[1],
            r.hip[2],
            r.proxy[0],
            r.proxy[1],
            r.proxy[2],
            r.force[0],
            r.force[1],
            r.force[2],
            id(r.object),
            id(r.triangle),
            f64::from(r.status),
            r.penetration,
            f64::from(u8::from(r.sticking)),
        ];
        for v in values {
            out.extend_from_slice(&(v as f32).to_le_bytes());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encodes_every_row() {
        let text = format!(
            "{}\n0,0,0,0.2,0,0,0.2,0,0,0,0,,,free,0,0,0,0\n0.001,0,0,0.09,0,0,0.1,0,0,3,1,0,17,sticking,0.01,1,0,0\n",
            haphe::servo::CSV_HEADER
        );
        let trace = Trace::read("t.csv", text.as_bytes()).expect("reads");
        let bytes = encode_trace(&trace);
        assert_eq!(bytes.len(), 2 * ROW_VALUES * 4);
        let value = |row: usize, k: usize| {
            let at = (row * ROW_VALUES + k) * 4;
            f32::from_le_bytes(bytes[at..at + 4].try_into().expect("four bytes"))
        };
        // Row 1: force z 3, object 0, triangle 17, the code of "sticking", sticking 1.
        assert_eq!((value(1, 9), value(1, 10), value(1, 11)), (3.0, 0.0, 17.0));
        let sticking = STATUS_NAMES
            .iter()
            .position(|s| *s == "sticking")
            .expect("a status");
        assert_eq!((value(1, 12), value(1, 14)), (sticking as f32, 1.0));
        // Row 0: free, no object or triangle.
        assert_eq!((value(0, 10), value(0, 11)), (-1.0, -1.0));
    }
}
