//! The glTF container and its buffers: a `.glb` (a header, a JSON chunk, a BIN chunk) or
//! a `.gltf` (JSON text), and the bytes of each buffer the meshes need, from the GLB's BIN
//! chunk, a `data:` URI or a side-car file fetched through a [`Resolve`].

use base64::Engine;
use gltf::json;

use super::places::{ix, place};
use crate::mesh::{GltfPlace, Place, ReadErrorKind};

/// The first four bytes of a binary glTF (`.glb`) file.
pub(crate) const GLB_MAGIC: &[u8; 4] = b"glTF";
const GLB_HEADER_BYTES: usize = 12;
const CHUNK_HEADER_BYTES: usize = 8;
const CHUNK_JSON: &[u8; 4] = b"JSON";
const CHUNK_BIN: &[u8; 4] = b"BIN\0";

/// Fetches the side-car files a `.gltf` refers to (its `.bin` buffers): the front end
/// that read the `.gltf` from a path resolves the names relative to it, and keeps to its
/// own size limit. The reader itself opens no files.
pub trait Resolve {
    /// The bytes of the file named `uri` (a relative reference, percent-decoded, such as
    /// `Box0.bin`). The reader needs its first `byte_length` bytes (the buffer's
    /// `byteLength`); a resolver may return just those, and must refuse a file it will
    /// not read (too large, absent) with a message saying why.
    ///
    /// # Errors
    /// Why the file cannot be had; the reader names the buffer and the URI around it.
    fn resolve(&mut self, uri: &str, byte_length: u64) -> Result<Vec<u8>, String>;
}

/// A resolver for bytes that came without a folder: every side-car file is refused (a
/// `.glb` and a `.gltf` with `data:` URIs need none).
#[derive(Debug, Clone, Copy, Default)]
pub struct NoSideCars;

impl Resolve for NoSideCars {
    fn resolve(&mut self, _uri: &str, _byte_length: u64) -> Result<Vec<u8>, String> {
        Err(
            "the glTF was given as bytes alone, with no folder to read side-car files \
             from; read it from its path, or use a .glb"
                .to_owned(),
        )
    }
}

/// The document of a glTF file and the GLB's binary chunk, if any.
pub(super) struct Container<'a> {
    pub root: json::Root,
    pub bin: Option<&'a [u8]>,
}

fn u32_at(bytes: &[u8], at: usize) -> Option<u32> {
    let word = bytes.get(at..at.checked_add(4)?)?;
    Some(u32::from_le_bytes([word[0], word[1], word[2], word[3]]))
}

/// Splits a `.glb` into its JSON chunk and BIN chunk, checking every length; other
/// chunk types after them are ignored, as the format asks.
fn split_glb(bytes: &[u8]) -> Result<(&[u8], Option<&[u8]>), ReadErrorKind> {
    let header_error = |message: String| ReadErrorKind::Invalid {
        at: Place::Header,
        message,
    };
    let (Some(version), Some(length)) = (u32_at(bytes, 4), u32_at(bytes, 8)) else {
        return Err(ReadErrorKind::Truncated {
            at: Place::Byte(0),
            message: format!(
                "a .glb starts with a {GLB_HEADER_BYTES}-byte header; the file has {} bytes",
                bytes.len()
            ),
        });
    };
    if version != 2 {
        return Err(header_error(format!(
            "binary glTF version {version}; haphe reads glTF 2.0"
        )));
    }
    let length = length as usize;
    if length < GLB_HEADER_BYTES + CHUNK_HEADER_BYTES {
        return Err(header_error(format!(
            "the header gives a length of {length} bytes, too short for a JSON chunk"
        )));
    }
    if length > bytes.len() {
        return Err(ReadErrorKind::Truncated {
            at: Place::Byte(bytes.len() as u64),
            message: format!(
                "the header gives a length of {length} bytes; the file has {}",
                bytes.len()
            ),
        });
    }
    let bytes = &bytes[..length];
    let mut chunks = Vec::new();
    let mut at = GLB_HEADER_BYTES;
    while at < bytes.len() && chunks.len() < 2 {
        let (Some(chunk_length), Some(kind)) = (u32_at(bytes, at), bytes.get(at + 4..at + 8))
        else {
            return Err(ReadErrorKind::Truncated {
                at: Place::Byte(at as u64),
                message: "a chunk header of 8 bytes is cut short".to_owned(),
            });
        };
        let start = at + CHUNK_HEADER_BYTES;
        let end = start.saturating_add(chunk_length as usize);
        if end > bytes.len() {
            return Err(ReadErrorKind::Truncated {
                at: Place::Byte(at as u64),
                message: format!(
                    "a chunk of {chunk_length} bytes starting at byte {start} ends past the \
                     {} bytes of the file",
                    bytes.len()
                ),
            });
        }
        chunks.push((at, kind, &bytes[start..end]));
        // Chunks are padded to 4 bytes; the next one starts at the padded end.
        at = end.next_multiple_of(4);
    }
    let Some(&(_, kind, json)) = chunks.first() else {
        return Err(header_error("no JSON chunk after the header".to_owned()));
    };
    if kind != CHUNK_JSON {
        return Err(header_error(format!(
            "the first chunk is {:?}, not JSON",
            String::from_utf8_lossy(kind)
        )));
    }
    let bin = chunks
        .get(1)
        .filter(|(_, kind, _)| *kind == CHUNK_BIN)
        .map(|&(_, _, data)| data);
    Ok((json, bin))
}

/// Parses the container: the GLB's chunks, or the whole file as JSON.
pub(super) fn open(bytes: &[u8]) -> Result<Container<'_>, ReadErrorKind> {
    let (json_bytes, bin, glb) = if bytes.starts_with(GLB_MAGIC) {
        let (json, bin) = split_glb(bytes)?;
        (json, bin, true)
    } else {
        (bytes, None, false)
    };
    let root: json::Root = serde_json::from_slice(json_bytes).map_err(|e| {
        let what = if glb { "the JSON chunk: " } else { "" };
        ReadErrorKind::Syntax {
            at: if glb {
                Place::Header
            } else {
                Place::Line(e.line())
            },
            message: format!("{what}not a glTF 2.0 document: {e}"),
        }
    })?;
    Ok(Container { root, bin })
}

/// Whether `uri` starts with a scheme (`data:`, `https:`, `file:`; RFC 3986: a letter,
/// then letters, digits, `+`, `-` or `.`, then a colon).
fn scheme(uri: &str) -> Option<&str> {
    let (head, _) = uri.split_once(':')?;
    let mut chars = head.chars();
    let first = chars.next()?;
    (first.is_ascii_alphabetic()
        && chars.all(|c| c.is_ascii_alphanumeric() || matches!(c, '+' | '-' | '.')))
    .then_some(head)
}

/// The bytes of a `data:` URI: only base64 data is accepted, as glTF writers produce.
fn data_uri(uri: &str) -> Result<Vec<u8>, String> {
    let Some((header, data)) = uri.split_once(',') else {
        return Err("a data URI without a comma before its data".to_owned());
    };
    if !header.ends_with(";base64") {
        return Err(format!(
            "the data URI '{header},…' is not base64; glTF buffers are written as base64"
        ));
    }
    let engine = base64::engine::GeneralPurpose::new(
        &base64::alphabet::STANDARD,
        base64::engine::GeneralPurposeConfig::new()
            .with_decode_padding_mode(base64::engine::DecodePaddingMode::Indifferent)
            .with_decode_allow_trailing_bits(true),
    );
    engine
        .decode(data.trim())
        .map_err(|e| format!("its base64 data cannot be decoded: {e}"))
}

/// `uri` with its `%XX` escapes decoded (a file name with spaces is written `a%20b.bin`).
fn percent_decoded(uri: &str) -> Result<String, String> {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = bytes
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok())
                .and_then(|h| u8::from_str_radix(h, 16).ok())
                .ok_or_else(|| format!("a '%' not followed by two hex digits in '{uri}'"))?;
            out.push(hex);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| format!("'{uri}' does not decode to UTF-8 text"))
}

/// The bytes of every buffer in `needed` (the others stay `None`), each cut to its
/// `byteLength` after checking that it has that many.
pub(super) fn load_buffers(
    container: &Container<'_>,
    needed: &[bool],
    resolver: &mut dyn Resolve,
) -> Result<Vec<Option<Vec<u8>>>, ReadErrorKind> {
    let buffers = &container.root.buffers;
    let mut out = Vec::with_capacity(buffers.len());
    for (index, buffer) in buffers.iter().enumerate() {
        if !needed.get(index).copied().unwrap_or(false) {
            out.push(None);
            continue;
        }
        let at = place(GltfPlace {
            buffer: Some(ix(index)),
            ..GltfPlace::default()
        });
        let byte_length = buffer.byte_length.0;
        let (data, source) = match &buffer.uri {
            None => match (index, container.bin) {
                (0, Some(bin)) => (bin.to_vec(), "the BIN chunk".to_owned()),
                _ => {
                    return Err(ReadErrorKind::Invalid {
                        at,
                        message: "the buffer has no uri, and it is not the first buffer of a \
                                  .glb with a BIN chunk"
                            .to_owned(),
                    });
                }
            },
            Some(uri) => match scheme(uri) {
                Some(s) if s.eq_ignore_ascii_case("data") => {
                    let data = data_uri(uri).map_err(|message| ReadErrorKind::Invalid {
                        at,
                        message: format!("its data URI: {message}"),
                    })?;
                    (data, "its data URI".to_owned())
                }
                Some(_) => {
                    return Err(ReadErrorKind::Unsupported {
                        at,
                        message: format!(
                            "the buffer's URI '{uri}' is not a file beside the glTF file; \
                             haphe reads data URIs and relative file names only"
                        ),
                    });
                }
                None => {
                    let missing = |message: String| ReadErrorKind::MissingResource {
                        at,
                        uri: uri.clone(),
                        message,
                    };
                    let name = percent_decoded(uri).map_err(missing)?;
                    if name.starts_with('/') || name.starts_with('\\') {
                        return Err(missing(
                            "an absolute path; a glTF refers to files relative to itself"
                                .to_owned(),
                        ));
                    }
                    let data = resolver.resolve(&name, byte_length).map_err(missing)?;
                    (data, format!("the file '{uri}'"))
                }
            },
        };
        if (data.len() as u64) < byte_length {
            return Err(ReadErrorKind::Truncated {
                at,
                message: format!(
                    "{source} holds {} bytes, fewer than the buffer's byteLength of {byte_length}",
                    data.len()
                ),
            });
        }
        let mut data = data;
        data.truncate(byte_length as usize);
        out.push(Some(data));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn schemes_are_told_from_file_names() {
        assert_eq!(
            scheme("data:application/octet-stream;base64,AAAA"),
            Some("data")
        );
        assert_eq!(scheme("https://example.com/a.bin"), Some("https"));
        assert_eq!(scheme("box.bin"), None);
        assert_eq!(scheme("a b:c.bin"), None);
    }

    #[test]
    fn percent_escapes_are_decoded() {
        assert_eq!(percent_decoded("a%20b.bin").as_deref(), Ok("a b.bin"));
        assert!(percent_decoded("a%2").is_err());
    }

    #[test]
    fn data_uris_decode_with_or_without_padding() {
        assert_eq!(
            data_uri("data:application/octet-stream;base64,AQID"),
            Ok(vec![1, 2, 3])
        );
        assert_eq!(
            data_uri("data:application/gltf-buffer;base64,AQI"),
            Ok(vec![1, 2])
        );
        assert!(data_uri("data:text/plain,hello").is_err());
    }
}
