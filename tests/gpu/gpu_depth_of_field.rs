//! Depth of field on the GPU tracer (tier 4): scenes/depth-of-field.lua rendered by the
//! adapter's kernel variant (on lavapipe the software megakernels) and by the hardware
//! variant's wavefront, in AA none, uniform and adaptive, against the CPU tracer (FLIP
//! mean < 0.01 and ≥ 99.9% of pixels within 2/255, as every scene of gpu_images); and the
//! GPU's tiles (`GpuRenderOptions::window`) against its full render, bit for bit. Both
//! tracers draw the same lens positions (the pixel's sequence), so an image that differs
//! means a lens position or thin-lens ray that differs.

use crate::common;

use common::tilings::{first_difference, join, tilings};
use common::{gpu_context, root};
use glint::diff::assert_images_match;
use glint::gpu::{render_gpu, GpuContext, GpuRenderOptions, KernelConfig, KernelVariant};
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::{AaDepth, AaMode, AaSamples, OptionOverrides};
use std::path::PathBuf;

const W: u32 = 40;
const H: u32 = 25;

fn scene(aa: AaMode) -> PackedScene {
    let overrides = OptionOverrides {
        aa: Some(aa),
        samples: Some(AaSamples::constant(2)),
        aa_depth: Some(AaDepth::constant(2)),
        width: Some(W),
        height: Some(H),
        ..OptionOverrides::default()
    };
    let scene = common::load_packed(&root().join("scenes/depth-of-field.lua"), &overrides);
    assert!(scene.features.contains(SceneFeatures::DEPTH_OF_FIELD));
    scene
}

fn out_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu_depth_of_field")
}

fn gpu_film(ctx: &GpuContext, scene: &PackedScene, name: &str) -> glint::film::Film {
    render_gpu(ctx, scene, &GpuRenderOptions::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"))
        .film
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn depth_of_field_matches_the_cpu_in_every_aa_mode_and_variant() {
    let Some(mut ctx) = gpu_context() else { return };
    let chosen = ctx.kernel;
    let hardware = KernelConfig {
        workgroup_side: chosen.workgroup_side,
        ..KernelConfig::for_variant(KernelVariant::Hardware, &ctx.limits)
    };
    for aa in [AaMode::None, AaMode::Uniform, AaMode::Adaptive] {
        let scene = scene(aa);
        let cpu = common::render_cpu(&scene);
        for (variant, kernel) in [("adapter's", chosen), ("hardware", hardware)] {
            ctx.kernel = kernel;
            let name = format!("depth-of-field {aa:?}, {variant} variant");
            let gpu = gpu_film(&ctx, &scene, &name);
            let report = assert_images_match(&name, &gpu, &cpu, 0.01, 0.999, &out_dir())
                .unwrap_or_else(|message| panic!("{message}"));
            eprintln!(
                "{name}: FLIP mean {:.5}, {:.3}% within 2/255",
                report.flip_mean,
                report.share_within(2.0 / 255.0) * 100.0
            );
        }
    }
    ctx.kernel = chosen;
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn depth_of_field_tiles_are_the_full_gpu_render_bit_for_bit() {
    let Some(ctx) = gpu_context() else { return };
    for aa in [AaMode::Uniform, AaMode::Adaptive] {
        let scene = scene(aa);
        let full = gpu_film(&ctx, &scene, "full");
        // The farm's own split into 3 tiles (each a GPU render on lavapipe: few).
        for (name, rects) in tilings(W, H, &[3]).into_iter().take(1) {
            let tiles: Vec<_> = rects
                .iter()
                .map(|&r| {
                    let options = GpuRenderOptions {
                        window: Some(r),
                        ..GpuRenderOptions::default()
                    };
                    let tile = render_gpu(&ctx, &scene, &options).unwrap().film;
                    (r, tile)
                })
                .collect();
            if let Some((x, y, a, b)) = first_difference(&full, &join(W, H, &tiles)) {
                panic!("{aa:?}, {name}: pixel ({x}, {y}) is {b:?} in the tiles, {a:?} in the full render");
            }
        }
    }
}
