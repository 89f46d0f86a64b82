//! The wavefront passes' pieces for scenes with refraction (`wavefront_shade`, `wavefront_shadow`, `wavefront_gather`), where a
//! dielectric's hit spawns two rays and a sample's paths form a tree:
//! - the vertex tree: each vertex's value (weight × its colour, weight × the background
//!   on a miss; the camera vertex's colour as it is) and links to the children its shade
//!   step appended, in the order `push_secondary_rays` pushes them (transmitted, then
//!   reflected), kept over every generation of the batch;
//! - the fold pass: per sample, the vertex tree walked with `trace_ray`'s own stack
//!   (children pushed in push order, popped last first: a vertex, then its reflected
//!   subtree, then its transmitted subtree), summing `colour += value` as its running sum
//!   does, so the float additions happen in the same order;
//! - the glass shadow rounds: each shadow request's ray through the glass between its
//!   point and its light point, as `dielectric::shadow_transmittance` traces it, but one
//!   leg a round over every live request: a closest pass (traversal) and a crossing step
//!   (no traversal: the opaque test, the normal-incidence transmission, the medium
//!   stack, the next leg appended), at most MAX_SHADOW_CROSSINGS + 1 rounds; then each
//!   slot × its transmittance, as `shade::point_light` finishes its term.
//!
//! Path entries carry their medium stack and their pending count (the entries under
//! them on `trace_ray`'s stack: `PathQueue::pending`), so the shade pass pushes children
//! where the stack would be and drops the rays `trace_ray` drops when it is full
//! ([`push_tree_children`]).
//! Design: docs/journal/2026-12-02-wavefront-split-measured.md; what was built:
//! docs/journal/2026-12-02-wavefront-tree.md.

use super::batch::{spawned_rays, Batch};
pub use super::queues::{HitQueue, LegQueue, VertexTree};
use crate::constants::{MAX_SHADOW_CROSSINGS, RAY_STACK_SIZE};
use crate::pack::PackedScene;
use crate::tracer::path::trace::{ShadedHit, StackEntry};
use crate::tracer::shading::dielectric::{cross_shadow_surface, shadow_leg_ray, ShadowLeg};
use crate::tracer::shading::shade::shadowed_term;
use crate::tracer::traversal::hit::{Hit, TraversalCounters};
use crate::tracer::traversal::traverse::closest_hit;
use glam::Vec3;

/// A vertex without a child in that place.
pub use crate::constants::NO_CHILD;

/// The fold pass: each sample's colour from its vertex tree, from its camera vertex
/// (`camera_vertices`; NO_CHILD: the sample traced nothing and keeps its colour).
// Mirror of src/tracer/wavefront/wavefront_tree.wgsl::wavefront_fold — change both.
pub fn wavefront_fold(tree: &VertexTree, camera_vertices: &[u32], colours: &mut [Vec3]) {
    for (colour, &vertex) in colours.iter_mut().zip(camera_vertices) {
        if vertex != NO_CHILD {
            *colour = fold_entry(tree, vertex);
        }
    }
}

/// The fold's invocation for sample `k`, whose camera vertex is vertex `k`: `trace_ray`'s
/// running sum over its stack — the camera vertex's value, then each vertex as it pops
/// (children pushed in push order, so the last pushed, a dielectric's reflected ray, is
/// summed first with its whole subtree). The stack never holds more than RAY_STACK_SIZE:
/// the shade pass appended only what `trace_ray`'s stack held.
// Mirror of src/tracer/wavefront/wavefront_tree.wgsl::fold_entry — change both.
pub fn fold_entry(tree: &VertexTree, k: u32) -> Vec3 {
    let mut stack = [NO_CHILD; RAY_STACK_SIZE as usize];
    let mut size = 0;
    let mut colour = tree.value[k as usize];
    push_children(tree, k, &mut stack, &mut size);
    while size > 0 {
        size -= 1;
        let vertex = stack[size];
        colour += tree.value[vertex as usize];
        push_children(tree, vertex, &mut stack, &mut size);
    }
    colour
}

/// Pushes `vertex`'s children onto the fold's stack in the order shade appended them.
// Mirror of src/tracer/wavefront/wavefront_tree.wgsl::push_children — change both.
fn push_children(
    tree: &VertexTree,
    vertex: u32,
    stack: &mut [u32; RAY_STACK_SIZE as usize],
    size: &mut usize,
) {
    for child in tree.children[vertex as usize] {
        if child != NO_CHILD {
            stack[*size] = child;
            *size += 1;
        }
    }
}

/// The rays path `i`'s hit (vertex `vertex_base` + i, sample `k`) spawns, pushed as
/// `trace_ray` pushes them onto its stack, which holds the path's pending entries then:
/// so the same rays are dropped where the stack is full, and each child's pending count
/// is its index in that stack. Each is appended to the next generation's queue and
/// linked as the vertex's child (the GPU's queues may lack room: its twin).
// Mirror of src/tracer/wavefront/wavefront_tree.wgsl::push_tree_children — change both.
pub(super) fn push_tree_children(
    scene: &PackedScene,
    batch: &mut Batch,
    i: usize,
    entry: &StackEntry,
    k: usize,
    shaded: &ShadedHit,
    hit: &Hit,
) {
    let pending = batch.paths.pending[i] as usize;
    let (stack, size) = spawned_rays(scene, entry, shaded, hit, pending);
    let base = batch.vertex_base as usize;
    let next_base = base + batch.paths.len();
    for (q, child) in stack.iter().enumerate().take(size).skip(pending) {
        let j = batch.next.append_path(child, q as u32, k as u32);
        batch.tree.children[base + i][q - pending] = (next_base + j) as u32;
    }
}

impl LegQueue {
    /// Appends request `request`'s `leg`; its index (the GPU's `atomicAdd`).
    // Mirror of src/tracer/wavefront/wavefront_tree.wgsl::append_leg — change both.
    fn append_leg(&mut self, request: u32, leg: &ShadowLeg) -> usize {
        let l = self.len();
        self.resize(l + 1);
        self.store_leg(l, request, leg);
        l
    }

    /// Writes request `request`'s `leg` as leg `l`.
    fn store_leg(&mut self, l: usize, request: u32, leg: &ShadowLeg) {
        (
            self.request[l],
            self.start[l],
            self.transmittance[l],
            self.media[l],
        ) = (request, leg.start, leg.transmittance, leg.media);
    }

    fn load_leg(&self, l: usize) -> ShadowLeg {
        ShadowLeg {
            start: self.start[l],
            transmittance: self.transmittance[l],
            media: self.media[l],
        }
    }
}

/// Shadow request `r`'s first leg (the shadow pass's invocation with refraction; round
/// 0's leg r, `batch.legs` sized to the requests): from its vertex's shadow origin, in
/// the media of the vertex's path.
// Mirror of src/tracer/wavefront/wavefront_tree.wgsl::start_shadow_leg — change both.
pub(super) fn start_shadow_leg(batch: &mut Batch, r: usize) {
    let i = (batch.shadows.slot[r] / batch.light_points) as usize;
    let first = ShadowLeg {
        start: batch.vertices.shadow_origin[i],
        transmittance: 1.0,
        media: batch.paths.media[i],
    };
    batch.legs.store_leg(r, r as u32, &first);
}

/// Request `r`'s light point and its vertex's magnitude.
// Mirror of src/tracer/wavefront/wavefront_tree.wgsl::request_target — change both.
fn request_target(batch: &Batch, r: usize) -> (Vec3, f32) {
    let i = (batch.shadows.slot[r] / batch.light_points) as usize;
    (batch.shadows.position[r], batch.vertices.magnitude[i])
}

/// The glass shadow rounds, after the shadow pass started every request's first leg
/// ([`start_shadow_leg`]): rounds of [`wavefront_leg_closest`] and
/// [`wavefront_crossing`] over the live legs until none is left (at most
/// MAX_SHADOW_CROSSINGS + 1: the crossing step blocks a leg at crossing
/// MAX_SHADOW_CROSSINGS), each request's slot × its transmittance once its last leg
/// ends ([`end_request`]). Returns the number of rounds.
pub fn glass_shadow_rounds(
    scene: &PackedScene,
    batch: &mut Batch,
    counters: &mut impl TraversalCounters,
) -> u32 {
    let mut rounds = 0;
    while !batch.legs.is_empty() {
        assert!(
            rounds <= MAX_SHADOW_CROSSINGS,
            "a leg past the last crossing"
        );
        let hits = wavefront_leg_closest(scene, batch, counters);
        let next = wavefront_crossing(scene, batch, &hits, rounds);
        wavefront_leg_args(batch, next);
        rounds += 1;
    }
    rounds
}

/// A round's closest pass: each live leg's ray to the first surface short of its light
/// point, the hits at the legs' indices.
// Mirror of src/tracer/wavefront/wavefront_tree.wgsl::wavefront_leg_closest — change both.
fn wavefront_leg_closest(
    scene: &PackedScene,
    batch: &Batch,
    counters: &mut impl TraversalCounters,
) -> HitQueue {
    let mut hits = HitQueue::default();
    hits.reset(batch.legs.len());
    for l in 0..batch.legs.len() {
        hits.store_hit(l, &leg_closest_entry(scene, batch, l, counters));
    }
    hits
}

/// The round's closest pass for leg `l`: its ray toward the request's light point, to
/// the first surface short of it.
// Mirror of src/tracer/wavefront/wavefront_tree.wgsl::leg_closest_entry — change both.
fn leg_closest_entry(
    scene: &PackedScene,
    batch: &Batch,
    l: usize,
    counters: &mut impl TraversalCounters,
) -> Hit {
    let (position, magnitude) = request_target(batch, batch.legs.request[l] as usize);
    let (ray, reach) = shadow_leg_ray(&batch.legs.load_leg(l), position, magnitude);
    closest_hit(scene, &ray, reach, counters)
}

/// A round's crossing step (crossing `crossing`), each live leg with its closest hit
/// in `hits`: the next round's legs.
// Mirror of src/tracer/wavefront/wavefront_tree.wgsl::wavefront_crossing — change both.
fn wavefront_crossing(
    scene: &PackedScene,
    batch: &mut Batch,
    hits: &HitQueue,
    crossing: u32,
) -> LegQueue {
    let mut next = LegQueue::default();
    for l in 0..batch.legs.len() {
        crossing_entry(scene, batch, l, &hits.load_hit(l), crossing, &mut next);
    }
    next
}

/// The round's crossing step for leg `l` (crossing `crossing`), whose closest hit is
/// `hit`: a miss ends the request with the transmittance so far, an opaque surface (or
/// the crossing after the last) with 0; glass appends the next leg to `next`.
// Mirror of src/tracer/wavefront/wavefront_tree.wgsl::crossing_entry — change both.
fn crossing_entry(
    scene: &PackedScene,
    batch: &mut Batch,
    l: usize,
    hit: &Hit,
    crossing: u32,
    next: &mut LegQueue,
) {
    let r = batch.legs.request[l];
    let leg = batch.legs.load_leg(l);
    if !hit.is_hit() {
        end_request(batch, r as usize, leg.transmittance);
        return;
    }
    let (position, magnitude) = request_target(batch, r as usize);
    let (ray, _) = shadow_leg_ray(&leg, position, magnitude);
    match cross_shadow_surface(scene, &ray, hit, crossing, &leg) {
        Some(beyond) => {
            next.append_leg(r, &beyond);
        }
        None => end_request(batch, r as usize, 0.0),
    }
}

/// Request `r`'s slot × its transmittance (`shade::point_light`'s last product), once,
/// when its last leg ends.
// Mirror of src/tracer/wavefront/wavefront_tree.wgsl::end_request — change both.
fn end_request(batch: &mut Batch, r: usize, transmittance: f32) {
    let slot = batch.shadows.slot[r] as usize;
    batch.slots.term[slot] = shadowed_term(batch.slots.term[slot], transmittance);
}

/// Ends a round (the leg args kernel's job on the GPU): the next round's legs become
/// the live ones.
// Mirror of src/tracer/wavefront/wavefront_tree.wgsl::wavefront_leg_args — change both.
fn wavefront_leg_args(batch: &mut Batch, next: LegQueue) {
    batch.legs = next;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fold sums in `trace_ray`'s pop order — vertex, its last-pushed child's subtree,
    /// then its first-pushed child's — with values whose sum depends on the order
    /// (1e8 + 1 rounds back to 1e8 in f32).
    #[test]
    fn fold_sums_in_pop_order() {
        let mut tree = VertexTree::default();
        tree.resize(4);
        // Vertex 0 pushed 1 (transmitted) then 2 (reflected); 2 pushed 3.
        tree.children[0] = [1, 2];
        tree.children[2] = [3, NO_CHILD];
        tree.value = [0.0, -1e8, 1e8, 1.0].map(Vec3::splat).to_vec();
        let pop_order = ((0.0f32 + 1e8) + 1.0) + -1e8;
        let push_order = ((0.0f32 + -1e8) + 1e8) + 1.0;
        assert_ne!(pop_order, push_order);
        assert_eq!(fold_entry(&tree, 0), Vec3::splat(pop_order));
        let mut colours = [Vec3::NAN];
        wavefront_fold(&tree, &[0], &mut colours);
        assert_eq!(colours[0], Vec3::splat(pop_order));
    }
}
