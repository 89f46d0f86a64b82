//! Adaptive AA's tracing passes through the wavefront passes: the corner pass and each
//! level's midpoint pass (the points [`adaptive`](crate::tracer::sampling::adaptive)'s `adaptive_corners`
//! and `adaptive_midpoints` trace, enumerated alike) as a [`SampleSource::Lattice`]
//! batch through the wavefront passes, whose samples' colours and hints then go into their
//! lattice points: the lattice, and so the image, is the megakernel passes' bit for bit.
//!
//! On the GPU (`src/tracer/wavefront/wavefront_lattice.wgsl`, hardware kernel variant) the camera
//! pass's invocation idx keeps sample idx's record at idx and appends its path to
//! generation 0's queue (an invocation whose point another traces appends none), and the
//! store pass's invocation idx writes sample idx into its point; here the batch holds the
//! traced points alone, in invocation order. Neither order changes a bit.

use super::wavefront::{camera_pass, trace_generations, Batch, SampleSource};
use crate::constants::AA_SPLIT_POINTS;
use crate::pack::PackedScene;
use crate::tracer::sampling::adaptive::{
    adaptive_tile_passes, corner_to_trace, lattice_index, lattice_position, midpoint_to_trace,
    AdaptiveTile, Lattice,
};
use crate::tracer::traversal::traverse::TraversalCounters;
use glam::Vec3;

/// The invocations of lattice pass `pass`: the corner pass's (corners, then centres at
/// depth ≥ 1), or AA_SPLIT_POINTS per square on level pass − 1's list.
// Mirror of src/tracer/wavefront/wavefront_lattice.wgsl::lattice_pass_len — change both.
pub fn lattice_pass_len(lat: &Lattice, pass: u32) -> u32 {
    let t = lat.tile;
    if pass == 0 {
        let corners = (t.size[0] + 1) * (t.size[1] + 1);
        let centres = if t.depth >= 1 {
            t.size[0] * t.size[1]
        } else {
            0
        };
        return corners + centres;
    }
    AA_SPLIT_POINTS * lat.work_counts[pass as usize - 1]
}

/// The lattice point invocation `idx` of the corner pass traces: pixel corner
/// (idx mod (w+1), idx div (w+1)) for idx < (w+1)(h+1), after those the centre of pixel
/// number idx − (w+1)(h+1).
// Mirror of src/tracer/wavefront/wavefront_lattice.wgsl::corner_pass_point — change both.
pub fn corner_pass_point(t: &AdaptiveTile, idx: u32) -> (u32, u32) {
    corner_to_trace(t, idx)
}

/// The lattice point invocation `idx` of level `level`'s midpoint pass traces: point
/// idx mod AA_SPLIT_POINTS of entry idx div AA_SPLIT_POINTS of the level's list (its top,
/// left, right and bottom edge midpoints, then its children's centres where those have
/// centres); None for a top (left) midpoint that the split square above (to the left)
/// traces, and for a child's centre at the deepest level.
// Mirror of src/tracer/wavefront/wavefront_lattice.wgsl::midpoint_pass_point — change both.
pub fn midpoint_pass_point(lat: &Lattice, level: u32, idx: u32) -> Option<(u32, u32)> {
    midpoint_to_trace(lat, level, idx)
}

/// The lattice point invocation `idx` of lattice pass `pass` (0: the corner pass, 1 + k:
/// level k's midpoint pass) traces, if any.
// Mirror of src/tracer/wavefront/wavefront_lattice.wgsl::lattice_pass_point — change both.
pub fn lattice_pass_point(lat: &Lattice, pass: u32, idx: u32) -> Option<(u32, u32)> {
    if pass == 0 {
        return Some(corner_pass_point(&lat.tile, idx));
    }
    midpoint_pass_point(lat, pass - 1, idx)
}

/// Lattice pass `pass` through the wavefront passes: the camera pass over the points its
/// invocations trace ([`wavefront_lattice_camera`]), the generations
/// ([`trace_generations`]), then each sample's colour and hint into its lattice point
/// ([`wavefront_lattice_store`]).
pub fn trace_lattice_pass(
    scene: &PackedScene,
    lat: &mut Lattice,
    pass: u32,
    counters: &mut impl TraversalCounters,
) {
    let mut batch = Batch::default();
    let traced = wavefront_lattice_camera(scene, lat, pass, &mut batch);
    trace_generations(scene, &mut batch, counters);
    for (k, &(i, j)) in traced.iter().enumerate() {
        wavefront_lattice_store(lat, &batch, k, i, j);
    }
}

/// The camera pass of lattice pass `pass`: the lattice points its invocations trace, in
/// invocation order, whose camera rays (at their lattice positions, jittered by the
/// [`SampleSource::Lattice`] source as `lattice_sample` jitters them) start `batch`.
// Mirror of src/tracer/wavefront/wavefront_lattice.wgsl::wavefront_lattice_camera, the pass's invocations in one loop (the GPU's keep each sample's record at the invocation's index; here the batch holds the traced points alone) — change both.
pub fn wavefront_lattice_camera(
    scene: &PackedScene,
    lat: &Lattice,
    pass: u32,
    batch: &mut Batch,
) -> Vec<(u32, u32)> {
    let t = lat.tile;
    let traced: Vec<(u32, u32)> = (0..lattice_pass_len(lat, pass))
        .filter_map(|idx| lattice_pass_point(lat, pass, idx))
        .collect();
    let points: Vec<[f32; 2]> = traced
        .iter()
        .map(|&(i, j)| {
            let (fx, fy) = lattice_position(&t, i, j);
            [fx, fy]
        })
        .collect();
    camera_pass(scene, &SampleSource::Lattice { points: &points }, batch);
    traced
}

/// Sample `k` of `batch` into lattice point (i, j): its colour and its hint.
// Mirror of the store of src/tracer/wavefront/wavefront_lattice.wgsl::wavefront_lattice_store — change both.
fn wavefront_lattice_store(lat: &mut Lattice, batch: &Batch, k: usize, i: u32, j: u32) {
    let at = lattice_index(&lat.tile, i, j);
    lat.points[at] = batch.samples.colour[k];
    lat.hints[at] = batch.samples.hint(k);
}

/// [`adaptive_tile`](crate::tracer::sampling::adaptive::adaptive_tile) with its tracing passes through the
/// wavefront passes ([`trace_lattice_pass`]): the same pixels, bit for bit.
pub fn adaptive_tile_wavefront(
    scene: &PackedScene,
    lat: &mut Lattice,
    threshold: f32,
    counters: &mut impl TraversalCounters,
) -> Vec<(Vec3, u32)> {
    adaptive_tile_passes(lat, threshold, |lat, pass| {
        trace_lattice_pass(scene, lat, pass, counters)
    })
}
