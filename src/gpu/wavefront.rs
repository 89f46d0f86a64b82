//! Whether a render runs AA none through the wavefront kernels (`shaders/wavefront.wgsl`,
//! twin of `cpu::wavefront`), and the shape the frame plan sizes their queues and
//! dispatches by.

use super::kernel::KernelConfig;
use super::plan::WavefrontShape;
use super::shader::wavefront_kernels;
use crate::constants::AA_NONE;
use crate::cpu::wavefront::light_points;
use crate::pack::{PackedScene, SceneFeatures};

/// The wavefront kernels' shape for `scene` under `kernel`, where `kernel` runs them for
/// it: AA none, a variant with `wavefront` (with refraction: a tree, whose vertex tree,
/// glass shadow rounds and fold `shaders/wavefront_tree.wgsl` adds). None: the megakernel.
pub fn wavefront_shape(kernel: KernelConfig, scene: &PackedScene) -> Option<WavefrontShape> {
    let g = &scene.globals;
    if g.aa_mode != AA_NONE || !wavefront_kernels(kernel, scene.features) {
        return None;
    }
    let tree = scene.features.contains(SceneFeatures::REFRACTION);
    let generations = if tree || scene.features.contains(SceneFeatures::REFLECTION) {
        g.max_depth + 1
    } else {
        1
    };
    Some(WavefrontShape {
        light_points: light_points(scene),
        generations,
        tree,
    })
}
