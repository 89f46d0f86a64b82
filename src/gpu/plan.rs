//! The dispatch plan of one GPU frame, as plain arithmetic (no device needed, so it is
//! unit-tested): which chunks of the image each pass covers, how the chunks group into the
//! frame's submits, and the scratch arrays' sizes.
//!
//! A chunk is as large as the adapter's storage-binding limit allows: AA none and uniform
//! AA cover full-width bands of rows (their scratch is per pixel or per sample), adaptive
//! AA square tiles whose lattice of (side·2^d + 1)² points fits one binding. The chunks
//! are grouped into at most [`GPU_FRAME_PARTS`] submits, queued back to back: the host
//! waits only to report progress and to read the image back once, so the number of
//! submits and host waits per frame does not grow with the image.

use super::buffers::GpuTile;
use super::lists::LIST_BUDGET_BYTES;
use super::shader::Entry;
use crate::constants::{
    AA_ADAPTIVE, AA_SPLIT_POINTS, AA_UNIFORM, ALL_STRATA, GPU_FRAME_PARTS, MAX_SHADOW_CROSSINGS,
    WAVEFRONT_WORK_BASE,
};
use crate::cpu::queues::REGIONS;
use crate::pack::PackedGlobals;
use crate::queues::layout::{paths_per_sample, vec4s_per_sample, Form};
use crate::tiling::{split_offset, AdaptiveTile, PixelRect};

/// The AA mode's passes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    None,
    Uniform {
        n: u32,
    },
    Adaptive {
        depth: u32,
    },
    /// AA none or uniform AA through the wavefront kernels (`shaders/wavefront.wgsl`).
    Wavefront(WavefrontShape),
    /// Adaptive AA with its corner and midpoint passes through the wavefront kernels
    /// (`shaders/wavefront_lattice.wgsl`): the lattice, then the queues, in `samples`.
    AdaptiveWavefront {
        depth: u32,
        shape: WavefrontShape,
    },
}

/// What sizes the wavefront kernels' queues and dispatches: the scene's light points (a
/// vertex's light slots: `cpu::wavefront::light_points`), the generations a path may
/// have (max_depth + 1 with mirrors or glass, else 1), the AA mode's strata, and whether
/// paths branch (a tree: scenes with refraction).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WavefrontShape {
    pub light_points: u32,
    pub generations: u32,
    /// Uniform AA's n: a chunk's samples are n² strata a pixel, averaged by the resolve
    /// pass. None: AA none, a pixel's centre, stored by the gather pass.
    pub uniform: Option<u32>,
    pub tree: bool,
    /// Dispatches of a chain's shadow pass a generation: 1, or with CSG (at most one
    /// invocation per list slot, one request each) the light points, each a slice of at
    /// most a request per sample (`shaders/wavefront.wgsl::wavefront_shadow`). A tree's: 1.
    pub shadow_slices: u32,
}

/// Glass shadow rounds a tree's generation runs (`shaders/wavefront_tree.wgsl`): a leg
/// crosses at most MAX_SHADOW_CROSSINGS surfaces and is blocked at the next.
pub const SHADOW_ROUNDS: u32 = MAX_SHADOW_CROSSINGS + 1;

/// Words of work_args before a tree's generations' (round r's legs at 3r, r < 10).
const TREE_ROUND_ARGS_WORDS: u64 = 30;

impl WavefrontShape {
    /// Samples a pixel: n² under uniform AA, else 1.
    pub fn samples_per_pixel(self) -> u64 {
        self.uniform.map_or(1, |n| (n * n) as u64)
    }

    /// The queues' layout: a tree's with refraction, else a chain's.
    fn form(self) -> Form {
        if self.tree {
            Form::Tree
        } else {
            Form::Chain
        }
    }

    /// vec4 entries of the queues a sample of a chunk takes (the regions of
    /// `cpu::queues::REGIONS`, laid out by `queues::layout`): its record, two path
    /// queues, a hit, a vertex, its light slots and shadow requests (L each) per path a
    /// generation may hold, and a tree's vertex tree, camera vertex and glass shadow legs.
    pub fn vec4s_per_sample(self) -> u64 {
        vec4s_per_sample(REGIONS, self.form(), self.light_points)
    }

    /// Tracing invocations (list slots) a wavefront dispatch may have per sample of the
    /// chunk: a tree's generation holds up to TREE_PATHS_PER_SAMPLE paths a sample.
    pub fn slots_per_sample(self) -> u64 {
        paths_per_sample(self.form())
    }

    /// Byte offset in work_args of the indirect arguments of generation g's passes over
    /// paths (g ≥ 1; written by generation g − 1's args kernel).
    fn paths_args(self, g: u32) -> u64 {
        4 * (self.args_prefix_words() + self.generation_words() * (g as u64 - 1))
    }

    /// Byte offset of slice `slice` of generation g's shadow pass's arguments.
    fn shadow_args(self, g: u32, slice: u32) -> u64 {
        4 * (3 + 3 * slice as u64) + self.paths_args(g + 1)
    }

    /// Words of work_args before the generations' (a tree's round arguments).
    fn args_prefix_words(self) -> u64 {
        if self.tree {
            TREE_ROUND_ARGS_WORDS
        } else {
            0
        }
    }

    /// Words of work_args a generation: the next generation's passes' 3, then 3 a
    /// shadow slice.
    fn generation_words(self) -> u64 {
        3 + 3 * self.shadow_slices as u64
    }

    /// Byte offset of a tree's round r's leg arguments (the same words every generation).
    fn round_args(r: u32) -> u64 {
        12 * r as u64
    }

    /// 24-byte levels of work_args (and 4-byte counters of work_counts) the kernels use:
    /// a generation's 6 words (after a tree's round arguments); at least the counters
    /// (5 for chains; a tree's 11: also three leg counters, two vertex bases and the
    /// light points).
    pub fn work_levels(self) -> u64 {
        if self.tree {
            (TREE_ROUND_ARGS_WORDS / 6 + self.generations as u64).max(11)
        } else {
            (self.generation_words() * self.generations as u64)
                .div_ceil(6)
                .max(5)
        }
    }
}

impl Mode {
    pub fn of(g: &PackedGlobals) -> Mode {
        match g.aa_mode {
            AA_ADAPTIVE => Mode::Adaptive { depth: g.aa_depth },
            AA_UNIFORM => Mode::Uniform { n: g.aa_samples },
            _ => Mode::None,
        }
    }
}

impl Mode {
    /// The entry points of the mode's passes, in [`Dispatch::entry`] order.
    pub fn entries(self) -> &'static [Entry] {
        match self {
            Mode::None => &[Entry::Render],
            Mode::Uniform { .. } => &[Entry::UniformSamples, Entry::UniformResolve],
            Mode::Adaptive { .. } => &[
                Entry::AdaptiveCorners,
                Entry::AdaptiveDecide,
                Entry::AdaptiveMidpoints,
                Entry::AdaptiveIntegrate,
                Entry::AdaptiveWorkArgs,
            ],
            Mode::Wavefront(shape) if shape.tree && shape.uniform.is_none() => {
                &Entry::WAVEFRONT_TREE[..10]
            }
            Mode::Wavefront(shape) if shape.tree => &Entry::WAVEFRONT_TREE,
            // AA none's gather stores its pixels: no resolve.
            Mode::Wavefront(shape) if shape.uniform.is_none() => &Entry::WAVEFRONT[..6],
            Mode::Wavefront(_) => &Entry::WAVEFRONT,
            Mode::AdaptiveWavefront { shape, .. } if shape.tree => &Entry::ADAPTIVE_WAVEFRONT_TREE,
            Mode::AdaptiveWavefront { .. } => &Entry::ADAPTIVE_WAVEFRONT,
        }
    }
}

/// One compute dispatch of the frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dispatch {
    /// Index into [`Mode::entries`].
    pub entry: usize,
    /// Index into [`FramePlan::chunks`].
    pub chunk: usize,
    pub params: GpuTile,
    /// Workgroups, or where in the work-args buffer (bytes) the GPU wrote them.
    pub workgroups: Workgroups,
    /// Clear the split flags and work counts first (a new adaptive tile).
    pub clears_work: bool,
    /// Binds the work-args buffer as storage (`adaptive_work_args`).
    pub writes_args: bool,
    /// Where `samples` and the work buffers are bound from.
    pub offsets: BindingOffsets,
}

/// Where a dispatch binds the `samples` buffer and the work buffers (`work_counts`,
/// `work_args`) from, in bytes: 0, or under adaptive AA through the wavefront kernels the
/// queues after the lattice ([`lattice_queue_bytes`]) and the wavefront's counters and
/// arguments after adaptive AA's ([`WAVEFRONT_WORK_BYTES`]), so that the generations'
/// kernels index them from 0 as for AA none.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct BindingOffsets {
    pub samples: u64,
    pub work: u64,
}

/// Byte offset of the wavefront's counters in `work_counts` and of its arguments in
/// `work_args` under adaptive AA (`shaders/wavefront_lattice.wgsl`).
pub const WAVEFRONT_WORK_BYTES: u64 = 4 * WAVEFRONT_WORK_BASE as u64;

/// Where the wavefront's queues start in `samples` (bytes) for adaptive tiles of side
/// `side` at depth `depth`: after the lattice, at a multiple of 256 bytes (the coarsest
/// storage offset alignment WebGPU allows).
// The same as shaders/wavefront_lattice.wgsl::lattice_queue_base.
pub fn lattice_queue_bytes(side: u32, depth: u32) -> u64 {
    let width = side as u64 * (1u64 << depth) + 1;
    (width * width).div_ceil(16) * 16 * 16
}

/// How many workgroups a dispatch runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Workgroups {
    Direct(u32, u32),
    Indirect(u64),
}

/// Byte offset of level `level`'s midpoint-pass arguments in the work-args buffer; the
/// next level's decide-pass arguments follow (see shaders/adaptive.wgsl::adaptive_work_args).
fn midpoint_args(level: u32) -> u64 {
    24 * level as u64
}

/// One chunk: `size` pixels at `origin`; its output, scratch and guard arrays are laid
/// out `side` pixels per row (adaptive tiles are `side` × `side` squares).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Chunk {
    pub origin: [u32; 2],
    pub size: [u32; 2],
    pub side: u32,
}

impl Chunk {
    /// The chunk as an adaptive tile of depth `depth`.
    fn adaptive_tile(&self, depth: u32) -> AdaptiveTile {
        AdaptiveTile {
            origin: self.origin,
            size: self.size,
            side: self.side,
            depth,
        }
    }

    /// Pixels of the chunk's output block (its rows at stride `side`).
    pub fn block_pixels(&self) -> u64 {
        self.side as u64 * self.size[1] as u64
    }
}

/// What the adapter allows.
#[derive(Clone, Copy, Debug)]
pub struct AdapterBounds {
    /// Bytes of one storage binding (and buffer).
    pub max_binding: u64,
    /// Workgroups per dispatch dimension.
    pub max_workgroups: u32,
    /// Side of the 2-D kernels' square workgroup (the 1-D kernels run its square):
    /// the context's `KernelConfig::workgroup_side`.
    pub workgroup_side: u32,
    /// Words of per-ray lists each tracing invocation keeps in a storage slot
    /// (`super::lists::LaneLists::words`; 0: none): chunks are then also bounded so that
    /// no tracing dispatch has more invocations than `LIST_BUDGET_BYTES` (or one
    /// binding) holds slots.
    pub lane_list_words: u32,
    /// AA none's wavefront kernels, where the kernel has them for the scene (None: the
    /// megakernel `main`).
    pub wavefront: Option<WavefrontShape>,
}

/// The frame's chunks, their grouping into submits and the scratch arrays' lengths.
#[derive(Clone, Debug)]
pub struct FramePlan {
    pub mode: Mode,
    pub chunks: Vec<Chunk>,
    /// Chunk index ranges, one per submit, in order.
    pub parts: Vec<std::ops::Range<usize>>,
    /// vec4 entries of the samples array (uniform AA's samples, adaptive AA's lattice).
    pub samples_len: u64,
    /// u32 entries of the split-flag array (adaptive AA), and of the lists of split
    /// squares (the same layout).
    pub split_len: u64,
    /// Levels of adaptive AA's work counts (6 u32 of indirect arguments each).
    pub work_levels: u64,
    /// u32 words of the per-ray lists' slots: `lane_list_words` times the most tracing
    /// invocations of any dispatch (0 without lists in storage).
    pub lists_len: u64,
}

/// Largest power of two L with (L + 1)² vec4 lattice points in `max_binding` bytes.
pub fn lattice_side(max_binding: u64) -> u32 {
    let mut side = 1u32;
    while ((2 * side as u64 + 1).pow(2) * 16) <= max_binding && side < (1 << 15) {
        side *= 2;
    }
    side
}

/// Most tracing invocations (list slots) one dispatch may have under `bounds` (also the
/// rule `glint view` bands its window by).
pub fn slot_budget(bounds: AdapterBounds) -> u64 {
    match bounds.lane_list_words as u64 {
        0 => u64::MAX,
        words => (bounds.max_binding.min(LIST_BUDGET_BYTES) / (4 * words)).max(1),
    }
}

/// Tracing invocations of adaptive AA's busiest pass over a tile of `w` × `h` pixels
/// laid out `side` wide, at depth `depth`: the corner pass, or the deepest midpoint
/// pass (AA_SPLIT_POINTS per square of level depth − 1, of which the tile has at most
/// side²·4^(depth − 1)).
fn adaptive_slots(w: u32, h: u32, side: u32, depth: u32) -> u64 {
    let (w, h) = (w as u64, h as u64);
    let corners = (w + 1) * (h + 1) + w * h;
    match depth {
        0 => corners,
        d => corners.max(AA_SPLIT_POINTS as u64 * (side as u64).pow(2) * 4u64.pow(d - 1)),
    }
}

/// The side of adaptive AA's square tiles over a window of `size` at depth `depth`: the
/// largest power of two whose lattice fits one binding, at most half the window's longer
/// side (so a frame has a few chunks to spread over its parts, and a small frame gets a
/// small lattice), whose busiest pass has at most `slots` tracing invocations and whose
/// `vec4s(side)` further entries of `samples` fit one binding.
fn adaptive_side(
    bounds: AdapterBounds,
    size: [u32; 2],
    depth: u32,
    slots: u64,
    vec4s: impl Fn(u32) -> u64,
) -> u32 {
    let side = (lattice_side(bounds.max_binding) >> depth).max(1);
    let mut side = side.min(size[0].max(size[1]).div_ceil(2).next_power_of_two());
    while side > 1
        && (adaptive_slots(side, side, side, depth) > slots
            || vec4s(side) * 16 > bounds.max_binding)
    {
        side /= 2;
    }
    side
}

/// Bands of `window`'s full width of at most `rows` rows, at least `min_bands` of them
/// (the render's chunks, and the view's bands).
pub(super) fn bands(window: PixelRect, rows: u32, min_bands: u32) -> Vec<Chunk> {
    let (w, h) = (window.width(), window.height());
    let rows = rows.min(h.div_ceil(min_bands.max(1))).max(1);
    (0..h.div_ceil(rows))
        .map(|k| Chunk {
            origin: [window.x0, window.y0 + k * rows],
            size: [w, rows.min(h - k * rows)],
            side: w,
        })
        .collect()
}

/// Each row of `window` in pieces of at most `width` pixels (each its own chunk, laid out
/// `width` wide), row by row.
fn row_pieces(window: PixelRect, width: u32) -> Vec<Chunk> {
    let w = window.width();
    (window.y0..window.y0 + window.height())
        .flat_map(|y| {
            (0..w.div_ceil(width)).map(move |k| Chunk {
                origin: [window.x0 + k * width, y],
                size: [width.min(w - k * width), 1],
                side: width,
            })
        })
        .collect()
}

/// Square tiles of side `side` from `window`'s top-left corner, row-major.
fn squares(window: PixelRect, side: u32) -> Vec<Chunk> {
    let (w, h) = (window.width(), window.height());
    let (nx, ny) = (w.div_ceil(side), h.div_ceil(side));
    (0..nx * ny)
        .map(|t| {
            let (x0, y0) = ((t % nx) * side, (t / nx) * side);
            Chunk {
                origin: [window.x0 + x0, window.y0 + y0],
                size: [side.min(w - x0), side.min(h - y0)],
                side,
            }
        })
        .collect()
}

/// `n` contiguous ranges covering 0..len as evenly as possible (n ≤ len).
fn split_even(len: usize, n: usize) -> Vec<std::ops::Range<usize>> {
    (0..n).map(|k| k * len / n..(k + 1) * len / n).collect()
}

impl FramePlan {
    /// The plan for a `g.width` × `g.height` frame under `g`'s AA mode.
    pub fn new(g: &PackedGlobals, bounds: AdapterBounds) -> FramePlan {
        FramePlan::for_window(g, bounds, PixelRect::full(g.width, g.height))
    }

    /// The plan for the pixels of `window` (inside the frame) alone: chunks as for a
    /// frame of the window's size, placed at its pixels (the kernels take every pixel's
    /// position from its chunk's origin, so each comes out as in the full frame).
    pub fn for_window(g: &PackedGlobals, bounds: AdapterBounds, window: PixelRect) -> FramePlan {
        let (w, h) = (window.width(), window.height());
        let mode = match (Mode::of(g), bounds.wavefront) {
            (Mode::None, Some(shape)) if shape.uniform.is_none() => Mode::Wavefront(shape),
            (Mode::Uniform { n }, Some(shape)) if shape.uniform == Some(n) => {
                Mode::Wavefront(shape)
            }
            (Mode::Adaptive { depth }, Some(shape)) if shape.uniform.is_none() => {
                Mode::AdaptiveWavefront { depth, shape }
            }
            (mode, _) => mode,
        };
        // Rows a band may have: its pixels must fit a 2-D dispatch and its output block
        // (16 B a pixel) one binding.
        let dispatch_rows = bounds.max_workgroups.saturating_mul(bounds.workgroup_side);
        let block_rows = (bounds.max_binding / (16 * w as u64)).min(u32::MAX as u64) as u32;
        // Rows whose tracing invocations have a list slot each (per pixel, or per sample).
        let slots = slot_budget(bounds);
        let slot_rows =
            |per_pixel: u64| (slots / (per_pixel * w as u64)).clamp(1, u32::MAX as u64) as u32;
        let parts = GPU_FRAME_PARTS.min(h) as usize;
        let (chunks, samples_len, split_len) = match mode {
            Mode::None => (
                bands(
                    window,
                    dispatch_rows.min(block_rows).min(slot_rows(1)),
                    parts as u32,
                ),
                1,
                1,
            ),
            Mode::Wavefront(shape) => {
                let rows = dispatch_rows.min(block_rows);
                wavefront_chunks(window, shape, bounds, rows, parts as u32)
            }
            Mode::Uniform { n } => {
                let per_row = w as u64 * (n * n) as u64;
                let sample_rows = bounds.max_binding / (16 * per_row);
                let rows = (sample_rows.min(u32::MAX as u64) as u32).min(block_rows);
                let rows = rows.min(slot_rows((n * n) as u64));
                let chunks = bands(window, rows.min(dispatch_rows), parts as u32);
                let rows = chunks.iter().map(|c| c.size[1]).max().unwrap_or(1);
                (chunks, per_row * rows as u64, 1)
            }
            Mode::Adaptive { depth } => {
                let side = adaptive_side(bounds, [w, h], depth, slots, |_| 0);
                let lattice = (side as u64 * (1 << depth) as u64 + 1).pow(2);
                let chunks = squares(window, side);
                (chunks, lattice, split_offset(side, depth).max(1) as u64)
            }
            Mode::AdaptiveWavefront { depth, shape } => {
                // The lattice, then the queues of the busiest lattice pass's samples
                // (adaptive_slots), in one binding.
                let vec4s = |side: u32| {
                    lattice_queue_bytes(side, depth) / 16
                        + adaptive_slots(side, side, side, depth) * shape.vec4s_per_sample()
                };
                // A tree's generation: up to TREE_PATHS_PER_SAMPLE paths a sample.
                let samples = slots / shape.slots_per_sample();
                let side = adaptive_side(bounds, [w, h], depth, samples, vec4s);
                let chunks = squares(window, side);
                (chunks, vec4s(side), split_offset(side, depth).max(1) as u64)
            }
        };
        let parts = split_even(chunks.len(), parts.min(chunks.len()));
        let work_levels = match mode {
            Mode::Adaptive { depth } => depth.max(1) as u64,
            Mode::Wavefront(shape) => shape.work_levels(),
            // The wavefront's from WAVEFRONT_WORK_BASE on, after adaptive AA's levels'.
            Mode::AdaptiveWavefront { shape, .. } => {
                WAVEFRONT_WORK_BASE as u64 + shape.work_levels()
            }
            _ => 1,
        };
        let chunk_slots = |c: &Chunk| match mode {
            Mode::None => c.block_pixels(),
            Mode::Wavefront(shape) => {
                c.block_pixels() * shape.samples_per_pixel() * shape.slots_per_sample()
            }
            Mode::Uniform { n } => c.size[0] as u64 * c.size[1] as u64 * (n * n) as u64,
            Mode::Adaptive { depth } => adaptive_slots(c.size[0], c.size[1], c.side, depth),
            Mode::AdaptiveWavefront { depth, shape } => {
                adaptive_slots(c.size[0], c.size[1], c.side, depth) * shape.slots_per_sample()
            }
        };
        let lists_len = match bounds.lane_list_words {
            0 => 0,
            words => words as u64 * chunks.iter().map(chunk_slots).max().unwrap_or(0),
        };
        FramePlan {
            mode,
            chunks,
            parts,
            samples_len,
            split_len,
            work_levels,
            lists_len,
        }
    }
}

impl FramePlan {
    /// The dispatches of chunk `index`, in order (`sentinel`: [`GpuTile::sentinel`]).
    pub fn dispatches(&self, index: usize, sentinel: u32, bounds: AdapterBounds) -> Vec<Dispatch> {
        let c = self.chunks[index];
        let [w, h] = c.size;
        let params = |level: u32, items: u32| GpuTile {
            origin: c.origin,
            size: c.size,
            side: c.side,
            level,
            items,
            sentinel,
            stratum: ALL_STRATA,
            slice: 0,
        };
        let linear = |items: u32| {
            let lanes = bounds.workgroup_side * bounds.workgroup_side;
            let (x, y) = linear_workgroups(items, lanes, bounds.max_workgroups);
            Workgroups::Direct(x, y)
        };
        let side = bounds.workgroup_side;
        let square = Workgroups::Direct(w.div_ceil(side), h.div_ceil(side));
        let run = |entry: usize, params: GpuTile, workgroups: Workgroups| Dispatch {
            entry,
            chunk: index,
            params,
            workgroups,
            clears_work: false,
            writes_args: false,
            offsets: BindingOffsets::default(),
        };
        match self.mode {
            Mode::None => vec![run(0, params(0, 0), square)],
            Mode::Wavefront(shape) => {
                // The camera pass starts the chunk (its counters cleared), the
                // generations follow; under uniform AA the resolve pass ends it.
                let n = w * h * shape.samples_per_pixel() as u32;
                let camera = Dispatch {
                    clears_work: true,
                    ..run(0, params(0, n), linear(n))
                };
                if shape.tree {
                    let mut out = tree_dispatches(shape, camera, 1, camera.offsets);
                    if shape.uniform.is_some() {
                        out.push(run(10, params(0, n), square));
                    }
                    return out;
                }
                let mut out = wavefront_generations(shape, camera, 1, camera.offsets);
                if shape.uniform.is_some() {
                    out.push(run(6, params(0, n), square));
                }
                out
            }
            Mode::Uniform { n } => {
                let items = w * h * n * n;
                vec![
                    run(0, params(0, items), linear(items)),
                    run(1, params(0, 0), square),
                ]
            }
            Mode::Adaptive { depth } => {
                // Every pixel corner, then every pixel centre (d ≥ 1).
                let first = c.adaptive_tile(depth).first_pass_len();
                let mut out = vec![Dispatch {
                    clears_work: true,
                    ..run(0, params(0, first), linear(first))
                }];
                for level in 0..depth {
                    out.push(if level == 0 {
                        run(1, params(0, w * h), linear(w * h))
                    } else {
                        let args = Workgroups::Indirect(midpoint_args(level - 1) + 12);
                        run(1, params(level, 0), args)
                    });
                    out.push(Dispatch {
                        writes_args: true,
                        ..run(4, params(level, 0), Workgroups::Direct(1, 1))
                    });
                    let args = Workgroups::Indirect(midpoint_args(level));
                    out.push(run(2, params(level, 0), args));
                }
                out.push(run(3, params(0, 0), square));
                out
            }
            Mode::AdaptiveWavefront { depth, shape } => {
                adaptive_wavefront_dispatches(c, depth, shape, &run, &params, &linear, square)
            }
        }
    }
}

/// The chunks of `window` through the wavefront kernels, and the samples array's vec4s:
/// bands of at most `rows` rows whose queues (of every sample of every pixel) fit one
/// binding and whose tracing invocations each have a list slot; where a tree's queues do
/// not fit even one row, pieces of rows.
fn wavefront_chunks(
    window: PixelRect,
    shape: WavefrontShape,
    bounds: AdapterBounds,
    rows: u32,
    parts: u32,
) -> (Vec<Chunk>, u64, u64) {
    let w = window.width() as u64;
    let slots = slot_budget(bounds);
    let per_pixel = shape.samples_per_pixel();
    let pixel_bytes = per_pixel * shape.vec4s_per_sample() * 16;
    let pixel_slots = per_pixel * shape.slots_per_sample();
    let queue_rows = bounds.max_binding / (w * pixel_bytes);
    let slot_rows = slots / (pixel_slots * w);
    let rows = (queue_rows.min(slot_rows).clamp(1, u32::MAX as u64) as u32).min(rows);
    let fit = (bounds.max_binding / pixel_bytes)
        .min(slots / pixel_slots)
        .max(1);
    let chunks = if w > fit {
        row_pieces(window, fit as u32)
    } else {
        bands(window, rows, parts)
    };
    let pixels = chunks.iter().map(|c| c.block_pixels()).max().unwrap_or(1);
    (chunks, shape.vec4s_per_sample() * per_pixel * pixels, 1)
}

/// The dispatches of adaptive tile `c` through the wavefront kernels
/// ([`Entry::ADAPTIVE_WAVEFRONT`]'s indices), from [`FramePlan::dispatches`]'s `run`,
/// `params` and `linear`: per lattice pass (the corner pass, then a midpoint pass a level
/// after its decide and work-args passes) the camera pass, five passes a generation and
/// the store pass; the integrate pass.
fn adaptive_wavefront_dispatches(
    c: Chunk,
    depth: u32,
    shape: WavefrontShape,
    run: &impl Fn(usize, GpuTile, Workgroups) -> Dispatch,
    params: &impl Fn(u32, u32) -> GpuTile,
    linear: &impl Fn(u32) -> Workgroups,
    square: Workgroups,
) -> Vec<Dispatch> {
    let [w, h] = c.size;
    // Each lattice pass's samples take the queues' first `n` slots.
    let n = adaptive_slots(w, h, c.side, depth) as u32;
    let queues = BindingOffsets {
        samples: lattice_queue_bytes(c.side, depth),
        work: 0,
    };
    let generation = BindingOffsets {
        work: WAVEFRONT_WORK_BYTES,
        ..queues
    };
    // Lattice pass `pass` (0: corners, 1 + k: level k's midpoints) over
    // `points` invocations: its camera pass, per generation closest, shade,
    // args, shadow, gather (generation 0's over the pass's invocations, the
    // rest at the args kernel's offsets, after adaptive AA's), the store pass.
    let lattice_pass = |pass: u32, points: Workgroups| {
        let camera = Dispatch {
            offsets: queues,
            ..run(3, params(pass, n), points)
        };
        // A tree: its rounds and fold between the generations and the store.
        let (mut out, store) = match shape.tree {
            true => (tree_dispatches(shape, camera, 4, generation), 13),
            false => (wavefront_generations(shape, camera, 4, generation), 9),
        };
        out.push(run(store, params(pass, n), points));
        out
    };
    let mut out = lattice_pass(0, linear(c.adaptive_tile(depth).first_pass_len()));
    out[0].clears_work = true;
    for level in 0..depth {
        out.push(if level == 0 {
            run(0, params(0, w * h), linear(w * h))
        } else {
            let args = Workgroups::Indirect(midpoint_args(level - 1) + 12);
            run(0, params(level, 0), args)
        });
        out.push(Dispatch {
            writes_args: true,
            ..run(1, params(level, 0), Workgroups::Direct(1, 1))
        });
        out.extend(lattice_pass(
            level + 1,
            Workgroups::Indirect(midpoint_args(level)),
        ));
    }
    out.push(run(2, params(0, 0), square));
    out
}

/// The wavefront kernels' dispatches of a chunk after its `camera` pass (which they
/// copy the chunk, items and stratum of): per generation g closest, shade, args, shadow,
/// gather (entries `closest` … `closest` + 4 of the mode's list, bound at `offsets`) —
/// generation 0's over the chunk's samples as the camera pass, later ones' and every
/// shadow pass's as the args kernel wrote them (`generation_words` a generation from
/// `offsets.work`: the next generation's, then this one's shadow pass, with CSG one
/// dispatch a slice, `GpuTile::slice` telling it which).
fn wavefront_generations(
    shape: WavefrontShape,
    camera: Dispatch,
    closest: usize,
    offsets: BindingOffsets,
) -> Vec<Dispatch> {
    let mut out = vec![camera];
    let args = |at: u64| Workgroups::Indirect(offsets.work + at);
    for g in 0..shape.generations {
        let pass = |entry: usize, workgroups: Workgroups| Dispatch {
            entry: closest + entry,
            params: GpuTile {
                level: g,
                ..camera.params
            },
            workgroups,
            clears_work: false,
            writes_args: false,
            offsets,
            ..camera
        };
        let paths = match g {
            0 => camera.workgroups,
            _ => args(shape.paths_args(g)),
        };
        out.push(pass(0, paths));
        out.push(pass(1, paths));
        let mut args_kernel = Dispatch {
            writes_args: true,
            ..pass(2, Workgroups::Direct(1, 1))
        };
        args_kernel.params.slice = shape.shadow_slices;
        out.push(args_kernel);
        for slice in 0..shape.shadow_slices {
            let mut shadow = pass(3, args(shape.shadow_args(g, slice)));
            shadow.params.slice = slice;
            out.push(shadow);
        }
        out.push(pass(4, paths));
    }
    out
}

/// `glint view`'s frame `stratum` of `band` through the wavefront kernels
/// ([`Entry::WAVEFRONT_VIEW`]): the camera pass over the band's pixels, one sample each
/// (its stratum `stratum`, every pass told so by [`GpuTile::stratum`]), the
/// generations, then the store into the sums over the same samples.
pub fn view_wavefront_dispatches(
    band: Chunk,
    shape: WavefrontShape,
    stratum: u32,
    sentinel: u32,
    bounds: AdapterBounds,
) -> Vec<Dispatch> {
    let items = band.size[0] * band.size[1];
    let lanes = bounds.workgroup_side * bounds.workgroup_side;
    let (x, y) = linear_workgroups(items, lanes, bounds.max_workgroups);
    let camera = Dispatch {
        entry: 0,
        chunk: 0,
        params: GpuTile {
            origin: band.origin,
            size: band.size,
            side: band.side,
            level: 0,
            items,
            sentinel,
            stratum,
            slice: 0,
        },
        workgroups: Workgroups::Direct(x, y),
        clears_work: true,
        writes_args: false,
        offsets: BindingOffsets::default(),
    };
    // A tree: its rounds and fold before the store.
    let (mut out, store) = match shape.tree {
        true => (tree_dispatches(shape, camera, 1, camera.offsets), 10),
        false => (wavefront_generations(shape, camera, 1, camera.offsets), 6),
    };
    out.push(Dispatch {
        entry: store,
        clears_work: false,
        ..camera
    });
    out
}

/// A tree's generations after its `camera` pass (which they copy the chunk, items and
/// stratum of): per generation g closest, shade, args, the shadow pass (each request's
/// first leg), then SHADOW_ROUNDS rounds of leg closest and crossing (level: the round)
/// with the leg args between rounds, and gather; after the last generation the fold over
/// the camera pass's samples (entries `closest` … `closest` + 8 of the mode's list:
/// `Entry::WAVEFRONT_TREE`'s after its camera pass, bound at `offsets`). Generation 0's
/// passes over paths run over the samples as the camera pass, later ones' and every
/// shadow pass and round as the args kernels wrote them (from `offsets.work`).
fn tree_dispatches(
    shape: WavefrontShape,
    camera: Dispatch,
    closest: usize,
    offsets: BindingOffsets,
) -> Vec<Dispatch> {
    let mut out = vec![camera];
    let args = |at: u64| Workgroups::Indirect(offsets.work + at);
    let pass = |entry: usize, level: u32, workgroups: Workgroups| Dispatch {
        entry: closest + entry,
        params: GpuTile {
            level,
            ..camera.params
        },
        workgroups,
        clears_work: false,
        writes_args: false,
        offsets,
        ..camera
    };
    let writes_args = |d: Dispatch| Dispatch {
        writes_args: true,
        ..d
    };
    let one = Workgroups::Direct(1, 1);
    for g in 0..shape.generations {
        let paths = match g {
            0 => camera.workgroups,
            _ => args(shape.paths_args(g)),
        };
        out.push(pass(0, g, paths));
        out.push(pass(1, g, paths));
        out.push(writes_args(pass(2, g, one)));
        out.push(pass(3, g, args(shape.shadow_args(g, 0))));
        for r in 0..SHADOW_ROUNDS {
            let legs = args(WavefrontShape::round_args(r));
            out.push(pass(4, r, legs));
            out.push(pass(5, r, legs));
            if r + 1 < SHADOW_ROUNDS {
                out.push(writes_args(pass(6, r, one)));
            }
        }
        out.push(pass(7, g, paths));
    }
    out.push(pass(8, 0, camera.workgroups));
    out
}

/// Workgroups of `lanes` invocations of a one-dimensional kernel over `items`
/// invocations: x at most `max_workgroups`, the rest in y (the kernels rebuild the index
/// with `linear_index`).
pub fn linear_workgroups(items: u32, lanes: u32, max_workgroups: u32) -> (u32, u32) {
    let groups = items.div_ceil(lanes);
    if groups <= max_workgroups {
        (groups, 1)
    } else {
        (max_workgroups, groups.div_ceil(max_workgroups))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constants::{TREE_PATHS_PER_SAMPLE, TREE_VERTICES_PER_SAMPLE};

    fn globals(w: u32, h: u32, aa_mode: u32) -> PackedGlobals {
        PackedGlobals {
            width: w,
            height: h,
            aa_mode,
            aa_samples: 4,
            aa_depth: 3,
            ..bytemuck::Zeroable::zeroed()
        }
    }

    const LAVAPIPE: AdapterBounds = AdapterBounds {
        max_binding: 128 << 20,
        max_workgroups: 65_535,
        workgroup_side: 8,
        lane_list_words: 0,
        wavefront: None,
    };

    /// Every pixel in exactly one chunk, every chunk in exactly one part.
    fn assert_covers(plan: &FramePlan, w: u32, h: u32) {
        let mut seen = vec![0u8; (w * h) as usize];
        for c in &plan.chunks {
            assert!(c.size[0] <= c.side, "{c:?}");
            for y in c.origin[1]..c.origin[1] + c.size[1] {
                for x in c.origin[0]..c.origin[0] + c.size[0] {
                    seen[(y * w + x) as usize] += 1;
                }
            }
        }
        assert!(seen.iter().all(|&s| s == 1), "{w}×{h} {:?}", plan.mode);
        let covered: Vec<usize> = plan.parts.iter().flat_map(|r| r.clone()).collect();
        assert_eq!(covered, (0..plan.chunks.len()).collect::<Vec<_>>());
    }

    #[test]
    fn chunks_cover_the_frame_once_in_a_fixed_number_of_parts() {
        for mode in [0, AA_UNIFORM, AA_ADAPTIVE] {
            let mut part_counts = Vec::new();
            for (w, h) in [(256, 256), (2048, 2048), (1920, 1080), (37, 5), (3000, 7)] {
                let plan = FramePlan::new(&globals(w, h, mode), LAVAPIPE);
                assert_covers(&plan, w, h);
                if w >= 256 && h >= 256 {
                    part_counts.push(plan.parts.len());
                }
            }
            assert!(
                part_counts.iter().all(|&p| p == GPU_FRAME_PARTS as usize),
                "{part_counts:?}"
            );
        }
    }

    #[test]
    fn scratch_fits_one_binding() {
        for mode in [AA_UNIFORM, AA_ADAPTIVE] {
            let plan = FramePlan::new(&globals(2048, 2048, mode), LAVAPIPE);
            assert!(
                plan.samples_len * 16 <= LAVAPIPE.max_binding,
                "{:?}",
                plan.mode
            );
            for c in &plan.chunks {
                assert!(c.block_pixels() * 16 <= LAVAPIPE.max_binding);
            }
        }
        assert_eq!(lattice_side(128 << 20), 2048);
    }

    /// With per-ray lists in storage (scrabble's 562 words a slot), every tracing
    /// invocation of every dispatch has a slot of its own (main: a chunk pixel; uniform
    /// AA: a sample; adaptive AA: a corner-pass point or AA_SPLIT_POINTS per square of a
    /// level), and the slots fit one binding; without lists the plan is as before.
    #[test]
    fn every_tracing_invocation_has_a_list_slot() {
        let words = 562u64;
        let bounds = AdapterBounds {
            lane_list_words: words as u32,
            ..LAVAPIPE
        };
        for mode in [0, AA_UNIFORM, AA_ADAPTIVE] {
            for (w, h) in [(512, 512), (2048, 2048), (37, 5)] {
                let g = globals(w, h, mode);
                let plan = FramePlan::new(&g, bounds);
                assert_covers(&plan, w, h);
                assert!(
                    plan.lists_len * 4 <= LAVAPIPE.max_binding,
                    "{:?}",
                    plan.mode
                );
                let slots = plan.lists_len / words;
                for (k, c) in plan.chunks.iter().enumerate() {
                    for d in plan.dispatches(k, 2, bounds) {
                        let traced = match (plan.mode, plan.mode.entries()[d.entry]) {
                            (_, Entry::Render) => c.block_pixels(),
                            (_, Entry::UniformSamples | Entry::AdaptiveCorners) => {
                                d.params.items as u64
                            }
                            (_, Entry::AdaptiveMidpoints) => {
                                8 * (c.side as u64 * (1 << d.params.level)).pow(2)
                            }
                            _ => 0,
                        };
                        assert!(
                            traced <= slots,
                            "{w}×{h} {:?} {d:?}: {traced} > {slots}",
                            plan.mode
                        );
                    }
                }
                let unbounded = FramePlan::new(&g, LAVAPIPE);
                assert_eq!(unbounded.lists_len, 0);
                assert!(unbounded.chunks.len() <= plan.chunks.len());
            }
        }
    }

    /// AA none through the wavefront kernels: bands cover the frame once, every band's
    /// queues fit one binding, and each band runs the camera pass (clearing its counters)
    /// then closest, shade, args, shadow and gather per generation — generation 0's over
    /// the band's samples, the rest and every shadow pass at the args kernel's offsets,
    /// inside the work-args buffer. With CSG the shadow pass is one dispatch per slice,
    /// every slice 0 … L − 1 once (a skipped one would leave its requests unlit), each at
    /// its own arguments (the args kernel's 3 + 3L words a generation).
    #[test]
    fn wavefront_bands_fit_their_queues_and_run_every_generation() {
        for shadow_slices in [1, 17] {
            let shape = WavefrontShape {
                light_points: 17,
                generations: 6,
                uniform: None,
                tree: false,
                shadow_slices,
            };
            assert_wavefront_bands(shape);
        }
    }

    fn assert_wavefront_bands(shape: WavefrontShape) {
        let bounds = AdapterBounds {
            wavefront: Some(shape),
            max_binding: 16 << 20,
            ..LAVAPIPE
        };
        let slices = shape.shadow_slices as usize;
        let words = 4 * (3 + 3 * slices as u64);
        for (w, h) in [(256, 256), (1920, 1080), (37, 5)] {
            let plan = FramePlan::new(&globals(w, h, 0), bounds);
            assert_eq!(plan.mode, Mode::Wavefront(shape));
            assert_covers(&plan, w, h);
            assert!(plan.samples_len * 16 <= bounds.max_binding, "{w}×{h}");
            for (k, c) in plan.chunks.iter().enumerate() {
                assert!(shape.vec4s_per_sample() * c.block_pixels() <= plan.samples_len);
                let d = plan.dispatches(k, 2, bounds);
                assert_eq!(d.len(), 1 + (4 + slices) * shape.generations as usize);
                assert!(d[0].clears_work && d[0].entry == 0);
                for (g, pass) in d[1..].chunks(4 + slices).enumerate() {
                    let entries: Vec<usize> = pass.iter().map(|d| d.entry).collect();
                    let mut expected_entries = vec![1, 2, 3];
                    expected_entries.extend(std::iter::repeat_n(4, slices));
                    expected_entries.push(5);
                    assert_eq!(entries, expected_entries);
                    assert!(pass.iter().all(|d| d.params.level == g as u32));
                    assert!(pass[2].writes_args);
                    assert_eq!(pass[2].params.slice, shape.shadow_slices);
                    let offsets = pass.iter().filter_map(|d| match d.workgroups {
                        Workgroups::Indirect(at) => Some(at),
                        Workgroups::Direct(..) => None,
                    });
                    for at in offsets {
                        assert!(at + 12 <= plan.work_levels * 24, "{at}");
                    }
                    let expected = match g {
                        0 => d[0].workgroups,
                        _ => Workgroups::Indirect(words * (g as u64 - 1)),
                    };
                    assert_eq!(pass[0].workgroups, expected);
                    assert_eq!(pass[3 + slices].workgroups, expected);
                    let shadows = &pass[3..3 + slices];
                    let slice_of: Vec<u32> = shadows.iter().map(|d| d.params.slice).collect();
                    assert_eq!(slice_of, (0..slices as u32).collect::<Vec<_>>());
                    for (s, shadow) in shadows.iter().enumerate() {
                        let at = words * g as u64 + 12 + 12 * s as u64;
                        assert_eq!(shadow.workgroups, Workgroups::Indirect(at));
                    }
                }
            }
            // Uniform AA keeps its own passes.
            let uniform = FramePlan::new(&globals(w, h, AA_UNIFORM), bounds);
            assert!(matches!(uniform.mode, Mode::Uniform { .. }));
        }
        assert!(plan_counters_fit(shape));
    }

    /// Adaptive AA through the wavefront kernels: square tiles cover the frame once, and
    /// each tile's lattice and queues fit one binding, the queues after the lattice at a
    /// 256-byte offset; each lattice pass (corners, then one a level) runs its camera
    /// pass (bound from the queues), closest, shade, args, shadow and gather per
    /// generation (bound from the queues and from the wavefront's counters and
    /// arguments, which lie after adaptive AA's levels' and inside the buffers) and its
    /// store pass (bound whole); every tracing invocation has a list slot.
    #[test]
    fn adaptive_wavefront_tiles_hold_lattice_and_queues_and_run_every_lattice_pass() {
        let shape = WavefrontShape {
            light_points: 17,
            generations: 3,
            uniform: None,
            tree: false,
            shadow_slices: 1,
        };
        let words = 562;
        let bounds = AdapterBounds {
            wavefront: Some(shape),
            max_binding: 16 << 20,
            lane_list_words: words,
            ..LAVAPIPE
        };
        let generations = shape.generations as usize;
        for depth in [1, 2, 3] {
            for (w, h) in [(256, 256), (1920, 1080), (37, 5)] {
                let g = PackedGlobals {
                    aa_depth: depth,
                    ..globals(w, h, AA_ADAPTIVE)
                };
                let plan = FramePlan::new(&g, bounds);
                assert_eq!(plan.mode, Mode::AdaptiveWavefront { depth, shape });
                assert_covers(&plan, w, h);
                assert!(plan.samples_len * 16 <= bounds.max_binding, "{w}×{h}");
                assert!(4 * depth as u64 <= WAVEFRONT_WORK_BYTES);
                let entries = plan.mode.entries();
                let entry = |d: &Dispatch| entries[d.entry];
                for (k, c) in plan.chunks.iter().enumerate() {
                    let lattice = (c.side as u64 * (1 << depth) + 1).pow(2);
                    let queues = BindingOffsets {
                        samples: lattice_queue_bytes(c.side, depth),
                        work: 0,
                    };
                    assert_eq!(queues.samples % 256, 0);
                    assert!(queues.samples >= 16 * lattice);
                    let d = plan.dispatches(k, 2, bounds);
                    assert!(d[0].clears_work);
                    assert_eq!(entry(&d[0]), Entry::WavefrontLatticeCamera);
                    let n = d[0].params.items as u64;
                    assert!(queues.samples / 16 + n * shape.vec4s_per_sample() <= plan.samples_len);
                    assert!(n * words as u64 <= plan.lists_len);
                    let cameras: Vec<usize> = (0..d.len())
                        .filter(|&i| entry(&d[i]) == Entry::WavefrontLatticeCamera)
                        .collect();
                    assert_eq!(cameras.len(), 1 + depth as usize);
                    for (pass, &at) in cameras.iter().enumerate() {
                        let run = &d[at..at + 2 + 5 * generations];
                        let (camera, store) = (run[0], run[run.len() - 1]);
                        assert_eq!(camera.params.level, pass as u32);
                        assert_eq!(camera.offsets, queues);
                        assert_eq!(entry(&store), Entry::WavefrontLatticeStore);
                        assert_eq!(store.params.level, pass as u32);
                        assert_eq!(store.offsets, BindingOffsets::default());
                        assert_eq!(store.workgroups, camera.workgroups);
                        for (g, gen) in run[1..run.len() - 1].chunks(5).enumerate() {
                            let names: Vec<Entry> = gen.iter().map(entry).collect();
                            assert_eq!(names, Entry::WAVEFRONT[1..6]);
                            assert!(gen[2].writes_args);
                            for p in gen {
                                assert_eq!(p.params.level, g as u32);
                                assert_eq!(p.params.items as u64, n);
                                assert_eq!(p.offsets.samples, queues.samples);
                                assert_eq!(p.offsets.work, WAVEFRONT_WORK_BYTES);
                                if let Workgroups::Indirect(at) = p.workgroups {
                                    let ours = at >= WAVEFRONT_WORK_BYTES;
                                    assert!(ours || g == 0, "{at}");
                                    assert!(at + 12 <= plan.work_levels * 24, "{at}");
                                }
                            }
                            if g == 0 {
                                assert_eq!(gen[0].workgroups, camera.workgroups);
                            }
                        }
                    }
                    // Adaptive AA's own arguments lie before the wavefront's.
                    for p in &d {
                        let adaptive = matches!(entry(p), Entry::AdaptiveDecide)
                            || p.offsets.samples == queues.samples && p.offsets.work == 0;
                        if let (true, Workgroups::Indirect(at)) = (adaptive, p.workgroups) {
                            assert!(at + 12 <= WAVEFRONT_WORK_BYTES, "{at}");
                        }
                    }
                    assert_eq!(entry(&d[d.len() - 1]), Entry::AdaptiveIntegrate);
                }
            }
        }
    }

    /// Adaptive AA's tiles in a scene with refraction: the lattice and the busiest lattice
    /// pass's tree queues fit one binding, each of its paths (TREE_PATHS_PER_SAMPLE a
    /// sample) has a list slot, and each lattice pass runs the lattice camera pass, a
    /// tree's generations with their rounds at the wavefront's binding offsets (their
    /// indirect arguments after adaptive AA's), the fold over the camera pass's
    /// invocations, then the store.
    #[test]
    fn adaptive_tree_tiles_run_the_trees_passes_and_fold_every_lattice_pass() {
        let shape = WavefrontShape {
            light_points: 5,
            generations: 4,
            uniform: None,
            tree: true,
            shadow_slices: 1,
        };
        let words = 562;
        let bounds = AdapterBounds {
            wavefront: Some(shape),
            max_binding: 64 << 20,
            lane_list_words: words,
            ..LAVAPIPE
        };
        let per_generation = 5 + 2 * SHADOW_ROUNDS as usize + SHADOW_ROUNDS as usize - 1;
        for depth in [1, 2] {
            let g = PackedGlobals {
                aa_depth: depth,
                ..globals(300, 200, AA_ADAPTIVE)
            };
            let plan = FramePlan::new(&g, bounds);
            assert_eq!(plan.mode, Mode::AdaptiveWavefront { depth, shape });
            assert_covers(&plan, 300, 200);
            assert!(plan.samples_len * 16 <= bounds.max_binding);
            let entries = plan.mode.entries();
            assert_eq!(entries, &Entry::ADAPTIVE_WAVEFRONT_TREE);
            let entry = |d: &Dispatch| entries[d.entry];
            for (k, c) in plan.chunks.iter().enumerate() {
                let queues = lattice_queue_bytes(c.side, depth);
                let d = plan.dispatches(k, 2, bounds);
                let n = d[0].params.items as u64;
                assert!(queues / 16 + n * shape.vec4s_per_sample() <= plan.samples_len);
                let paths = n * TREE_PATHS_PER_SAMPLE as u64;
                assert!(paths * words as u64 <= plan.lists_len, "slots");
                let cameras: Vec<usize> = (0..d.len())
                    .filter(|&i| entry(&d[i]) == Entry::WavefrontLatticeCamera)
                    .collect();
                assert_eq!(cameras.len(), 1 + depth as usize);
                for (pass, &at) in cameras.iter().enumerate() {
                    let run = &d[at..at + 3 + per_generation * shape.generations as usize];
                    let (camera, fold, store) = (run[0], run[run.len() - 2], run[run.len() - 1]);
                    assert_eq!(camera.params.level, pass as u32);
                    assert_eq!(camera.offsets.samples, queues);
                    assert_eq!(entry(&fold), Entry::WavefrontFold);
                    assert_eq!(fold.workgroups, camera.workgroups);
                    assert_eq!(entry(&store), Entry::WavefrontLatticeStore);
                    assert_eq!(store.workgroups, camera.workgroups);
                    assert_eq!(store.offsets, BindingOffsets::default());
                    for p in &run[1..run.len() - 1] {
                        assert!(entries[p.entry].is_wavefront(), "{p:?}");
                        assert_eq!(p.params.items as u64, n);
                        assert_eq!(p.offsets.samples, queues);
                        assert_eq!(p.offsets.work, WAVEFRONT_WORK_BYTES);
                        match p.workgroups {
                            Workgroups::Indirect(at) if p.workgroups != camera.workgroups => {
                                assert!(at >= WAVEFRONT_WORK_BYTES, "{at}");
                                assert!(at + 12 <= plan.work_levels * 24, "{at}");
                            }
                            _ => {}
                        }
                    }
                    let gens = &run[1..run.len() - 2];
                    for gen in gens.chunks(per_generation) {
                        let names: Vec<Entry> = gen.iter().map(entry).collect();
                        assert_eq!(names[..4], Entry::WAVEFRONT_TREE[1..5]);
                        assert_eq!(names[per_generation - 1], Entry::WavefrontGather);
                    }
                }
                assert_eq!(entry(&d[d.len() - 1]), Entry::AdaptiveIntegrate);
            }
        }
    }

    /// Uniform AA through the wavefront kernels: a band's samples are its pixels × n²
    /// (stratum s of pixel p is sample p·n² + s), its queues fit one binding and each of
    /// its samples has a list slot; each band runs the camera pass, the generations over
    /// its samples, then the resolve pass over its pixels. AA none's shape leaves uniform
    /// AA to its own passes, and uniform AA's shape AA none.
    #[test]
    fn wavefront_uniform_bands_sample_every_stratum_then_resolve() {
        let words = 272u64;
        for n in [1, 2, 3, 4] {
            let shape = WavefrontShape {
                light_points: 5,
                generations: 3,
                uniform: Some(n),
                tree: false,
                shadow_slices: 1,
            };
            // (A row of 1920 pixels at 4×4 takes 30 720 slots: 32 MiB of lists.)
            let bounds = AdapterBounds {
                wavefront: Some(shape),
                max_binding: 64 << 20,
                lane_list_words: words as u32,
                ..LAVAPIPE
            };
            for (w, h) in [(256, 256), (1920, 1080), (37, 5)] {
                let g = PackedGlobals {
                    aa_samples: n,
                    ..globals(w, h, AA_UNIFORM)
                };
                let plan = FramePlan::new(&g, bounds);
                assert_eq!(plan.mode, Mode::Wavefront(shape));
                assert_eq!(plan.mode.entries(), &Entry::WAVEFRONT);
                assert_covers(&plan, w, h);
                assert!(plan.samples_len * 16 <= bounds.max_binding, "{w}×{h}");
                assert!(plan.lists_len * 4 <= bounds.max_binding, "{w}×{h}");
                let nn = (n * n) as u64;
                for (k, c) in plan.chunks.iter().enumerate() {
                    let samples = c.size[0] as u64 * c.size[1] as u64 * nn;
                    assert!(shape.vec4s_per_sample() * samples <= plan.samples_len);
                    assert!(
                        samples * words <= plan.lists_len,
                        "{w}×{h}: a slot a sample"
                    );
                    let d = plan.dispatches(k, 2, bounds);
                    assert_eq!(d.len(), 2 + 5 * shape.generations as usize);
                    assert!(d[..d.len() - 1]
                        .iter()
                        .all(|d| d.params.items as u64 == samples));
                    assert_eq!(d[0].workgroups, d[1].workgroups, "camera, generation 0");
                    let Workgroups::Direct(x, y) = d[0].workgroups else {
                        panic!("the camera pass is direct")
                    };
                    assert!(x as u64 * y as u64 * 64 >= samples);
                    let resolve = d.last().unwrap();
                    assert_eq!(resolve.entry, 6);
                    assert_eq!(
                        resolve.workgroups,
                        Workgroups::Direct(c.size[0].div_ceil(8), c.size[1].div_ceil(8))
                    );
                }
                let none = FramePlan::new(&globals(w, h, 0), bounds);
                assert!(matches!(none.mode, Mode::None));
                let aa_none = AdapterBounds {
                    wavefront: Some(WavefrontShape {
                        uniform: None,
                        ..shape
                    }),
                    ..bounds
                };
                let uniform = FramePlan::new(&g, aa_none);
                assert!(matches!(uniform.mode, Mode::Uniform { .. }));
                assert_eq!(
                    FramePlan::new(&globals(w, h, 0), aa_none).mode.entries(),
                    &Entry::WAVEFRONT[..6]
                );
            }
        }
    }

    /// `glint view`'s frame s of a band through the wavefront kernels: the camera pass
    /// over the band's pixels (one sample each), every generation's five passes, then the
    /// store over the same samples; every pass carries the frame's stratum.
    #[test]
    fn a_view_frame_samples_one_stratum_a_pixel_then_stores() {
        let shape = WavefrontShape {
            light_points: 3,
            generations: 4,
            uniform: Some(3),
            tree: false,
            shadow_slices: 1,
        };
        let band = bands(PixelRect::full(37, 5), 5, 1)[0];
        let d = view_wavefront_dispatches(band, shape, 7, 2, LAVAPIPE);
        assert_eq!(d.len(), 2 + 5 * shape.generations as usize);
        let entries: Vec<usize> = d.iter().map(|d| d.entry).collect();
        let mut expected = vec![0];
        for _ in 0..shape.generations {
            expected.extend([1, 2, 3, 4, 5]);
        }
        expected.push(6);
        assert_eq!(entries, expected);
        assert_eq!(Entry::WAVEFRONT_VIEW[6], Entry::WavefrontViewStore);
        assert!(d
            .iter()
            .all(|d| d.params.stratum == 7 && d.params.items == 37 * 5));
        assert_eq!(
            d[4].workgroups,
            Workgroups::Indirect(12),
            "generation 0's shadows"
        );
        assert_eq!(
            d[6].workgroups,
            Workgroups::Indirect(0),
            "generation 1's paths"
        );
        let (camera, store) = (d[0], d[d.len() - 1]);
        assert_eq!(camera.workgroups, Workgroups::Direct(3, 1));
        assert_eq!(
            (store.workgroups, store.params),
            (camera.workgroups, camera.params)
        );
        assert!(camera.clears_work && !store.clears_work);
    }

    /// A view frame of a tree: the camera pass of the frame's stratum, a tree's
    /// generations with their rounds, the fold over the band's samples, then the store
    /// (entries of `Entry::WAVEFRONT_VIEW_TREE`), every pass told the stratum.
    #[test]
    fn a_view_frame_of_a_tree_folds_then_stores() {
        let shape = WavefrontShape {
            light_points: 3,
            generations: 4,
            uniform: None,
            tree: true,
            shadow_slices: 1,
        };
        let band = bands(PixelRect::full(37, 5), 5, 1)[0];
        let d = view_wavefront_dispatches(band, shape, 2, 2, LAVAPIPE);
        let per_generation = 5 + 2 * SHADOW_ROUNDS as usize + SHADOW_ROUNDS as usize - 1;
        assert_eq!(d.len(), 3 + per_generation * shape.generations as usize);
        let names: Vec<Entry> = d
            .iter()
            .map(|d| Entry::WAVEFRONT_VIEW_TREE[d.entry])
            .collect();
        assert_eq!(names[..5], Entry::WAVEFRONT_VIEW_TREE[..5]);
        assert_eq!(names[names.len() - 2], Entry::WavefrontFold);
        assert_eq!(names[names.len() - 1], Entry::WavefrontViewStore);
        assert!(d
            .iter()
            .all(|d| d.params.stratum == 2 && d.params.items == 37 * 5));
        let (camera, fold, store) = (d[0], d[d.len() - 2], d[d.len() - 1]);
        assert_eq!(fold.workgroups, camera.workgroups);
        assert_eq!(
            (store.workgroups, store.params),
            (camera.workgroups, camera.params)
        );
        assert!(camera.clears_work && !store.clears_work);
    }

    /// A tree's bands (scenes with refraction): their queues fit one binding, every
    /// closest or shade invocation of a generation (up to TREE_PATHS_PER_SAMPLE a sample)
    /// has a list slot, and each band runs the camera pass, then per generation closest,
    /// shade, args, shadow, SHADOW_ROUNDS rounds of leg closest and crossing with the leg
    /// args between them, gather — then the fold; every indirect offset inside the
    /// work-args buffer, rounds at the same offsets every generation, the generations'
    /// after them.
    #[test]
    fn tree_bands_run_every_generation_every_round_and_the_fold() {
        let shape = WavefrontShape {
            light_points: 17,
            generations: 9,
            uniform: None,
            tree: true,
            shadow_slices: 1,
        };
        assert_eq!(
            shape.vec4s_per_sample(),
            3 + (14 + 10 * 17) * TREE_PATHS_PER_SAMPLE as u64 + 2 * TREE_VERTICES_PER_SAMPLE as u64
        );
        let words = 562;
        let bounds = AdapterBounds {
            wavefront: Some(shape),
            max_binding: 16 << 20,
            lane_list_words: words,
            ..LAVAPIPE
        };
        // 1920 samples of 13.5 KiB are more than one 16 MiB binding: rows in pieces.
        for (w, h) in [(256, 256), (1920, 1080), (37, 5)] {
            let plan = FramePlan::new(&globals(w, h, 0), bounds);
            assert_eq!(plan.mode, Mode::Wavefront(shape));
            assert_eq!(plan.mode.entries(), &Entry::WAVEFRONT_TREE[..10]);
            assert_eq!(plan.chunks.len() > h as usize, w == 1920, "{w}×{h}");
            assert_covers(&plan, w, h);
            assert!(plan.samples_len * 16 <= bounds.max_binding, "{w}×{h}");
            assert!(plan.lists_len * 4 <= bounds.max_binding.min(LIST_BUDGET_BYTES));
            assert!(plan.work_levels >= 11, "the eleven counters");
            for (k, c) in plan.chunks.iter().enumerate() {
                assert!(shape.vec4s_per_sample() * c.block_pixels() <= plan.samples_len);
                let paths = TREE_PATHS_PER_SAMPLE as u64 * c.block_pixels();
                assert!(paths * words as u64 <= plan.lists_len, "{w}×{h}: slots");
                let d = plan.dispatches(k, 2, bounds);
                let per_generation = 5 + 2 * SHADOW_ROUNDS as usize + SHADOW_ROUNDS as usize - 1;
                assert_eq!(d.len(), 2 + per_generation * shape.generations as usize);
                assert!(d[0].clears_work && d[0].entry == 0);
                let fold = d.last().unwrap();
                assert_eq!((fold.entry, fold.workgroups), (9, d[0].workgroups));
                for (g, pass) in d[1..d.len() - 1].chunks(per_generation).enumerate() {
                    let g = g as u32;
                    let entries: Vec<usize> = pass.iter().map(|d| d.entry).collect();
                    let mut expected = vec![1, 2, 3, 4];
                    for r in 0..SHADOW_ROUNDS {
                        expected.extend([5, 6]);
                        if r + 1 < SHADOW_ROUNDS {
                            expected.push(7);
                        }
                    }
                    expected.push(8);
                    assert_eq!(entries, expected);
                    let rounds = &pass[4..pass.len() - 1];
                    for (r, round) in rounds.chunks(3).enumerate() {
                        assert!(round.iter().all(|d| d.params.level == r as u32));
                        assert_eq!(round[0].workgroups, Workgroups::Indirect(12 * r as u64));
                        assert_eq!(round[1].workgroups, round[0].workgroups);
                        if round.len() == 3 {
                            assert!(round[2].writes_args);
                        }
                    }
                    for d in pass[..4].iter().chain(&pass[pass.len() - 1..]) {
                        assert_eq!(d.params.level, g);
                    }
                    assert!(pass[2].writes_args);
                    let expected = match g {
                        0 => d[0].workgroups,
                        _ => Workgroups::Indirect(4 * (30 + 6 * (g as u64 - 1))),
                    };
                    assert_eq!(pass[0].workgroups, expected);
                    assert_eq!(pass[1].workgroups, expected);
                    assert_eq!(pass[pass.len() - 1].workgroups, expected);
                    assert_eq!(
                        pass[3].workgroups,
                        Workgroups::Indirect(4 * (30 + 6 * g as u64 + 3))
                    );
                    for at in pass.iter().filter_map(|d| match d.workgroups {
                        Workgroups::Indirect(at) => Some(at),
                        Workgroups::Direct(..) => None,
                    }) {
                        assert!(at + 12 <= plan.work_levels * 24, "{at}");
                    }
                }
            }
        }
    }

    /// A tree's bands under uniform n×n AA: each pixel's n² samples take n² times a
    /// sample's queues and list slots in the band's binding, the generations and the fold
    /// run over every sample, and the resolve pass (the 11th entry) ends the band over
    /// its pixels.
    #[test]
    fn uniform_tree_bands_sample_every_stratum_then_fold_then_resolve() {
        let n = 2;
        let shape = WavefrontShape {
            light_points: 3,
            generations: 9,
            uniform: Some(n),
            tree: true,
            shadow_slices: 1,
        };
        let words = 562;
        let bounds = AdapterBounds {
            wavefront: Some(shape),
            max_binding: 16 << 20,
            lane_list_words: words,
            ..LAVAPIPE
        };
        let mut g = globals(200, 120, AA_UNIFORM);
        g.aa_samples = n;
        let plan = FramePlan::new(&g, bounds);
        assert_eq!(plan.mode, Mode::Wavefront(shape));
        assert_eq!(plan.mode.entries(), &Entry::WAVEFRONT_TREE);
        assert_eq!(plan.mode.entries()[10], Entry::WavefrontResolve);
        assert_covers(&plan, 200, 120);
        assert!(plan.samples_len * 16 <= bounds.max_binding);
        for (k, c) in plan.chunks.iter().enumerate() {
            let samples = c.block_pixels() * (n * n) as u64;
            assert!(shape.vec4s_per_sample() * samples <= plan.samples_len);
            let paths = TREE_PATHS_PER_SAMPLE as u64 * samples;
            assert!(paths * words as u64 <= plan.lists_len, "slots");
            let d = plan.dispatches(k, 2, bounds);
            let per_generation = 5 + 2 * SHADOW_ROUNDS as usize + SHADOW_ROUNDS as usize - 1;
            assert_eq!(d.len(), 3 + per_generation * shape.generations as usize);
            assert_eq!(d[0].params.items as u64, samples);
            let (fold, resolve) = (d[d.len() - 2], d[d.len() - 1]);
            assert_eq!((fold.entry, fold.workgroups), (9, d[0].workgroups));
            let side = bounds.workgroup_side;
            let square = Workgroups::Direct(c.size[0].div_ceil(side), c.size[1].div_ceil(side));
            assert_eq!((resolve.entry, resolve.workgroups), (10, square));
        }
        // Without its shape (another n) uniform AA keeps its own passes.
        g.aa_samples = 3;
        assert!(matches!(
            FramePlan::new(&g, bounds).mode,
            Mode::Uniform { n: 3 }
        ));
    }

    /// The five counters (three path counters, two shadow counters) fit `work_counts`.
    fn plan_counters_fit(shape: WavefrontShape) -> bool {
        let bounds = AdapterBounds {
            wavefront: Some(WavefrontShape {
                generations: 1,
                ..shape
            }),
            ..LAVAPIPE
        };
        FramePlan::new(&globals(8, 8, 0), bounds).work_levels >= 5
    }

    #[test]
    fn linear_dispatches_stay_within_the_dimension_limit() {
        assert_eq!(linear_workgroups(64 * 10, 64, 65_535), (10, 1));
        assert_eq!(linear_workgroups(64 * 10, 16, 65_535), (40, 1));
        for lanes in [1, 16, 64] {
            let (x, y) = linear_workgroups(5 * 1024 * 1024, lanes, 65_535);
            assert!(x <= 65_535 && x as u64 * y as u64 * lanes as u64 >= 5 * 1024 * 1024);
        }
    }
}
