//! STL reader, ASCII and binary, told apart by content.
//!
//! A binary STL is an 80-byte header, a little-endian `u32` triangle count and 50 bytes per
//! triangle (normal, three corners as `f32`, a 2-byte attribute). Many exporters start the
//! header with `solid`, like an ASCII file, so the size decides: a file of at least 84 bytes
//! whose size is exactly `84 + 50 × count` is binary; otherwise a file starting with `solid`
//! is ASCII; anything else is a binary file of the wrong size, reported with the expected
//! and actual size.
//!
//! Both are parsed here: binary files in a straight pass over 50-byte records, ASCII files
//! word by word with the tokenizer of the other text formats (`text.rs`), so that an error
//! names the line of the word at fault and the facet (counted from 0 over the whole
//! file). Several solids in one ASCII file are all read.
//!
//! STL has no shared vertices: each triangle gets three new vertices, in file units, and
//! `read_mesh` welds them. The facet normals are ignored (haphe computes its own from the
//! winding).

use glam::DVec3;

use super::text::{Words, show};
use super::{skip_ascii_whitespace, starts_with_word};
use crate::mesh::{Mesh, Place, ReadErrorKind};

/// Size of the binary header: 80 bytes of text plus the `u32` triangle count.
const HEADER_BYTES: usize = 84;
/// Size of one binary triangle record.
const RECORD_BYTES: usize = 50;
/// Most triangles whose corners fit 32-bit vertex indices.
const MAX_TRIANGLES: usize = u32::MAX as usize / 3;

/// Reads STL bytes into a mesh in file units (three vertices per triangle).
///
/// # Errors
/// A binary file of the wrong size ([`ReadErrorKind::Truncated`] or
/// [`ReadErrorKind::Syntax`] with the byte offset, expected and actual size), a non-finite
/// coordinate (its byte offset, or the facet's line in ASCII), an ASCII syntax error (the
/// facet and its line), [`ReadErrorKind::Empty`] for no content.
pub(super) fn read_stl(bytes: &[u8]) -> Result<Mesh, ReadErrorKind> {
    let text = skip_ascii_whitespace(bytes);
    if text.is_empty() {
        return Err(ReadErrorKind::Empty);
    }
    if looks_binary(bytes) {
        return read_binary(bytes);
    }
    if starts_with_word(text, b"solid") {
        let skipped = bytes.len() - text.len();
        let line_offset = bytes[..skipped].iter().filter(|&&b| b == b'\n').count();
        return read_ascii(text, line_offset).map_err(|e| with_binary_hint(e, bytes));
    }
    Err(binary_size_error(bytes))
}

/// True when the size matches a binary STL's triangle count.
pub(super) fn looks_binary(bytes: &[u8]) -> bool {
    announced_count(bytes).is_some_and(|count| expected_size(count) == bytes.len() as u64)
}

/// The triangle count in a binary header, when there is a header.
fn announced_count(bytes: &[u8]) -> Option<u32> {
    let count: [u8; 4] = bytes.get(80..HEADER_BYTES)?.try_into().ok()?;
    Some(u32::from_le_bytes(count))
}

/// The size of a binary STL with `count` triangles.
fn expected_size(count: u32) -> u64 {
    HEADER_BYTES as u64 + RECORD_BYTES as u64 * u64::from(count)
}

/// The error for a file that is neither ASCII nor a binary STL of the right size.
fn binary_size_error(bytes: &[u8]) -> ReadErrorKind {
    let len = bytes.len() as u64;
    let Some(count) = announced_count(bytes) else {
        return ReadErrorKind::Truncated {
            at: Place::Byte(len),
            message: format!(
                "not an ASCII STL (no 'solid'), and a binary STL needs an {HEADER_BYTES}-byte \
                 header; the file has {len} bytes"
            ),
        };
    };
    let expected = expected_size(count);
    if len < expected {
        ReadErrorKind::Truncated {
            at: Place::Byte(len),
            message: format!(
                "the binary header announces {count} triangles ({expected} bytes), the file \
                 has {len} bytes"
            ),
        }
    } else {
        ReadErrorKind::Syntax {
            at: Place::Byte(expected),
            message: format!(
                "the binary header announces {count} triangles ({expected} bytes), the file \
                 has {len} bytes: {} bytes after the last triangle",
                len - expected
            ),
        }
    }
}

/// Adds to an ASCII error the size check of a binary reading, for binary files whose header
/// starts with `solid` but whose size is wrong.
fn with_binary_hint(error: ReadErrorKind, bytes: &[u8]) -> ReadErrorKind {
    let Some(count) = announced_count(bytes) else {
        return error;
    };
    let hint = format!(
        " (if this is a binary STL: its header announces {count} triangles = {} bytes, the \
         file has {} bytes)",
        expected_size(count),
        bytes.len()
    );
    match error {
        ReadErrorKind::Syntax { at, message } => ReadErrorKind::Syntax {
            at,
            message: message + &hint,
        },
        ReadErrorKind::Truncated { at, message } => ReadErrorKind::Truncated {
            at,
            message: message + &hint,
        },
        other => other,
    }
}

/// Reads a binary STL whose size has been checked.
fn read_binary(bytes: &[u8]) -> Result<Mesh, ReadErrorKind> {
    let records = &bytes[HEADER_BYTES..];
    let count = records.len() / RECORD_BYTES;
    if count > MAX_TRIANGLES {
        return Err(ReadErrorKind::TooLarge {
            at: Place::Byte(80),
            message: format!("{count} triangles need more than 32-bit vertex indices"),
        });
    }
    let mut vertices = Vec::with_capacity(3 * count);
    for (t, record) in records.chunks_exact(RECORD_BYTES).enumerate() {
        // Bytes 0..12 are the normal, 12..48 the three corners, 48..50 the attribute.
        let Ok(record) = <&[u8; RECORD_BYTES]>::try_from(record) else {
            continue; // never: chunks_exact gives whole records
        };
        let xyz: [f32; 9] = std::array::from_fn(|k| {
            let at = 12 + 4 * k;
            f32::from_le_bytes([record[at], record[at + 1], record[at + 2], record[at + 3]])
        });
        if !xyz.iter().all(|v| v.is_finite()) {
            let corner = xyz
                .chunks_exact(3)
                .position(|c| !c.iter().all(|v| v.is_finite()));
            return Err(ReadErrorKind::NonFinite {
                at: Place::Byte(
                    (HEADER_BYTES + t * RECORD_BYTES + 12 + 12 * corner.unwrap_or(0)) as u64,
                ),
            });
        }
        let corner = |c: usize| {
            DVec3::new(
                f64::from(xyz[3 * c]),
                f64::from(xyz[3 * c + 1]),
                f64::from(xyz[3 * c + 2]),
            )
        };
        vertices.extend_from_slice(&[corner(0), corner(1), corner(2)]);
    }
    Ok(soup(vertices))
}

/// Triangles over consecutive vertex triples.
fn soup(vertices: Vec<DVec3>) -> Mesh {
    let triangles = (0..vertices.len() as u32 / 3)
        .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
        .collect();
    Mesh {
        vertices,
        triangles,
    }
}

/// Reads an ASCII STL (`text` starts with `solid`; `line_offset` lines precede it), one
/// solid after the other:
///
/// ```text
/// solid [name]
///   facet normal nx ny nz
///     outer loop
///       vertex x y z        (three times)
///     endloop
///   endfacet                (any number of facets)
/// endsolid [name]
/// ```
///
/// Coordinates are single-precision numbers, as in a binary STL (read as `f32`, then
/// widened). What follows the last `endsolid`, other than another solid, is ignored.
fn read_ascii(text: &[u8], line_offset: usize) -> Result<Mesh, ReadErrorKind> {
    let mut words = Words::new(text, line_offset + 1);
    let mut vertices = Vec::new();
    let mut facets = 0usize;
    while let Some((line, _solid)) = words.next_word() {
        // The name: any text, but text (a binary header that starts with "solid" is not).
        if std::str::from_utf8(words.rest_of_line()).is_err() {
            return Err(ReadErrorKind::Syntax {
                at: Place::Line(line),
                message: "the 'solid' line of an ASCII STL is not text".to_owned(),
            });
        }
        loop {
            let (line, word) = next_or_truncated(&mut words, "'facet' or 'endsolid'", facets)?;
            match word {
                b"endsolid" => {
                    words.rest_of_line();
                    break;
                }
                b"facet" => {
                    if 3 * (facets + 1) > u32::MAX as usize {
                        return Err(ReadErrorKind::TooLarge {
                            at: Place::Line(line),
                            message: format!(
                                "{} facets need more than 32-bit vertex indices",
                                facets + 1
                            ),
                        });
                    }
                    read_facet(&mut words, facets, &mut vertices)?;
                    facets += 1;
                }
                other => return Err(unexpected(line, facets, "'facet' or 'endsolid'", other)),
            }
        }
        // Another solid may follow.
        if !words.peek_is(b"solid") {
            break;
        }
    }
    Ok(soup(vertices))
}

/// Reads facet number `facet` after its `facet` keyword, appending its three corners.
fn read_facet(
    words: &mut Words<'_>,
    facet: usize,
    vertices: &mut Vec<DVec3>,
) -> Result<(), ReadErrorKind> {
    expect(words, b"normal", facet)?;
    for _ in 0..3 {
        // The facet normal is read as a number and ignored: haphe takes the winding.
        number(words, facet)?;
    }
    expect(words, b"outer", facet)?;
    expect(words, b"loop", facet)?;
    for _ in 0..3 {
        let line = expect(words, b"vertex", facet)?;
        let corner = [
            number(words, facet)?,
            number(words, facet)?,
            number(words, facet)?,
        ];
        if !corner.iter().all(|v| v.is_finite()) {
            return Err(ReadErrorKind::NonFinite {
                at: Place::Line(line),
            });
        }
        vertices.push(DVec3::from_array(corner.map(f64::from)));
    }
    expect(words, b"endloop", facet)?;
    expect(words, b"endfacet", facet)?;
    Ok(())
}

/// The next word, or the error of a file that ends in or after facet `facet` where `what`
/// should follow.
fn next_or_truncated<'a>(
    words: &mut Words<'a>,
    what: &str,
    facet: usize,
) -> Result<(usize, &'a [u8]), ReadErrorKind> {
    words.next_word().ok_or_else(|| ReadErrorKind::Truncated {
        at: Place::Line(words.end_line()),
        message: format!("facet {facet}: the file ends where {what} should follow"),
    })
}

/// Reads the keyword `keyword` of facet `facet`; returns its line.
fn expect(words: &mut Words<'_>, keyword: &[u8], facet: usize) -> Result<usize, ReadErrorKind> {
    let (line, word) = words.next_word().ok_or_else(|| ReadErrorKind::Truncated {
        at: Place::Line(words.end_line()),
        message: format!(
            "facet {facet}: the file ends where '{}' should follow",
            show(keyword)
        ),
    })?;
    if word == keyword {
        Ok(line)
    } else {
        Err(unexpected(
            line,
            facet,
            &format!("'{}'", show(keyword)),
            word,
        ))
    }
}

/// Reads a number of facet `facet`.
fn number(words: &mut Words<'_>, facet: usize) -> Result<f32, ReadErrorKind> {
    let (line, word) = next_or_truncated(words, "a number", facet)?;
    std::str::from_utf8(word)
        .ok()
        .and_then(|w| w.parse::<f32>().ok())
        .ok_or_else(|| unexpected(line, facet, "a number", word))
}

/// The error for `found` on `line` in facet `facet` where `what` was expected.
fn unexpected(line: usize, facet: usize, what: &str, found: &[u8]) -> ReadErrorKind {
    ReadErrorKind::Syntax {
        at: Place::Line(line),
        message: format!("facet {facet}: expected {what}, found '{}'", show(found)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A binary STL with `header` (padded to 80 bytes) and the given triangles.
    fn binary(header: &[u8], triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
        let mut bytes = header.to_vec();
        bytes.resize(80, b' ');
        bytes.extend((triangles.len() as u32).to_le_bytes());
        for t in triangles {
            bytes.extend([0u8; 12]);
            for v in t {
                for x in v {
                    bytes.extend(x.to_le_bytes());
                }
            }
            bytes.extend([0u8; 2]);
        }
        bytes
    }

    const TRI: [[f32; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    const TRI2: [[f32; 3]; 3] = [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];

    const ASCII: &str = "solid square\n\
        facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\n\
        facet normal 0 0 1\n outer loop\n  vertex 1 0 0\n  vertex 1 1 0\n  vertex 0 1 0\n endloop\nendfacet\n\
        endsolid square\n";

    #[test]
    fn binary_with_a_solid_header_is_binary() {
        let bytes = binary(b"solid trap", &[TRI, TRI2]);
        assert!(looks_binary(&bytes));
        let mesh = read_stl(&bytes).unwrap();
        assert_eq!(mesh.vertices.len(), 6);
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [3, 4, 5]]);
        assert_eq!(mesh.vertices[4], DVec3::new(1.0, 1.0, 0.0));
    }

    #[test]
    fn empty_binary_has_no_triangles() {
        let mesh = read_stl(&binary(b"", &[])).unwrap();
        assert!(mesh.triangles.is_empty() && mesh.vertices.is_empty());
    }

    #[test]
    fn truncated_binary_names_the_sizes() {
        let bytes = binary(b"bin", &[TRI, TRI2]);
        let cut = &bytes[..bytes.len() - 7];
        assert_eq!(
            read_stl(cut),
            Err(ReadErrorKind::Truncated {
                at: Place::Byte(177),
                message: "the binary header announces 2 triangles (184 bytes), the file has \
                          177 bytes"
                    .into()
            })
        );
        let mut long = bytes.clone();
        long.extend([0u8; 3]);
        assert!(matches!(
            read_stl(&long),
            Err(ReadErrorKind::Syntax {
                at: Place::Byte(184),
                ..
            })
        ));
        assert!(matches!(
            read_stl(&bytes[..50]),
            Err(ReadErrorKind::Truncated {
                at: Place::Byte(50),
                ..
            })
        ));
        assert_eq!(read_stl(b""), Err(ReadErrorKind::Empty));
    }

    #[test]
    fn truncated_binary_with_solid_header_hints_at_the_size() {
        let bytes = binary(b"solid x", &[TRI, TRI2]);
        let err = read_stl(&bytes[..150]).unwrap_err();
        assert!(
            err.to_string()
                .contains("announces 2 triangles = 184 bytes"),
            "{err}"
        );
    }

    #[test]
    fn binary_non_finite_names_the_byte() {
        let mut t = TRI2;
        t[1][2] = f32::INFINITY;
        let err = read_stl(&binary(b"", &[TRI, t])).unwrap_err();
        // Second record at 134; its second corner at 134 + 24.
        assert_eq!(
            err,
            ReadErrorKind::NonFinite {
                at: Place::Byte(158)
            }
        );
    }

    #[test]
    fn ascii_square() {
        let mesh = read_stl(ASCII.as_bytes()).unwrap();
        assert_eq!(mesh.triangles.len(), 2);
        assert_eq!(mesh.vertices[4], DVec3::new(1.0, 1.0, 0.0));
        let crlf = ASCII.replace('\n', "\r\n");
        assert_eq!(read_stl(crlf.as_bytes()).unwrap(), mesh);
        let indented = format!("\n  {}", ASCII.replace("solid square\n", "solid\n\n"));
        assert_eq!(read_stl(indented.as_bytes()).unwrap(), mesh);
    }

    #[test]
    fn ascii_empty_solid() {
        let mesh = read_stl(b"solid Empty\nendsolid Empty").unwrap();
        assert!(mesh.triangles.is_empty());
    }

    #[test]
    fn ascii_several_solids() {
        let twice = format!("{ASCII}\n{}", ASCII.replace("square", "again"));
        assert_eq!(read_stl(twice.as_bytes()).unwrap().triangles.len(), 4);
    }

    #[test]
    fn many_solids_read_in_linear_time() {
        // Regression: each solid used to rescan (and, without a name, copy) the rest of the
        // file: 16 000 empty solids took 1.5 s, 180 000 would take minutes.
        for unit in ["solid\nendsolid\n", "solid a\nendsolid a\n"] {
            let text = unit.repeat(100_000);
            let start = std::time::Instant::now();
            assert!(read_stl(text.as_bytes()).unwrap().triangles.is_empty());
            assert!(start.elapsed().as_secs_f64() < 2.0, "{:?}", start.elapsed());
        }
    }

    #[test]
    fn ascii_errors_name_facet_and_line() {
        let bad = ASCII.replacen("vertex 1 1 0", "vertex 1 x 0", 1);
        let err = read_stl(bad.as_bytes()).unwrap_err();
        assert!(
            matches!(&err, ReadErrorKind::Syntax { at: Place::Line(12), message } if message.starts_with("facet 1: expected a number, found 'x'")),
            "{err:?}"
        );
        let bad = ASCII.replacen("outer loop", "outer lop", 1);
        let err = read_stl(bad.as_bytes()).unwrap_err();
        assert!(
            matches!(&err, ReadErrorKind::Syntax { at: Place::Line(3), message } if message.starts_with("facet 0: expected 'loop', found 'lop'")),
            "{err:?}"
        );
        let non_finite = ASCII.replacen("vertex 1 1 0", "vertex 1 1e39 0", 1);
        assert_eq!(
            read_stl(non_finite.as_bytes()),
            Err(ReadErrorKind::NonFinite {
                at: Place::Line(12)
            })
        );
        // In the second solid, lines and facets count from the start of the file.
        let twice = format!("{ASCII}{}", bad);
        let err = read_stl(twice.as_bytes()).unwrap_err();
        assert!(
            matches!(&err, ReadErrorKind::Syntax { at: Place::Line(19), message } if message.starts_with("facet 2: expected 'loop', found 'lop'")),
            "{err:?}"
        );
        // A word where a facet or the end of the solid should be.
        let stray = ASCII.replacen("endsolid", "endsolidx", 1);
        let err = read_stl(stray.as_bytes()).unwrap_err();
        assert!(
            matches!(&err, ReadErrorKind::Syntax { at: Place::Line(16), message } if message.starts_with("facet 2: expected 'facet' or 'endsolid', found 'endsolidx'")),
            "{err:?}"
        );
    }

    #[test]
    fn ascii_truncated() {
        let cut = &ASCII[..ASCII.find("endfacet\nendsolid").unwrap()];
        let err = read_stl(cut.as_bytes()).unwrap_err();
        assert!(
            matches!(
                err,
                ReadErrorKind::Truncated {
                    at: Place::Line(15),
                    ..
                }
            ),
            "{err:?}"
        );
        let no_end = &ASCII[..ASCII.find("endsolid").unwrap()];
        let err = read_stl(no_end.as_bytes()).unwrap_err();
        assert!(
            matches!(
                err,
                ReadErrorKind::Truncated {
                    at: Place::Line(16),
                    ..
                }
            ),
            "{err:?}"
        );
    }

    #[test]
    fn ascii_with_a_binary_solid_line_is_not_read_as_binary() {
        // Too short for its count, starts with "solid", not UTF-8: an error, not garbage.
        let mut bytes = binary(b"solid \xff\xfe", &[TRI, TRI2]);
        bytes.truncate(150);
        let err = read_stl(&bytes).unwrap_err();
        assert!(
            matches!(
                err,
                ReadErrorKind::Syntax {
                    at: Place::Line(1),
                    ..
                }
            ),
            "{err:?}"
        );
    }

    #[test]
    fn neither_ascii_nor_binary() {
        assert!(matches!(
            read_stl(b"hello"),
            Err(ReadErrorKind::Truncated { .. })
        ));
    }
}
