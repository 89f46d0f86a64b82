//! The farm's promise on the GPU tracer: a pixel window rendered alone
//! (`GpuRenderOptions::window`) holds, bit for bit, the pixels of the GPU's full render,
//! for several tilings and every AA mode (the CPU twin: tests/images/farm_tiles.rs).

use crate::common;

use common::tilings::{first_difference, join, tilings};
use glint::gpu::{render_gpu, GpuRenderOptions};
use glint::scene::{AaDepth, AaMode, AaSamples, OptionOverrides};

const W: u32 = 29;
const H: u32 = 19;

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn gpu_tiles_are_the_full_render_bit_for_bit() {
    let Some(ctx) = common::gpu_context() else {
        return;
    };
    let wanted = [
        "--tile of 3",
        "--tile of 7",
        "3-column strips",
        "1-pixel edges",
    ];
    for aa in [AaMode::None, AaMode::Uniform, AaMode::Adaptive] {
        let overrides = OptionOverrides {
            aa: Some(aa),
            samples: Some(AaSamples::constant(2)),
            aa_depth: Some(AaDepth::constant(2)),
            width: Some(W),
            height: Some(H),
            ..OptionOverrides::default()
        };
        let scene = common::load_packed(&common::root().join("scenes/demo.lua"), &overrides);
        let full = render_gpu(&ctx, &scene, &GpuRenderOptions::default())
            .unwrap()
            .film;
        for (name, rects) in tilings(W, H, &[3, 7]) {
            if !wanted.contains(&name.as_str()) {
                continue;
            }
            let tiles: Vec<_> = rects
                .iter()
                .map(|&r| {
                    let options = GpuRenderOptions {
                        window: Some(r),
                        ..GpuRenderOptions::default()
                    };
                    (r, render_gpu(&ctx, &scene, &options).unwrap().film)
                })
                .collect();
            let joined = join(W, H, &tiles);
            if let Some((x, y, a, b)) = first_difference(&full, &joined) {
                panic!("{aa:?}, {name}: pixel ({x}, {y}) is {b:?} in the tiles, {a:?} in the full render");
            }
        }
    }
}
