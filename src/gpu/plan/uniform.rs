//! The plain forms' chunks and dispatches: AA none through the megakernel `main` (a
//! band of pixels, one pass) and uniform AA through `uniform_samples` and
//! `uniform_resolve` (a band's n² samples a pixel, then their average).

use super::chunking::bands;
use super::{Chunk, ChunkPasses, Dispatch};
use crate::tiling::PixelRect;

/// AA none's chunks through the megakernel: bands of at most `rows` rows, at least
/// `parts` of them; no samples nor split flags (one entry each, as a binding may not be
/// empty).
pub(super) fn plain_chunks(window: PixelRect, rows: u32, parts: u32) -> (Vec<Chunk>, u64, u64) {
    (bands(window, rows, parts), 1, 1)
}

/// Uniform AA's chunks: bands of at most `rows` rows whose n² samples a pixel fit one
/// binding (`max_binding` bytes, 16 a sample) and whose tracing invocations each have a
/// list slot (`slot_rows` rows for n² invocations a pixel), and the samples array's
/// vec4s.
pub(super) fn uniform_chunks(
    window: PixelRect,
    n: u32,
    max_binding: u64,
    rows: u32,
    slot_rows: impl Fn(u64) -> u32,
    parts: u32,
) -> (Vec<Chunk>, u64, u64) {
    let per_row = window.width() as u64 * (n * n) as u64;
    let sample_rows = max_binding / (16 * per_row);
    let rows = (sample_rows.min(u32::MAX as u64) as u32).min(rows);
    let rows = rows.min(slot_rows((n * n) as u64));
    let chunks = bands(window, rows, parts);
    let rows = chunks.iter().map(|c| c.size[1]).max().unwrap_or(1);
    (chunks, per_row * rows as u64, 1)
}

/// AA none's dispatch of a chunk through the megakernel: `main` over its pixels.
pub(super) fn plain_dispatches(p: &ChunkPasses) -> Vec<Dispatch> {
    vec![p.run(0, p.params(0, 0), p.square())]
}

/// Uniform AA's dispatches of a chunk: its n² samples a pixel, then the resolve over
/// its pixels.
pub(super) fn uniform_dispatches(p: &ChunkPasses, n: u32) -> Vec<Dispatch> {
    let [w, h] = p.chunk.size;
    let items = w * h * n * n;
    vec![
        p.run(0, p.params(0, items), p.linear(items)),
        p.run(1, p.params(0, 0), p.square()),
    ]
}
