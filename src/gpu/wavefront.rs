//! Whether a render runs AA none, uniform AA or adaptive AA's tracing passes through the
//! wavefront kernels (`src/tracer/wavefront/wavefront.wgsl` and `src/tracer/wavefront/wavefront_lattice.wgsl`,
//! twins of `tracer::wavefront::wavefront` and `tracer::wavefront::wavefront_lattice`), and the shape the frame plan
//! sizes their queues and dispatches by.

use super::plan::shape::WavefrontShape;
use crate::constants::{AA_ADAPTIVE, AA_NONE};
use crate::gpu::compile::kernel::KernelConfig;
use crate::gpu::compile::shader::wavefront_kernels;
use crate::pack::{PackedScene, SceneFeatures};
use crate::tracer::wavefront::batch::light_points;

/// The wavefront kernels' shape for `scene` under `kernel`, where `kernel` runs them for
/// it (a variant with `wavefront`: [`wavefront_kernels`]): AA none, uniform AA and
/// adaptive AA's corner and midpoint passes (with refraction a tree, whose vertex tree,
/// glass shadow rounds and fold `src/tracer/wavefront/wavefront_tree.wgsl` adds). None: the
/// megakernels.
pub fn wavefront_shape(kernel: KernelConfig, scene: &PackedScene) -> Option<WavefrontShape> {
    let g = &scene.globals;
    let uniform = match g.aa_mode {
        AA_NONE | AA_ADAPTIVE => None,
        _ => Some(g.aa_samples),
    };
    shape(kernel, scene, uniform)
}

/// The wavefront kernels' shape for `glint view`'s frames of `scene` under `kernel`,
/// where `kernel` runs them for it ([`wavefront_kernels`]): one sample a pixel a frame,
/// whatever the AA mode (its strata are the frames). None: `view_sample`.
pub fn view_wavefront_shape(kernel: KernelConfig, scene: &PackedScene) -> Option<WavefrontShape> {
    shape(kernel, scene, None)
}

/// The shape of `scene`'s paths under `kernel` with these strata, where the module has
/// the wavefront kernels.
fn shape(
    kernel: KernelConfig,
    scene: &PackedScene,
    uniform: Option<u32>,
) -> Option<WavefrontShape> {
    if !wavefront_kernels(kernel, scene.features) {
        return None;
    }
    let tree = scene.features.contains(SceneFeatures::REFRACTION);
    let generations = if tree || scene.features.contains(SceneFeatures::REFLECTION) {
        scene.globals.max_depth + 1
    } else {
        1
    };
    Some(WavefrontShape {
        light_points: light_points(scene),
        generations,
        uniform,
        tree,
        // With CSG one shadow request per invocation and list slot: a slice per light
        // point (src/tracer/wavefront/wavefront_shadow.wgsl::wavefront_shadow).
        shadow_slices: if !tree && scene.features.contains(SceneFeatures::CSG) {
            light_points(scene)
        } else {
            1
        },
    })
}
