//! The traversal's mailboxes in the hardware kernel variant (`KernelConfig::mailboxes`,
//! src/mailboxes.rs): a frame of instanced meshes that span several grid cells renders
//! the same pixels with the full caches, with the one item slot every adapter now keeps,
//! and with none, and matches the CPU tracer (tier 4). The mailboxes change which
//! primitives are tested again, never a pixel; the ray-by-ray check is
//! `gpu_probes::probes_instanced_meshes`.

use crate::common;

use common::{gpu_context, packed_from_file};
use glint::gpu::{render_gpu, GpuRenderOptions, KernelConfig, KernelVariant};
use glint::mailboxes::Mailboxes;
use glint::pack::SceneFeatures;
use glint::scene::{AaMode, OptionOverrides};

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn hardware_variant_renders_the_same_pixels_with_any_mailboxes() {
    let Some(mut ctx) = gpu_context() else { return };
    let file = "scenes/cs488/a4-2021plus/macho-cows.lua";
    let small = OptionOverrides {
        width: Some(48),
        height: Some(40),
        aa: Some(AaMode::None),
        ..OptionOverrides::default()
    };
    let scene = packed_from_file(&common::root().join(file), &small).remove(0);
    assert!(
        scene.features.contains(SceneFeatures::MESH)
            && scene.features.contains(SceneFeatures::GRID),
        "{file}: instanced meshes through the scene grid"
    );
    let hardware = KernelConfig::for_variant(KernelVariant::Hardware, &ctx.limits);
    assert_eq!(
        hardware.mailboxes,
        Mailboxes::LastItem,
        "the hardware variant's choice"
    );
    let mut films = Vec::new();
    for mailboxes in Mailboxes::ALL {
        ctx.kernel = KernelConfig {
            mailboxes,
            ..hardware
        };
        let render = render_gpu(&ctx, &scene, &GpuRenderOptions::default())
            .unwrap_or_else(|e| panic!("{file}, {}: {e}", ctx.kernel));
        films.push((mailboxes, render.film, render.info.cpu_fallback_pixels));
    }
    let (_, first, first_fallback) = &films[0];
    for (mailboxes, film, fallback) in &films[1..] {
        let differing = first
            .pixels
            .iter()
            .zip(&film.pixels)
            .filter(|(a, b)| a != b)
            .count();
        assert_eq!(
            (differing, fallback),
            (0, first_fallback),
            "{file}: pixels differing from the full mailboxes' and CPU-fallback pixels, {mailboxes}"
        );
    }
    ctx.kernel = hardware;
    common::assert_gpu_matches_cpu(
        &ctx,
        "gpu_mailboxes",
        &format!("{file}, {hardware}"),
        &scene,
        0.01,
    );
}
