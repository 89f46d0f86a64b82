//! Test hooks: entry points that exist so the tests can look inside the tracers. They are
//! not part of glint's API (a renderer calls [`crate::tracer`], [`crate::gpu`] and
//! [`crate::pipeline`]) and may change with the tests that use them.
//!
//! - [`probe`]: tier-3 kernel probes, the same rays traced by the GPU's and the CPU's
//!   `closest_hit` + `surface_at`, compared ray by ray.
//! - [`csg_interval_ends`]: one CSG object's inside intervals along a line.
//! - [`adaptive_lattice_sample`]: one sample of adaptive AA's lattice and its fine-detail
//!   hint.
//! - [`scratch`]: test folders under the temp dir that remove themselves.
//!
//! (The GPU's test hook, the loop limiter's sentinel, is a hidden field of
//! [`crate::gpu::GpuRenderOptions`].)

pub mod probe;
pub mod scratch;

use crate::pack::load_instance;
use crate::pack::PackedScene;
use crate::tracer::geometry::csg::{csg_count_at, csg_evaluate, csg_t_at, csg_tag_at, CsgStack};
use glam::Vec3;

/// The inside intervals of CSG item `item` along `o + t·d` (world space) as
/// (t, tag) ends — entering, leaving, entering… (not mirrored: the WGSL has no such function).
pub fn csg_interval_ends(scene: &PackedScene, item: u32, o: Vec3, d: Vec3) -> Vec<(f32, u32)> {
    let mut stack = CsgStack::default();
    csg_evaluate(&mut stack, scene, load_instance(scene, item), o, d);
    (0..csg_count_at(&stack, 0))
        .map(|k| (csg_t_at(&stack, k), csg_tag_at(&stack, k)))
        .collect()
}

/// Adaptive anti-aliasing's sample at lattice position (fx, fy) of `scene` (jittered as
/// the passes jitter it): its colour and whether it saw fine detail (a penumbra, or
/// texture detail at the pixel's scale), the hint that splits its squares down to
/// AA_FINE_DETAIL_DEPTH whatever their contrast.
pub fn adaptive_lattice_sample(scene: &PackedScene, fx: f32, fy: f32) -> (Vec3, bool) {
    let mut counters = crate::tracer::traversal::traverse::NoCounters;
    let (colour, hint) =
        crate::tracer::sampling::pixel_sample::lattice_sample(scene, fx, fy, &mut counters);
    (colour, hint.fine_detail)
}
