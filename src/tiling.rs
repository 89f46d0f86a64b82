//! What both tracers share about splitting a frame into work: the progress callback and
//! the layout of adaptive anti-aliasing's per-tile arrays (lattice points and split
//! flags). Plain data and index arithmetic only, so `cpu` and `gpu` both depend on it and
//! neither on the other.

/// Progress of a render: called with (parts done, parts in all) as parts complete (tiles
/// on the CPU, submitted parts of the frame on the GPU).
pub type RenderProgress<'a> = &'a (dyn Fn(u64, u64) + Sync);

/// One tile of the adaptive passes.
// Mirror of the adaptive fields of src/pack/layout.wgsl::GpuTile — change both.
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
    // Mirror of src/tracer/sampling/adaptive.wgsl::adaptive_scale — change both.
    pub fn adaptive_scale(&self) -> u32 {
        1 << self.depth
    }
    /// Points per lattice row: side·2^d + 1.
    pub fn lattice_width(&self) -> u32 {
        self.side * self.adaptive_scale() + 1
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
// Mirror of src/tracer/sampling/adaptive.wgsl::split_offset — change both.
pub fn split_offset(side: u32, level: u32) -> u32 {
    side * side * (((1u32 << (2 * level)) - 1) / 3)
}

/// A rectangle of film pixels, half-open: columns `x0..x1`, rows `y0..y1` (a farm's tile
/// or `--crop` window). Both tracers render a window with the full image's pixel
/// coordinates, so each pixel comes out as in the full render.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PixelRect {
    pub x0: u32,
    pub x1: u32,
    pub y0: u32,
    pub y1: u32,
}

impl PixelRect {
    /// The whole `width × height` image.
    pub fn full(width: u32, height: u32) -> PixelRect {
        PixelRect {
            x0: 0,
            x1: width,
            y0: 0,
            y1: height,
        }
    }
    pub fn width(&self) -> u32 {
        self.x1 - self.x0
    }
    pub fn height(&self) -> u32 {
        self.y1 - self.y0
    }
    /// Pixels inside.
    pub fn area(&self) -> u64 {
        u64::from(self.width()) * u64::from(self.height())
    }
    /// Whether it holds no pixel.
    pub fn is_empty(&self) -> bool {
        self.x0 >= self.x1 || self.y0 >= self.y1
    }
    /// Whether it lies inside a `width × height` image.
    pub fn fits(&self, width: u32, height: u32) -> bool {
        self.x1 <= width && self.y1 <= height
    }
    /// The pixels both hold, if any.
    pub fn intersection(&self, other: &PixelRect) -> Option<PixelRect> {
        let r = PixelRect {
            x0: self.x0.max(other.x0),
            x1: self.x1.min(other.x1),
            y0: self.y0.max(other.y0),
            y1: self.y1.min(other.y1),
        };
        (!r.is_empty()).then_some(r)
    }
}

impl std::fmt::Display for PixelRect {
    /// As `--crop` takes it: `x0,x1,y0,y1`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{},{},{},{}", self.x0, self.x1, self.y0, self.y1)
    }
}
