//! Adaptive anti-aliasing in passes over a per-tile lattice (`cpu::adaptive`) against the
//! per-pixel reference walk (`cpu::render::adaptive_pixel`): the same decisions, samples
//! and summation order, so the images are identical bit for bit.

mod common;

use common::{corpus, packed_from_file};
use glint::cpu::render::{adaptive_leaf_counts, render_pixel};
use glint::cpu::traverse::NoCounters;
use glint::scene::{AaMode, OptionOverrides};

fn check(file: &str, size: u32, depth: u32) {
    let overrides = OptionOverrides {
        width: Some(size),
        height: Some(size),
        aa: Some(AaMode::Adaptive),
        aa_depth: Some(glint::scene::AaDepth::constant(depth)),
        ..OptionOverrides::default()
    };
    let scene = packed_from_file(&corpus().join("a4-2021plus").join(file), &overrides).remove(0);
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
}

#[test]
fn lattice_matches_per_pixel_walk() {
    check("nonhier.lua", 40, 0);
    check("nonhier.lua", 40, 1);
    check("nonhier.lua", 37, 3);
    check("nonhier.lua", 24, 6);
    check("macho-cows.lua", 32, 3);
}
