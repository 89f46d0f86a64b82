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
//! This file holds the camera and closest passes and the generation loop; the batch and
//! its queues' entries are [`super::batch`]'s, the other passes [`super::wavefront_shade`],
//! [`super::wavefront_shadow`] and [`super::wavefront_gather`], each beside its WGSL twin.
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

pub use super::batch::Batch;
use super::batch::{each_path, light_points, start_generation};
pub use super::queues::{
    CameraVertices, HitQueue, LightSlots, PathQueue, SampleRecords, ShadowQueue, VertexKind,
    VertexQueue, VertexTree,
};
use super::wavefront_gather::{fold_pass, gather_pass};
use super::wavefront_shade::shade_pass;
use super::wavefront_shadow::{glass_shadow_pass, shadow_pass};
use crate::constants::{
    AA_ADAPTIVE, AA_UNIFORM, SAMPLE_CAMERA_MIRROR, SAMPLE_MIRRORS_CORNERS, T_MISS,
};
use crate::film::Film;
use crate::pack::{PackedScene, SceneFeatures};
use crate::tracer::base::ray::{camera_ray, thin_lens_ray, Ray};
use crate::tracer::base::rng::SampleSeed;
use crate::tracer::path::trace::camera_entry;
pub use crate::tracer::sampling::sample_source::SampleSource;
use crate::tracer::sampling::sample_source::{lens_position, CameraSample};
use crate::tracer::traversal::hit::TraversalCounters;
use crate::tracer::traversal::traverse::closest_hit;
use glam::Vec3;

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
    if batch.keeps_tree {
        batch.camera_vertices.resize(count);
    }
    for k in 0..count {
        wavefront_camera(scene, source, batch, k);
    }
    start_generation(batch);
}

/// The camera pass's invocation for sample `k` of `source`: its seed, and its camera ray
/// as generation 0's path k.
// Mirror of src/tracer/wavefront/wavefront.wgsl::wavefront_camera, which takes the Strata and Stratum sources (AA none's, uniform AA's, glint view's) only so far — change both.
fn wavefront_camera(scene: &PackedScene, source: &SampleSource, batch: &mut Batch, k: usize) {
    let CameraSample { fx, fy, seed } = source.camera_sample(scene, k);
    // Path k (a tree's vertex k).
    start_sample(scene, batch, k, k, fx, fy, seed);
}

/// Sample `k`'s record (its seed; no colour or items yet) and its camera ray at
/// (`fx`, `fy`), which starts in the media around the camera (`camera_entry`; a chain's
/// shading never reads them), as generation 0's path `at` — in a tree also the sample's
/// camera vertex — with nothing under it on `trace_ray`'s stack.
// Mirror of src/tracer/wavefront/wavefront.wgsl::start_sample — change both.
fn start_sample(
    scene: &PackedScene,
    batch: &mut Batch,
    k: usize,
    at: usize,
    fx: f32,
    fy: f32,
    seed: SampleSeed,
) {
    let s = &mut batch.samples;
    (s.seed_pixel[k], s.seed_sample[k]) = (seed.pixel, seed.sample);
    if seed.mirrors_corners {
        s.set_flag(k, SAMPLE_MIRRORS_CORNERS);
    }
    let g = &scene.globals;
    let mut ray = camera_ray(g, fx, fy);
    if scene.features.contains(SceneFeatures::DEPTH_OF_FIELD) {
        ray = thin_lens_ray(g, &ray, lens_position(g, seed));
    }
    let entry = camera_entry(g, &ray);
    if batch.keeps_tree {
        batch.camera_vertices.index[k] = at as u32;
    }
    batch.paths.store_path(at, &entry, 0, k as u32);
}

/// The closest pass: each path's ray to its closest hit.
pub fn closest_pass(scene: &PackedScene, batch: &mut Batch, counters: &mut impl TraversalCounters) {
    each_path(scene, batch, counters, wavefront_closest);
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
/// closest, shade, shadow (with refraction, then the glass rounds) and gather passes,
/// until one spawns no ray; then, with refraction, the fold.
pub fn trace_generations(
    scene: &PackedScene,
    batch: &mut Batch,
    counters: &mut impl TraversalCounters,
) {
    loop {
        closest_pass(scene, batch, counters);
        shade_pass(scene, batch, counters);
        shadow_pass(scene, batch, counters);
        if batch.keeps_tree {
            // Shadow rays pass through glass: rounds of legs (`wavefront_tree`).
            glass_shadow_pass(scene, batch, counters);
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
    use crate::tracer::wavefront::batch::tests::entry;

    /// A generation's end hands its appended paths over as the next generation's (its
    /// queues sized to them: `batch::start_generation`); an empty next generation ends
    /// the batch.
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
        assert!(batch.shadows.is_empty() && batch.next.is_empty());
        assert!(!wavefront_args(&mut batch));
    }
}
