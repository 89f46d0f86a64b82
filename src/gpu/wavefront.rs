//! Whether a render runs AA none, uniform AA or adaptive AA's tracing passes through the
//! wavefront kernels (`shaders/wavefront.wgsl` and `shaders/wavefront_lattice.wgsl`,
//! twins of `cpu::wavefront` and `cpu::wavefront_lattice`), and the shape the frame plan
//! sizes their queues and dispatches by.

use super::kernel::KernelConfig;
use super::plan::WavefrontShape;
use super::shader::wavefront_kernels;
use crate::constants::{AA_ADAPTIVE, AA_NONE, AA_UNIFORM};
use crate::cpu::wavefront::light_points;
use crate::pack::{PackedScene, SceneFeatures};

/// The wavefront kernels' shape for `scene` under `kernel`, where `kernel` runs them for
/// it: any AA mode (adaptive AA's corner and midpoint passes), a variant with
/// `wavefront`, no refraction. None: the megakernels.
pub fn wavefront_shape(kernel: KernelConfig, scene: &PackedScene) -> Option<WavefrontShape> {
    let g = &scene.globals;
    let uniform = match g.aa_mode {
        AA_NONE | AA_ADAPTIVE => None,
        AA_UNIFORM => Some(g.aa_samples),
        _ => return None,
    };
    Some(WavefrontShape {
        uniform,
        ..view_wavefront_shape(kernel, scene)?
    })
}

/// The wavefront kernels' shape for `glint view`'s frames of `scene` under `kernel`,
/// where `kernel` runs them for it (a variant with `wavefront`, no refraction): one
/// sample a pixel a frame, whatever the AA mode (its strata are the frames). None:
/// `view_sample`.
pub fn view_wavefront_shape(kernel: KernelConfig, scene: &PackedScene) -> Option<WavefrontShape> {
    if !wavefront_kernels(kernel, scene.features) {
        return None;
    }
    let generations = if scene.features.contains(SceneFeatures::REFLECTION) {
        scene.globals.max_depth + 1
    } else {
        1
    };
    Some(WavefrontShape {
        light_points: light_points(scene),
        generations,
        uniform: None,
    })
}
