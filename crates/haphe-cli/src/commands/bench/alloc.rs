//! The counting global allocator of the `haphe` binary (a program has one): `haphe bench`
//! reads its counters for its memory figures and to check that the timed queries allocate
//! nothing. It is in the binary with the `bench` feature only.

pub use haphe_counting_alloc::{allocations, live_bytes};

#[global_allocator]
static ALLOCATOR: haphe_counting_alloc::Counting = haphe_counting_alloc::Counting;
