//! The commands, one file each: its arguments (`Args`, flattening the shared ones of
//! [`crate::args`]) and its `run`, which checks them and hands the work to the library,
//! [`crate::input`] and [`crate::session`].

#[cfg(feature = "bench")]
pub mod bench;
pub mod build;
pub mod demo;
pub mod devices;
pub mod generate;
#[cfg(not(all(feature = "view", feature = "bench")))]
pub mod missing;
pub mod query;
pub mod repair;
pub mod run;
pub mod simulate;
pub mod validate;
pub mod verify;
#[cfg(feature = "view")]
pub mod view;
