//! Pixels and tiles: anti-aliasing, tiles in parallel with rayon. Every sample depends
//! only on (pixel, sample) hashes or its film position, so the image is the same for any
//! thread count. Adaptive anti-aliasing renders a tile at a time in passes
//! ([`super::adaptive`]); [`render_pixel`] is the per-pixel reference of every mode.

use super::adaptive::{adaptive_tile, square_splits, Lattice};
use super::pixel_sample::{
    lattice_sample, quincunx_mean, sample, square_contrast_of, square_hints_of, SampleHint,
};
use super::sample_source::stratum_position;
use crate::constants::{
    adaptive_tile_side, AA_ADAPTIVE, AA_STACK_SIZE, AA_UNIFORM, CPU_ADAPTIVE_LATTICE_SIDE,
    TILE_SIZE,
};
use crate::film::Film;
use crate::pack::PackedScene;
pub use crate::tiling::RenderProgress;
use crate::tiling::{AdaptiveTile, PixelRect};
use crate::tracer::traversal::traverse::{Counters, NoCounters, TraversalCounters};
use glam::Vec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// A square of the adaptive subdivision: top-left corner, side, depth, the colours at its
/// four corners (top-left, top-right, bottom-left, bottom-right) and their hints, and
/// (above the deepest level) its centre's colour and hint.
#[derive(Clone, Copy)]
struct AdaptiveSquare {
    x: f32,
    y: f32,
    size: f32,
    depth: u32,
    corners: [Vec3; 4],
    hints: [SampleHint; 4],
    centre: Vec3,
    centre_hint: SampleHint,
}

/// Adaptive anti-aliasing of pixel (x, y) (after Whitted 1980): sample the corners and
/// (at `aa_depth` ≥ 1) the centre; where they differ by more than `aa_threshold`, or their
/// hints call for it ([`square_splits`]: a penumbra, or different items hit), split into
/// four and recurse — here with an explicit stack — down to `aa_depth`, each square above
/// the deepest level with a centre sample of its own; a square that does not split is
/// the [`quincunx_mean`] of its corners and centre (the mean of its corners at the
/// deepest level), weighted by its area. Sample positions lie on a dyadic lattice, each
/// jittered by its own hash ([`lattice_sample`]), so neighbouring squares see the same
/// colour at a shared corner. The renderers run the same walk per tile in passes
/// ([`super::adaptive`], on both tracers); this is its per-pixel reference.
pub fn adaptive_pixel(
    scene: &PackedScene,
    x: u32,
    y: u32,
    threshold: f32,
    max_depth: u32,
    counters: &mut impl TraversalCounters,
) -> Vec3 {
    let (fx, fy) = (x as f32, y as f32);
    // (Overwritten below: the corners always, the centre where the pixel has one.)
    let unsampled = SampleHint {
        fine_detail: false,
        item: 0,
    };
    let mut pixel = AdaptiveSquare {
        x: fx,
        y: fy,
        size: 1.0,
        depth: 0,
        corners: [Vec3::ZERO; 4],
        hints: [unsampled; 4],
        centre: Vec3::ZERO,
        centre_hint: unsampled,
    };
    // Corner k is (k & 1, k >> 1).
    for k in 0..4 {
        let (cx, cy) = (fx + (k & 1) as f32, fy + (k >> 1) as f32);
        (pixel.corners[k], pixel.hints[k]) = lattice_sample(scene, cx, cy, counters);
    }
    if max_depth > 0 {
        (pixel.centre, pixel.centre_hint) = lattice_sample(scene, fx + 0.5, fy + 0.5, counters);
    }
    let mut stack = [pixel; AA_STACK_SIZE as usize];
    let mut size = 1;
    let mut sum = Vec3::ZERO;
    while size > 0 {
        size -= 1;
        let sq = stack[size];
        // Weight of this square in the pixel: its area.
        let area = sq.size * sq.size;
        if sq.depth >= max_depth {
            sum += (sq.corners[0] + sq.corners[1] + sq.corners[2] + sq.corners[3]) * (0.25 * area);
            continue;
        }
        let [h0, h1, h2, h3] = sq.hints;
        let hints = square_hints_of(&[h0, h1, h2, h3, sq.centre_hint]);
        let spread = square_contrast_of(&sq.corners, sq.centre);
        if !square_splits(spread, hints, sq.depth, threshold) {
            sum += quincunx_mean(&sq.corners, sq.centre) * area;
            continue;
        }
        let h = sq.size * 0.5;
        // Top, left, centre, right and bottom midpoints (the centre traced already).
        let offsets = [(h, 0.0), (0.0, h), (h, h), (sq.size, h), (h, sq.size)];
        let mut mid = [sq.centre; 5];
        let mut mid_hints = [sq.centre_hint; 5];
        for m in [0, 1, 3, 4] {
            let (px, py) = (sq.x + offsets[m].0, sq.y + offsets[m].1);
            (mid[m], mid_hints[m]) = lattice_sample(scene, px, py, counters);
        }
        for mut child in square_children(&sq, &mid, &mid_hints) {
            if child.depth < max_depth {
                let q = child.size * 0.5;
                (child.centre, child.centre_hint) =
                    lattice_sample(scene, child.x + q, child.y + q, counters);
            }
            stack[size] = child;
            size += 1;
        }
    }
    sum
}

/// The four children of `sq` (top-left, top-right, bottom-left, bottom-right) from its
/// corners and its top, left, centre, right and bottom midpoints `mid`.
fn square_children(
    sq: &AdaptiveSquare,
    mid: &[Vec3; 5],
    mid_hints: &[SampleHint; 5],
) -> [AdaptiveSquare; 4] {
    let h = sq.size * 0.5;
    let [tl, tr, bl, br] = sq.corners;
    let [top, left, centre, right, bottom] = *mid;
    let [p_top, p_left, p_centre, p_right, p_bottom] = *mid_hints;
    let [p_tl, p_tr, p_bl, p_br] = sq.hints;
    let child = |x: f32, y: f32, corners: [Vec3; 4], hints: [SampleHint; 4]| AdaptiveSquare {
        x,
        y,
        size: h,
        depth: sq.depth + 1,
        corners,
        hints,
        centre: Vec3::ZERO,
        centre_hint: p_centre,
    };
    [
        child(
            sq.x,
            sq.y,
            [tl, top, left, centre],
            [p_tl, p_top, p_left, p_centre],
        ),
        child(
            sq.x + h,
            sq.y,
            [top, tr, centre, right],
            [p_top, p_tr, p_centre, p_right],
        ),
        child(
            sq.x,
            sq.y + h,
            [left, centre, bl, bottom],
            [p_left, p_centre, p_bl, p_bottom],
        ),
        child(
            sq.x + h,
            sq.y + h,
            [centre, right, bottom, br],
            [p_centre, p_right, p_bottom, p_br],
        ),
    ]
}

/// Colour of pixel (x, y) under the scene's anti-aliasing mode: the per-pixel reference
/// (the GPU tracer's fallback for pixels it flags). The GPU splits it into passes of one
/// sample per invocation: AA none is src/tracer/sampling/render.wgsl::main, uniform AA
/// `uniform_samples` and `uniform_resolve` (same sum order), adaptive AA the lattice
/// passes of src/tracer/sampling/adaptive.wgsl (mirrored by [`super::adaptive`]).
pub fn render_pixel(
    scene: &PackedScene,
    x: u32,
    y: u32,
    counters: &mut impl TraversalCounters,
) -> Vec3 {
    let g = &scene.globals;
    if g.aa_mode == AA_ADAPTIVE {
        return adaptive_pixel(scene, x, y, g.aa_threshold, g.aa_depth, counters);
    }
    // Uniform: n×n strata, one jittered sample in each. None: one stratum, its centre
    // (x + 0.5 exactly). One loop for both keeps one `sample` call site (see above).
    let uniform = g.aa_mode == AA_UNIFORM;
    let n = if uniform { g.aa_samples } else { 1 };
    uniform_resolve(uniform_samples(scene, x, y, n, uniform, counters), n)
}

/// Pixel (x, y)'s n² samples ([`uniform_sample`] of strata 0 … n² − 1), in sample order:
/// the GPU's first pass of uniform AA traces them one an invocation.
// Mirror of src/tracer/sampling/render.wgsl::uniform_samples — change both.
pub fn uniform_samples<'a, C: TraversalCounters>(
    scene: &'a PackedScene,
    x: u32,
    y: u32,
    n: u32,
    uniform: bool,
    counters: &'a mut C,
) -> impl Iterator<Item = Vec3> + 'a {
    (0..n * n).map(move |s| uniform_sample(scene, x, y, s, n, uniform, counters))
}

/// A pixel's mean of its n² `samples`, summed in sample order then divided by n² (the
/// order every form sums in, so each gives this pixel bit for bit).
// Mirror of src/tracer/sampling/render.wgsl::uniform_resolve — change both.
pub fn uniform_resolve(samples: impl Iterator<Item = Vec3>, n: u32) -> Vec3 {
    let mut sum = Vec3::ZERO;
    for colour in samples {
        sum += colour;
    }
    sum / (n * n) as f32
}

/// Sample `s` of pixel (x, y) under n×n stratification: the colour at its stratum's
/// [`stratum_position`] (jittered when `uniform`, else the stratum's centre).
// Mirror of src/tracer/sampling/render.wgsl::uniform_sample — change both.
pub fn uniform_sample(
    scene: &PackedScene,
    x: u32,
    y: u32,
    s: u32,
    n: u32,
    uniform: bool,
    counters: &mut impl TraversalCounters,
) -> Vec3 {
    let at = stratum_position(&scene.globals, [x, y], s, n, uniform);
    sample(scene, at.fx, at.fy, at.seed, counters)
}

/// Per-render counters (only gathered when asked, see [`render_with_counters`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct RenderCounters {
    pub rays: u64,
    pub cells_visited: u64,
    pub items_tested: u64,
}

/// Renders the whole image on the current rayon pool.
pub fn render(scene: &PackedScene, progress: RenderProgress) -> Film {
    let g = &scene.globals;
    render_window(scene, PixelRect::full(g.width, g.height), progress)
}

/// Renders the pixels of `window` (inside the image) into a film of the window's size:
/// each pixel as in the full render, since no sample depends on the tiles around it
/// (a farm's tiles, `--crop`).
pub fn render_window(scene: &PackedScene, window: PixelRect, progress: RenderProgress) -> Film {
    render_tiles(scene, window, progress, |x0, y0, w, h| {
        render_tile(scene, x0, y0, w, h, &mut NoCounters)
    })
}

/// Renders with traversal counters (slower; for `--stats`).
pub fn render_with_counters(
    scene: &PackedScene,
    progress: RenderProgress,
) -> (Film, RenderCounters) {
    let cells = AtomicU64::new(0);
    let items = AtomicU64::new(0);
    let rays = AtomicU64::new(0);
    let g = &scene.globals;
    let window = PixelRect::full(g.width, g.height);
    let film = render_tiles(scene, window, progress, |x0, y0, w, h| {
        let mut c = CountingRays::default();
        let pixels = render_tile(scene, x0, y0, w, h, &mut c);
        cells.fetch_add(c.inner.cells_visited, Ordering::Relaxed);
        items.fetch_add(c.inner.items_tested, Ordering::Relaxed);
        rays.fetch_add(c.rays, Ordering::Relaxed);
        pixels
    });
    let counters = RenderCounters {
        rays: rays.into_inner(),
        cells_visited: cells.into_inner(),
        items_tested: items.into_inner(),
    };
    (film, counters)
}

/// Side of the CPU's tiles: [`TILE_SIZE`], smaller under deep adaptive anti-aliasing.
fn tile_side(scene: &PackedScene) -> u32 {
    let g = &scene.globals;
    if g.aa_mode == AA_ADAPTIVE {
        adaptive_tile_side(TILE_SIZE, CPU_ADAPTIVE_LATTICE_SIDE, g.aa_depth)
    } else {
        TILE_SIZE
    }
}

/// The pixels of the w×h tile at (x0, y0), row-major.
fn render_tile(
    scene: &PackedScene,
    x0: u32,
    y0: u32,
    w: u32,
    h: u32,
    counters: &mut impl TraversalCounters,
) -> Vec<[f32; 3]> {
    let g = &scene.globals;
    if g.aa_mode == AA_ADAPTIVE {
        let tile = AdaptiveTile {
            origin: [x0, y0],
            size: [w, h],
            side: w.max(h),
            depth: g.aa_depth,
        };
        let mut lattice = Lattice::new(tile);
        return adaptive_tile(scene, &mut lattice, g.aa_threshold, counters)
            .into_iter()
            .map(|(c, _)| c.to_array())
            .collect();
    }
    let mut out = Vec::with_capacity((w * h) as usize);
    for y in y0..y0 + h {
        for x in x0..x0 + w {
            out.push(render_pixel(scene, x, y, counters).to_array());
        }
    }
    out
}

/// Leaf squares per pixel of adaptive anti-aliasing (1 where a pixel was not split),
/// row-major: the split decisions, for comparing tracers. Zeros in other modes.
pub fn adaptive_leaf_counts(scene: &PackedScene) -> Vec<u32> {
    let g = &scene.globals;
    let (w, h) = (g.width, g.height);
    let mut out = vec![0; (w * h) as usize];
    if g.aa_mode != AA_ADAPTIVE {
        return out;
    }
    let side = tile_side(scene);
    let tiles_x = w.div_ceil(side);
    // Tiles in parallel (`--debug aa-samples` maps whole images with this).
    let tiles: Vec<(AdaptiveTile, Vec<u32>)> = (0..tiles_x * h.div_ceil(side))
        .into_par_iter()
        .map(|t| {
            let (x0, y0) = ((t % tiles_x) * side, (t / tiles_x) * side);
            let tile = AdaptiveTile {
                origin: [x0, y0],
                size: [side.min(w - x0), side.min(h - y0)],
                side,
                depth: g.aa_depth,
            };
            let mut lattice = Lattice::new(tile);
            let pixels = adaptive_tile(scene, &mut lattice, g.aa_threshold, &mut NoCounters);
            (tile, pixels.into_iter().map(|(_, leaves)| leaves).collect())
        })
        .collect();
    for (tile, leaves) in tiles {
        let [x0, y0] = tile.origin;
        for (k, l) in leaves.into_iter().enumerate() {
            let (tx, ty) = (k as u32 % tile.size[0], k as u32 / tile.size[0]);
            out[((y0 + ty) * w + x0 + tx) as usize] = l;
        }
    }
    out
}

/// Counts traversals (each one a ray) as well as cells and items.
#[derive(Default)]
struct CountingRays {
    inner: Counters,
    rays: u64,
}

impl TraversalCounters for CountingRays {
    fn traversal_started(&mut self) {
        self.rays += 1;
    }
    fn cell_visited(&mut self) {
        self.inner.cell_visited();
    }
    fn item_tested(&mut self) {
        self.inner.item_tested();
    }
}

/// The film of `window`, its tiles (squares of [`tile_side`] from the window's corner,
/// in image coordinates) rendered in parallel by `tile_pixels(x0, y0, w, h)`.
fn render_tiles(
    scene: &PackedScene,
    window: PixelRect,
    progress: RenderProgress,
    tile_pixels: impl Fn(u32, u32, u32, u32) -> Vec<[f32; 3]> + Sync,
) -> Film {
    let (w, h) = (window.width(), window.height());
    let side = tile_side(scene);
    let tiles_x = w.div_ceil(side);
    let tiles_y = h.div_ceil(side);
    let total = (tiles_x * tiles_y) as u64;
    let done = AtomicU64::new(0);
    // Tile origin within the window.
    let origin = |tile: u32| ((tile % tiles_x) * side, (tile / tiles_x) * side);
    let tiles: Vec<(u32, Vec<[f32; 3]>)> = (0..tiles_x * tiles_y)
        .into_par_iter()
        .map(|tile| {
            let (x0, y0) = origin(tile);
            let (tw, th) = (side.min(w - x0), side.min(h - y0));
            let pixels = tile_pixels(window.x0 + x0, window.y0 + y0, tw, th);
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
            (tile, pixels)
        })
        .collect();
    let mut film = Film::new(w, h);
    for (tile, pixels) in tiles {
        let (x0, y0) = origin(tile);
        let mut it = pixels.into_iter();
        for y in y0..(y0 + side).min(h) {
            for x in x0..(x0 + side).min(w) {
                film.set(x, y, it.next().expect("tile pixel count"));
            }
        }
    }
    film
}
