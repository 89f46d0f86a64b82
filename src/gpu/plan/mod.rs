//! The dispatch plan of one GPU frame, as plain arithmetic (no device needed, so it is
//! unit-tested): which chunks of the image each pass covers, how the chunks group into the
//! frame's submits, and the scratch arrays' sizes. This file holds what every form
//! shares (the modes, a dispatch, a chunk, the plan); each form's chunks and dispatches
//! are in a file of their own: `uniform` (AA none and uniform AA through the megakernels),
//! `adaptive` (the lattice), `chain` and `tree` (the wavefront kernels), `view` (`glint
//! view`'s frames), with the cutting into chunks in `chunking` and the queues' sizes in
//! `shape`.
//!
//! A chunk is as large as the adapter's storage-binding limit allows: AA none and uniform
//! AA cover full-width bands of rows (their scratch is per pixel or per sample), adaptive
//! AA square tiles whose lattice of (side·2^d + 1)² points fits one binding. The chunks
//! are grouped into at most [`GPU_FRAME_PARTS`] submits, queued back to back: the host
//! waits only to report progress and to read the image back once, so the number of
//! submits and host waits per frame does not grow with the image.

mod adaptive;
mod chain;
pub mod chunking;
pub mod shape;
mod tree;
mod uniform;
pub mod view;

use crate::constants::{AA_ADAPTIVE, AA_UNIFORM, ALL_STRATA, GPU_FRAME_PARTS, WAVEFRONT_WORK_BASE};
use crate::gpu::compile::shader::Entry;
use crate::gpu::upload::buffers::GpuTile;
use crate::pack::PackedGlobals;
use crate::tiling::{AdaptiveTile, PixelRect};
use adaptive::{adaptive_chunks, adaptive_dispatches, adaptive_wavefront_dispatches};
use chain::{wavefront_chunks, wavefront_dispatches};
use chunking::{adaptive_slots, slot_budget, split_even};
use shape::WavefrontShape;
use uniform::{plain_chunks, plain_dispatches, uniform_chunks, uniform_dispatches};

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
    /// AA none or uniform AA through the wavefront kernels (`src/tracer/wavefront/wavefront.wgsl`).
    Wavefront(WavefrontShape),
    /// Adaptive AA with its corner and midpoint passes through the wavefront kernels
    /// (`src/tracer/wavefront/wavefront_lattice.wgsl`): the lattice, then the queues, in `samples`.
    AdaptiveWavefront {
        depth: u32,
        shape: WavefrontShape,
    },
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

impl Dispatch {
    /// A pass of the generations that follow this camera pass: the same chunk, items and
    /// stratum, entry `entry` at level `level` (a generation, or a tree's glass round),
    /// `workgroups` of it bound at `offsets`, clearing nothing and writing no arguments.
    pub(super) fn generation_pass(
        self,
        entry: usize,
        level: u32,
        workgroups: Workgroups,
        offsets: BindingOffsets,
    ) -> Dispatch {
        Dispatch {
            entry,
            params: GpuTile {
                level,
                ..self.params
            },
            workgroups,
            clears_work: false,
            writes_args: false,
            offsets,
            ..self
        }
    }
}

/// The passes of the generations that follow a camera pass: entries from `closest` on
/// of the mode's list, bound at `offsets`, copying the camera pass's chunk, items and
/// stratum.
#[derive(Clone, Copy)]
pub(super) struct Generations {
    pub(super) camera: Dispatch,
    pub(super) closest: usize,
    pub(super) offsets: BindingOffsets,
}

impl Generations {
    /// Entry `closest` + `entry` at level `level` (a generation, or a tree's glass round).
    pub(super) fn pass(self, entry: usize, level: u32, workgroups: Workgroups) -> Dispatch {
        self.camera
            .generation_pass(self.closest + entry, level, workgroups, self.offsets)
    }

    /// The indirect workgroups an args kernel wrote at byte `at` of its `work_args`.
    pub(super) fn args(self, at: u64) -> Workgroups {
        Workgroups::Indirect(self.offsets.work + at)
    }

    /// The workgroups of generation g's passes over paths: generation 0's over the
    /// samples as the camera pass, later ones' as the args kernel wrote them.
    pub(super) fn paths(self, shape: WavefrontShape, g: u32) -> Workgroups {
        match g {
            0 => self.camera.workgroups,
            _ => self.args(shape.paths_args(g)),
        }
    }
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

/// How many workgroups a dispatch runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Workgroups {
    Direct(u32, u32),
    Indirect(u64),
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
            Mode::None => plain_chunks(
                window,
                dispatch_rows.min(block_rows).min(slot_rows(1)),
                parts as u32,
            ),
            Mode::Wavefront(shape) => {
                let rows = dispatch_rows.min(block_rows);
                wavefront_chunks(window, shape, bounds, rows, parts as u32)
            }
            Mode::Uniform { n } => {
                let rows = block_rows.min(dispatch_rows);
                uniform_chunks(window, n, bounds.max_binding, rows, slot_rows, parts as u32)
            }
            Mode::Adaptive { depth } => adaptive_chunks(window, depth, None, bounds, slots),
            Mode::AdaptiveWavefront { depth, shape } => {
                adaptive_chunks(window, depth, Some(shape), bounds, slots)
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
        let p = ChunkPasses {
            index,
            chunk: self.chunks[index],
            sentinel,
            bounds,
        };
        match self.mode {
            Mode::None => plain_dispatches(&p),
            Mode::Uniform { n } => uniform_dispatches(&p, n),
            Mode::Adaptive { depth } => adaptive_dispatches(&p, depth),
            Mode::Wavefront(shape) => wavefront_dispatches(&p, shape),
            Mode::AdaptiveWavefront { depth, shape } => {
                adaptive_wavefront_dispatches(&p, depth, shape)
            }
        }
    }
}

/// What every form builds a chunk's dispatches from: the chunk, its index in the plan,
/// the guard buffer's sentinel and the adapter's bounds.
#[derive(Clone, Copy)]
struct ChunkPasses {
    index: usize,
    chunk: Chunk,
    sentinel: u32,
    bounds: AdapterBounds,
}

impl ChunkPasses {
    /// The chunk's uniform record for a pass at `level` over `items` invocations.
    fn params(&self, level: u32, items: u32) -> GpuTile {
        let c = self.chunk;
        GpuTile {
            origin: c.origin,
            size: c.size,
            side: c.side,
            level,
            items,
            sentinel: self.sentinel,
            stratum: ALL_STRATA,
            slice: 0,
        }
    }

    /// Workgroups of a one-dimensional kernel over `items` invocations.
    fn linear(&self, items: u32) -> Workgroups {
        let lanes = self.bounds.workgroup_side * self.bounds.workgroup_side;
        let (x, y) = linear_workgroups(items, lanes, self.bounds.max_workgroups);
        Workgroups::Direct(x, y)
    }

    /// Workgroups of a two-dimensional kernel over the chunk's pixels.
    fn square(&self) -> Workgroups {
        let side = self.bounds.workgroup_side;
        let [w, h] = self.chunk.size;
        Workgroups::Direct(w.div_ceil(side), h.div_ceil(side))
    }

    /// Entry `entry` of the mode's list over the chunk, nothing cleared nor written.
    fn run(&self, entry: usize, params: GpuTile, workgroups: Workgroups) -> Dispatch {
        Dispatch {
            entry,
            chunk: self.index,
            params,
            workgroups,
            clears_work: false,
            writes_args: false,
            offsets: BindingOffsets::default(),
        }
    }
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

// The plan's tests, a file a form (after the code, as the house rules read it).
#[cfg(test)]
mod tests;
