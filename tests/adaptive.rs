//! Adaptive anti-aliasing in passes over a per-tile lattice (`cpu::adaptive`) against the
//! per-pixel reference walk (`cpu::render::adaptive_pixel`): the same decisions, samples
//! and summation order, so the images are identical bit for bit.

mod common;

use common::{corpus, packed_from_file, root};
use glint::constants::AA_PENUMBRA_DEPTH;
use glint::cpu::render::{adaptive_leaf_counts, render_pixel};
use glint::cpu::traverse::NoCounters;
use glint::scene::{AaMode, OptionOverrides};

fn check(file: &str, size: u32, depth: u32) {
    check_path(&corpus().join("a4-2021plus").join(file), size, depth, None);
}

/// Passes against per-pixel walk on `path` at size² and depth `depth` (and threshold
/// `threshold`, else the scene's); returns the leaf counts.
fn check_path(path: &std::path::Path, size: u32, depth: u32, threshold: Option<f32>) -> Vec<u32> {
    let file = path.display();
    let overrides = OptionOverrides {
        width: Some(size),
        height: Some(size),
        aa: Some(AaMode::Adaptive),
        aa_depth: Some(glint::scene::AaDepth::constant(depth)),
        aa_threshold: threshold,
        ..OptionOverrides::default()
    };
    let scene = packed_from_file(path, &overrides).remove(0);
    let film = glint::cpu::render(&scene, &|_, _| {});
    let leaves = adaptive_leaf_counts(&scene);
    let mut split = 0;
    for y in 0..size {
        for x in 0..size {
            let reference = render_pixel(&scene, x, y, &mut NoCounters).to_array();
            let got = film.pixels[(y * size + x) as usize];
            assert_eq!(got, reference, "{file} d={depth} pixel ({x}, {y})");
            let l = leaves[(y * size + x) as usize];
            assert_eq!(l % 3, 1, "leaf count {l}");
            split += (l > 1) as u32;
        }
    }
    assert!(depth == 0 || split > 0, "{file} d={depth}: nothing split");
    leaves
}

#[test]
fn lattice_matches_per_pixel_walk() {
    check("nonhier.lua", 40, 0);
    check("nonhier.lua", 40, 1);
    check("nonhier.lua", 37, 3);
    check("nonhier.lua", 24, 6);
    check("macho-cows.lua", 32, 3);
}

/// Soft shadows: a lattice sample that saw a penumbra splits the squares it is a corner
/// of down to AA_PENUMBRA_DEPTH, in the passes as in the per-pixel walk. With a threshold
/// no contrast exceeds, only penumbrae split, and no deeper than that.
#[test]
fn penumbrae_split_down_to_their_depth() {
    let path = root().join("scenes/soft-shadows.lua");
    check_path(&path, 40, 3, None);
    let leaves = check_path(&path, 40, 3, Some(f32::MAX));
    let deepest = 1 << (2 * AA_PENUMBRA_DEPTH);
    let full = leaves.iter().filter(|&&l| l == deepest).count();
    eprintln!(
        "{full} of {} pixels split to 4^{AA_PENUMBRA_DEPTH}",
        leaves.len()
    );
    assert!(full > 0, "no penumbra split");
    assert!(
        leaves.iter().all(|&l| l <= deepest),
        "deeper than penumbra depth"
    );
}
