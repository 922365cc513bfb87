//! Checks of the PLY header: a scan before `ply-rs-bw` reads it, and the layout of each
//! element before its entries are read.

use ply_rs_bw::ply::{ElementDef, PropertyType, ScalarType};
use rustc_hash::{FxHashMap, FxHashSet};

use super::source::{Source, min_entry_bytes};
use crate::mesh::{Place, ReadErrorKind};

/// What the scan learnt: where each element is declared.
pub(super) struct Scan {
    /// Element names with their declaration line.
    elements: FxHashMap<String, usize>,
}

impl Scan {
    /// The line declaring element `name` (the header if unknown).
    pub(super) fn element_place(&self, name: &str) -> Place {
        self.elements
            .get(name)
            .map_or(Place::Header, |&line| Place::Line(line))
    }
}

/// Scans the header lines: `ply` first, text only, no element or property declared twice,
/// an `end_header` line. The grammar of each line is left to `ply-rs-bw`.
pub(super) fn scan(bytes: &[u8]) -> Result<Scan, ReadErrorKind> {
    let mut elements: FxHashMap<String, usize> = FxHashMap::default();
    let mut properties: FxHashSet<&str> = FxHashSet::default();
    for (n, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let number = n + 1;
        let Ok(text) = std::str::from_utf8(raw) else {
            return Err(ReadErrorKind::Syntax {
                at: Place::Line(number),
                message: "the PLY header is not text".to_owned(),
            });
        };
        let mut words = text.split_ascii_whitespace();
        let first = words.next();
        if number == 1 {
            if first != Some("ply") || words.next().is_some() {
                return Err(ReadErrorKind::Syntax {
                    at: Place::Line(1),
                    message: "not a PLY file: the first line must be 'ply'".to_owned(),
                });
            }
            continue;
        }
        let twice = |what: &str, name: &str| ReadErrorKind::Syntax {
            at: Place::Line(number),
            message: format!("{what} '{name}' is declared twice"),
        };
        match first {
            Some("end_header") => return Ok(Scan { elements }),
            Some("element") => {
                if let Some(name) = words.next()
                    && elements.insert(name.to_owned(), number).is_some()
                {
                    return Err(twice("element", name));
                }
                properties.clear();
            }
            Some("property") => {
                if let Some(name) = words.last()
                    && !properties.insert(name)
                {
                    return Err(twice("property", name));
                }
            }
            _ => {}
        }
    }
    // The header ran to the end of the file: the missing line comes after the last one.
    let lines = bytes.iter().filter(|&&b| b == b'\n').count()
        + usize::from(bytes.last().is_some_and(|&b| b != b'\n'));
    Err(ReadErrorKind::Truncated {
        at: Place::Line(lines + 1),
        message: "the PLY header has no 'end_header' line".to_owned(),
    })
}

/// Checks an element before its entries are read: some property if it has entries, and in
/// a binary file, enough bytes left for the announced count.
pub(super) fn check_element(
    def: &ElementDef,
    declared: Place,
    source: &Source<'_>,
) -> Result<(), ReadErrorKind> {
    if def.count > 0 && def.properties.is_empty() {
        return Err(ReadErrorKind::Syntax {
            at: declared,
            message: format!(
                "element '{}' announces {} entries but has no properties",
                def.name, def.count
            ),
        });
    }
    if let Some(left) = source.binary_bytes_left() {
        let min = min_entry_bytes(def);
        if def.count.checked_mul(min).is_none_or(|need| need > left) {
            return Err(ReadErrorKind::Truncated {
                at: source.place(),
                message: format!(
                    "element '{}' announces {} entries of at least {min} bytes, {left} bytes \
                     are left",
                    def.name, def.count
                ),
            });
        }
    }
    Ok(())
}

/// Checks that `def` has an index list under one of `names`, with integer length and items.
pub(super) fn check_index_list(
    def: &ElementDef,
    declared: Place,
    names: &[&str],
) -> Result<(), ReadErrorKind> {
    let integer = |s: &ScalarType| !matches!(s, ScalarType::Float | ScalarType::Double);
    let list = names.iter().find_map(|&n| def.properties.get(n));
    match list.map(|p| &p.data_type) {
        Some(PropertyType::List(length, item)) if integer(length) && integer(item) => Ok(()),
        _ => Err(ReadErrorKind::Syntax {
            at: declared,
            message: format!(
                "element '{}' has no integer list property '{}'",
                def.name, names[0]
            ),
        }),
    }
}
