//! The wavefront passes' pieces for scenes with refraction (`tracer::wavefront::wavefront`), where a
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
//! where the stack would be and drops the rays `trace_ray` drops when it is full.
//! Design: docs/journal/2026-12-02-wavefront-split-measured.md; what was built:
//! docs/journal/2026-12-02-wavefront-tree.md.

pub use super::queues::{HitQueue, LegQueue, VertexTree};
use crate::constants::{MAX_SHADOW_CROSSINGS, RAY_STACK_SIZE};
use crate::pack::PackedScene;
use crate::tracer::shading::dielectric::{
    cross_shadow_surface, shadow_leg_ray, MediumStack, ShadowLeg,
};
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

impl LegQueue {
    /// Appends request `request`'s `leg`; its index (the GPU's `atomicAdd`).
    // Mirror of src/tracer/wavefront/wavefront_tree.wgsl::append_leg — change both.
    fn append_leg(&mut self, request: u32, leg: &ShadowLeg) -> usize {
        let l = self.len();
        self.resize(l + 1);
        (
            self.request[l],
            self.start[l],
            self.transmittance[l],
            self.media[l],
        ) = (request, leg.start, leg.transmittance, leg.media);
        l
    }

    fn load_leg(&self, l: usize) -> ShadowLeg {
        ShadowLeg {
            start: self.start[l],
            transmittance: self.transmittance[l],
            media: self.media[l],
        }
    }
}

/// What the glass shadow rounds read of a generation: per shadow request its light slot
/// (its vertex is slot div light_points) and its light point; per vertex where its shadow rays start (origin, the
/// surface's magnitude, the media around it). (`tracer::wavefront::wavefront`'s queues, borrowed.)
pub struct ShadowRequests<'a> {
    pub slot: &'a [u32],
    pub position: &'a [Vec3],
    pub shadow_origin: &'a [Vec3],
    pub magnitude: &'a [f32],
    pub media: &'a [MediumStack],
    /// Slots a vertex: vertex i's slot j is `slots[i·light_points + j]`.
    pub light_points: u32,
}

impl ShadowRequests<'_> {
    /// The vertex request `r` is for.
    fn vertex(&self, r: usize) -> usize {
        (self.slot[r] / self.light_points) as usize
    }
}

/// The glass shadow pass: every shadow request's first leg from its vertex's shadow
/// origin in the vertex's media, then rounds of [`leg_closest_entry`] and
/// [`crossing_entry`] over the live legs until none is left (at most
/// MAX_SHADOW_CROSSINGS + 1: the crossing step blocks a leg at crossing
/// MAX_SHADOW_CROSSINGS), then each request's slot × its transmittance. Returns the
/// number of rounds.
pub fn glass_shadow_rounds(
    scene: &PackedScene,
    requests: &ShadowRequests,
    slots: &mut [Vec3],
    counters: &mut impl TraversalCounters,
) -> u32 {
    let count = requests.slot.len();
    let mut transmittance = vec![0.0f32; count];
    let mut legs = LegQueue::default();
    for r in 0..count {
        let i = requests.vertex(r);
        let first = ShadowLeg {
            start: requests.shadow_origin[i],
            transmittance: 1.0,
            media: requests.media[i],
        };
        legs.append_leg(r as u32, &first);
    }
    let mut rounds = 0;
    while !legs.is_empty() {
        assert!(
            rounds <= MAX_SHADOW_CROSSINGS,
            "a leg past the last crossing"
        );
        let mut hits = HitQueue::default();
        hits.reset(legs.len());
        for l in 0..legs.len() {
            hits.store_hit(l, &leg_closest_entry(scene, requests, &legs, l, counters));
        }
        let mut next = LegQueue::default();
        for l in 0..legs.len() {
            crossing_entry(
                scene,
                requests,
                &legs,
                l,
                &hits.load_hit(l),
                rounds,
                &mut next,
                &mut transmittance,
            );
        }
        legs = next;
        rounds += 1;
    }
    for (r, &t) in transmittance.iter().enumerate() {
        let slot = requests.slot[r] as usize;
        slots[slot] = shadowed_term(slots[slot], t);
    }
    rounds
}

/// The round's closest pass for leg `l`: its ray toward the request's light point, to
/// the first surface short of it.
// Mirror of src/tracer/wavefront/wavefront_tree.wgsl::leg_closest_entry — change both.
fn leg_closest_entry(
    scene: &PackedScene,
    requests: &ShadowRequests,
    legs: &LegQueue,
    l: usize,
    counters: &mut impl TraversalCounters,
) -> Hit {
    let r = legs.request[l] as usize;
    let magnitude = requests.magnitude[requests.vertex(r)];
    let (ray, reach) = shadow_leg_ray(&legs.load_leg(l), requests.position[r], magnitude);
    closest_hit(scene, &ray, reach, counters)
}

/// The round's crossing step for leg `l` (crossing `crossing`), whose closest hit is
/// `hit`: a miss ends the request with the transmittance so far, an opaque surface (or
/// the crossing after the last) with 0; glass appends the next leg to `next`.
// Mirror of src/tracer/wavefront/wavefront_tree.wgsl::crossing_entry — change both.
#[allow(clippy::too_many_arguments)]
fn crossing_entry(
    scene: &PackedScene,
    requests: &ShadowRequests,
    legs: &LegQueue,
    l: usize,
    hit: &Hit,
    crossing: u32,
    next: &mut LegQueue,
    transmittance: &mut [f32],
) {
    let r = legs.request[l];
    let leg = legs.load_leg(l);
    if !hit.is_hit() {
        transmittance[r as usize] = leg.transmittance;
        return;
    }
    let magnitude = requests.magnitude[requests.vertex(r as usize)];
    let (ray, _) = shadow_leg_ray(&leg, requests.position[r as usize], magnitude);
    match cross_shadow_surface(scene, &ray, hit, crossing, &leg) {
        Some(beyond) => {
            next.append_leg(r, &beyond);
        }
        None => transmittance[r as usize] = 0.0,
    }
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
