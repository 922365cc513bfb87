//! Hostile inputs to the library: every one gets an error naming the place or the same
//! answer as the brute force, never a wrong one. One file per theme; see
//! `docs/limits-of-input.md`.

mod coordinates;
mod long_segments;
mod polygons;
mod readers;
mod self_intersections;
mod values;
