//! Whether a render runs AA none, or adaptive AA's tracing passes, through the wavefront
//! kernels (`shaders/wavefront.wgsl` and `shaders/wavefront_lattice.wgsl`, twins of
//! `cpu::wavefront` and `cpu::wavefront_lattice`), and the shape the frame plan sizes
//! their queues and dispatches by.

use super::kernel::KernelConfig;
use super::plan::WavefrontShape;
use super::shader::wavefront_kernels;
use crate::constants::{AA_ADAPTIVE, AA_NONE};
use crate::cpu::wavefront::light_points;
use crate::pack::{PackedScene, SceneFeatures};

/// The wavefront kernels' shape for `scene` under `kernel`, where `kernel` runs them for
/// it: AA none or adaptive AA, a variant with `wavefront`, no refraction. None: the
/// megakernels.
pub fn wavefront_shape(kernel: KernelConfig, scene: &PackedScene) -> Option<WavefrontShape> {
    let g = &scene.globals;
    let aa = g.aa_mode == AA_NONE || g.aa_mode == AA_ADAPTIVE;
    if !aa || !wavefront_kernels(kernel, scene.features) {
        return None;
    }
    let generations = if scene.features.contains(SceneFeatures::REFLECTION) {
        g.max_depth + 1
    } else {
        1
    };
    Some(WavefrontShape {
        light_points: light_points(scene),
        generations,
    })
}
