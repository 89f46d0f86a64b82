//! Pixels and tiles: anti-aliasing per pixel, tiles in parallel with rayon. Every sample
//! depends only on (pixel, sample) hashes, so the image is the same for any thread count.

use super::ray::camera_ray;
use super::rng::random_unit;
use super::trace::trace_ray;
use super::traverse::{Counters, NoCounters, TraversalCounters};
use crate::constants::{AA_ADAPTIVE, AA_STACK_SIZE, AA_UNIFORM, TILE_SIZE};
use crate::film::Film;
use crate::pack::PackedScene;
use glam::Vec3;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU64, Ordering};

/// Colour at film position (fx, fy) in pixels.
// Mirror of shaders/render.wgsl::sample — change both.
fn sample(scene: &PackedScene, fx: f32, fy: f32, counters: &mut impl TraversalCounters) -> Vec3 {
    trace_ray(scene, camera_ray(&scene.globals, fx, fy), counters)
}

/// A square of the adaptive subdivision: top-left corner, side, depth, and the colours
/// at its four corners (top-left, top-right, bottom-left, bottom-right).
#[derive(Clone, Copy)]
struct AdaptiveSquare {
    x: f32,
    y: f32,
    size: f32,
    depth: u32,
    corners: [Vec3; 4],
}

/// Largest per-channel spread of four colours.
// Mirror of shaders/render.wgsl::contrast — change both.
fn contrast(c: &[Vec3; 4]) -> f32 {
    let lo = c[0].min(c[1]).min(c[2]).min(c[3]);
    let hi = c[0].max(c[1]).max(c[2]).max(c[3]);
    (hi - lo).max_element()
}

/// Adaptive anti-aliasing of pixel (x, y) (Whitted 1980): sample the corners; where they
/// differ by more than `aa_threshold`, split into four and recurse — here with an explicit
/// stack — down to `aa_depth`. Sample positions lie on a dyadic lattice, so neighbouring
/// pixels see the same colour at a shared corner.
// Mirror of shaders/render.wgsl::adaptive_pixel — change both.
fn adaptive_pixel(
    scene: &PackedScene,
    x: u32,
    y: u32,
    threshold: f32,
    max_depth: u32,
    counters: &mut impl TraversalCounters,
) -> Vec3 {
    let (fx, fy) = (x as f32, y as f32);
    // Corner k is (k & 1, k >> 1). (One `sample` call site per loop: the GPU compiler
    // inlines every call, and the shader's size and compile time grow with the sites.)
    let mut corners = [Vec3::ZERO; 4];
    for (k, corner) in corners.iter_mut().enumerate() {
        *corner = sample(scene, fx + (k & 1) as f32, fy + (k >> 1) as f32, counters);
    }
    let mut stack = [AdaptiveSquare {
        x: fx,
        y: fy,
        size: 1.0,
        depth: 0,
        corners,
    }; AA_STACK_SIZE as usize];
    let mut size = 1;
    let mut sum = Vec3::ZERO;
    while size > 0 {
        size -= 1;
        let sq = stack[size];
        // Weight of this square in the pixel: its area.
        let area = sq.size * sq.size;
        if sq.depth >= max_depth || contrast(&sq.corners) <= threshold {
            sum += (sq.corners[0] + sq.corners[1] + sq.corners[2] + sq.corners[3]) * (0.25 * area);
            continue;
        }
        let h = sq.size * 0.5;
        let [tl, tr, bl, br] = sq.corners;
        // Top, left, centre, right and bottom midpoints.
        let offsets = [(h, 0.0), (0.0, h), (h, h), (sq.size, h), (h, sq.size)];
        let mut mid = [Vec3::ZERO; 5];
        for (m, (ox, oy)) in mid.iter_mut().zip(offsets) {
            *m = sample(scene, sq.x + ox, sq.y + oy, counters);
        }
        let [top, left, centre, right, bottom] = mid;
        let depth = sq.depth + 1;
        let children = [
            (sq.x, sq.y, [tl, top, left, centre]),
            (sq.x + h, sq.y, [top, tr, centre, right]),
            (sq.x, sq.y + h, [left, centre, bl, bottom]),
            (sq.x + h, sq.y + h, [centre, right, bottom, br]),
        ];
        for (cx, cy, corners) in children {
            stack[size] = AdaptiveSquare {
                x: cx,
                y: cy,
                size: h,
                depth,
                corners,
            };
            size += 1;
        }
    }
    sum
}

/// Colour of pixel (x, y) under the scene's anti-aliasing mode.
// Mirror of shaders/render.wgsl::render_pixel — change both.
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
    let pixel = y * g.width + x;
    let mut sum = Vec3::ZERO;
    for j in 0..n {
        for i in 0..n {
            let s = j * n + i;
            let (jx, jy) = if uniform {
                (random_unit(pixel, s, 0), random_unit(pixel, s, 1))
            } else {
                (0.5, 0.5)
            };
            let fx = x as f32 + (i as f32 + jx) / n as f32;
            let fy = y as f32 + (j as f32 + jy) / n as f32;
            sum += sample(scene, fx, fy, counters);
        }
    }
    sum / (n * n) as f32
}

/// Progress of a render: called with (tiles done, tiles in all) after each tile.
pub type RenderProgress<'a> = &'a (dyn Fn(u64, u64) + Sync);

/// Per-render counters (only gathered when asked, see [`render_with_counters`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct RenderCounters {
    pub rays: u64,
    pub cells_visited: u64,
    pub items_tested: u64,
}

/// Renders the whole image on the current rayon pool.
pub fn render(scene: &PackedScene, progress: RenderProgress) -> Film {
    render_tiles(scene, progress, |x, y| {
        render_pixel(scene, x, y, &mut NoCounters)
    })
    .0
}

/// Renders with traversal counters (slower; for `--stats`).
pub fn render_with_counters(
    scene: &PackedScene,
    progress: RenderProgress,
) -> (Film, RenderCounters) {
    let cells = AtomicU64::new(0);
    let items = AtomicU64::new(0);
    let rays = AtomicU64::new(0);
    let film = render_tiles(scene, progress, |x, y| {
        let mut c = CountingRays::default();
        let colour = render_pixel(scene, x, y, &mut c);
        cells.fetch_add(c.inner.cells_visited, Ordering::Relaxed);
        items.fetch_add(c.inner.items_tested, Ordering::Relaxed);
        rays.fetch_add(c.rays, Ordering::Relaxed);
        colour
    })
    .0;
    let counters = RenderCounters {
        rays: rays.into_inner(),
        cells_visited: cells.into_inner(),
        items_tested: items.into_inner(),
    };
    (film, counters)
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

fn render_tiles(
    scene: &PackedScene,
    progress: RenderProgress,
    pixel: impl Fn(u32, u32) -> Vec3 + Sync,
) -> (Film, ()) {
    let (w, h) = (scene.globals.width, scene.globals.height);
    let tiles_x = w.div_ceil(TILE_SIZE);
    let tiles_y = h.div_ceil(TILE_SIZE);
    let total = (tiles_x * tiles_y) as u64;
    let done = AtomicU64::new(0);
    let tiles: Vec<(u32, Vec<[f32; 3]>)> = (0..tiles_x * tiles_y)
        .into_par_iter()
        .map(|tile| {
            let (x0, y0) = ((tile % tiles_x) * TILE_SIZE, (tile / tiles_x) * TILE_SIZE);
            let mut out = Vec::with_capacity((TILE_SIZE * TILE_SIZE) as usize);
            for y in y0..(y0 + TILE_SIZE).min(h) {
                for x in x0..(x0 + TILE_SIZE).min(w) {
                    out.push(pixel(x, y).to_array());
                }
            }
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
            (tile, out)
        })
        .collect();
    let mut film = Film::new(w, h);
    for (tile, pixels) in tiles {
        let (x0, y0) = ((tile % tiles_x) * TILE_SIZE, (tile / tiles_x) * TILE_SIZE);
        let mut it = pixels.into_iter();
        for y in y0..(y0 + TILE_SIZE).min(h) {
            for x in x0..(x0 + TILE_SIZE).min(w) {
                film.set(x, y, it.next().expect("tile pixel count"));
            }
        }
    }
    (film, ())
}
