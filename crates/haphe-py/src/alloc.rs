//! The counting global allocator (feature `count-allocations`): every allocation the Rust
//! side of the module makes is counted, so a test can show that a loop of proxy ticks
//! allocates nothing inside the library and its bindings. Python's own objects (the floats
//! and tuples a tick returns) come from Python's allocator and are not counted.

pub use haphe_counting_alloc::allocations;

#[global_allocator]
static ALLOCATOR: haphe_counting_alloc::Counting = haphe_counting_alloc::Counting;
