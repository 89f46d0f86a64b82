//! The farm's promise on the CPU tracer: a tile rendered alone (`render_window`) holds,
//! bit for bit, the pixels of the full render, for every tiling, AA mode and thread count
//! (so `glint assemble` of any tiling is the full image).

use crate::common;

use common::tilings::{first_difference, join, tilings};
use glint::film::Film;
use glint::pack::PackedScene;
use glint::scene::{AaDepth, AaMode, AaSamples, OptionOverrides};
use glint::tracer::sampling::render::render_window;

/// Odd sizes, so no tiling lines up with the CPU's own 16- or 8-pixel tiles.
const W: u32 = 37;
const H: u32 = 23;

fn packed(aa: AaMode, scene: &str) -> PackedScene {
    let overrides = OptionOverrides {
        aa: Some(aa),
        samples: Some(AaSamples::constant(3)),
        aa_depth: Some(AaDepth::constant(3)),
        width: Some(W),
        height: Some(H),
        ..OptionOverrides::default()
    };
    common::load_packed(&common::root().join(scene), &overrides)
}

fn in_pool<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

fn assert_tilings_match(scene: &PackedScene, full: &Film, threads: usize, label: &str) {
    for (name, rects) in tilings(W, H, &[2, 3, 4, 7, 16]) {
        let tiles: Vec<_> = in_pool(threads, || {
            rects
                .iter()
                .map(|&r| (r, render_window(scene, r, &|_, _| {})))
                .collect()
        });
        let joined = join(W, H, &tiles);
        if let Some((x, y, a, b)) = first_difference(full, &joined) {
            panic!("{label}, {name}, {threads} threads: pixel ({x}, {y}) is {b:?} in the tiles, {a:?} in the full render");
        }
    }
}

#[test]
fn cpu_tiles_are_the_full_render_bit_for_bit() {
    // demo.lua: textures, an area light's penumbrae, mirrors and many edges for adaptive
    // AA; depth-of-field.lua: a thin lens, whose lens positions come from each pixel's
    // sequence (and, under adaptive AA, from the lattice point's place in its pixel).
    for path in ["scenes/demo.lua", "scenes/depth-of-field.lua"] {
        for aa in [AaMode::None, AaMode::Uniform, AaMode::Adaptive] {
            let scene = packed(aa, path);
            let full = in_pool(2, || common::render_cpu(&scene));
            for threads in [1, 3] {
                assert_tilings_match(&scene, &full, threads, &format!("{path}, {aa:?}"));
            }
        }
    }
}
