//! Object File Format (OFF) reader.
//!
//! ```text
//! [ST][C][N][4]OFF [nv nf ne]      keyword, counts on the same line or the next one
//! nv nf [ne]
//! x y z [normal, colour, texture coordinates ...]        nv lines
//! n i1 i2 ... in [colour ...]                            nf lines, 0-based indices
//! ```
//!
//! Comments (`#` to the end of a line) and blank lines may appear anywhere; leading white
//! space is fine, and the counts may follow the keyword without a space (`OFF8 6 12`). The
//! prefixes `C`, `N`, `ST` add values after the coordinates, which are ignored; `4OFF` has a
//! homogeneous `w` that divides `x y z`; `nOFF` is read when its dimension is 3. The keyword
//! itself is optional. Binary OFF is not supported (a clear error). Polygons are
//! triangulated ([`super::polygon`]).
//!
//! No crate was worth depending on for this: the format fits on a page.

use glam::DVec3;

use super::polygon::Triangulator;
use super::text::{self, tokens};
use crate::mesh::{Mesh, Place, ReadErrorKind};

/// The meaningful lines of an OFF file: comments stripped, blank lines skipped, with their
/// 1-based numbers.
struct Lines<'a> {
    physical: text::Lines<'a>,
}

impl<'a> Lines<'a> {
    fn new(bytes: &'a [u8]) -> Self {
        Lines {
            physical: text::Lines::new(bytes, 1),
        }
    }

    /// The next line with content, as (line number, content without comment).
    fn next_content(&mut self) -> Option<(usize, &'a [u8])> {
        while let Some((number, line)) = self.physical.next_line() {
            let line = match line.iter().position(|&b| b == b'#') {
                Some(hash) => &line[..hash],
                None => line,
            };
            if !line.trim_ascii().is_empty() {
                return Some((number, line));
            }
        }
        None
    }

    /// The line just after the last one, for errors at the end of the file.
    fn end_line(&self) -> usize {
        self.physical.line() + 1
    }
}

/// The parsed header: what each vertex line holds and the counts.
struct Header {
    /// Coordinates per vertex (3, or 4 with `w`).
    coordinates: usize,
    vertices: usize,
    faces: usize,
}

/// Reads OFF bytes into a mesh in file units.
///
/// # Errors
/// With the line: a malformed header or number, a file that ends before the announced
/// vertices or faces, a face with fewer than three corners or fewer indices than it
/// announces, an index out of range, a non-finite position. [`ReadErrorKind::Empty`] for a
/// file with nothing but white space and comments.
pub(super) fn read_off(bytes: &[u8]) -> Result<Mesh, ReadErrorKind> {
    let mut lines = Lines::new(bytes);
    let header = read_header(&mut lines)?;
    // Capacity from the counts, but never more than the file could hold (a hostile count
    // must not allocate gigabytes): every vertex or face needs at least two bytes.
    let room = bytes.len() / 2;
    let mut vertices = Vec::with_capacity(header.vertices.min(room));
    for v in 0..header.vertices {
        let Some((line, text)) = lines.next_content() else {
            return Err(ReadErrorKind::Truncated {
                at: Place::Line(lines.end_line()),
                message: format!(
                    "the header announces {} vertices, found {v}",
                    header.vertices
                ),
            });
        };
        vertices.push(parse_vertex(text, line, header.coordinates)?);
    }
    let mut triangles = Vec::with_capacity(header.faces.min(room));
    let mut polygon: Vec<u32> = Vec::new();
    let mut triangulator = Triangulator::default();
    for f in 0..header.faces {
        let Some((line, text)) = lines.next_content() else {
            return Err(ReadErrorKind::Truncated {
                at: Place::Line(lines.end_line()),
                message: format!("the header announces {} faces, found {f}", header.faces),
            });
        };
        parse_face(text, line, vertices.len(), &mut polygon)?;
        triangulator
            .triangulate(&polygon, &vertices, &mut triangles)
            .map_err(|e| ReadErrorKind::PolygonTooComplex {
                at: Place::Line(line),
                face: f,
                corners: e.corners,
            })?;
    }
    Ok(Mesh {
        vertices,
        triangles,
    })
}

/// Words of the header, which may spread over lines (`OFF`, then the counts).
struct Words<'l, 'a> {
    lines: &'l mut Lines<'a>,
    /// The current line's number and what is left of it.
    line: usize,
    rest: &'a [u8],
}

impl<'a> Words<'_, 'a> {
    /// What is left of the current line, moving to the next line with content when it is
    /// used up; `None` at the end of the file.
    fn rest(&mut self) -> Option<&'a [u8]> {
        while self.rest.trim_ascii().is_empty() {
            let (line, text) = self.lines.next_content()?;
            (self.line, self.rest) = (line, text);
        }
        self.rest = self.rest.trim_ascii_start();
        Some(self.rest)
    }

    /// The next word, with its line.
    fn next(&mut self) -> Option<&'a [u8]> {
        let rest = self.rest()?;
        let len = rest
            .iter()
            .position(|b| b.is_ascii_whitespace())
            .unwrap_or(rest.len());
        self.rest = &rest[len..];
        Some(&rest[..len])
    }

    /// The next word parsed as a count; errors name `what` and the line.
    fn count(&mut self, what: &str) -> Result<usize, ReadErrorKind> {
        let Some(word) = self.next() else {
            return Err(ReadErrorKind::Truncated {
                at: Place::Line(self.lines.end_line()),
                message: format!("the {what} is missing"),
            });
        };
        std::str::from_utf8(word)
            .ok()
            .and_then(|s| s.parse::<usize>().ok())
            .ok_or_else(|| ReadErrorKind::Syntax {
                at: Place::Line(self.line),
                message: format!(
                    "expected the {what}, found '{}'",
                    String::from_utf8_lossy(word)
                ),
            })
    }
}

/// Reads the keyword (optional) and the counts, which may share its line.
fn read_header(lines: &mut Lines<'_>) -> Result<Header, ReadErrorKind> {
    let mut words = Words {
        lines,
        line: 0,
        rest: &[],
    };
    let Some(text) = words.rest() else {
        return Err(ReadErrorKind::Empty);
    };
    let first_line = words.line;
    let syntax = |message: String| ReadErrorKind::Syntax {
        at: Place::Line(first_line),
        message,
    };
    let mut coordinates = 3;
    let first_word = text
        .split(|b| b.is_ascii_whitespace())
        .next()
        .unwrap_or(text);
    if !first_word.iter().all(u8::is_ascii_digit) {
        // The keyword: letters ending in "OFF", maybe followed by the counts (`OFF8 6 12`).
        let keyword_len = text
            .iter()
            .position(|b| b.is_ascii_whitespace())
            .unwrap_or(text.len());
        let Some(at) = text[..keyword_len]
            .windows(3)
            .position(|w| w.eq_ignore_ascii_case(b"OFF"))
        else {
            return Err(syntax(
                "expected the OFF keyword or the vertex and face counts".to_owned(),
            ));
        };
        let prefix = &text[..at];
        if !prefix.iter().all(|b| b"STCN4n".contains(b)) {
            return Err(syntax(format!(
                "unknown OFF keyword '{}OFF'",
                String::from_utf8_lossy(prefix)
            )));
        }
        if prefix.contains(&b'4') {
            coordinates += 1;
        }
        words.rest = &text[at + 3..];
        let after = words.rest.trim_ascii_start();
        if after.starts_with(b"BINARY") {
            return Err(syntax("binary OFF is not supported".to_owned()));
        }
        if prefix.contains(&b'n') {
            let dimension = words.count("nOFF dimension")?;
            if dimension != 3 {
                return Err(ReadErrorKind::Syntax {
                    at: Place::Line(words.line),
                    message: format!("nOFF of dimension {dimension} is not supported (only 3)"),
                });
            }
        }
    }
    let vertices = words.count("vertex count")?;
    let counts_line = words.line;
    if words.rest.trim_ascii().is_empty() {
        return Err(ReadErrorKind::Syntax {
            at: Place::Line(counts_line),
            message: "the face count must follow the vertex count on its line".to_owned(),
        });
    }
    let faces = words.count("face count")?;
    // The edge count, if any, is unused; the vertices start on the next line.
    if vertices > u32::MAX as usize {
        return Err(ReadErrorKind::TooLarge {
            at: Place::Line(counts_line),
            message: format!("{vertices} vertices do not fit 32-bit indices"),
        });
    }
    Ok(Header {
        coordinates,
        vertices,
        faces,
    })
}

/// A vertex line: `x y z` (and `w` for 4OFF); anything after is ignored.
fn parse_vertex(text: &[u8], line: usize, coordinates: usize) -> Result<DVec3, ReadErrorKind> {
    let mut values = [1.0; 4];
    let mut words = tokens(text);
    for (axis, value) in values.iter_mut().take(coordinates).enumerate() {
        let Some(word) = words.next() else {
            return Err(ReadErrorKind::Syntax {
                at: Place::Line(line),
                message: format!("a vertex needs {coordinates} coordinates, found {axis}"),
            });
        };
        *value = std::str::from_utf8(word)
            .ok()
            .and_then(|s| s.parse::<f64>().ok())
            .ok_or_else(|| ReadErrorKind::Syntax {
                at: Place::Line(line),
                message: format!("'{}' is not a number", String::from_utf8_lossy(word)),
            })?;
    }
    let p = DVec3::new(values[0], values[1], values[2]) / values[3];
    if !p.is_finite() {
        return Err(ReadErrorKind::NonFinite {
            at: Place::Line(line),
        });
    }
    Ok(p)
}

/// A face line: `n i1 ... in`, then ignored colour values; fills `polygon`.
fn parse_face(
    text: &[u8],
    line: usize,
    vertex_count: usize,
    polygon: &mut Vec<u32>,
) -> Result<(), ReadErrorKind> {
    let syntax = |message: String| ReadErrorKind::Syntax {
        at: Place::Line(line),
        message,
    };
    let integer = |word: &[u8]| -> Result<i64, ReadErrorKind> {
        std::str::from_utf8(word)
            .ok()
            .and_then(|s| s.parse::<i64>().ok())
            .ok_or_else(|| {
                syntax(format!(
                    "'{}' is not an integer",
                    String::from_utf8_lossy(word)
                ))
            })
    };
    let mut words = tokens(text);
    let corners = integer(words.next().unwrap_or(b""))?;
    if corners < 3 {
        return Err(ReadErrorKind::TooFewCorners {
            at: Place::Line(line),
            corners: corners.max(0) as usize,
        });
    }
    polygon.clear();
    for found in 0..corners {
        let Some(word) = words.next() else {
            return Err(syntax(format!(
                "the face announces {corners} corners, the line has {found}"
            )));
        };
        let index = integer(word)?;
        match u32::try_from(index) {
            Ok(i) if (i as usize) < vertex_count => polygon.push(i),
            _ => {
                return Err(ReadErrorKind::IndexOutOfRange {
                    at: Place::Line(line),
                    index,
                    count: vertex_count,
                });
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const CUBE: &str = "OFF\n8 6 12\n\
        0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n\
        4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";

    fn read(text: &str) -> Result<Mesh, ReadErrorKind> {
        read_off(text.as_bytes())
    }

    #[test]
    fn cube_of_quads() {
        let mesh = read(CUBE).unwrap();
        assert_eq!((mesh.vertices.len(), mesh.triangles.len()), (8, 12));
        // Outward normals: the winding of each quad is kept.
        for t in 0..12 {
            let [a, b, c] = mesh.corners(t);
            let centre = (a + b + c) / 3.0 - DVec3::splat(0.5);
            assert!((b - a).cross(c - a).dot(centre) > 0.0, "triangle {t}");
        }
    }

    #[test]
    fn counts_on_the_keyword_line_or_glued_to_it() {
        let same_line = CUBE.replacen("OFF\n8 6 12", "OFF 8 6 12", 1);
        assert_eq!(read(&same_line).unwrap().triangles.len(), 12);
        let glued = CUBE.replacen("OFF\n8 6 12", "\t   OFF8 6 12 # note", 1);
        assert_eq!(read(&glued).unwrap().triangles.len(), 12);
        let no_keyword = CUBE.replacen("OFF\n", "", 1);
        assert_eq!(read(&no_keyword).unwrap().triangles.len(), 12);
        let comments = CUBE.replacen("OFF\n", "OFF\n# a comment\n\n  # another\n", 1);
        assert_eq!(read(&comments).unwrap().triangles.len(), 12);
    }

    #[test]
    fn variants_and_extra_values_are_ignored() {
        let text = "COFF\r\n3 1 0\r\n0 0 0 255 0 0 255\r\n1 0 0 0 255 0 255\r\n0 1 0 0 0 255 255\r\n3 0 1 2 0.5 0.5 0.5\r\n";
        let mesh = read(text).unwrap();
        assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
        let noff = "NOFF 3 1\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n";
        assert_eq!(read(noff).unwrap().triangles.len(), 1);
        let stoff = "STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n";
        assert_eq!(read(stoff).unwrap().triangles.len(), 1);
        let homogeneous = "4OFF\n3 1 0\n0 0 0 2\n2 0 0 2\n0 2 0 2\n3 0 1 2\n";
        assert_eq!(read(homogeneous).unwrap().vertices[1], DVec3::X);
        let n_dim = "nOFF\n3\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        assert_eq!(read(n_dim).unwrap().triangles.len(), 1);
        assert!(matches!(
            read("nOFF 4\n3 1 0\n"),
            Err(ReadErrorKind::Syntax {
                at: Place::Line(1),
                ..
            })
        ));
        assert!(matches!(
            read("OFF BINARY\n"),
            Err(ReadErrorKind::Syntax {
                at: Place::Line(1),
                ..
            })
        ));
    }

    #[test]
    fn truncation_names_the_line_after_the_end() {
        let cut = &CUBE[..CUBE.find("4 0 1 5 4").unwrap()];
        assert_eq!(
            read(cut),
            Err(ReadErrorKind::Truncated {
                at: Place::Line(13),
                message: "the header announces 6 faces, found 2".into()
            })
        );
        assert!(matches!(
            read("OFF\n3 1 0\n0 0 0\n"),
            Err(ReadErrorKind::Truncated {
                at: Place::Line(4),
                ..
            })
        ));
        assert!(matches!(
            read("OFF\n"),
            Err(ReadErrorKind::Truncated { .. })
        ));
        assert_eq!(read("  \n# nothing\n"), Err(ReadErrorKind::Empty));
    }

    #[test]
    fn bad_faces_name_the_line() {
        let base = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
        let face = |f: &str| read(&format!("{base}{f}\n"));
        assert_eq!(
            face("3 0 1 3"),
            Err(ReadErrorKind::IndexOutOfRange {
                at: Place::Line(6),
                index: 3,
                count: 3
            })
        );
        assert_eq!(
            face("3 0 -1 2"),
            Err(ReadErrorKind::IndexOutOfRange {
                at: Place::Line(6),
                index: -1,
                count: 3
            })
        );
        assert_eq!(
            face("2 0 1"),
            Err(ReadErrorKind::TooFewCorners {
                at: Place::Line(6),
                corners: 2
            })
        );
        assert!(matches!(
            face("4 0 1 2"),
            Err(ReadErrorKind::Syntax {
                at: Place::Line(6),
                ..
            })
        ));
        assert!(matches!(
            face("3 0 1 x"),
            Err(ReadErrorKind::Syntax {
                at: Place::Line(6),
                ..
            })
        ));
    }

    #[test]
    fn bad_headers_and_vertices() {
        assert!(matches!(
            read("PLY\n"),
            Err(ReadErrorKind::Syntax {
                at: Place::Line(1),
                ..
            })
        ));
        assert!(matches!(
            read("XOFF 1 0\n"),
            Err(ReadErrorKind::Syntax {
                at: Place::Line(1),
                ..
            })
        ));
        assert!(matches!(
            read("OFF\n3\n"),
            Err(ReadErrorKind::Syntax {
                at: Place::Line(2),
                ..
            })
        ));
        assert!(matches!(
            read("OFF\n-3 1\n"),
            Err(ReadErrorKind::Syntax {
                at: Place::Line(2),
                ..
            })
        ));
        assert!(matches!(
            read("OFF 1 0\n0 0\n"),
            Err(ReadErrorKind::Syntax {
                at: Place::Line(2),
                ..
            })
        ));
        assert_eq!(
            read("OFF 1 0\n0 nan 0\n"),
            Err(ReadErrorKind::NonFinite { at: Place::Line(2) })
        );
        // A huge count does not allocate; it only runs out of lines.
        assert!(matches!(
            read("OFF 99999999999 0\n0 0 0\n"),
            Err(ReadErrorKind::TooLarge { .. })
        ));
        assert!(matches!(
            read("OFF 3 99999999999999\n0 0 0\n0 0 0\n0 0 0\n"),
            Err(ReadErrorKind::Truncated { .. })
        ));
    }
}
