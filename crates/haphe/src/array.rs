//! Arrays that are either owned or used in place from the bytes of a loaded map file.
//!
//! A surface and map built in memory own their arrays ([`Vec`]); loaded from a saved file
//! ([`decode_in_place`](crate::map::decode_in_place)), each array is a typed view of one
//! shared, aligned buffer ([`MapBytes`]), so loading copies nothing and recomputes nothing.
//! Both read the same way: an [`Array`] dereferences to a slice.

use std::fmt;
use std::io::Read;
use std::ops::{Deref, DerefMut, Range};
use std::sync::Arc;

use bytemuck::Pod;
use yoke::Yoke;

/// The bytes of a saved map, held so that a loaded surface and map can use their arrays in
/// place: an 8-byte-aligned heap buffer, or a memory-mapped file.
///
/// Cloning is cheap (a reference count); the bytes live as long as any clone or any
/// surface or map decoded from them.
#[derive(Clone)]
pub struct MapBytes(Arc<Backing>);

enum Backing {
    /// `len` bytes in 8-byte words.
    Heap { words: Vec<u64>, len: usize },
    /// A file mapped into memory by the caller.
    Mapped(memmap2::Mmap),
}

impl Backing {
    fn bytes(&self) -> &[u8] {
        match self {
            Backing::Heap { words, len } => {
                let bytes: &[u8] = bytemuck::cast_slice(words);
                bytes.get(..*len).unwrap_or(&[])
            }
            Backing::Mapped(map) => map,
        }
    }
}

impl MapBytes {
    /// Copies `bytes` into a new aligned buffer (one copy into fresh memory).
    pub fn copy_from_slice(bytes: &[u8]) -> MapBytes {
        let mut words = vec![0u64; bytes.len().div_ceil(8)];
        bytemuck::cast_slice_mut::<u64, u8>(&mut words)[..bytes.len()].copy_from_slice(bytes);
        MapBytes(Arc::new(Backing::Heap {
            words,
            len: bytes.len(),
        }))
    }

    /// Reads everything `reader` yields into a new aligned buffer.
    ///
    /// # Errors
    /// Whatever reading fails with.
    pub fn read_from(mut reader: impl Read) -> std::io::Result<MapBytes> {
        const STEP_WORDS: usize = 1 << 17;
        let mut words: Vec<u64> = Vec::new();
        let mut len = 0usize;
        loop {
            if len + 8 > words.len() * 8 {
                let grow = words.len().max(STEP_WORDS);
                words.resize(words.len() + grow, 0);
            }
            let buf = &mut bytemuck::cast_slice_mut::<u64, u8>(&mut words)[len..];
            match reader.read(buf) {
                Ok(0) => break,
                Ok(n) => len += n,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                Err(e) => return Err(e),
            }
        }
        words.truncate(len.div_ceil(8));
        words.shrink_to_fit();
        Ok(MapBytes(Arc::new(Backing::Heap { words, len })))
    }

    /// Holds a memory-mapped map file (the mapping is page-aligned, so every array of the
    /// file is used in place). Mapping the file is the caller's `unsafe` step: the file
    /// must not be changed while it is mapped.
    pub fn from_mmap(map: memmap2::Mmap) -> MapBytes {
        if !(map.as_ptr() as usize).is_multiple_of(8) {
            return MapBytes::copy_from_slice(&map);
        }
        MapBytes(Arc::new(Backing::Mapped(map)))
    }

    /// The bytes.
    #[inline]
    pub fn as_slice(&self) -> &[u8] {
        self.0.bytes()
    }

    /// Number of bytes.
    pub fn len(&self) -> usize {
        self.as_slice().len()
    }

    /// Whether there are no bytes.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl fmt::Debug for MapBytes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = match &*self.0 {
            Backing::Heap { .. } => "heap",
            Backing::Mapped(_) => "mapped",
        };
        write!(f, "MapBytes({} bytes, {kind})", self.len())
    }
}

/// A typed view of a byte range of a [`MapBytes`]: the slice, found once when the view is
/// made, held together with the buffer it borrows from (a [`Yoke`]), so that reading it
/// costs what reading a [`Vec`] does.
struct View<T: 'static> {
    slice: Yoke<&'static [T], Arc<Backing>>,
    /// Length in bytes.
    len: usize,
}

impl<T: 'static> Clone for View<T> {
    fn clone(&self) -> Self {
        View {
            slice: self.slice.clone(),
            len: self.len,
        }
    }
}

/// An array of `T`: owned, or a view of a loaded buffer. Reads as a slice; writing to a
/// view first copies it (only map building writes, never to a loaded array).
#[derive(Clone)]
pub(crate) struct Array<T: 'static> {
    owned: Vec<T>,
    view: Option<View<T>>,
}

impl<T: Pod> Array<T> {
    /// A view of `range` of `bytes` when it is aligned for `T` and a whole number of
    /// elements, else `None`.
    pub(crate) fn view(bytes: &MapBytes, range: Range<usize>) -> Option<Array<T>> {
        let len = range.len();
        let slice = Yoke::try_attach_to_cart(Arc::clone(&bytes.0), |backing: &Backing| {
            let part = backing.bytes().get(range).ok_or(())?;
            bytemuck::try_cast_slice::<u8, T>(part).map_err(|_| ())
        })
        .ok()?;
        Some(Array {
            owned: Vec::new(),
            view: Some(View { slice, len }),
        })
    }

    /// The owned vector, copying a view first.
    pub(crate) fn to_mut(&mut self) -> &mut Vec<T> {
        if let Some(view) = self.view.take() {
            self.owned = view.slice.get().to_vec();
        }
        &mut self.owned
    }

    /// Bytes of memory the array holds (a view: its share of the loaded buffer).
    pub(crate) fn heap_bytes(&self) -> usize {
        match &self.view {
            None => self.owned.capacity() * size_of::<T>(),
            Some(view) => view.len,
        }
    }

    /// Whether the array is a view of a loaded buffer.
    #[cfg(test)]
    pub(crate) fn is_view(&self) -> bool {
        self.view.is_some()
    }
}

impl<T: 'static> Default for Array<T> {
    fn default() -> Self {
        Array {
            owned: Vec::new(),
            view: None,
        }
    }
}

impl<T: 'static> From<Vec<T>> for Array<T> {
    fn from(owned: Vec<T>) -> Self {
        Array { owned, view: None }
    }
}

impl<T: Pod> Deref for Array<T> {
    type Target = [T];
    #[inline]
    fn deref(&self) -> &[T] {
        match &self.view {
            None => &self.owned,
            Some(view) => view.slice.get(),
        }
    }
}

impl<T: Pod> DerefMut for Array<T> {
    #[inline]
    fn deref_mut(&mut self) -> &mut [T] {
        self.to_mut()
    }
}

impl<'a, T: Pod> IntoIterator for &'a Array<T> {
    type Item = &'a T;
    type IntoIter = std::slice::Iter<'a, T>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

impl<'a, T: Pod> IntoIterator for &'a mut Array<T> {
    type Item = &'a mut T;
    type IntoIter = std::slice::IterMut<'a, T>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter_mut()
    }
}

impl<T: Pod + PartialEq> PartialEq for Array<T> {
    fn eq(&self, other: &Self) -> bool {
        **self == **other
    }
}

impl<T: Pod + fmt::Debug> fmt::Debug for Array<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(&**self, f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_view_reads_like_the_vector_and_copies_on_write() {
        let words: Vec<u32> = (0..100).collect();
        let bytes = MapBytes::copy_from_slice(bytemuck::cast_slice(&words));
        let mut a = Array::<u32>::view(&bytes, 40..80).expect("aligned");
        assert!(a.is_view());
        assert_eq!(&a[..], &words[10..20]);
        a[0] = 7;
        assert!(!a.is_view());
        assert_eq!(a[..2], [7, 11]);
        assert!(Array::<u64>::view(&bytes, 4..12).is_none(), "misaligned");
        assert!(
            Array::<u32>::view(&bytes, 0..6).is_none(),
            "not whole elements"
        );
        assert!(
            Array::<u32>::view(&bytes, 396..404).is_none(),
            "past the end"
        );
    }

    #[test]
    fn read_from_keeps_every_byte() {
        let data: Vec<u8> = (0..1_000_003u32).map(|i| (i * 7) as u8).collect();
        let bytes = MapBytes::read_from(&data[..]).expect("reads");
        assert_eq!(bytes.as_slice(), &data[..]);
    }
}
