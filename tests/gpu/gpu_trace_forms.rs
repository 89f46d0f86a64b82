//! `trace_ray`'s two forms in scenes with mirrors but no dielectrics
//! (`KernelConfig::camera_ray_in_loop`, `CAMERA_RAY_IN_LOOP` in src/tracer/path/trace.wgsl): the
//! hardware variant takes the camera ray as the loop's first entry, so its kernels inline
//! the traversal and shading once; the software variant traces and shades the camera
//! ray's hit before the loop (llvmpipe's faster form). Both take the CPU twin's steps in
//! its order, so they must render the same bits and split the same adaptive-AA squares,
//! and match the CPU tracer (tier 4).

use crate::common;

use common::{gpu_context, packed_from_file};
use glint::gpu::compile::shader::{all_feature_sets, assemble_with, Entry};
use glint::gpu::{render_gpu, GpuContext, GpuRenderOptions, KernelConfig, KernelVariant};
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::{AaDepth, AaMode, AaSamples, OptionOverrides};

/// Call sites of `callee` in `block` and the blocks nested in it.
fn call_sites(module: &naga::Module, block: &naga::Block, callee: &str) -> usize {
    block
        .iter()
        .map(|statement| match statement {
            naga::Statement::Block(inner) => call_sites(module, inner, callee),
            naga::Statement::If { accept, reject, .. } => {
                call_sites(module, accept, callee) + call_sites(module, reject, callee)
            }
            naga::Statement::Switch { cases, .. } => cases
                .iter()
                .map(|case| call_sites(module, &case.body, callee))
                .sum(),
            naga::Statement::Loop {
                body, continuing, ..
            } => call_sites(module, body, callee) + call_sites(module, continuing, callee),
            naga::Statement::Call { function, .. } => {
                usize::from(module.functions[*function].name.as_deref() == Some(callee))
            }
            _ => 0,
        })
        .sum()
}

/// How many times `trace_ray` of the render module specialised to `features` and `kernel`
/// calls `closest_hit` and `shade_hit` (each call site an inlined copy on a GPU compiler).
fn trace_ray_call_sites(features: SceneFeatures, kernel: KernelConfig) -> (usize, usize) {
    let source = assemble_with(features, Entry::Render, kernel);
    let module = naga::front::wgsl::parse_str(&source)
        .unwrap_or_else(|e| panic!("[{features}; {kernel}]: {}", e.emit_to_string(&source)));
    let (_, trace_ray) = module
        .functions
        .iter()
        .find(|(_, f)| f.name.as_deref() == Some("trace_ray"))
        .expect("trace_ray in the render module");
    let count = |callee| call_sites(&module, &trace_ray.body, callee);
    (count("closest_hit"), count("shade_hit"))
}

/// The hardware variant's `trace_ray` traces and shades in one place for every feature
/// set (one call site of `closest_hit` and of `shade_hit`); the software variant keeps
/// the camera ray's hit before the loop, a second call site of each, exactly in scenes
/// with mirrors and no dielectrics. Fails if the hardware variant goes back to tracing
/// twice (issue 38: demo's kernels twice the code), or if the software variant loses the
/// form llvmpipe runs faster.
#[test]
fn hardware_kernels_trace_and_shade_in_one_place() {
    let limits = wgpu::Limits::default();
    let hardware = KernelConfig::for_variant(KernelVariant::Hardware, &limits);
    let software = KernelConfig::for_variant(KernelVariant::Software, &limits);
    let mut mirror_sets = 0;
    // The forms differ only with mirrors: every feature set with them (all, all but each
    // other feature, each pair), and none (a naga parse of a debug build takes a good
    // part of a second on a busy machine, so not all of all_feature_sets).
    let sets = all_feature_sets()
        .into_iter()
        .filter(|f| f.contains(SceneFeatures::REFLECTION) || *f == SceneFeatures::empty());
    for features in sets {
        let mirrors_only = features.contains(SceneFeatures::REFLECTION)
            && !features.contains(SceneFeatures::REFRACTION);
        mirror_sets += usize::from(mirrors_only);
        assert_eq!(
            trace_ray_call_sites(features, hardware),
            (1, 1),
            "[{features}] hardware variant: closest_hit and shade_hit call sites in trace_ray"
        );
        let twice = if mirrors_only { 2 } else { 1 };
        assert_eq!(
            trace_ray_call_sites(features, software),
            (twice, twice),
            "[{features}] software variant: closest_hit and shade_hit call sites in trace_ray"
        );
    }
    assert!(mirror_sets > 3, "too few mirror-only feature sets checked");
}

fn small(aa: AaMode) -> OptionOverrides {
    OptionOverrides {
        width: Some(48),
        height: Some(40),
        aa: Some(aa),
        samples: Some(AaSamples::constant(2)),
        aa_depth: Some(AaDepth::constant(2)),
        ..OptionOverrides::default()
    }
}

/// `scene` rendered by the adapter's variant (on lavapipe the software one, the camera
/// ray's hit before the loop), by that variant with the camera ray in the loop (the one
/// change alone), and by the hardware variant (`--kernel-variant hardware`, which has the
/// loop form): the same bits, the same adaptive-AA leaves per pixel (the hints
/// camera_item, mirrored_item and fine_detail_seen decide splits), and the loop form
/// against the CPU tracer, image and splits.
fn same_in_both_forms(ctx: &mut GpuContext, name: &str, scene: &PackedScene) {
    let chosen = ctx.kernel;
    let hardware = KernelConfig {
        workgroup_side: chosen.workgroup_side,
        ..KernelConfig::for_variant(KernelVariant::Hardware, &ctx.limits)
    };
    let kernels = [
        KernelConfig {
            camera_ray_in_loop: false,
            ..chosen
        },
        KernelConfig {
            camera_ray_in_loop: true,
            ..chosen
        },
        hardware,
    ];
    let mut renders = Vec::new();
    for kernel in kernels {
        ctx.kernel = kernel;
        let render = render_gpu(ctx, scene, &GpuRenderOptions::default())
            .unwrap_or_else(|e| panic!("{name}, {kernel}: {e}"));
        renders.push((kernel, render));
    }
    ctx.kernel = chosen;
    let (first_kernel, first) = &renders[0];
    assert_eq!(
        first.info.cpu_fallback_pixels, 0,
        "{name}: the loop limiter tripped; the comparison needs every pixel from the GPU"
    );
    for (kernel, render) in &renders[1..] {
        let differing = first
            .film
            .pixels
            .iter()
            .zip(&render.film.pixels)
            .filter(|(a, b)| a != b)
            .count();
        assert_eq!(
            differing, 0,
            "{name}: {differing} pixels differ between [{first_kernel}] and [{kernel}]"
        );
        assert_eq!(render.info.cpu_fallback_pixels, 0, "{name}: [{kernel}]");
        assert!(
            render.leaf_counts == first.leaf_counts,
            "{name}: adaptive AA split differently in [{first_kernel}] and [{kernel}]"
        );
    }
    if scene.globals.aa_mode == glint::constants::AA_ADAPTIVE {
        let cpu = glint::tracer::sampling::render::adaptive_leaf_counts(scene);
        let split = cpu.iter().filter(|&&l| l > 1).count();
        assert!(split > 0, "{name}: nothing split");
        assert!(
            renders[1].1.leaf_counts == cpu,
            "{name}: the loop form split differently from the CPU tracer"
        );
    }
    ctx.kernel = kernels[1];
    common::assert_gpu_matches_cpu(ctx, "gpu_trace_forms", name, scene, 0.01);
    ctx.kernel = chosen;
}

/// demo.lua and tori.lua (mirrors, no glass; the CS488 corpus has no mirrors) in every AA
/// mode: the two forms of `trace_ray` render the same (see [`same_in_both_forms`]).
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn mirror_scenes_render_the_same_in_both_forms() {
    let Some(mut ctx) = gpu_context() else { return };
    for file in ["scenes/demo.lua", "scenes/tori.lua"] {
        for aa in [AaMode::None, AaMode::Uniform, AaMode::Adaptive] {
            let path = common::root().join(file);
            let scene = packed_from_file(&path, &small(aa)).remove(0);
            let features = scene.features;
            assert!(
                features.contains(SceneFeatures::REFLECTION)
                    && !features.contains(SceneFeatures::REFRACTION),
                "{file}: [{features}]"
            );
            same_in_both_forms(&mut ctx, &format!("{file} {aa:?}"), &scene);
        }
    }
}

/// Mirrored walls of one colour under adaptive AA with a threshold no contrast exceeds:
/// only the items a mirror shows split squares (mirrored_item), so a loop form that lost
/// the hint would split nothing there; both forms split as the CPU does.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn mirrored_item_hint_is_the_same_in_both_forms() {
    let Some(mut ctx) = gpu_context() else { return };
    let overrides = OptionOverrides {
        aa: Some(AaMode::Adaptive),
        aa_threshold: Some(f32::MAX),
        ..OptionOverrides::default()
    };
    let scene = common::packed_from_source(&common::mirrored_walls_source(), &overrides).remove(0);
    same_in_both_forms(&mut ctx, "mirrored-walls", &scene);
}

/// A striped, textured quad that is also a mirror, under adaptive AA: its stripes at the
/// pixel's scale split squares (fine_detail_seen, noted at the camera ray's hit, depth 0,
/// which the loop form notes inside the loop) and it spawns a reflected ray: both forms
/// split as the CPU does, and render the same bits.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn texture_detail_hint_is_the_same_in_both_forms() {
    let Some(mut ctx) = gpu_context() else { return };
    let dir = common::temp_dir("gpu-trace-forms-stripes");
    let overrides = OptionOverrides {
        aa: Some(AaMode::Adaptive),
        aa_threshold: Some(0.15),
        aa_depth: Some(AaDepth::constant(3)),
        ..OptionOverrides::default()
    };
    let scene = common::striped_quad_with(&dir, &overrides, "m:set_reflection(0.3, 0.3, 0.3)");
    let features = scene.features;
    assert!(
        features.contains(SceneFeatures::TEXTURE)
            && features.contains(SceneFeatures::REFLECTION)
            && !features.contains(SceneFeatures::REFRACTION),
        "[{features}]"
    );
    same_in_both_forms(&mut ctx, "mirror-stripes", &scene);
}
