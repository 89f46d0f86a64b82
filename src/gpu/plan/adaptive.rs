//! Adaptive AA's chunks and dispatches, the lattice form: square tiles whose lattice of
//! (side·2^d + 1)² points fits one binding, traced by the corner pass and a midpoint
//! pass a level (each after the level's decide and work-args passes), then integrated;
//! through the megakernels, or with its corner and midpoint passes through the wavefront
//! kernels (the lattice, then the queues, in `samples`).

use super::chain::generation_dispatches;
use super::chunking::{adaptive_side, adaptive_slots, squares};
use super::shape::WavefrontShape;
use super::{AdapterBounds, BindingOffsets, Chunk, ChunkPasses, Dispatch, Workgroups};
use crate::constants::WAVEFRONT_WORK_BASE;
use crate::tiling::{split_offset, AdaptiveTile, PixelRect};

/// Byte offset of the wavefront's counters in `work_counts` and of its arguments in
/// `work_args` under adaptive AA (`src/tracer/wavefront/wavefront_lattice.wgsl`).
pub const WAVEFRONT_WORK_BYTES: u64 = 4 * WAVEFRONT_WORK_BASE as u64;

/// Where the wavefront's queues start in `samples` (vec4 entries) for adaptive tile
/// `tile`: after its lattice, at a multiple of 16 entries (256 bytes, the coarsest
/// storage offset alignment WebGPU allows).
// Mirror of src/tracer/wavefront/wavefront_lattice.wgsl::lattice_queue_base — change both.
pub fn lattice_queue_base(tile: &AdaptiveTile) -> u64 {
    (tile.lattice_len() as u64).div_ceil(16) * 16
}

/// [`lattice_queue_base`] in bytes, for adaptive tiles of side `side` at depth `depth`.
pub fn lattice_queue_bytes(side: u32, depth: u32) -> u64 {
    let tile = AdaptiveTile {
        origin: [0, 0],
        size: [side, side],
        side,
        depth,
    };
    16 * lattice_queue_base(&tile)
}

/// Byte offset of level `level`'s midpoint-pass arguments in the work-args buffer; the
/// next level's decide-pass arguments follow (see src/tracer/sampling/adaptive.wgsl::adaptive_work_args).
fn midpoint_args(level: u32) -> u64 {
    24 * level as u64
}

/// Adaptive AA's chunks of `window` at depth `depth`, and the samples and split arrays'
/// lengths: square tiles whose busiest pass has at most `slots` tracing invocations and
/// whose lattice fits one binding, with the queues of the busiest lattice pass's samples
/// after it through the wavefront kernels (`shape`).
pub(super) fn adaptive_chunks(
    window: PixelRect,
    depth: u32,
    shape: Option<WavefrontShape>,
    bounds: AdapterBounds,
    slots: u64,
) -> (Vec<Chunk>, u64, u64) {
    let size = [window.width(), window.height()];
    let Some(shape) = shape else {
        let side = adaptive_side(bounds, size, depth, slots, |_| 0);
        let lattice = (side as u64 * (1 << depth) as u64 + 1).pow(2);
        let chunks = squares(window, side);
        return (chunks, lattice, split_offset(side, depth).max(1) as u64);
    };
    // The lattice, then the queues of the busiest lattice pass's samples
    // (adaptive_slots), in one binding.
    let vec4s = |side: u32| {
        lattice_queue_bytes(side, depth) / 16
            + adaptive_slots(side, side, side, depth) * shape.vec4s_per_sample()
    };
    // A tree's generation: up to TREE_PATHS_PER_SAMPLE paths a sample.
    let samples = slots / shape.slots_per_sample();
    let side = adaptive_side(bounds, size, depth, samples, vec4s);
    let chunks = squares(window, side);
    (chunks, vec4s(side), split_offset(side, depth).max(1) as u64)
}

/// Adaptive AA's dispatches of a tile through the megakernels: every pixel corner (its
/// work cleared), then per level the decide pass (every pixel centre at level 0, else
/// the previous level's split squares), the work-args pass and the midpoint pass, then
/// the integrate pass.
pub(super) fn adaptive_dispatches(p: &ChunkPasses, depth: u32) -> Vec<Dispatch> {
    // Every pixel corner, then every pixel centre (d ≥ 1).
    let first = p.chunk.adaptive_tile(depth).first_pass_len();
    let mut out = vec![Dispatch {
        clears_work: true,
        ..p.run(0, p.params(0, first), p.linear(first))
    }];
    for level in 0..depth {
        out.extend(decide_and_work_args(p, level, [1, 4]));
        let args = Workgroups::Indirect(midpoint_args(level));
        out.push(p.run(2, p.params(level, 0), args));
    }
    out.push(p.run(3, p.params(0, 0), p.square()));
    out
}

/// What starts level `level` of a tile in both forms: the decide pass (entry `decide`
/// of the mode's list; every pixel centre at level 0, else the previous level's split
/// squares, at the arguments its work-args pass wrote) and the work-args pass (entry
/// `work_args`), which writes the arguments of the level's midpoint pass.
fn decide_and_work_args(
    p: &ChunkPasses,
    level: u32,
    [decide, work_args]: [usize; 2],
) -> [Dispatch; 2] {
    let [w, h] = p.chunk.size;
    let decide = if level == 0 {
        p.run(decide, p.params(0, w * h), p.linear(w * h))
    } else {
        let args = Workgroups::Indirect(midpoint_args(level - 1) + 12);
        p.run(decide, p.params(level, 0), args)
    };
    let work_args = Dispatch {
        writes_args: true,
        ..p.run(work_args, p.params(level, 0), Workgroups::Direct(1, 1))
    };
    [decide, work_args]
}

/// The dispatches of adaptive tile `c` through the wavefront kernels
/// ([`Entry::ADAPTIVE_WAVEFRONT`]'s indices): per lattice pass (the corner pass, then a midpoint pass a level
/// after its decide and work-args passes) the camera pass, five passes a generation and
/// the store pass; the integrate pass.
pub(super) fn adaptive_wavefront_dispatches(
    p: &ChunkPasses,
    depth: u32,
    shape: WavefrontShape,
) -> Vec<Dispatch> {
    let c = p.chunk;
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
            ..p.run(3, p.params(pass, n), points)
        };
        // A tree: its rounds and fold between the generations and the store.
        let (mut out, store) = generation_dispatches(shape, camera, 4, generation);
        out.push(p.run(store, p.params(pass, n), points));
        out
    };
    let mut out = lattice_pass(0, p.linear(c.adaptive_tile(depth).first_pass_len()));
    out[0].clears_work = true;
    for level in 0..depth {
        out.extend(decide_and_work_args(p, level, [0, 1]));
        out.extend(lattice_pass(
            level + 1,
            Workgroups::Indirect(midpoint_args(level)),
        ));
    }
    out.push(p.run(2, p.params(0, 0), p.square()));
    out
}
