//! The wavefront's shade pass (`wavefront_shade.wgsl` on the GPU): each hit of the
//! generation shaded without tracing — a miss's background; a hit's own term, for each
//! light point facing it its unshadowed term in the vertex's light slot and a shadow
//! request for the shadow pass (`wavefront_shadow`), the rays it spawns appended to the
//! next generation's queue (in a tree linked as the vertex's children: `wavefront_tree`),
//! and at a camera hit the sample's hints for adaptive AA.

use super::batch::{each_path, light_points, spawned_rays, Batch, VertexKind};
use super::wavefront_tree::push_tree_children;
use crate::constants::{LIGHT_AREA, SAMPLE_CAMERA_MIRROR, SAMPLE_FINE_DETAIL};
use crate::pack::layout::load_light;
use crate::pack::{PackedLight, PackedScene};
use crate::tracer::base::ray::offset_ray;
use crate::tracer::base::rng::{shadow_stream, SampleSeed};
use crate::tracer::path::trace::{
    is_mirror, note_texture_detail, shading_point, ShadedHit, StackEntry,
};
use crate::tracer::shading::shade::{
    ambient_term, area_light_point, background, phong_at, unshadowed_term, LitPoint,
};
use crate::tracer::shading::surface::Surface;
use crate::tracer::traversal::hit::{Hit, TraversalCounters};
use glam::Vec3;

/// The shade pass: each hit shaded without tracing.
pub fn shade_pass(scene: &PackedScene, batch: &mut Batch, counters: &mut impl TraversalCounters) {
    each_path(scene, batch, counters, wavefront_shade);
}

/// The shade pass's invocation for path `i`: a miss's background; a hit's own term, for
/// each light point facing it its unshadowed term in its slot and a shadow request, the
/// reflected ray in the next generation's queue, and at depth 0 the sample's hints (the
/// texture detail, whether the camera's surface is a mirror).
// Mirror of src/tracer/wavefront/wavefront_shade.wgsl::wavefront_shade — change both.
fn wavefront_shade(
    scene: &PackedScene,
    batch: &mut Batch,
    i: usize,
    counters: &mut impl TraversalCounters,
) {
    let entry = batch.paths.load_path(i);
    let hit = batch.hits.load_hit(i);
    let k = batch.paths.sample[i] as usize;
    if !Hit::is_hit(&hit) {
        batch.vertices.kind[i] = VertexKind::Miss;
        batch.vertices.own[i] = background(scene, entry.ray.dir);
        return;
    }
    let point = shading_point(scene, &entry, &hit);
    if entry.depth == 0 {
        note_sample_hints(scene, batch, k, &point.s, counters);
    }
    let (s, n) = (point.s, point.n);
    if let Some(colour) = point.uv_colour {
        batch.vertices.kind[i] = VertexKind::Unlit;
        batch.vertices.own[i] = colour;
        return;
    }
    let phong = phong_at(scene, &s);
    batch.vertices.kind[i] = VertexKind::Lit;
    batch.vertices.own[i] = ambient_term(scene, phong);
    let origin = offset_ray(s.p, n, s.magnitude);
    batch.vertices.shadow_origin[i] = origin;
    batch.vertices.magnitude[i] = s.magnitude;
    let v = -entry.ray.dir;
    let seed = batch.samples.seed(k, entry.depth);
    ask_light_shadows(scene, batch, i, &LitPoint { s, phong, n, v }, seed);
    let shaded = ShadedHit {
        s,
        facing: point.facing,
        n,
        colour: Vec3::ZERO,
        ends: false,
    };
    push_next_paths(scene, batch, i, &entry, k, &shaded, &hit);
}

/// At a camera hit (depth 0) of sample `k`: its hints, the texture detail seen at `s`
/// and whether the camera's surface is a mirror.
// Mirror of src/tracer/wavefront/wavefront_shade.wgsl::note_sample_hints — change both.
fn note_sample_hints(
    scene: &PackedScene,
    batch: &mut Batch,
    k: usize,
    s: &Surface,
    counters: &mut impl TraversalCounters,
) {
    let mut watch = DetailWatch {
        inner: counters,
        seen: false,
    };
    note_texture_detail(scene, s, &mut watch);
    if watch.seen {
        batch.samples.set_flag(k, SAMPLE_FINE_DETAIL);
    }
    if is_mirror(scene, s.material) {
        batch.samples.set_flag(k, SAMPLE_CAMERA_MIRROR);
    }
}

/// Counters that pass everything on and note texture detail.
struct DetailWatch<'a, C: TraversalCounters> {
    inner: &'a mut C,
    seen: bool,
}

impl<C: TraversalCounters> TraversalCounters for DetailWatch<'_, C> {
    fn texture_detail(&mut self) {
        self.seen = true;
        self.inner.texture_detail();
    }
}

/// Every light point of path `i`'s hit at `s` (an area light's strata from `seed`'s
/// shadow streams), in slot order, through [`ask_shadow`].
// Mirror of src/tracer/wavefront/wavefront_shade.wgsl::ask_light_shadows — change both.
fn ask_light_shadows(
    scene: &PackedScene,
    batch: &mut Batch,
    i: usize,
    lit: &LitPoint,
    seed: SampleSeed,
) {
    let points = light_points(scene);
    let mut slot = i as u32 * points;
    for index in 0..scene.globals.num_lights as usize {
        let light = load_light(scene, index as u32);
        if light.kind == LIGHT_AREA {
            let stream = shadow_stream(seed, index as u32);
            for stratum in 0..light.samples * light.samples {
                let position = area_light_point(light, &stream, stratum);
                ask_shadow(scene, batch, lit, position, light, slot, points);
                slot += 1;
            }
        } else {
            let position = Vec3::from(light.position);
            ask_shadow(scene, batch, lit, position, light, slot, points);
            slot += 1;
        }
    }
}

/// Light point `slot` (of `points` a vertex) at `position`: where it faces the point,
/// its unshadowed term in the slot and a shadow request (a slot facing away keeps the
/// zero its generation started with).
// Mirror of src/tracer/wavefront/wavefront_shade.wgsl::ask_shadow — change both.
fn ask_shadow(
    scene: &PackedScene,
    batch: &mut Batch,
    lit: &LitPoint,
    position: Vec3,
    light: &PackedLight,
    slot: u32,
    points: u32,
) {
    debug_assert_eq!(points, batch.light_points);
    if let Some(term) = unshadowed_term(scene, lit, position, light) {
        batch.slots.term[slot as usize] = term;
        batch.shadows.append_request(slot, position);
    }
}

/// The rays path `i`'s hit (sample `k`) spawns, appended to the next generation's
/// queue: a tree's through [`push_tree_children`]; a chain's at most the reflected ray,
/// pushed onto an empty stack as `trace_ray`'s chain has it (so the same ray is dropped
/// where the stack is full).
// Mirror of src/tracer/wavefront/wavefront_shade.wgsl::push_next_paths — change both.
fn push_next_paths(
    scene: &PackedScene,
    batch: &mut Batch,
    i: usize,
    entry: &StackEntry,
    k: usize,
    shaded: &ShadedHit,
    hit: &Hit,
) {
    if batch.keeps_tree {
        push_tree_children(scene, batch, i, entry, k, shaded, hit);
        return;
    }
    let (stack, size) = spawned_rays(scene, entry, shaded, hit, 0);
    if size > 0 {
        batch.next.append_path(&stack[0], 0, k as u32);
    }
}
