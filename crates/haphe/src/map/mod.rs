//! Stage 2 — the voxel map of one object (to be written).
