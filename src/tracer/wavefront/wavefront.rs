//! The wavefront form of [`trace_ray`](crate::tracer::path::trace::trace_ray): a batch of camera
//! samples goes through passes over queues instead of one sample at a time through a
//! megakernel. Without refraction every path is a chain (at most one reflected ray a
//! vertex); with it a dielectric's hit spawns two rays and the paths form a tree, whose
//! pieces (pending counts, the vertex tree and its fold, glass shadow rounds) are in
//! [`wavefront_tree`](super::wavefront_tree).
//!
//! Per batch the camera pass fills generation 0's path queue; per generation the closest
//! pass traces each path's ray to its hit, the shade pass shades each hit
//! without tracing (the point's own term; per light point facing it, its unshadowed term
//! in the vertex's slot and a shadow request; the reflected ray appended to the next
//! generation's queue; adaptive AA's hints), the shadow pass traces each request (any
//! hit; through glass: rounds of legs) and zeroes the slot of a blocked one, and the
//! gather pass sums each vertex's colour in `shade_phong`'s order (ambient, then each
//! light's slot in light order, an area light's strata in stratum order × 1/n²) into its
//! sample's colour (chains) or its vertex's value (trees, summed by the fold).
//!
//! These are the GPU's wavefront kernels' reference (docs/gpu.md), whose queues are
//! filled by atomics in any order: so every entry carries its sample's index and every
//! sum runs in one invocation in the CPU's fixed order — no pass depends on the order of
//! a queue, and the image is `trace_ray`'s bit for bit (tests/images/wavefront.rs). The
//! queues are structures of arrays, one Vec a field, as the GPU lays them out in its
//! storage buffers (both from one specification: [`super::queues`]); a pass is a loop over one queue of a function of one entry (one GPU
//! invocation). Design and measurements: docs/journal/2026-12-02-wavefront-split-measured.md.
//!
//! Sample sources ([`SampleSource`]): AA none's pixel centres and uniform AA's jittered
//! strata (whole films: [`render_film`]), one stratum of each pixel (`glint view`'s
//! frames), adaptive AA's lattice points (a sample's colour and [`SampleHint`]:
//! [`trace_batch`]).

use super::queues::CHAIN_MEDIA;
pub use super::queues::{
    CameraVertices, HitQueue, LightSlots, PathQueue, SampleRecords, ShadowQueue, VertexKind,
    VertexQueue, VertexTree,
};
use super::wavefront_tree::{glass_shadow_rounds, wavefront_fold, ShadowRequests};
use crate::constants::{
    AA_ADAPTIVE, AA_UNIFORM, LIGHT_AREA, RAY_STACK_SIZE, SAMPLE_CAMERA_MIRROR, SAMPLE_FINE_DETAIL,
    SAMPLE_MIRRORS_CORNERS, T_MISS,
};
use crate::film::Film;
use crate::pack::{PackedScene, SceneFeatures};
use crate::tracer::base::ray::{camera_ray, offset_ray, Ray};
use crate::tracer::base::rng::{shadow_stream, SampleSeed};
use crate::tracer::path::trace::{
    camera_medium_stack, is_mirror, note_texture_detail, push_secondary_rays, shading_point,
    ShadedHit, StackEntry,
};
use crate::tracer::sampling::pixel_sample::{sample_item_key, SampleHint};
use crate::tracer::sampling::sample_source::CameraSample;
pub use crate::tracer::sampling::sample_source::SampleSource;
use crate::tracer::shading::shade::{
    add_stratum, ambient_term, area_light_mean, area_light_point, background, penumbra, phong_at,
    shadow_blocked, shadowed_term, unshadowed_term,
};
use crate::tracer::shading::surface::{Phong, Surface};
use crate::tracer::shading::texture::camera_cone;
use crate::tracer::traversal::hit::{Hit, TraversalCounters};
use crate::tracer::traversal::traverse::closest_hit;
use glam::Vec3;

impl SampleRecords {
    /// The [`SampleHint`] of sample `k`.
    pub fn hint(&self, k: usize) -> SampleHint {
        SampleHint {
            fine_detail: self.flags[k] & SAMPLE_FINE_DETAIL != 0,
            item: sample_item_key(self.camera_item[k], self.mirrored_item[k]),
        }
    }

    /// Sample `k`'s seed at a vertex of depth `depth`.
    fn seed(&self, k: usize, depth: u32) -> SampleSeed {
        SampleSeed {
            pixel: self.seed_pixel[k],
            sample: self.seed_sample[k],
            depth,
            mirrors_corners: self.flags[k] & SAMPLE_MIRRORS_CORNERS != 0,
        }
    }

    /// Sets `flag` (a SAMPLE_* bit) of sample `k`.
    fn set_flag(&mut self, k: usize, flag: u32) {
        self.flags[k] |= flag;
    }
}

impl PathQueue {
    /// Appends `entry` of sample `sample`; its index (the GPU's `atomicAdd` on the
    /// queue's counter).
    fn append_path(&mut self, entry: &StackEntry, pending: u32, sample: u32) -> usize {
        let i = self.len();
        self.resize(i + 1);
        self.store_path(i, entry, pending, sample);
        i
    }

    /// Writes `entry` of sample `sample` as entry `i`.
    fn store_path(&mut self, i: usize, entry: &StackEntry, pending: u32, sample: u32) {
        self.origin[i] = entry.ray.origin;
        self.dir[i] = entry.ray.dir;
        self.weight[i] = entry.weight;
        self.depth[i] = entry.depth;
        self.cone[i] = entry.cone;
        self.media[i] = entry.media;
        self.pending[i] = pending;
        self.sample[i] = sample;
    }

    /// Entry `i` as `trace_ray`'s stack holds it.
    fn load_path(&self, i: usize) -> StackEntry {
        StackEntry {
            ray: Ray {
                origin: self.origin[i],
                dir: self.dir[i],
            },
            weight: self.weight[i],
            depth: self.depth[i],
            cone: self.cone[i],
            media: self.media[i],
        }
    }
}

impl ShadowQueue {
    /// Appends a request for light slot `slot` (vertex i's slot j is i·light_points +
    /// j); its index (the GPU's `atomicAdd`).
    fn append_request(&mut self, slot: u32, position: Vec3) -> usize {
        let r = self.len();
        self.resize(r + 1);
        (self.slot[r], self.position[r]) = (slot, position);
        r
    }
}

/// The light points of a scene: one per point light, n² per n×n area light; slot j of a
/// vertex is light point j, lights in order, an area light's strata in stratum order.
// Mirror of src/tracer/wavefront/wavefront.wgsl::light_points — change both.
pub fn light_points(scene: &PackedScene) -> u32 {
    scene.lights[..scene.globals.num_lights as usize]
        .iter()
        .map(|light| {
            if light.kind == LIGHT_AREA {
                light.samples * light.samples
            } else {
                1
            }
        })
        .sum()
}

/// A batch in flight: its samples, the current generation's queues and the next
/// generation's path queue.
#[derive(Clone, Debug, Default)]
pub struct Batch {
    pub samples: SampleRecords,
    pub paths: PathQueue,
    pub hits: HitQueue,
    pub vertices: VertexQueue,
    /// `light_points` slots a vertex: vertex i's slot j at i·light_points + j.
    pub slots: LightSlots,
    pub light_points: u32,
    pub shadows: ShadowQueue,
    pub next: PathQueue,
    /// Generations started so far (the camera rays' is 1).
    pub generations: u32,
    /// Scenes with refraction: every vertex of every generation so far, kept for the
    /// fold (path i of the current generation is vertex `vertex_base` + i).
    pub tree: VertexTree,
    pub vertex_base: u32,
    /// Scenes with refraction: each sample's camera vertex, where the fold starts.
    pub camera_vertices: CameraVertices,
    /// Whether the batch keeps the tree (scenes with refraction) rather than adding
    /// each vertex's colour straight into its sample's (chains).
    pub keeps_tree: bool,
}

/// The camera pass: every sample of `source` through [`wavefront_camera`] (the GPU's
/// `wavefront_camera`), into a batch sized for them.
pub fn camera_pass(scene: &PackedScene, source: &SampleSource, batch: &mut Batch) {
    let count = source.len();
    *batch = Batch {
        light_points: light_points(scene),
        ..Batch::default()
    };
    batch.keeps_tree = scene.features.contains(SceneFeatures::REFRACTION);
    batch.samples.resize(count);
    batch.paths.resize(count);
    for k in 0..count {
        wavefront_camera(scene, source, batch, k);
    }
    if batch.keeps_tree {
        // Camera rays start in the media around the camera (chains keep the placeholder);
        // sample k's camera ray is path k, vertex k.
        batch.paths.media.fill(camera_medium_stack(&scene.globals));
        batch.camera_vertices.index = (0..count as u32).collect();
    }
    start_generation(batch);
}

/// The camera pass's invocation for sample `k` of `source`: its seed, and its camera ray
/// as generation 0's path k.
// Mirror of src/tracer/wavefront/wavefront.wgsl::wavefront_camera, which takes the Strata and Stratum sources (AA none's, uniform AA's, glint view's) only so far — change both.
fn wavefront_camera(scene: &PackedScene, source: &SampleSource, batch: &mut Batch, k: usize) {
    let g = &scene.globals;
    let CameraSample { fx, fy, seed } = source.camera_sample(scene, k);
    let s = &mut batch.samples;
    (s.seed_pixel[k], s.seed_sample[k]) = (seed.pixel, seed.sample);
    if seed.mirrors_corners {
        s.set_flag(k, SAMPLE_MIRRORS_CORNERS);
    }
    let ray = camera_ray(g, fx, fy);
    let entry = StackEntry {
        ray,
        weight: Vec3::ONE,
        depth: 0,
        cone: camera_cone(g, &ray),
        media: CHAIN_MEDIA,
    };
    batch.paths.store_path(k, &entry, 0, k as u32);
}

/// Sizes the per-path queues of the generation in `batch.paths` (the GPU sizes them for
/// the whole batch once; the args kernel's counters say how many are live).
fn start_generation(batch: &mut Batch) {
    let len = batch.paths.len();
    batch.hits.reset(len);
    batch.vertices.reset(len);
    batch.slots.clear();
    batch.slots.resize(len * batch.light_points as usize);
    batch.shadows = ShadowQueue::default();
    batch.next.clear();
    batch.generations += 1;
    if batch.keeps_tree {
        batch.vertex_base = batch.tree.len() as u32;
        batch.tree.resize(batch.vertex_base as usize + len);
    }
}

/// The closest pass: each path's ray to its closest hit.
pub fn closest_pass(scene: &PackedScene, batch: &mut Batch, counters: &mut impl TraversalCounters) {
    for i in 0..batch.paths.len() {
        wavefront_closest(scene, batch, i, counters);
    }
}

/// The closest pass's invocation for path `i`: its hit, and the items a sample's hint
/// keeps (the camera ray's; at depth 1, the item seen in a camera-hit mirror). The hit is
/// stored before the hints, in the WGSL's order (which reads the depth after the store to
/// keep it out of the traversal's registers).
// Mirror of src/tracer/wavefront/wavefront.wgsl::wavefront_closest — change both.
fn wavefront_closest(
    scene: &PackedScene,
    batch: &mut Batch,
    i: usize,
    counters: &mut impl TraversalCounters,
) {
    let paths = &batch.paths;
    let ray = Ray {
        origin: paths.origin[i],
        dir: paths.dir[i],
    };
    let hit = closest_hit(scene, &ray, T_MISS, counters);
    batch.hits.store_hit(i, &hit);
    let paths = &batch.paths;
    let k = paths.sample[i] as usize;
    let samples = &mut batch.samples;
    if paths.depth[i] == 0 {
        samples.camera_item[k] = hit.item;
        counters.camera_hit(hit.item);
    }
    if samples.flags[k] & SAMPLE_CAMERA_MIRROR != 0 && paths.depth[i] == 1 {
        // The one ray a mirror spawns: what the camera sees in it.
        samples.mirrored_item[k] = hit.item;
        counters.mirror_hit(hit.item);
    }
}

/// The shade pass: each hit shaded without tracing.
pub fn shade_pass(scene: &PackedScene, batch: &mut Batch, counters: &mut impl TraversalCounters) {
    for i in 0..batch.paths.len() {
        wavefront_shade(scene, batch, i, counters);
    }
}

/// The shade pass's invocation for path `i`: a miss's background; a hit's own term, for
/// each light point facing it its unshadowed term in its slot and a shadow request, the
/// reflected ray in the next generation's queue, and at depth 0 the sample's hints (the
/// texture detail, whether the camera's surface is a mirror).
// Mirror of src/tracer/wavefront/wavefront.wgsl::wavefront_shade — change both.
fn wavefront_shade(
    scene: &PackedScene,
    batch: &mut Batch,
    i: usize,
    counters: &mut impl TraversalCounters,
) {
    let g = &scene.globals;
    let entry = batch.paths.load_path(i);
    let hit = batch.hits.load_hit(i);
    let k = batch.paths.sample[i] as usize;
    if !Hit::is_hit(&hit) {
        batch.vertices.kind[i] = VertexKind::Miss;
        batch.vertices.own[i] = background(g, entry.ray.dir);
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
    ask_light_shadows(scene, batch, i, &s, phong, n, v, seed);
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
// Mirror of src/tracer/wavefront/wavefront.wgsl::note_sample_hints — change both.
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

/// Every light point of path `i`'s hit at `s` (an area light's strata from `seed`'s
/// shadow streams), in slot order: for each facing it, its unshadowed term in its slot
/// and a shadow request.
// Mirror of src/tracer/wavefront/wavefront.wgsl::ask_light_shadows — change both.
#[allow(clippy::too_many_arguments)]
fn ask_light_shadows(
    scene: &PackedScene,
    batch: &mut Batch,
    i: usize,
    s: &Surface,
    phong: Phong,
    n: Vec3,
    v: Vec3,
    seed: SampleSeed,
) {
    let first_slot = i * light_points(scene) as usize;
    let mut slot = 0;
    let ask = |position: Vec3, light: &crate::pack::PackedLight, slot: u32, batch: &mut Batch| {
        if let Some(term) = unshadowed_term(scene, s, phong, n, v, position, light) {
            let slot = (first_slot + slot as usize) as u32;
            batch.slots.term[slot as usize] = term;
            batch.shadows.append_request(slot, position);
        }
    };
    let lights = &scene.lights[..scene.globals.num_lights as usize];
    for (index, light) in lights.iter().enumerate() {
        if light.kind == LIGHT_AREA {
            let stream = shadow_stream(seed, index as u32);
            for stratum in 0..light.samples * light.samples {
                let position = area_light_point(light, &stream, stratum);
                ask(position, light, slot, batch);
                slot += 1;
            }
        } else {
            ask(Vec3::from(light.position), light, slot, batch);
            slot += 1;
        }
    }
}

/// The rays path `i`'s hit (sample `k`) spawns, pushed as `trace_ray` pushes them onto
/// its stack, which holds the path's pending entries then (none in a chain: the ray
/// popped before its hit was shaded): so the same rays are dropped where the stack is
/// full, and each child's pending count is its index in that stack. Each is appended to
/// the next generation's queue, and in a tree linked as the vertex's child.
// Mirror of src/tracer/wavefront/wavefront.wgsl::push_next_paths — change both.
fn push_next_paths(
    scene: &PackedScene,
    batch: &mut Batch,
    i: usize,
    entry: &StackEntry,
    k: usize,
    shaded: &ShadedHit,
    hit: &Hit,
) {
    let pending = batch.paths.pending[i] as usize;
    let mut stack = [*entry; RAY_STACK_SIZE as usize];
    let mut size = pending;
    push_secondary_rays(scene, &mut stack, &mut size, entry, shaded, hit);
    for (q, child) in stack.iter().enumerate().take(size).skip(pending) {
        let j = batch.next.append_path(child, q as u32, k as u32);
        if batch.keeps_tree {
            let vertex = batch.vertex_base as usize + i;
            let child_vertex = batch.vertex_base as usize + batch.paths.len() + j;
            batch.tree.children[vertex][q - pending] = child_vertex as u32;
        }
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

/// The shadow pass: each request's shadow ray (any hit), in request order (on the GPU
/// one request an invocation; with CSG L dispatches, slice s requests s·N … s·N + N − 1).
// Mirror of the loop of src/tracer/wavefront/wavefront.wgsl::wavefront_shadow (one request an invocation, with CSG over slices) — change both.
pub fn shadow_pass(scene: &PackedScene, batch: &mut Batch, counters: &mut impl TraversalCounters) {
    for r in 0..batch.shadows.len() {
        shadow_request(scene, batch, r, counters);
    }
}

/// The shadow pass's invocation for request `r`: its slot's term × the transmittance
/// (`shade::point_light`'s last product: 1 or, where the ray is blocked, zero).
// Mirror of src/tracer/wavefront/wavefront.wgsl::shadow_request — change both.
fn shadow_request(
    scene: &PackedScene,
    batch: &mut Batch,
    r: usize,
    counters: &mut impl TraversalCounters,
) {
    let points = light_points(scene) as usize;
    let slot = batch.shadows.slot[r] as usize;
    let i = slot / points;
    let origin = batch.vertices.shadow_origin[i];
    let magnitude = batch.vertices.magnitude[i];
    let position = batch.shadows.position[r];
    let transmittance = if shadow_blocked(scene, origin, position, magnitude, counters) {
        0.0
    } else {
        1.0
    };
    batch.slots.term[slot] = shadowed_term(batch.slots.term[slot], transmittance);
}

/// The shadow pass through glass (scenes with refraction): rounds of legs
/// ([`glass_shadow_rounds`]) over the generation's requests; the number of rounds.
pub fn glass_shadow_pass(
    scene: &PackedScene,
    batch: &mut Batch,
    counters: &mut impl TraversalCounters,
) -> u32 {
    let requests = ShadowRequests {
        slot: &batch.shadows.slot,
        position: &batch.shadows.position,
        shadow_origin: &batch.vertices.shadow_origin,
        magnitude: &batch.vertices.magnitude,
        media: &batch.paths.media,
        light_points: batch.light_points,
    };
    glass_shadow_rounds(scene, &requests, &mut batch.slots.term, counters)
}

/// The fold pass (scenes with refraction, after the last generation): each sample's
/// colour from its vertex tree ([`wavefront_fold`]).
pub fn fold_pass(batch: &mut Batch) {
    wavefront_fold(
        &batch.tree,
        &batch.camera_vertices.index,
        &mut batch.samples.colour,
    );
}

/// The gather pass: each vertex's colour into its sample's.
pub fn gather_pass(scene: &PackedScene, batch: &mut Batch, counters: &mut impl TraversalCounters) {
    for i in 0..batch.paths.len() {
        wavefront_gather(scene, batch, i, counters);
    }
}

/// The gather pass's invocation for path `i`: its vertex's colour as `shade_phong` sums
/// it (ambient, then each light in order: a point light's slot, an area light's strata
/// summed in stratum order and averaged, a penumbra at depth 0 noted in the sample's
/// hint), then into the sample's colour: the camera vertex's is the colour, a deeper
/// one's adds weight × colour (`trace_ray`'s order: generation order is its pop order).
// Mirror of src/tracer/wavefront/wavefront.wgsl::wavefront_gather — change both.
fn wavefront_gather(
    scene: &PackedScene,
    batch: &mut Batch,
    i: usize,
    counters: &mut impl TraversalCounters,
) {
    let depth = batch.paths.depth[i];
    let k = batch.paths.sample[i] as usize;
    let mut colour = batch.vertices.own[i];
    if batch.vertices.kind[i] == VertexKind::Lit {
        let slots = &batch.slots.term[i * light_points(scene) as usize..];
        let mut slot = 0;
        for light in &scene.lights[..scene.globals.num_lights as usize] {
            if light.kind == LIGHT_AREA {
                let strata = light.samples * light.samples;
                let mut sum = Vec3::ZERO;
                let mut lit = 0;
                for _ in 0..strata {
                    add_stratum(&mut sum, &mut lit, slots[slot]);
                    slot += 1;
                }
                if penumbra(depth, lit, light.samples) {
                    batch.samples.set_flag(k, SAMPLE_FINE_DETAIL);
                    counters.partial_light();
                }
                colour += area_light_mean(sum, light.samples);
            } else {
                colour += slots[slot];
                slot += 1;
            }
        }
    }
    let value = if depth == 0 {
        colour
    } else {
        batch.paths.weight[i] * colour
    };
    if batch.keeps_tree {
        // A tree's values are summed by the fold, in `trace_ray`'s pop order.
        batch.tree.value[batch.vertex_base as usize + i] = value;
    } else if depth == 0 {
        batch.samples.colour[k] = value;
    } else {
        batch.samples.colour[k] += value;
    }
}

/// Ends a generation (the args kernel's job on the GPU): the next generation's paths
/// become the current ones; false when there are none.
// Mirror of src/tracer/wavefront/wavefront.wgsl::wavefront_args — change both.
pub fn wavefront_args(batch: &mut Batch) -> bool {
    std::mem::swap(&mut batch.paths, &mut batch.next);
    if batch.paths.is_empty() {
        return false;
    }
    start_generation(batch);
    true
}

/// Every sample of `source` through the passes: its colour (`trace_ray`'s) and its
/// hint (`pixel_sample::hinted_sample`'s), in source order. With refraction (a
/// dielectric's hit spawns two rays: a tree, not a chain) the fold pass sums each
/// sample's vertex values once its last generation is done.
pub fn trace_batch(
    scene: &PackedScene,
    source: &SampleSource,
    counters: &mut impl TraversalCounters,
) -> Batch {
    let mut batch = Batch::default();
    camera_pass(scene, source, &mut batch);
    trace_generations(scene, &mut batch, counters);
    batch
}

/// A batch that the camera pass started, through its generations: per generation the
/// closest, shade, shadow and gather passes, until one spawns no ray; then, with
/// refraction, the fold.
pub fn trace_generations(
    scene: &PackedScene,
    batch: &mut Batch,
    counters: &mut impl TraversalCounters,
) {
    loop {
        closest_pass(scene, batch, counters);
        shade_pass(scene, batch, counters);
        if batch.keeps_tree {
            // Shadow rays pass through glass: rounds of legs (`wavefront_tree`).
            glass_shadow_pass(scene, batch, counters);
        } else {
            shadow_pass(scene, batch, counters);
        }
        gather_pass(scene, batch, counters);
        if !wavefront_args(batch) {
            if batch.keeps_tree {
                fold_pass(batch);
            }
            return;
        }
    }
}

/// The whole film under AA none or uniform AA, `batch_pixels` pixels a batch: each
/// pixel's samples through [`trace_batch`], summed in sample order and divided by n²
/// (`render::render_pixel`'s order).
pub fn render_film(
    scene: &PackedScene,
    batch_pixels: usize,
    counters: &mut impl TraversalCounters,
) -> Film {
    let g = &scene.globals;
    assert!(
        g.aa_mode != AA_ADAPTIVE,
        "adaptive AA samples lattice points"
    );
    let uniform = g.aa_mode == AA_UNIFORM;
    let n = if uniform { g.aa_samples } else { 1 };
    let pixels: Vec<[u32; 2]> = (0..g.height)
        .flat_map(|y| (0..g.width).map(move |x| [x, y]))
        .collect();
    let mut film = Film::new(g.width, g.height);
    for chunk in pixels.chunks(batch_pixels.max(1)) {
        let source = SampleSource::Strata {
            pixels: chunk,
            n,
            uniform,
        };
        let batch = trace_batch(scene, &source, counters);
        for (p, &[x, y]) in chunk.iter().enumerate() {
            film.set(x, y, wavefront_resolve(scene, &batch, p).to_array());
        }
    }
    film
}

/// Pixel `p` of a batch of the Strata source with n² samples a pixel (n = 1 under AA
/// none): its samples' colours (p·n² … p·n² + n² − 1) summed in sample order, divided by
/// n² (`render::render_pixel`'s order).
// Mirror of src/tracer/wavefront/wavefront.wgsl::wavefront_resolve — change both.
pub fn wavefront_resolve(scene: &PackedScene, batch: &Batch, p: usize) -> Vec3 {
    let g = &scene.globals;
    let n = if g.aa_mode == AA_UNIFORM {
        g.aa_samples
    } else {
        1
    };
    let per_pixel = (n * n) as usize;
    let mut sum = Vec3::ZERO;
    for c in &batch.samples.colour[p * per_pixel..(p + 1) * per_pixel] {
        sum += *c;
    }
    sum / (n * n) as f32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constants::NO_ITEM;
    use glam::Vec2;

    fn entry(depth: u32) -> StackEntry {
        StackEntry {
            ray: Ray {
                origin: Vec3::new(1.0, 2.0, 3.0),
                dir: Vec3::Z,
            },
            weight: Vec3::splat(0.5),
            depth,
            cone: Vec2::new(0.25, 0.125),
            media: crate::tracer::shading::dielectric::MediumStack {
                iors: [1.0; crate::constants::MEDIUM_STACK_SIZE as usize],
                count: 0,
            },
        }
    }

    /// Appends hand out consecutive indices and keep each field of an entry at its
    /// index (what the GPU's atomicAdd on a counter gives one invocation).
    #[test]
    fn appends_take_consecutive_slots() {
        let mut q = PathQueue::default();
        assert_eq!(q.append_path(&entry(0), 0, 7), 0);
        assert_eq!(q.append_path(&entry(3), 0, 2), 1);
        assert_eq!(q.len(), 2);
        assert_eq!((q.depth[1], q.sample[1]), (3, 2));
        assert_eq!((q.depth[0], q.sample[0]), (0, 7));
        assert_eq!(q.cone[1], Vec2::new(0.25, 0.125));
        let mut s = ShadowQueue::default();
        assert_eq!(s.append_request(4, Vec3::X), 0);
        assert_eq!(s.append_request(9, Vec3::Y), 1);
        assert_eq!((s.slot[1], s.position[1]), (9, Vec3::Y));
    }

    /// A new generation takes the appended paths, sizes its hit, vertex and slot queues
    /// to them (slots zeroed: a light point facing away keeps zero), empties the shadow
    /// and next queues; an empty next generation ends the batch.
    #[test]
    fn generations_hand_over_and_end_when_empty() {
        let mut batch = Batch {
            light_points: 3,
            ..Batch::default()
        };
        batch.paths.append_path(&entry(0), 0, 0);
        start_generation(&mut batch);
        batch.slots.term[2] = Vec3::ONE;
        batch.shadows.append_request(2, Vec3::X);
        batch.next.append_path(&entry(1), 0, 0);
        batch.next.append_path(&entry(1), 0, 5);
        assert!(wavefront_args(&mut batch));
        assert_eq!(batch.generations, 2);
        assert_eq!(batch.paths.sample, vec![0, 5]);
        assert_eq!(batch.slots.term, vec![Vec3::ZERO; 6]);
        assert_eq!(batch.hits.item, vec![NO_ITEM; 2]);
        assert!(batch.shadows.is_empty() && batch.next.is_empty());
        assert!(!wavefront_args(&mut batch));
    }

    /// `x × 1` keeps every bit of x (the shadow pass's unblocked product), −0.0, NaN and
    /// infinities included, and a blocked ray gives +0.0 whatever the term: what
    /// `point_light` returns in both cases.
    #[test]
    fn shadowed_term_keeps_the_bits() {
        for x in [
            0.0f32,
            -0.0,
            1.5,
            -2.25,
            f32::NAN,
            -f32::NAN,
            f32::INFINITY,
            f32::MIN_POSITIVE / 2.0,
        ] {
            let term = Vec3::new(x, 1.0, -x);
            let kept = shadowed_term(term, 1.0);
            assert_eq!(
                kept.to_array().map(f32::to_bits),
                term.to_array().map(f32::to_bits)
            );
            let blocked = shadowed_term(term, 0.0);
            assert_eq!(blocked.to_array().map(f32::to_bits), [0; 3]);
        }
    }
}
