//! The GPU frame's dispatch plan on a device: the submits and host waits of one frame are
//! counted by the render code itself (`GpuRenderInfo`), so the test does not depend on
//! timing. They must not grow with the image: 256² and 2048² frames take the same
//! number, in every AA mode, and no more than `GPU_FRAME_PARTS`.

mod common;

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
