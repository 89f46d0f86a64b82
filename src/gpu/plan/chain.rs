//! The wavefront form's chunks and dispatches (AA none and uniform AA through the
//! wavefront kernels), and a chain's generations, which adaptive AA's lattice passes and
//! the view's frames run too: per generation closest, shade, args, shadow and gather.
//! Trees (scenes with refraction) run `tree`'s generations instead
//! ([`generation_dispatches`] picks).

use super::chunking::{bands, row_pieces, slot_budget};
use super::shape::WavefrontShape;
use super::tree::tree_generations;
use super::{AdapterBounds, BindingOffsets, Chunk, ChunkPasses, Dispatch, Generations, Workgroups};
use crate::tiling::PixelRect;

/// The chunks of `window` through the wavefront kernels, and the samples array's vec4s:
/// bands of at most `rows` rows whose queues (of every sample of every pixel) fit one
/// binding and whose tracing invocations each have a list slot; where a tree's queues do
/// not fit even one row, pieces of rows.
pub(super) fn wavefront_chunks(
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

/// The dispatches of a chunk through the wavefront kernels ([`Entry::WAVEFRONT`]'s or,
/// for a tree, [`Entry::WAVEFRONT_TREE`]'s indices): the camera pass starts the chunk
/// (its counters cleared), the generations follow; under uniform AA the resolve pass
/// ends it.
///
/// [`Entry::WAVEFRONT`]: crate::gpu::compile::shader::Entry::WAVEFRONT
/// [`Entry::WAVEFRONT_TREE`]: crate::gpu::compile::shader::Entry::WAVEFRONT_TREE
pub(super) fn wavefront_dispatches(p: &ChunkPasses, shape: WavefrontShape) -> Vec<Dispatch> {
    let [w, h] = p.chunk.size;
    let n = w * h * shape.samples_per_pixel() as u32;
    let camera = Dispatch {
        clears_work: true,
        ..p.run(0, p.params(0, n), p.linear(n))
    };
    let (mut out, resolve) = generation_dispatches(shape, camera, 1, camera.offsets);
    if shape.uniform.is_some() {
        out.push(p.run(resolve, p.params(0, n), p.square()));
    }
    out
}

/// A `camera` pass, then its generations' dispatches (entries from `closest` on, bound at
/// `offsets`): a chain's ([`chain_generations`]) or, with refraction, a tree's (its glass
/// rounds and fold too: [`tree_generations`]); and the entry that follows them (the
/// resolve or store pass: 5 after `closest` for a chain, 9 for a tree).
pub(super) fn generation_dispatches(
    shape: WavefrontShape,
    camera: Dispatch,
    closest: usize,
    offsets: BindingOffsets,
) -> (Vec<Dispatch>, usize) {
    let generations = Generations {
        camera,
        closest,
        offsets,
    };
    let mut out = vec![camera];
    if shape.tree {
        out.extend(tree_generations(shape, generations));
        (out, closest + 9)
    } else {
        out.extend(chain_generations(shape, generations));
        (out, closest + 5)
    }
}

/// A chain's generations: per generation g closest, shade, args, shadow, gather (entries
/// `closest` … `closest` + 4) — generation 0's over the chunk's samples as the camera
/// pass, later ones' and every shadow pass's as the args kernel wrote them
/// (`generation_words` a generation from `offsets.work`: the next generation's, then this
/// one's shadow pass, with CSG one dispatch a slice, `GpuTile::slice` telling it which).
fn chain_generations(shape: WavefrontShape, generations: Generations) -> Vec<Dispatch> {
    let mut out = Vec::new();
    for g in 0..shape.generations {
        let pass = |entry: usize, workgroups: Workgroups| generations.pass(entry, g, workgroups);
        let paths = generations.paths(shape, g);
        out.push(pass(0, paths));
        out.push(pass(1, paths));
        let mut args_kernel = Dispatch {
            writes_args: true,
            ..pass(2, Workgroups::Direct(1, 1))
        };
        args_kernel.params.slice = shape.shadow_slices;
        out.push(args_kernel);
        for slice in 0..shape.shadow_slices {
            let mut shadow = pass(3, generations.args(shape.shadow_args(g, slice)));
            shadow.params.slice = slice;
            out.push(shadow);
        }
        out.push(pass(4, paths));
    }
    out
}
