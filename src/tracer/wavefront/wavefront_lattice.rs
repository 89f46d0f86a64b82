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
//!
//! `adaptive::adaptive_tile_passes` runs a tile's passes with [`trace_lattice_pass`] as its
//! tracing pass: the pixels of `adaptive::adaptive_tile`, bit for bit.

use super::wavefront::{camera_pass, trace_generations, Batch};
use crate::constants::AA_SPLIT_POINTS;
use crate::pack::PackedScene;
use crate::tracer::sampling::adaptive::{
    corner_to_trace, lattice_index, lattice_position, midpoint_to_trace, Lattice,
};
use crate::tracer::sampling::pixel_sample::encode_hint;
use crate::tracer::sampling::sample_source::SampleSource;
use crate::tracer::traversal::traverse::TraversalCounters;

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

/// The lattice point invocation `idx` of lattice pass `pass` (0: the corner pass, 1 + k:
/// level k's midpoint pass) traces, if any: the megakernel passes' points
/// (`adaptive::corner_to_trace`, `adaptive::midpoint_to_trace`).
// Mirror of src/tracer/wavefront/wavefront_lattice.wgsl::lattice_pass_point — change both.
pub fn lattice_pass_point(lat: &Lattice, pass: u32, idx: u32) -> Option<(u32, u32)> {
    if pass == 0 {
        return Some(corner_to_trace(&lat.tile, idx));
    }
    midpoint_to_trace(lat, pass - 1, idx)
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
    lat.hints[at] = encode_hint(batch.samples.hint(k));
}
