//! Errors of the readers: every one names the file and the place.

use std::fmt;

/// Where in a file a problem is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Place {
    /// A line of a text file, counted from 1.
    Line(usize),
    /// A byte offset in a binary file, counted from 0.
    Byte(u64),
    /// A face (polygon or triangle) as numbered in the file, counted from 0.
    Face(usize),
    /// A vertex as numbered in the file, counted from 0.
    Vertex(usize),
    /// A triangle strip (an entry of a PLY `tristrips` element), counted from 0.
    Strip(usize),
    /// The file header (STL's 84 bytes, PLY's header, OFF's first line, glTF's JSON).
    Header,
    /// An object of a glTF file: a node, mesh, primitive, accessor or buffer.
    Gltf(GltfPlace),
}

/// Where in a glTF file a problem is: the objects on the way to it, each by its index in
/// the file's arrays (counted from 0). Shown as, for example,
/// `node 3, mesh 1, primitive 0, accessor 5 (POSITION)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct GltfPlace {
    /// The scene.
    pub scene: Option<u32>,
    /// The node.
    pub node: Option<u32>,
    /// The mesh.
    pub mesh: Option<u32>,
    /// The primitive, within its mesh.
    pub primitive: Option<u32>,
    /// The accessor, and what it holds (`POSITION`, `indices`, ...).
    pub accessor: Option<(u32, &'static str)>,
    /// The buffer view.
    pub buffer_view: Option<u32>,
    /// The buffer.
    pub buffer: Option<u32>,
}

impl fmt::Display for GltfPlace {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let named = |list: [(&str, Option<u32>); 2]| {
            list.into_iter()
                .filter_map(|(name, index)| index.map(|i| format!("{name} {i}")))
                .collect::<Vec<_>>()
        };
        let parts: Vec<String> = named([("scene", self.scene), ("node", self.node)])
            .into_iter()
            .chain(named([("mesh", self.mesh), ("primitive", self.primitive)]))
            .chain(
                self.accessor
                    .map(|(i, what)| format!("accessor {i} ({what})")),
            )
            .chain(named([
                ("buffer view", self.buffer_view),
                ("buffer", self.buffer),
            ]))
            .collect();
        if parts.is_empty() {
            f.write_str("document")
        } else {
            f.write_str(&parts.join(", "))
        }
    }
}

impl fmt::Display for Place {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Place::Line(n) => write!(f, "line {n}"),
            Place::Byte(n) => write!(f, "byte {n}"),
            Place::Face(n) => write!(f, "face {n}"),
            Place::Vertex(n) => write!(f, "vertex {n}"),
            Place::Strip(n) => write!(f, "triangle strip {n}"),
            Place::Header => f.write_str("header"),
            Place::Gltf(place) => place.fmt(f),
        }
    }
}

/// What went wrong while reading a mesh, and where.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ReadErrorKind {
    /// The file has no bytes, or only white space and comments.
    #[error("the file is empty")]
    Empty,
    /// The content is not one of the supported formats.
    #[error("not a mesh file haphe can read (OBJ, STL, PLY, OFF or glTF): {reason}")]
    UnknownFormat {
        /// Why detection failed.
        reason: String,
    },
    /// A malformed statement, number or header.
    #[error("{at}: {message}")]
    Syntax {
        /// Where.
        at: Place,
        /// What was expected and what was found.
        message: String,
    },
    /// The file ends before the data its header announces.
    #[error("{at}: the file ends early: {message}")]
    Truncated {
        /// Where the missing data should start.
        at: Place,
        /// What is missing.
        message: String,
    },
    /// A face refers to a vertex that does not exist.
    #[error("{at}: vertex index {index} is out of range (the file has {count} vertices)")]
    IndexOutOfRange {
        /// The face (or its line).
        at: Place,
        /// The index as written in the file.
        index: i64,
        /// How many vertices there are.
        count: usize,
    },
    /// A vertex coordinate is NaN or infinite.
    #[error("{at}: a vertex coordinate is not a finite number")]
    NonFinite {
        /// The vertex (or its line).
        at: Place,
    },
    /// A face corner refers to a texture coordinate that does not exist (an OBJ `f 1/9`).
    #[error(
        "{at}: texture coordinate index {index} is out of range (the file has {count} texture coordinates)"
    )]
    TextureIndexOutOfRange {
        /// The face (or its line).
        at: Place,
        /// The index as written in the file.
        index: i64,
        /// How many texture coordinates there are.
        count: usize,
    },
    /// A texture coordinate is NaN or infinite.
    #[error("{at}: a texture coordinate is not a finite number")]
    NonFiniteTextureCoordinate {
        /// The texture coordinate or vertex (or its line).
        at: Place,
    },
    /// A vertex coordinate is larger than `MAX_COORDINATE`
    /// (areas and volumes of such a mesh overflow).
    #[error(
        "{at}: a vertex coordinate of {value:e} m is beyond the {limit:e} m haphe accepts (after scaling to metres)",
        limit = super::MAX_COORDINATE
    )]
    CoordinateTooLarge {
        /// The vertex.
        at: Place,
        /// The coordinate, metres.
        value: f64,
    },
    /// A face with fewer than three corners.
    #[error("{at}: a face has {corners} corner(s); a face needs at least 3")]
    TooFewCorners {
        /// The face (or its line).
        at: Place,
        /// How many corners it has.
        corners: usize,
    },
    /// The file holds vertices (a point cloud, a wireframe) but no faces.
    #[error("no faces: {}", match vertices {
        0 => "the file holds no geometry".to_owned(),
        n => format!("the file holds {n} vertices (a point cloud or a wireframe) but no triangles or polygons"),
    })]
    NoFaces {
        /// How many vertices were read.
        vertices: usize,
    },
    /// A non-convex polygon too large for ear clipping's work budget (thousands of
    /// corners): a fan of it would overlap itself, so it is refused.
    #[error(
        "{}a non-convex polygon of {corners} corners, more than ear clipping can cut within \
         its work budget; split it into smaller faces",
        match at { Place::Face(_) => format!("{at}: "), _ => format!("{at}: face {face}: ") }
    )]
    PolygonTooComplex {
        /// Where the face is (its line, or the face itself).
        at: Place,
        /// The face as numbered in the file, counted from 0.
        face: usize,
        /// Its corners.
        corners: usize,
    },
    /// A reference, count or layout the format forbids (an accessor reaching past its
    /// buffer, a node graph with a cycle, an index to an object that does not exist).
    #[error("{at}: {message}")]
    Invalid {
        /// Where.
        at: Place,
        /// What is wrong.
        message: String,
    },
    /// The file needs something haphe does not read (a required glTF extension, such as
    /// Draco compression).
    #[error("{at}: {message}")]
    Unsupported {
        /// Where.
        at: Place,
        /// What is needed, by name, and what to do instead.
        message: String,
    },
    /// A file the mesh file refers to (a glTF side-car buffer) could not be read.
    #[error("{at}: cannot read the file '{uri}' it refers to: {message}")]
    MissingResource {
        /// Where the reference is.
        at: Place,
        /// The reference, as written in the file.
        uri: String,
        /// Why it could not be read.
        message: String,
    },
    /// More vertices or faces than haphe's 32-bit indices hold.
    #[error("{at}: too large: {message}")]
    TooLarge {
        /// Where.
        at: Place,
        /// What overflowed.
        message: String,
    },
}

/// A mesh file could not be read: the file's name and what went wrong where.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}: {kind}")]
pub struct ReadError {
    /// The name the caller gave for the bytes (usually the path).
    pub file: String,
    /// What went wrong, and where.
    pub kind: ReadErrorKind,
}
