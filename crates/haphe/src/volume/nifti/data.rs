//! The data of a NIfTI-1 file: the gzip stream decompressed no further than the header's
//! data need, and the first volume's values decoded (either byte order, every scalar
//! datatype read) and scaled by `scl_slope` and `scl_inter`.

use std::io::Read;

use flate2::read::MultiGzDecoder;

use super::error::{ReadVolumeError as Kind, header_error, truncated};
use super::header::{ByteOrder, Datatype, HEADER_BYTES, Layout, layout};

/// The most bytes deflate makes of one compressed byte (its longest run, 258 bytes, costs
/// at least two bits: 1032 per byte). A header announcing more data than the compressed
/// bytes could hold is refused before anything is decompressed.
const DEFLATE_MAX_RATIO: u64 = 1032;
/// The first step of the decompressed buffer's growth; it then doubles, never past what
/// the header announces.
const FIRST_CHUNK_BYTES: u64 = 1 << 20;

/// Whether `bytes` start with gzip's magic (`1f 8b`).
pub(super) fn is_gzip(bytes: &[u8]) -> bool {
    bytes.starts_with(&[0x1f, 0x8b])
}

/// Decompresses a gzip file: its header first, checked; then the data up to the end of the
/// first volume, and no further.
///
/// # Errors
/// A corrupt or truncated stream, a header error, data the stream cannot hold.
pub(super) fn inflate(bytes: &[u8]) -> Result<(Layout, Vec<u8>), Kind> {
    let mut stream = MultiGzDecoder::new(bytes);
    let mut file = Vec::with_capacity(HEADER_BYTES);
    read_up_to(&mut stream, &mut file, HEADER_BYTES as u64)?;
    let layout = layout(&file).map_err(|e| match e {
        Kind::Truncated {
            needed, available, ..
        } => truncated("decompressed stream", needed, available),
        other => other,
    })?;
    let end = layout.end();
    let most = (bytes.len() as u64).saturating_mul(DEFLATE_MAX_RATIO);
    if end > most {
        return Err(header_error(
            "dim",
            format!(
                "the data end at byte {end}, beyond the {most} bytes that {} compressed bytes \
                 can hold",
                bytes.len()
            ),
        ));
    }
    read_up_to(&mut stream, &mut file, end)?;
    if (file.len() as u64) < end {
        return Err(truncated("decompressed stream", end, file.len() as u64));
    }
    Ok((layout, file))
}

/// Reads `stream` into `out` until it holds `end` bytes or the stream ends; the buffer
/// grows by doubling from [`FIRST_CHUNK_BYTES`], never beyond `end`.
fn read_up_to(stream: &mut impl Read, out: &mut Vec<u8>, end: u64) -> Result<(), Kind> {
    while (out.len() as u64) < end {
        let have = out.len() as u64;
        let step = (end - have).min(have.max(FIRST_CHUNK_BYTES));
        out.reserve_exact(step as usize);
        let read = stream
            .by_ref()
            .take(step)
            .read_to_end(out)
            .map_err(|e| Kind::Gzip {
                file: String::new(),
                message: e.to_string(),
            })?;
        if (read as u64) < step {
            break;
        }
    }
    Ok(())
}

/// The values of `data` (the first volume's bytes) as `f32`, scaled by `slope` and `inter`
/// when a slope is given.
pub(super) fn decode(
    data: &[u8],
    datatype: Datatype,
    order: ByteOrder,
    scale: Option<(f64, f64)>,
) -> Vec<f32> {
    macro_rules! values {
        ($t:ty) => {{
            let (chunks, _) = data.as_chunks::<{ size_of::<$t>() }>();
            let read = |b: &[u8; size_of::<$t>()]| match order {
                ByteOrder::Little => <$t>::from_le_bytes(*b),
                ByteOrder::Big => <$t>::from_be_bytes(*b),
            };
            match scale {
                None => chunks.iter().map(|b| read(b) as f32).collect(),
                Some((slope, inter)) => chunks
                    .iter()
                    .map(|b| (read(b) as f64 * slope + inter) as f32)
                    .collect(),
            }
        }};
    }
    match datatype.name {
        "uint8" => values!(u8),
        "int8" => values!(i8),
        "uint16" => values!(u16),
        "int16" => values!(i16),
        "uint32" => values!(u32),
        "int32" => values!(i32),
        "uint64" => values!(u64),
        "int64" => values!(i64),
        "float32" => values!(f32),
        _ => values!(f64),
    }
}

/// The scaling of the values: `Some((slope, inter))` when `scl_slope` is non-zero and
/// finite and not the identity (nibabel's rule), else `None`.
///
/// # Errors
/// A slope that applies with an intercept that is not finite.
pub(super) fn scaling(slope: f32, inter: f32) -> Result<Option<(f64, f64)>, Kind> {
    if slope == 0.0 || !slope.is_finite() || (slope == 1.0 && inter == 0.0) {
        return Ok(None);
    }
    if !inter.is_finite() {
        return Err(header_error(
            "scl_inter",
            format!("{inter} with scl_slope {slope}: the intercept must be finite"),
        ));
    }
    Ok(Some((slope.into(), inter.into())))
}
