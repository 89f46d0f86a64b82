//! Adaptive anti-aliasing per tile, in passes over a dyadic lattice (Whitted 1980). The
//! decisions, samples and summation order are those of `adaptive_pixel` (in `render.rs`)
//! (which stays as the per-pixel reference); here each sample is traced once, where the
//! per-pixel walk traces a shared corner up to four times.
//!
//! For a tile of `size` pixels and depth d, lattice point (i, j) is film position
//! (x0 + i/2^d, y0 + j/2^d), its sample taken within the lattice cell around it
//! ([`lattice_sample`]: jittered by a hash of the position). Squares of level k have a
//! side of 2^(d−k) lattice steps; the level-0 squares are the pixels. The passes:
//! 1. [`adaptive_corners`]: trace every pixel corner and, at d ≥ 1, every pixel centre;
//! 2. for k in 0..d: [`adaptive_decide`] flags each level-k square that exists (every
//!    pixel at k = 0, else the four children of each square split at k − 1, taken from
//!    the compacted list of those) and whose samples (corners and centre) differ by
//!    more than the threshold or, above level AA_FINE_DETAIL_DEPTH, one of which
//!    saw fine detail (a penumbra, or texture detail at the pixel's scale) or, above
//!    AA_ITEM_EDGE_DEPTH, whose camera rays hit different items (or a mirror that shows
//!    different items; each lattice sample keeps that hint with its colour), appending it
//!    to level k's list of split squares; [`adaptive_work_args`] sizes the passes over
//!    that list, and then [`adaptive_midpoints`] traces the four
//!    edge midpoints of each square on that list (one shared with a split neighbour is
//!    traced by one of the two only) and, below level d − 1, its four children's
//!    centres (its own centre was traced before). Work is over the lists, so idle
//!    invocations do not grow with depth; the lists' order (on the GPU, that of atomic
//!    appends) changes nothing: every sample and flag has its own slot;
//! 3. [`adaptive_integrate`]: each pixel walks its quadtree in the per-pixel walk's order;
//!    an unsplit square above level d is the quincunx mean of its corners and centre, one
//!    of level d the mean of its corners, each weighted by its area.
//!
//! Every function here has a WGSL twin of the same name in `src/tracer/sampling/adaptive.wgsl`, where
//! each call is one invocation (one ray at most, for Mesa's loop limiter).

use super::pixel_sample::{
    add_sample_hint, decode_hint, encode_hint, lattice_sample, quincunx_mean, square_contrast_of,
    SampleHint, SquareHints,
};
use crate::constants::{AA_FINE_DETAIL_DEPTH, AA_ITEM_EDGE_DEPTH, AA_SPLIT_POINTS};
use crate::pack::PackedScene;
pub use crate::tiling::{split_offset, AdaptiveTile};
use crate::tracer::traversal::traverse::TraversalCounters;
use glam::Vec3;

/// Index of level-`level` square (a, b)'s split flag.
// Mirror of src/tracer/sampling/adaptive.wgsl::split_index — change both.
fn split_index(tile: &AdaptiveTile, level: u32, a: u32, b: u32) -> usize {
    (split_offset(tile.side, level) + b * (tile.side << level) + a) as usize
}

/// Index of lattice point (i, j).
// Mirror of src/tracer/sampling/adaptive.wgsl::lattice_index — change both.
pub(crate) fn lattice_index(tile: &AdaptiveTile, i: u32, j: u32) -> usize {
    (j * tile.lattice_width() + i) as usize
}

/// Film position of lattice point (i, j): exact (a dyadic fraction of few bits), so it is
/// the very position the per-pixel walk reaches by halving.
// Mirror of src/tracer/sampling/adaptive.wgsl::lattice_position — change both.
pub(crate) fn lattice_position(tile: &AdaptiveTile, i: u32, j: u32) -> (f32, f32) {
    let s = tile.adaptive_scale();
    let scale = s as f32;
    (
        (tile.origin[0] + i / s) as f32 + (i % s) as f32 / scale,
        (tile.origin[1] + j / s) as f32 + (j % s) as f32 / scale,
    )
}

/// Packs level-`level`-square (a, b) into one list entry (a, b < 2^16: the lattice side
/// is at most 2^15).
// Mirror of src/tracer/sampling/adaptive.wgsl::pack_square — change both.
fn pack_square(a: u32, b: u32) -> u32 {
    a | (b << 16)
}

// Mirror of src/tracer/sampling/adaptive.wgsl::unpack_square — change both.
fn unpack_square(entry: u32) -> (u32, u32) {
    (entry & 0xffff, entry >> 16)
}

/// A tile's lattice colours and hints ([`lattice_sample`]; each hint as
/// [`encode_hint`] stores it, the GPU's lattice sample's fourth component), split flags
/// and, per level, the list of split squares (at the level's split-flag offset,
/// [`split_offset`]), its length and the sizes of the passes over it
/// ([`adaptive_work_args`]).
pub struct Lattice {
    pub tile: AdaptiveTile,
    pub points: Vec<Vec3>,
    pub hints: Vec<f32>,
    pub split: Vec<u32>,
    pub work_list: Vec<u32>,
    pub work_counts: Vec<u32>,
    pub work_args: Vec<WorkArgs>,
}

/// The sizes of the two passes over a level's list of split squares, in invocations:
/// the level's midpoint pass and the next level's decide pass. (The GPU's `work_args`
/// holds them as the workgroups of indirect dispatches.)
#[derive(Clone, Copy, Debug, Default)]
pub struct WorkArgs {
    pub midpoints: u32,
    pub children: u32,
}

impl Lattice {
    pub fn new(tile: AdaptiveTile) -> Lattice {
        Lattice {
            tile,
            points: vec![Vec3::ZERO; tile.lattice_len()],
            hints: vec![0.0; tile.lattice_len()],
            split: vec![0; tile.split_len()],
            work_list: vec![0; tile.split_len()],
            work_counts: vec![0; tile.depth as usize],
            work_args: vec![WorkArgs::default(); tile.depth as usize],
        }
    }
    // Mirror of src/tracer/sampling/adaptive.wgsl::lattice_point — change both.
    fn lattice_point(&self, i: u32, j: u32) -> Vec3 {
        self.points[lattice_index(&self.tile, i, j)]
    }
    // Mirror of src/tracer/sampling/adaptive.wgsl::point_hint — change both.
    fn point_hint(&self, i: u32, j: u32) -> SampleHint {
        decode_hint(self.hints[lattice_index(&self.tile, i, j)])
    }
    // Mirror of src/tracer/sampling/adaptive.wgsl::is_split — change both.
    pub(crate) fn is_split(&self, level: u32, a: u32, b: u32) -> bool {
        self.split[split_index(&self.tile, level, a, b)] != 0
    }
    /// Entry `k` of level `level`'s list of split squares.
    // Mirror of src/tracer/sampling/adaptive.wgsl::split_square — change both.
    pub(crate) fn split_square(&self, level: u32, k: u32) -> (u32, u32) {
        unpack_square(self.work_list[(split_offset(self.tile.side, level) + k) as usize])
    }
}

/// Traces lattice point (i, j) into the lattice: its colour and hint.
// Mirror of src/tracer/sampling/adaptive.wgsl::trace_lattice_point — change both.
fn trace_lattice_point(
    scene: &PackedScene,
    lat: &mut Lattice,
    i: u32,
    j: u32,
    counters: &mut impl TraversalCounters,
) {
    let t = lat.tile;
    let (fx, fy) = lattice_position(&t, i, j);
    let k = lattice_index(&t, i, j);
    let (colour, hint) = lattice_sample(scene, fx, fy, counters);
    lat.points[k] = colour;
    lat.hints[k] = encode_hint(hint);
}

/// Lattice point of the centre of square (a, b) of `level` (when [`square_has_centre`]).
// Mirror of src/tracer/sampling/adaptive.wgsl::square_centre — change both.
pub(crate) fn square_centre(tile: &AdaptiveTile, level: u32, a: u32, b: u32) -> (u32, u32) {
    let l = tile.adaptive_scale() >> level;
    (a * l + l / 2, b * l + l / 2)
}

/// Whether the squares of `level` have a traced centre of their own: every level above
/// aa_depth (a square of the deepest level, one lattice step wide, has corners only). Its
/// decision and, unsplit, its colour use it: the quincunx of corners and centre samples
/// rows half the square apart, where the corners alone sample them a whole square apart.
// Mirror of src/tracer/sampling/adaptive.wgsl::square_has_centre — change both.
pub(crate) fn square_has_centre(tile: &AdaptiveTile, level: u32) -> bool {
    level < tile.depth
}

/// Invocation `idx` of the corner pass ([`AdaptiveTile::first_pass_len`] of them): traces
/// pixel corner (idx mod (w+1), idx div (w+1)) for idx < (w+1)(h+1), after those the
/// centre of pixel number idx − (w+1)(h+1).
// Mirror of src/tracer/sampling/adaptive.wgsl::adaptive_corners — change both.
fn adaptive_corners(
    scene: &PackedScene,
    lat: &mut Lattice,
    idx: u32,
    counters: &mut impl TraversalCounters,
) {
    let (i, j) = corner_to_trace(&lat.tile, idx);
    trace_lattice_point(scene, lat, i, j, counters);
}

/// The lattice point that invocation `idx` of the corner pass traces (see
/// [`adaptive_corners`]): pixel corner (idx mod (w+1), idx div (w+1)) for
/// idx < (w+1)(h+1), after those the centre of pixel number idx − (w+1)(h+1). Both
/// forms' corner passes take it: [`adaptive_corners`] here and the wavefront's
/// `wavefront_lattice::lattice_pass_point`.
// Mirror of src/tracer/sampling/adaptive.wgsl::corner_to_trace — change both.
pub(crate) fn corner_to_trace(t: &AdaptiveTile, idx: u32) -> (u32, u32) {
    let s = t.adaptive_scale();
    let corners = (t.size[0] + 1) * (t.size[1] + 1);
    if idx < corners {
        return ((idx % (t.size[0] + 1)) * s, (idx / (t.size[0] + 1)) * s);
    }
    let pixel = idx - corners;
    square_centre(t, 0, pixel % t.size[0], pixel / t.size[0])
}

/// The samples at the corners of square (a, b) of `level`: top-left, top-right,
/// bottom-left, bottom-right.
// Mirror of src/tracer/sampling/adaptive.wgsl::square_corners — change both.
fn square_corners(lat: &Lattice, level: u32, a: u32, b: u32) -> [Vec3; 4] {
    let l = lat.tile.adaptive_scale() >> level;
    let (i, j) = (a * l, b * l);
    [
        lat.lattice_point(i, j),
        lat.lattice_point(i + l, j),
        lat.lattice_point(i, j + l),
        lat.lattice_point(i + l, j + l),
    ]
}

/// The hints of square (a, b) of `level` (< aa_depth: a square that decides has a centre):
/// whether one of its corners or its centre saw fine detail, and whether their camera rays
/// hit different items.
// Mirror of src/tracer/sampling/adaptive.wgsl::square_hints — change both.
fn square_hints(lat: &Lattice, level: u32, a: u32, b: u32) -> SquareHints {
    let l = lat.tile.adaptive_scale() >> level;
    let (i, j) = (a * l, b * l);
    let first = lat.point_hint(i, j);
    let mut hints = SquareHints {
        fine_detail: first.fine_detail,
        items_differ: false,
    };
    hints = add_sample_hint(hints, first, lat.point_hint(i + l, j));
    hints = add_sample_hint(hints, first, lat.point_hint(i, j + l));
    hints = add_sample_hint(hints, first, lat.point_hint(i + l, j + l));
    let (ci, cj) = square_centre(&lat.tile, level, a, b);
    add_sample_hint(hints, first, lat.point_hint(ci, cj))
}

/// The contrast the split decision of square (a, b) of `level` (< aa_depth) weighs: of
/// its corners and centre ([`square_contrast_of`]).
// Mirror of src/tracer/sampling/adaptive.wgsl::square_contrast — change both.
fn square_contrast(lat: &Lattice, level: u32, a: u32, b: u32) -> f32 {
    let corners = square_corners(lat, level, a, b);
    let (ci, cj) = square_centre(&lat.tile, level, a, b);
    square_contrast_of(&corners, lat.lattice_point(ci, cj))
}

/// Whether a square of `level` whose samples' contrast is `spread` splits: the contrast
/// times the square's side (2^−level pixels) exceeds `threshold` (NaN included), that is,
/// the samples differ by more than 2^level · `threshold`; or, whatever the contrast, one
/// of them saw fine detail and the level is above AA_FINE_DETAIL_DEPTH (soft-shadow noise
/// and texture detail at the pixel's scale count as contrast, down to the density of
/// uniform 4×4), or their camera rays hit
/// different items and the level is above AA_ITEM_EDGE_DEPTH (an edge between objects of
/// about the same colour, where a seam or gap thinner than the samples' spacing may lie).
/// The side weighs the contrast because a square's error in its pixel scales with its
/// size: a small square of the same contrast matters less (measured in
/// docs/journal/2026-11-30-threshold-weighed-by-side.md: fewer rays for the same error). The per-pixel walk's test too.
// Mirror of src/tracer/sampling/adaptive.wgsl::square_splits — change both.
pub(crate) fn square_splits(spread: f32, hints: SquareHints, level: u32, threshold: f32) -> bool {
    // (A power of two: the product is exact, on both tracers.)
    let level_threshold = threshold * (1u32 << level) as f32;
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    let differ = !(spread <= level_threshold);
    differ
        || (hints.fine_detail && level < AA_FINE_DETAIL_DEPTH)
        || (hints.items_differ && level < AA_ITEM_EDGE_DEPTH)
}

/// Invocation `idx` of the decide pass of `level`: square (idx mod w, idx div w) at
/// level 0, else child idx mod 4 (top-left, top-right, bottom-left, bottom-right) of
/// entry idx div 4 of level − 1's split list. Flags it for splitting by [`square_splits`]
/// and then appends it to level's split list.
// Mirror of src/tracer/sampling/adaptive.wgsl::adaptive_decide — change both.
fn adaptive_decide(lat: &mut Lattice, level: u32, idx: u32, threshold: f32) {
    let t = lat.tile;
    let (a, b) = if level == 0 {
        (idx % t.size[0], idx / t.size[0])
    } else {
        let (pa, pb) = lat.split_square(level - 1, idx / 4);
        (2 * pa + (idx % 4) % 2, 2 * pb + (idx % 4) / 2)
    };
    let split = square_splits(
        square_contrast(lat, level, a, b),
        square_hints(lat, level, a, b),
        level,
        threshold,
    );
    lat.split[split_index(&t, level, a, b)] = split as u32;
    if split {
        let slot = lat.work_counts[level as usize];
        lat.work_counts[level as usize] += 1;
        lat.work_list[(split_offset(t.side, level) + slot) as usize] = pack_square(a, b);
    }
}

/// After the decide pass of `level`, the sizes of the passes over its list of split
/// squares ([`WorkArgs`]): the midpoint pass (AA_SPLIT_POINTS invocations a square) and
/// the next level's decide pass (4 children a square). The GPU's twin writes them as the
/// indirect dispatch arguments of those passes, in workgroups; the CPU's passes loop over
/// the invocations.
// Mirror of src/tracer/sampling/adaptive.wgsl::adaptive_work_args — change both.
fn adaptive_work_args(lat: &mut Lattice, level: u32) {
    let n = lat.work_counts[level as usize];
    lat.work_args[level as usize] = WorkArgs {
        midpoints: AA_SPLIT_POINTS * n,
        children: 4 * n,
    };
}

/// Invocation `idx` of the midpoint pass of `level`: point idx mod AA_SPLIT_POINTS of
/// entry idx div AA_SPLIT_POINTS of level's split list — its top, left, right and bottom
/// edge midpoints, then the centres of its top-left, top-right, bottom-left and
/// bottom-right children where those have centres ([`square_has_centre`]). (Its own
/// centre, the children's shared corner, was traced with its corners.) A top (left)
/// midpoint is the bottom (right) one of the square above (to the left); when that one
/// is split too, it traces the point.
// Mirror of src/tracer/sampling/adaptive.wgsl::adaptive_midpoints — change both.
fn adaptive_midpoints(
    scene: &PackedScene,
    lat: &mut Lattice,
    level: u32,
    idx: u32,
    counters: &mut impl TraversalCounters,
) {
    if let Some((i, j)) = midpoint_to_trace(lat, level, idx) {
        trace_lattice_point(scene, lat, i, j, counters);
    }
}

/// The lattice point that invocation `idx` of level `level`'s midpoint pass traces (see
/// [`adaptive_midpoints`]); None where another invocation traces it, or the child has no
/// centre. Both forms' midpoint passes take it: [`adaptive_midpoints`] here and the
/// wavefront's `wavefront_lattice::lattice_pass_point`.
// Mirror of src/tracer/sampling/adaptive.wgsl::midpoint_to_trace — change both.
pub(crate) fn midpoint_to_trace(lat: &Lattice, level: u32, idx: u32) -> Option<(u32, u32)> {
    let t = lat.tile;
    let m = idx % AA_SPLIT_POINTS;
    let (a, b) = lat.split_square(level, idx / AA_SPLIT_POINTS);
    if (m == 0 && b > 0 && lat.is_split(level, a, b - 1))
        || (m == 1 && a > 0 && lat.is_split(level, a - 1, b))
        || (m >= 4 && !square_has_centre(&t, level + 1))
    {
        return None;
    }
    let l = t.adaptive_scale() >> level;
    let (h, q) = (l / 2, l / 4);
    let offsets = [
        (h, 0),
        (0, h),
        (l, h),
        (h, l),
        (q, q),
        (h + q, q),
        (q, h + q),
        (h + q, h + q),
    ];
    let (ox, oy) = offsets[m as usize];
    Some((a * l + ox, b * l + oy))
}

/// Colour of tile pixel (tx, ty) and its number of leaf squares: the area-weighted mean
/// over its quadtree, walked depth first without a stack (a split square's children
/// bottom-right, bottom-left, top-right, top-left: [`next_square`]), which is the order
/// in which the per-pixel walk pops them, so the sum runs in that walk's order; a leaf
/// with a centre is the [`quincunx_mean`] of its corners and centre, one of the deepest
/// level the mean of its corners, each weighted by its area. (Stackless because the GPU
/// twin's private stack, indexed at run time, cost llvmpipe per-lane scatters and
/// gathers: docs/gpu.md#the-kernel-variant-chosen-from-the-adapter.)
// Mirror of src/tracer/sampling/adaptive.wgsl::adaptive_integrate — change both.
fn adaptive_integrate(lat: &Lattice, tx: u32, ty: u32) -> (Vec3, u32) {
    let t = lat.tile;
    // (level, a, b)
    let mut sq = [0, tx, ty];
    let mut sum = Vec3::ZERO;
    let mut leaves = 0;
    loop {
        let [level, a, b] = sq;
        if level < t.depth && lat.is_split(level, a, b) {
            sq = [level + 1, 2 * a + 1, 2 * b + 1];
            continue;
        }
        let c = square_corners(lat, level, a, b);
        leaves += 1;
        let side = 1.0 / (1u32 << level) as f32;
        let area = side * side;
        if square_has_centre(&t, level) {
            let (ci, cj) = square_centre(&t, level, a, b);
            sum += quincunx_mean(&c, lat.lattice_point(ci, cj)) * area;
        } else {
            sum += (c[0] + c[1] + c[2] + c[3]) * (0.25 * area);
        }
        sq = next_square(level, a, b);
        if sq[0] == 0 {
            return (sum, leaves);
        }
    }
}

/// The square the integrate walk visits after the subtree of square (level, a, b): its
/// next sibling (bottom-right → bottom-left → top-right → top-left), or, after a top-left
/// child, its parent's next; level 0 when the pixel's walk is over.
// Mirror of src/tracer/sampling/adaptive.wgsl::next_square — change both.
fn next_square(level: u32, a: u32, b: u32) -> [u32; 3] {
    let mut sq = [level, a, b];
    while sq[0] > 0 && sq[1] & 1 == 0 && sq[2] & 1 == 0 {
        sq = [sq[0] - 1, sq[1] / 2, sq[2] / 2];
    }
    if sq[0] == 0 {
        return sq;
    }
    if sq[1] & 1 == 1 {
        return [sq[0], sq[1] - 1, sq[2]];
    }
    [sq[0], sq[1] + 1, sq[2] - 1]
}

/// Runs every pass over `lat`'s tile; returns its pixels, row-major, with their leaf
/// counts.
pub fn adaptive_tile(
    scene: &PackedScene,
    lat: &mut Lattice,
    threshold: f32,
    counters: &mut impl TraversalCounters,
) -> Vec<(Vec3, u32)> {
    adaptive_tile_passes(lat, threshold, |lat, pass| {
        if pass == 0 {
            for idx in 0..lat.tile.first_pass_len() {
                adaptive_corners(scene, lat, idx, counters);
            }
        } else {
            let level = pass - 1;
            for idx in 0..lat.work_args[level as usize].midpoints {
                adaptive_midpoints(scene, lat, level, idx, counters);
            }
        }
    })
}

/// Every pass over `lat`'s tile, the tracing passes through `trace_pass(lat, pass)`
/// (pass 0: the corner pass, 1 + k: level k's midpoint pass; [`adaptive_tile`]'s
/// megakernel passes, or `wavefront_lattice`'s through the wavefront passes); its
/// pixels, row-major, with their leaf counts.
pub fn adaptive_tile_passes(
    lat: &mut Lattice,
    threshold: f32,
    mut trace_pass: impl FnMut(&mut Lattice, u32),
) -> Vec<(Vec3, u32)> {
    let t = lat.tile;
    let [w, h] = t.size;
    trace_pass(lat, 0);
    for level in 0..t.depth {
        let squares = if level == 0 {
            w * h
        } else {
            lat.work_args[level as usize - 1].children
        };
        for idx in 0..squares {
            adaptive_decide(lat, level, idx, threshold);
        }
        adaptive_work_args(lat, level);
        trace_pass(lat, level + 1);
    }
    let mut out = Vec::with_capacity((w * h) as usize);
    for ty in 0..h {
        for tx in 0..w {
            out.push(adaptive_integrate(lat, tx, ty));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{adaptive_integrate, next_square, split_index, square_splits, Lattice};
    use crate::constants::{AA_FINE_DETAIL_DEPTH, AA_ITEM_EDGE_DEPTH};
    use crate::tiling::AdaptiveTile;
    use crate::tracer::sampling::pixel_sample::SquareHints;
    use glam::Vec3;

    const PLAIN: SquareHints = SquareHints {
        fine_detail: false,
        items_differ: false,
    };

    #[test]
    fn the_threshold_weighs_contrast_by_the_squares_side() {
        // Level k compares the contrast with 2^k · threshold.
        for (contrast, splits_down_to) in [(0.05, 0), (0.15, 1), (0.3, 2), (0.7, 3)] {
            for level in 0..4 {
                assert_eq!(
                    square_splits(contrast, PLAIN, level, 0.1),
                    level < splits_down_to,
                    "contrast {contrast} at level {level}"
                );
            }
        }
        // A NaN contrast (∞ − ∞) splits.
        assert!(square_splits(f32::NAN, PLAIN, 3, 0.1));
    }

    #[test]
    fn penumbrae_and_item_edges_split_down_to_their_depths_whatever_the_contrast() {
        let penumbra = SquareHints {
            fine_detail: true,
            ..PLAIN
        };
        let items = SquareHints {
            items_differ: true,
            ..PLAIN
        };
        for level in 0..5 {
            assert_eq!(
                square_splits(0.0, penumbra, level, f32::MAX),
                level < AA_FINE_DETAIL_DEPTH
            );
            assert_eq!(
                square_splits(0.0, items, level, f32::MAX),
                level < AA_ITEM_EDGE_DEPTH
            );
            assert!(!square_splits(0.0, PLAIN, level, f32::MAX));
        }
    }

    /// The integrate walk against the per-pixel walk's stack (children pushed top-left,
    /// top-right, bottom-left, bottom-right, popped last first) on random split trees and
    /// colours: the same leaves in the same order, so the same sums bit for bit.
    #[test]
    fn the_stackless_integrate_walk_sums_in_the_stacks_order() {
        let mut state = 0x9e37_79b9_u32;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            state
        };
        for depth in 0..=4 {
            let tile = AdaptiveTile {
                origin: [0, 0],
                size: [3, 2],
                side: 3,
                depth,
            };
            let mut lat = Lattice::new(tile);
            for p in lat.points.iter_mut() {
                *p = Vec3::new(next() as f32, next() as f32, next() as f32) / 4e9;
            }
            for level in 0..depth {
                for b in 0..(tile.size[1] << level) {
                    for a in 0..(tile.size[0] << level) {
                        let parent_split = level == 0 || lat.is_split(level - 1, a / 2, b / 2);
                        let flag = parent_split && next() % 3 != 0;
                        lat.split[split_index(&tile, level, a, b)] = flag as u32;
                    }
                }
            }
            for (tx, ty) in [(0, 0), (1, 0), (2, 1)] {
                let (sum, leaves) = adaptive_integrate(&lat, tx, ty);
                let (want_sum, want_leaves, order) = stack_walk(&lat, tx, ty);
                assert_eq!(leaves, want_leaves, "depth {depth}, pixel ({tx}, {ty})");
                assert_eq!(sum.to_array(), want_sum.to_array(), "depth {depth}");
                // next_square visits the stack's order: each leaf's successor.
                for pair in order.windows(2) {
                    let [level, a, b] = pair[0];
                    let mut sq = next_square(level, a, b);
                    while sq != pair[1] {
                        assert!(sq[0] < depth && lat.is_split(sq[0], sq[1], sq[2]));
                        sq = [sq[0] + 1, 2 * sq[1] + 1, 2 * sq[2] + 1];
                    }
                }
                if let Some(last) = order.last() {
                    let [level, a, b] = *last;
                    assert_eq!(next_square(level, a, b)[0], 0);
                }
            }
        }
    }

    /// The per-pixel walk's order with an explicit stack: the sum, the leaves and their
    /// (level, a, b) in visiting order.
    fn stack_walk(lat: &Lattice, tx: u32, ty: u32) -> (Vec3, u32, Vec<[u32; 3]>) {
        let t = lat.tile;
        let mut stack = vec![[0, tx, ty]];
        let (mut sum, mut order) = (Vec3::ZERO, Vec::new());
        while let Some([level, a, b]) = stack.pop() {
            if level < t.depth && lat.is_split(level, a, b) {
                for (da, db) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    stack.push([level + 1, 2 * a + da, 2 * b + db]);
                }
                continue;
            }
            let c = super::square_corners(lat, level, a, b);
            let side = 1.0 / (1u32 << level) as f32;
            if super::square_has_centre(&t, level) {
                let (ci, cj) = super::square_centre(&t, level, a, b);
                sum += super::quincunx_mean(&c, lat.lattice_point(ci, cj)) * (side * side);
            } else {
                sum += (c[0] + c[1] + c[2] + c[3]) * (0.25 * side * side);
            }
            order.push([level, a, b]);
        }
        (sum, order.len() as u32, order)
    }
}
