//! The counting global allocator (feature `count-allocations`): every allocation the library
//! makes is counted, so a C test can show that a loop of proxy ticks allocates nothing.

pub use haphe_counting_alloc::allocations;

#[global_allocator]
static ALLOCATOR: haphe_counting_alloc::Counting = haphe_counting_alloc::Counting;
