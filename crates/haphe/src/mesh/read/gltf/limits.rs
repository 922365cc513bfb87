//! The limits a glTF file is held to before anything is allocated.

/// The most triangles the default scene may place (counting a mesh once per node that
/// uses it): a file over this is refused before its triangles are made.
pub const MAX_TRIANGLES: usize = 1 << 24;

/// The most accessor elements read from a file's buffers, all accessors together (one
/// element is one position or one index).
pub(crate) const MAX_DECODED_ELEMENTS: u64 = 1 << 26;

/// The most accessor elements without a buffer view (zeros, or sparse substitutions over
/// zeros), all accessors together: such a count is backed by no data.
pub(crate) const MAX_UNBACKED_ELEMENTS: u64 = 1 << 20;
