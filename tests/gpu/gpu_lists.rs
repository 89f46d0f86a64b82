//! The per-ray lists in storage (`KernelConfig::lists_in_storage`, the hardware kernel
//! variant: src/gpu/compile/lists.rs): the dielectric ray stack and the CSG interval lists in a
//! storage slot per tracing invocation render exactly what the private arrays render,
//! and match the CPU tracer (tier 4), in every AA mode (each mode's tracing passes claim
//! slots their own way: a chunk pixel, a sample, a lattice point of a pass).

use crate::common;

use common::{gpu_context, packed_from_file};
use glint::gpu::compile::lists::LaneLists;
use glint::gpu::compile::shader::{assemble_with, Entry};
use glint::gpu::{render_gpu, GpuContext, GpuRenderOptions, KernelConfig};
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::{AaDepth, AaMode, OptionOverrides};

fn small(aa: AaMode) -> OptionOverrides {
    OptionOverrides {
        width: Some(48),
        height: Some(40),
        aa: Some(aa),
        samples: Some(glint::scene::AaSamples::constant(2)),
        aa_depth: Some(AaDepth::constant(2)),
        ..OptionOverrides::default()
    }
}

/// `scene` rendered with lists in storage and with private arrays: the same pixels, the
/// same few re-rendered by the CPU where lavapipe's loop limiter tripped (at most a tenth
/// of the image: the rest is traced by the GPU both ways), and the storage variant
/// against the CPU.
fn same_either_way(ctx: &mut GpuContext, name: &str, scene: &PackedScene) {
    let chosen = ctx.kernel;
    let (mut films, mut fallbacks) = (Vec::new(), Vec::new());
    for lists_in_storage in [false, true] {
        ctx.kernel = KernelConfig {
            lists_in_storage,
            ..chosen
        };
        let words = LaneLists::of(scene.features, ctx.kernel).words();
        assert_eq!(words > 0, lists_in_storage, "{name}: {}", ctx.kernel);
        let render = render_gpu(ctx, scene, &GpuRenderOptions::default())
            .unwrap_or_else(|e| panic!("{name}, {}: {e}", ctx.kernel));
        fallbacks.push(render.info.cpu_fallback_pixels);
        films.push(render.film);
    }
    let differing = films[0]
        .pixels
        .iter()
        .zip(&films[1].pixels)
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(
        differing, 0,
        "{name}: {differing} pixels differ with lists in storage"
    );
    let pixels = films[0].pixels.len() as u64;
    assert!(
        fallbacks[0] == fallbacks[1] && fallbacks[0] * 10 < pixels,
        "{name}: CPU-fallback pixels {fallbacks:?} of {pixels}"
    );
    let name = format!("{name}, lists in storage");
    common::assert_gpu_matches_cpu(ctx, "gpu_lists", &name, scene, 0.01);
    ctx.kernel = chosen;
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn glass_and_csg_render_the_same_with_lists_in_storage() {
    let Some(mut ctx) = gpu_context() else { return };
    for (file, feature) in [
        ("scenes/glass.lua", SceneFeatures::REFRACTION),
        ("scenes/csg.lua", SceneFeatures::CSG),
    ] {
        for aa in [AaMode::None, AaMode::Uniform, AaMode::Adaptive] {
            let path = common::root().join(file);
            let scene = packed_from_file(&path, &small(aa)).remove(0);
            assert!(scene.features.contains(feature), "{file}");
            same_either_way(&mut ctx, &format!("{file} {aa:?}"), &scene);
        }
    }
}

/// The storage variant has no private array of the ray stack or of the CSG lists left
/// (what a GPU compiler would put in scratch memory), and the software variant keeps them.
#[test]
fn lists_in_storage_leave_no_private_list_arrays() {
    let mut features = SceneFeatures::empty();
    for f in [
        SceneFeatures::SPHERE,
        SceneFeatures::CUBE,
        SceneFeatures::CSG,
        SceneFeatures::REFRACTION,
        SceneFeatures::TEXTURE,
    ] {
        features.insert(f);
    }
    for lists_in_storage in [false, true] {
        let kernel = KernelConfig {
            lists_in_storage,
            ..KernelConfig::default()
        };
        for entry in [Entry::Render, Entry::Probe] {
            let source = assemble_with(features, entry, kernel);
            let stack = "alias RayStack = array<StackEntry, RAY_STACK_SIZE>;";
            let csg = "var<private> csg_t: array<f32, CSG_EVENT_CAPACITY>;";
            // The probe module traces no secondary rays.
            let privates = match entry {
                Entry::Render => vec![stack, csg],
                _ => vec![csg],
            };
            for private in privates {
                assert_eq!(
                    source.contains(private),
                    !lists_in_storage,
                    "{entry:?} {kernel}: {private}"
                );
            }
        }
    }
}
