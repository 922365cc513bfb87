//! Iteration over the surface cells of a map (offline work: validation, statistics).

use super::VoxelMap;

impl VoxelMap {
    /// The triangle list of every surface cell, in storage order (each list ordered along
    /// its cell's slab, as [`VoxelMap::triangles_in`] gives it). For offline work such as
    /// finding self-intersections; a tick looks cells up by coordinates with
    /// [`VoxelMap::triangles_in`].
    pub fn surface_cell_triangles(&self) -> impl ExactSizeIterator<Item = &[u32]> + '_ {
        self.triangle_start.windows(2).map(|w| {
            self.triangle_refs
                .get(w[0] as usize..w[1] as usize)
                .unwrap_or(&[])
        })
    }
}
