//! Arrays that are either owned or used in place from the bytes of a loaded map file.
//!
//! A surface and map built in memory own their arrays ([`Vec`]); loaded from a saved file
//! ([`decode_in_place`](crate::map::decode_in_place)), each array is a typed view of one
//! shared, aligned buffer ([`MapBytes`]), so loading copies nothing and recomputes nothing.
//! Both read the same way: an [`Array`] dereferences to a slice.

use std::fmt;
use std::io::Read;
use std::ops::{Deref, Range};
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
    #[cfg(feature = "mmap")]
    Mapped(memmap2::Mmap),
}

impl Backing {
    fn bytes(&self) -> &[u8] {
        match self {
            Backing::Heap { words, len } => {
                let bytes: &[u8] = bytemuck::cast_slice(words);
                bytes.get(..*len).unwrap_or(&[])
            }
            #[cfg(feature = "mmap")]
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
    /// must not be changed while it is mapped. With the `mmap` feature (on by default).
    #[cfg(feature = "mmap")]
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
            #[cfg(feature = "mmap")]
            Backing::Mapped(_) => "mapped",
        };
        write!(f, "MapBytes({} bytes, {kind})", self.len())
    }
}

/// What an [`Array`]'s slice lives in: its own vector, or the bytes of a loaded map.
enum Cart<T> {
    Owned(Vec<T>),
    Loaded(Arc<Backing>),
}

/// An array of `T`: owned, or a view of a loaded buffer. Reads as a slice: the slice is
/// found once, when the array is made, and kept with what it borrows from (a [`Yoke`]),
/// so that reading it costs what reading a [`Vec`] does, with no test of which kind it
/// is. Clones share the data; changing an array ([`Array::modify`]) copies it first
/// unless it is the only owner of its vector (only map building changes arrays, never a
/// loaded one).
#[derive(Clone)]
pub(crate) struct Array<T: 'static> {
    slice: Yoke<&'static [T], Arc<Cart<T>>>,
}

impl<T: Pod> Array<T> {
    /// A view of `range` of `bytes` when it is aligned for `T` and a whole number of
    /// elements, else `None`.
    pub(crate) fn view(bytes: &MapBytes, range: Range<usize>) -> Option<Array<T>> {
        let cart = Arc::new(Cart::Loaded(Arc::clone(&bytes.0)));
        let slice = Yoke::try_attach_to_cart(cart, |cart: &Cart<T>| match cart {
            Cart::Loaded(backing) => {
                let part = backing.bytes().get(range).ok_or(())?;
                bytemuck::try_cast_slice::<u8, T>(part).map_err(|_| ())
            }
            Cart::Owned(_) => Err(()),
        })
        .ok()?;
        Some(Array { slice })
    }

    /// Changes the array through its vector (copying a view, or data another clone
    /// shares, first), then reads it as before.
    pub(crate) fn modify<R>(&mut self, change: impl FnOnce(&mut Vec<T>) -> R) -> R {
        let mut owned = self.take_vec();
        let result = change(&mut owned);
        *self = Array::from(owned);
        result
    }

    /// The array's vector (a copy of a view, or of data another clone shares), leaving
    /// the array empty: for changing it in many places before putting it back with
    /// `Array::from`.
    pub(crate) fn take_vec(&mut self) -> Vec<T> {
        let this = std::mem::take(self);
        let unique = Arc::strong_count(this.slice.backing_cart()) == 1;
        match this.slice.backing_cart().as_ref() {
            Cart::Owned(_) if unique => match Arc::try_unwrap(this.slice.into_backing_cart()) {
                Ok(Cart::Owned(owned)) => owned,
                _ => Vec::new(),
            },
            _ => this.slice.get().to_vec(),
        }
    }

    /// Bytes of memory the array holds (a view: its share of the loaded buffer).
    pub(crate) fn heap_bytes(&self) -> usize {
        match self.slice.backing_cart().as_ref() {
            Cart::Owned(owned) => owned.capacity() * size_of::<T>(),
            Cart::Loaded(_) => size_of_val(*self.slice.get()),
        }
    }

    /// Whether the array is a view of a loaded buffer.
    #[cfg(test)]
    pub(crate) fn is_view(&self) -> bool {
        matches!(self.slice.backing_cart().as_ref(), Cart::Loaded(_))
    }
}

impl<T: 'static> Default for Array<T> {
    fn default() -> Self {
        Array::from(Vec::new())
    }
}

impl<T: 'static> From<Vec<T>> for Array<T> {
    fn from(owned: Vec<T>) -> Self {
        let slice =
            Yoke::attach_to_cart(Arc::new(Cart::Owned(owned)), |cart: &Cart<T>| match cart {
                Cart::Owned(owned) => owned.as_slice(),
                Cart::Loaded(_) => &[],
            });
        Array { slice }
    }
}

impl<T: Pod> Deref for Array<T> {
    type Target = [T];
    #[inline]
    fn deref(&self) -> &[T] {
        self.slice.get()
    }
}

impl<'a, T: Pod> IntoIterator for &'a Array<T> {
    type Item = &'a T;
    type IntoIter = std::slice::Iter<'a, T>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
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
        let shared = a.clone();
        a.modify(|a| a[0] = 7);
        assert!(!a.is_view());
        assert_eq!(a[..2], [7, 11]);
        assert_eq!(shared[..2], [10, 11], "a clone keeps what it had");
        // An owned array changes in place; one shared with a clone is copied first.
        let mut owned = Array::from(vec![1u32, 2, 3]);
        let other = owned.clone();
        owned.modify(|v| v.push(4));
        assert_eq!(
            (&owned[..], &other[..]),
            (&[1, 2, 3, 4][..], &[1, 2, 3][..])
        );
        let before = owned.as_ptr();
        owned.modify(|v| v[0] = 9);
        assert_eq!((owned.as_ptr(), owned[0]), (before, 9), "in place");
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
