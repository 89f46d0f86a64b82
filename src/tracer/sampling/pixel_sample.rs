//! What the per-pixel reference (`render`) and the tiled adaptive passes (`adaptive`)
//! both build on: one camera sample's colour, the contrast of a square's corners and
//! centre, and an unsplit square's colour.

use super::sample_source::{lattice_jitter, lens_position};
use crate::constants::{AA_CENTRE_WEIGHT, AA_ITEM_KEY_MASK, NO_ITEM};
use crate::pack::{PackedScene, SceneFeatures};
use crate::tracer::base::ray::{camera_ray, thin_lens_ray};
use crate::tracer::base::rng::SampleSeed;
use crate::tracer::path::trace::trace_ray;
use crate::tracer::traversal::traverse::TraversalCounters;
use glam::Vec3;

/// Colour at film position (fx, fy) in pixels; `seed` names the camera sample (and, with
/// depth of field, its lens position).
// Mirror of src/tracer/sampling/pixel_sample.wgsl::sample — change both.
pub(crate) fn sample(
    scene: &PackedScene,
    fx: f32,
    fy: f32,
    seed: SampleSeed,
    counters: &mut impl TraversalCounters,
) -> Vec3 {
    let g = &scene.globals;
    let mut ray = camera_ray(g, fx, fy);
    if scene.features.contains(SceneFeatures::DEPTH_OF_FIELD) {
        ray = thin_lens_ray(g, &ray, lens_position(g, seed));
    }
    trace_ray(scene, ray, seed, counters)
}

/// What adaptive AA's split decisions read from a lattice sample beside its colour:
/// whether its first surface showed fine detail that the colours of a few samples may not
/// show (an area light reaching it through some of its shadow samples but not all,
/// [`TraversalCounters::partial_light`]: soft-shadow noise; or a texture's detail at the
/// pixel's scale, [`TraversalCounters::texture_detail`]), and the item its camera ray hit
/// first, as [`sample_item_key`] (with the item seen in it, where that is a mirror).
// Mirror of src/tracer/sampling/pixel_sample.wgsl::SampleHint — change both.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SampleHint {
    pub fine_detail: bool,
    pub item: u32,
}

/// The part of item number `item` (`NO_ITEM`: none) that a [`SampleHint`] keeps: its
/// low AA_ITEM_KEY_MASK bits (what the GPU's float can hold exactly).
// Mirror of src/tracer/sampling/pixel_sample.wgsl::item_key — change both.
pub(crate) fn item_key(item: u32) -> u32 {
    item & AA_ITEM_KEY_MASK
}

/// A hint as a lattice sample's fourth component, as both tracers' lattices keep it:
/// ±(item + 1), negative for fine detail (an integer of at most 2^24, so the float is
/// exact and [`decode_hint`] gives it back).
// Mirror of src/tracer/sampling/pixel_sample.wgsl::encode_hint — change both.
pub(crate) fn encode_hint(hint: SampleHint) -> f32 {
    let sign = if hint.fine_detail { -1.0 } else { 1.0 };
    sign * hint.item.wrapping_add(1) as f32
}

/// The hint [`encode_hint`] stored.
// Mirror of src/tracer/sampling/pixel_sample.wgsl::decode_hint — change both.
pub(crate) fn decode_hint(w: f32) -> SampleHint {
    SampleHint {
        fine_detail: w < 0.0,
        item: (w.abs() as u32).wrapping_sub(1),
    }
}

/// What the split decision of a square reads beside its samples' contrast: whether one of
/// its samples saw fine detail, and whether they hit different items.
// Mirror of src/tracer/sampling/pixel_sample.wgsl::SquareHints — change both.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct SquareHints {
    pub fine_detail: bool,
    pub items_differ: bool,
}

/// `hints` with sample hint `h` added (`first`: the square's first sample's hint).
// Mirror of src/tracer/sampling/pixel_sample.wgsl::add_sample_hint — change both.
pub(crate) fn add_sample_hint(hints: SquareHints, first: SampleHint, h: SampleHint) -> SquareHints {
    SquareHints {
        fine_detail: hints.fine_detail || h.fine_detail,
        items_differ: hints.items_differ || h.item != first.item,
    }
}

/// The [`SquareHints`] of a square's samples (its corners and centre), as
/// `adaptive::square_hints` combines them.
pub(crate) fn square_hints_of(hints: &[SampleHint]) -> SquareHints {
    let first = hints[0];
    let start = SquareHints {
        fine_detail: first.fine_detail,
        items_differ: false,
    };
    hints[1..]
        .iter()
        .fold(start, |acc, &h| add_sample_hint(acc, first, h))
}

/// [`item_key`] of a sample whose camera ray hit item `camera` first and, where that is a
/// mirror, whose reflected ray hit item `mirrored` first (`NO_ITEM`: not a mirror, or the
/// reflected ray hit nothing): the camera item's key mixed with a hash of the mirrored
/// one, so two samples of one mirror that show different items differ. Two keys may
/// collide (24 bits); that can only cost a split that the contrast may still make.
// Mirror of src/tracer/sampling/pixel_sample.wgsl::sample_item_key — change both.
pub(crate) fn sample_item_key(camera: u32, mirrored: u32) -> u32 {
    if mirrored == NO_ITEM {
        return item_key(camera);
    }
    // (mirrored + 1 ≠ 0; the odd multiplier spreads neighbouring item numbers.)
    item_key(camera ^ (mirrored + 1).wrapping_mul(0x9e37_79b1))
}

/// Counters that pass everything on and note what a [`SampleHint`] keeps.
struct HintWatch<'a, C: TraversalCounters> {
    inner: &'a mut C,
    fine_detail: bool,
    camera: u32,
    mirrored: u32,
}

impl<C: TraversalCounters> TraversalCounters for HintWatch<'_, C> {
    fn traversal_started(&mut self) {
        self.inner.traversal_started();
    }
    fn cell_visited(&mut self) {
        self.inner.cell_visited();
    }
    fn item_tested(&mut self) {
        self.inner.item_tested();
    }
    fn partial_light(&mut self) {
        self.fine_detail = true;
        self.inner.partial_light();
    }
    fn camera_hit(&mut self, item: u32) {
        self.camera = item;
        self.inner.camera_hit(item);
    }
    fn texture_detail(&mut self) {
        self.fine_detail = true;
        self.inner.texture_detail();
    }
    fn mirror_hit(&mut self, item: u32) {
        self.mirrored = item;
        self.inner.mirror_hit(item);
    }
}

/// [`sample`], and its [`SampleHint`]. Adaptive AA's lattice samples.
// Mirror of src/tracer/sampling/pixel_sample.wgsl::hinted_sample — change both.
pub(crate) fn hinted_sample(
    scene: &PackedScene,
    fx: f32,
    fy: f32,
    seed: SampleSeed,
    counters: &mut impl TraversalCounters,
) -> (Vec3, SampleHint) {
    let mut watch = HintWatch {
        inner: counters,
        fine_detail: false,
        camera: NO_ITEM,
        mirrored: NO_ITEM,
    };
    let colour = sample(scene, fx, fy, seed, &mut watch);
    let hint = SampleHint {
        fine_detail: watch.fine_detail,
        item: sample_item_key(watch.camera, watch.mirrored),
    };
    (colour, hint)
}

/// Adaptive AA's sample at lattice point (fx, fy), a dyadic film position (exact):
/// [`hinted_sample`] at the point's [`lattice_jitter`] (the point jittered, with its own
/// seed), so a point shared by neighbouring squares, pixels or chunks is the same sample
/// whichever pass traces it.
// Mirror of src/tracer/sampling/pixel_sample.wgsl::lattice_sample — change both.
pub fn lattice_sample(
    scene: &PackedScene,
    fx: f32,
    fy: f32,
    counters: &mut impl TraversalCounters,
) -> (Vec3, SampleHint) {
    let at = lattice_jitter(&scene.globals, fx, fy);
    hinted_sample(scene, at.fx, at.fy, at.seed, counters)
}

/// Largest per-channel spread of a square's four corner samples and its centre sample:
/// what the split decision of adaptive AA weighs, which so sees detail between the
/// corners too.
// Mirror of src/tracer/sampling/pixel_sample.wgsl::square_contrast_of — change both.
pub(crate) fn square_contrast_of(corners: &[Vec3; 4], centre: Vec3) -> f32 {
    let c = corners;
    let lo = c[0].min(c[1]).min(c[2]).min(c[3]).min(centre);
    let hi = c[0].max(c[1]).max(c[2]).max(c[3]).max(centre);
    (hi - lo).max_element()
}

/// Colour of a square that adaptive AA did not split, from its corner samples and its
/// centre sample: the centre weighs AA_CENTRE_WEIGHT, the corners share the rest.
// Mirror of src/tracer/sampling/pixel_sample.wgsl::quincunx_mean — change both.
pub(crate) fn quincunx_mean(corners: &[Vec3; 4], centre: Vec3) -> Vec3 {
    let corner_weight = 0.25 * (1.0 - AA_CENTRE_WEIGHT);
    (corners[0] + corners[1] + corners[2] + corners[3]) * corner_weight + centre * AA_CENTRE_WEIGHT
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sample that saw no mirror keeps its camera item's key; one that saw a mirror is
    /// keyed by what it saw in it too: different items seen in one mirror give different
    /// keys (over the first thousand item numbers, and the miss), each within the mask.
    #[test]
    fn mirrored_items_key_samples_apart() {
        for camera in [0, 1, 7, 1 << 20, NO_ITEM] {
            assert_eq!(sample_item_key(camera, NO_ITEM), item_key(camera));
            let keys: std::collections::HashSet<u32> = (0..1000)
                .map(|mirrored| sample_item_key(camera, mirrored))
                .collect();
            assert_eq!(keys.len(), 1000, "camera item {camera}");
            assert!(keys.iter().all(|&k| k <= AA_ITEM_KEY_MASK));
            assert!(!keys.contains(&item_key(camera)), "camera item {camera}");
        }
    }
}
