//! Where the entries of a PLY payload come from, and how ply-rs-bw errors become ours.

use ply_rs_bw::parser::{ParseError, Parser};
use ply_rs_bw::ply::{ElementDef, PropertyAccess, PropertyType, ScalarType};

use crate::mesh::{Place, ReadErrorKind};

/// Longest message kept from a `ply-rs-bw` error (it quotes whole lines).
const MAX_MESSAGE_CHARS: usize = 240;

/// Where the entries come from: ASCII lines or binary records.
pub(super) enum Source<'a> {
    Ascii {
        /// The payload after the header.
        text: &'a [u8],
        /// Read position in `text`.
        pos: usize,
        /// Number of the last line read.
        line: usize,
    },
    Binary {
        /// The bytes not read yet.
        rest: &'a [u8],
        /// The file's size, to turn `rest` into an offset.
        total: usize,
        big_endian: bool,
    },
}

impl Source<'_> {
    /// How many entries may be reserved for a `count` from the header: never more than the
    /// bytes left could hold (a hostile count must not allocate gigabytes).
    pub(super) fn capacity_for(&self, count: usize) -> usize {
        let left = match self {
            Source::Ascii { text, pos, .. } => text.len().saturating_sub(*pos) / 2,
            Source::Binary { rest, .. } => rest.len(),
        };
        count.min(left)
    }

    /// The bytes left in a binary payload (`None` for ASCII).
    pub(super) fn binary_bytes_left(&self) -> Option<usize> {
        match self {
            Source::Ascii { .. } => None,
            Source::Binary { rest, .. } => Some(rest.len()),
        }
    }

    /// The place where the next entry starts.
    pub(super) fn place(&self) -> Place {
        match self {
            Source::Ascii { line, .. } => Place::Line(line + 1),
            Source::Binary { rest, total, .. } => Place::Byte((total - rest.len()) as u64),
        }
    }

    /// Reads entry `index` of element `def`.
    pub(super) fn entry<E: PropertyAccess>(
        &mut self,
        parser: &Parser<E>,
        def: &ElementDef,
        index: usize,
    ) -> Result<E, ReadErrorKind> {
        let ends_early = |at: Place| ReadErrorKind::Truncated {
            at,
            message: format!(
                "element '{}' announces {} entries, the file ends in entry {index}",
                def.name, def.count
            ),
        };
        match self {
            Source::Ascii { text, pos, line } => {
                // The next line with content (blank lines are skipped).
                let content = loop {
                    if *pos >= text.len() {
                        return Err(ends_early(Place::Line(*line + 1)));
                    }
                    let rest = &text[*pos..];
                    let len = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
                    *pos += len + 1;
                    *line += 1;
                    if !rest[..len].trim_ascii().is_empty() {
                        break &rest[..len];
                    }
                };
                let at = Place::Line(*line);
                let content = std::str::from_utf8(content).map_err(|_| ReadErrorKind::Syntax {
                    at,
                    message: "an ASCII entry is not text".to_owned(),
                })?;
                parser
                    .read_ascii_element(content, def)
                    .map_err(|e| map_parse_error(&e, at))
            }
            Source::Binary {
                rest,
                total,
                big_endian,
            } => {
                let at = Place::Byte((*total - rest.len()) as u64);
                let result = if *big_endian {
                    parser.read_big_endian_element(rest, def)
                } else {
                    parser.read_little_endian_element(rest, def)
                };
                result.map_err(|e| match e.kind() {
                    std::io::ErrorKind::UnexpectedEof => ends_early(at),
                    _ => map_parse_error(&e, at),
                })
            }
        }
    }
}

/// Turns a `ply-rs-bw` error into ours: its line when it has one, else `fallback`; its
/// multi-line message folded onto one line and shortened.
pub(super) fn map_parse_error(error: &ParseError, fallback: Place) -> ReadErrorKind {
    let at = error.line().map_or(fallback, Place::Line);
    let text = error.to_string();
    // Its Display starts with "Line N: " when it has a line; we print the place ourselves.
    let text = match (error.line(), text.split_once(": ")) {
        (Some(_), Some((prefix, rest))) if prefix.starts_with("Line ") => rest,
        _ => text.as_str(),
    };
    let mut message: String = text
        .split(['\n', '\t'])
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .collect::<Vec<_>>()
        .join("; ");
    if let Some((cut, _)) = message.char_indices().nth(MAX_MESSAGE_CHARS) {
        message.truncate(cut);
        message.push('…');
    }
    if error.kind() == std::io::ErrorKind::UnexpectedEof {
        ReadErrorKind::Truncated { at, message }
    } else {
        ReadErrorKind::Syntax { at, message }
    }
}

/// Size in bytes of a binary scalar.
fn scalar_bytes(scalar: &ScalarType) -> usize {
    match scalar {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    }
}

/// Smallest binary size of one entry: scalars, and list lengths with empty lists.
pub(super) fn min_entry_bytes(def: &ElementDef) -> usize {
    def.properties
        .values()
        .map(|p| match &p.data_type {
            PropertyType::Scalar(s) | PropertyType::List(s, _) => scalar_bytes(s),
        })
        .sum()
}
