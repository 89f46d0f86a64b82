//! What both tracers share about splitting a frame into work: the progress callback and
//! the layout of adaptive anti-aliasing's per-tile arrays (lattice points and split
//! flags). Plain data and index arithmetic only, so `cpu` and `gpu` both depend on it and
//! neither on the other.

/// Progress of a render: called with (parts done, parts in all) as parts complete (tiles
/// on the CPU, submitted parts of the frame on the GPU).
pub type RenderProgress<'a> = &'a (dyn Fn(u64, u64) + Sync);

/// One tile of the adaptive passes.
// Mirror of the adaptive fields of shaders/layout.wgsl::GpuTile — change both.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AdaptiveTile {
    /// Top-left pixel.
    pub origin: [u32; 2],
    /// Pixels across and down (at most `side`).
    pub size: [u32; 2],
    /// The tile side the arrays are laid out for (row stride, in pixels).
    pub side: u32,
    /// aa_depth.
    pub depth: u32,
}

impl AdaptiveTile {
    /// Lattice steps per pixel: 2^d.
    // Mirror of shaders/adaptive.wgsl::adaptive_scale — change both.
    pub fn scale(&self) -> u32 {
        1 << self.depth
    }
    /// Points per lattice row: side·2^d + 1.
    pub fn lattice_width(&self) -> u32 {
        self.side * self.scale() + 1
    }
    /// Lattice points of the arrays.
    pub fn lattice_len(&self) -> usize {
        (self.lattice_width() as usize).pow(2)
    }
    /// Whether each pixel's centre is a lattice point, traced by the first pass with the
    /// corners (d ≥ 1; at d = 0 the lattice is the corners alone).
    pub fn pixels_have_centres(&self) -> bool {
        self.depth > 0
    }
    /// Invocations of the first pass: every pixel corner, then every pixel centre where
    /// [`Self::pixels_have_centres`].
    pub fn first_pass_len(&self) -> u32 {
        let [w, h] = self.size;
        let centres = if self.pixels_have_centres() { w * h } else { 0 };
        (w + 1) * (h + 1) + centres
    }
    /// Split flags of the arrays: levels 0..d.
    pub fn split_len(&self) -> usize {
        split_offset(self.side, self.depth) as usize
    }
}

/// First split flag of level `level`: side²·(4^level − 1)/3 (level k has (side·2^k)²).
// Mirror of shaders/adaptive.wgsl::split_offset — change both.
pub fn split_offset(side: u32, level: u32) -> u32 {
    side * side * (((1u32 << (2 * level)) - 1) / 3)
}
