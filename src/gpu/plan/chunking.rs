//! How a frame is cut into chunks, shared by every form: full-width bands of rows,
//! pieces of rows, square tiles (adaptive AA's, whose lattice must fit one binding), the
//! chunks' grouping into parts, and the tracing invocations (list slots) one dispatch may
//! have.

use super::{AdapterBounds, Chunk};
use crate::constants::AA_SPLIT_POINTS;
use crate::gpu::compile::lists::LIST_BUDGET_BYTES;
use crate::tiling::PixelRect;

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
pub(super) fn adaptive_slots(w: u32, h: u32, side: u32, depth: u32) -> u64 {
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
pub(super) fn adaptive_side(
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
pub(crate) fn bands(window: PixelRect, rows: u32, min_bands: u32) -> Vec<Chunk> {
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
pub(super) fn row_pieces(window: PixelRect, width: u32) -> Vec<Chunk> {
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
pub(super) fn squares(window: PixelRect, side: u32) -> Vec<Chunk> {
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
pub(super) fn split_even(len: usize, n: usize) -> Vec<std::ops::Range<usize>> {
    (0..n).map(|k| k * len / n..(k + 1) * len / n).collect()
}
