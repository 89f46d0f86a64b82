//! The GPU frame's dispatch plan on a device: the submits and host waits of one frame are
//! counted by the render code itself (`GpuRenderInfo`), so the test does not depend on
//! timing. They must not grow with the image: 256² and 2048² frames take the same
//! number, in every AA mode, and no more than `GPU_FRAME_PARTS`. And the kernel variants
//! an adapter may choose (workgroup size, mailboxes) render the same image.

use crate::common;

use common::{gpu_context, packed_from_source};
use glint::constants::GPU_FRAME_PARTS;
use glint::gpu::{render_gpu, GpuRenderInfo, GpuRenderOptions};
use glint::scene::{AaMode, OptionOverrides};

const SCENE: &str = "
    red = gr.material({0.8, 0.2, 0.2}, {0.5, 0.5, 0.5}, 40)
    root = gr.node('root')
    s = gr.sphere('s') s:translate(0, 0, -4) s:set_material(red) root:add_child(s)
    l = gr.light({-4, 3, 2}, {0.9, 0.9, 0.9}, {1, 0, 0})
    gr.render(root, 'frame.png', 64, 64, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 50,
              {0.1, 0.1, 0.1}, {l})
";

fn render_info(ctx: &glint::gpu::GpuContext, size: u32, aa: AaMode) -> GpuRenderInfo {
    let overrides = OptionOverrides {
        width: Some(size),
        height: Some(size),
        aa: Some(aa),
        samples: Some(glint::scene::AaSamples::constant(2)),
        aa_depth: Some(glint::scene::AaDepth::constant(2)),
        ..OptionOverrides::default()
    };
    let scene = packed_from_source(SCENE, &overrides).remove(0);
    let info = render_gpu(ctx, &scene, &GpuRenderOptions::default())
        .unwrap()
        .info;
    eprintln!(
        "{size}² {aa:?}: {} chunks, {} dispatches, {} submits, {} host waits",
        info.tiles, info.dispatches, info.submits, info.host_waits
    );
    info
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn submits_and_host_waits_do_not_grow_with_the_image() {
    let Some(ctx) = gpu_context() else { return };
    for aa in [AaMode::None, AaMode::Uniform, AaMode::Adaptive] {
        let small = render_info(&ctx, 256, aa);
        let large = render_info(&ctx, 2048, aa);
        assert_eq!(small.submits, large.submits, "{aa:?}");
        assert_eq!(small.host_waits, large.host_waits, "{aa:?}");
        assert!(
            small.submits <= GPU_FRAME_PARTS,
            "{aa:?}: {}",
            small.submits
        );
        assert!(
            small.host_waits <= GPU_FRAME_PARTS,
            "{aa:?}: {}",
            small.host_waits
        );
        // The large frame has more work per submit, not more submits.
        assert!(large.tiles >= small.tiles, "{aa:?}");
    }
}

/// Every kernel variant (the workgroup side an adapter's limits may force, with each of
/// the traversal's mailbox variants, the scene's tables bound sampled or as read-only
/// storage textures) renders the very same image, in every AA mode (the
/// 1-D kernels and the indirect arguments of adaptive AA depend on the workgroup size),
/// and that image matches the CPU tracer's: a mismatch between the dispatch plan's
/// workgroup counts and the shader's `@workgroup_size` would leave pixels unrendered.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn every_kernel_variant_renders_the_same_image() {
    use glint::gpu::KernelConfig;
    use glint::mailboxes::Mailboxes;
    let Some(mut ctx) = gpu_context() else { return };
    let chosen = ctx.kernel;
    let path = common::corpus().join("a4-2021plus/nonhier.lua");
    for aa in [AaMode::None, AaMode::Adaptive] {
        let overrides = OptionOverrides {
            width: Some(72),
            height: Some(56),
            aa: Some(aa),
            aa_depth: Some(glint::scene::AaDepth::constant(2)),
            ..OptionOverrides::default()
        };
        let scene = common::load_packed(&path, &overrides);
        ctx.kernel = chosen;
        let name = format!("nonhier {aa:?}, {chosen}");
        let reference = common::assert_gpu_matches_cpu(&ctx, "gpu_frame", &name, &scene, 0.01);
        assert!(reference.cpu_fallback_pixels == 0, "{name}");
        let first = render_gpu(&ctx, &scene, &GpuRenderOptions::default())
            .unwrap()
            .film;
        for (workgroup_side, mailboxes, storage_tables) in [
            (8, Mailboxes::Full, !chosen.storage_tables),
            (8, Mailboxes::LastItem, chosen.storage_tables),
            (8, Mailboxes::LastItem, !chosen.storage_tables),
            (8, Mailboxes::Off, chosen.storage_tables),
            (4, Mailboxes::Full, chosen.storage_tables),
            (2, Mailboxes::LastItem, !chosen.storage_tables),
        ] {
            ctx.kernel = KernelConfig {
                workgroup_side,
                mailboxes,
                storage_tables,
                ..chosen
            };
            let film = render_gpu(&ctx, &scene, &GpuRenderOptions::default())
                .unwrap_or_else(|e| panic!("{aa:?} {}: {e}", ctx.kernel))
                .film;
            let differing = film
                .pixels
                .iter()
                .zip(&first.pixels)
                .filter(|(a, b)| a != b)
                .count();
            assert_eq!(
                differing, 0,
                "{aa:?}: {} renders {differing} pixels differently from {chosen}",
                ctx.kernel
            );
        }
    }
}

/// Timing each pass (`glint bench --gpu --passes`) changes how the frame is encoded (a
/// compute pass per dispatch, two timestamps each), not what it renders: the same image
/// and submits as a plain frame; every dispatch counted once, under its own entry point
/// and, for adaptive AA's per-level passes, its level; and the passes' times within the
/// frame's.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn pass_times_cover_every_dispatch_and_change_no_pixel() {
    let Some(ctx) = gpu_context() else { return };
    if !ctx
        .device
        .features()
        .contains(wgpu::Features::TIMESTAMP_QUERY)
    {
        eprintln!("skipped: the adapter has no timestamp queries");
        return;
    }
    for aa in [AaMode::None, AaMode::Adaptive] {
        let overrides = OptionOverrides {
            width: Some(300),
            height: Some(200),
            aa: Some(aa),
            aa_depth: Some(glint::scene::AaDepth::constant(2)),
            ..OptionOverrides::default()
        };
        let scene = packed_from_source(SCENE, &overrides).remove(0);
        let plain = render_gpu(&ctx, &scene, &GpuRenderOptions::default()).unwrap();
        assert!(plain.pass_times.is_empty());
        let timed_options = GpuRenderOptions {
            pass_times: true,
            ..GpuRenderOptions::default()
        };
        let timed = render_gpu(&ctx, &scene, &timed_options).unwrap();
        assert!(plain.film.pixels == timed.film.pixels, "{aa:?}");
        assert_eq!(plain.info.submits, timed.info.submits, "{aa:?}");
        let counted: u32 = timed.pass_times.iter().map(|p| p.dispatches).sum();
        assert_eq!(counted, timed.info.dispatches, "{aa:?}");
        let kinds: Vec<(&str, u32)> = timed
            .pass_times
            .iter()
            .map(|p| (p.entry, p.level))
            .collect();
        let expected: Vec<(&str, u32)> = match aa {
            AaMode::Adaptive => vec![
                ("adaptive_corners", 0),
                ("adaptive_decide", 0),
                ("adaptive_work_args", 0),
                ("adaptive_midpoints", 0),
                ("adaptive_decide", 1),
                ("adaptive_work_args", 1),
                ("adaptive_midpoints", 1),
                ("adaptive_integrate", 0),
            ],
            _ => vec![("main", 0)],
        };
        assert_eq!(kinds, expected, "{aa:?}");
        let passes: std::time::Duration = timed.pass_times.iter().map(|p| p.time).sum();
        let frame = timed.info.gpu_time.unwrap();
        assert!(passes <= frame, "{aa:?}: {passes:?} > {frame:?}");
        assert!(passes > std::time::Duration::ZERO, "{aa:?}");
    }
}

/// A frame takes its large buffers from the context's pool and gives them back
/// (`gpu::device::scratch`): the next frame of the same size reuses them instead of growing the
/// pool, and a frame on kept buffers that held another scene's lattice and flags renders
/// the image a fresh context renders.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn kept_frame_buffers_are_reused_and_change_no_pixel() {
    let Some(ctx) = gpu_context() else { return };
    let fresh = gpu_context().unwrap();
    let frame = |ctx: &glint::gpu::GpuContext, source: &str, depth: u32| {
        let overrides = OptionOverrides {
            width: Some(300),
            height: Some(200),
            aa: Some(AaMode::Adaptive),
            aa_depth: Some(glint::scene::AaDepth::constant(depth)),
            ..OptionOverrides::default()
        };
        let scene = packed_from_source(source, &overrides).remove(0);
        render_gpu(ctx, &scene, &GpuRenderOptions::default()).unwrap()
    };
    let other = SCENE.replace("s:translate(0, 0, -4)", "s:translate(0.7, -0.3, -3)");
    frame(&ctx, &other, 3);
    let kept = ctx.kept_frame_bytes();
    assert!(kept > 0);
    let on_kept = frame(&ctx, SCENE, 3);
    assert_eq!(ctx.kept_frame_bytes(), kept, "the pool grew");
    let on_fresh = frame(&fresh, SCENE, 3);
    assert!(on_kept.film.pixels == on_fresh.film.pixels);
    assert_eq!(on_kept.leaf_counts, on_fresh.leaf_counts);
    // A shallower frame fits in the kept buffers too (at most twice its size each), or
    // gets its own; either way the same image.
    let shallow = frame(&ctx, SCENE, 1);
    assert!(shallow.film.pixels == frame(&fresh, SCENE, 1).film.pixels);
}
