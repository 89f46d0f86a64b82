//! GPU parity for cylinders and cones. Tier 3 (kernel probes): ≥ 4096 seeded rays per
//! kind through the GPU's `closest_hit` + `surface_at` and the CPU's; ≥ 99.9% must agree
//! on hit/miss and item with |Δt|/t ≤ 1e-4 and normals within 1e-4 (the thresholds of
//! `gpu_probes.rs`). Tier 4 (images): `scenes/columns.lua` at 128×128 on both tracers,
//! FLIP mean < 0.01 and ≥ 99.9% of pixels within 2/255 (as in `gpu_images.rs`).

mod common;

use common::probes::check;
use common::{gpu_context, packed_from_file, packed_from_source, root, Rng};
use glint::diff::assert_images_match;
use glint::gpu::render_gpu_with_info;
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::{GridMode, OptionOverrides};
use std::fmt::Write;

/// Lua for `count` random cylinders (`cone == false`) or cones (random zmin < zmax:
/// single nappes, tips at z = 0, double cones) in [-10, 10]³.
fn random_scene(seed: u64, cone: bool, count: usize) -> String {
    let mut rng = Rng(seed);
    let mut lua = String::from(
        "m = gr.material({0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, 25)\nroot = gr.node('root')\n",
    );
    for i in 0..count {
        let ctor = if cone {
            let (zmin, zmax) = match rng.next_u64() % 4 {
                0 => (0.0, rng.range(0.3, 2.0)),
                1 => {
                    let z = rng.range(0.1, 1.5);
                    (z, z + rng.range(0.2, 1.5))
                }
                2 => (-rng.range(0.3, 1.5), -rng.range(0.0, 0.2)),
                _ => (-rng.range(0.2, 1.5), rng.range(0.2, 1.5)),
            };
            format!("gr.cone('c{i}', {zmin}, {zmax})")
        } else {
            format!("gr.cylinder('c{i}')")
        };
        let s = [0; 3].map(|_| rng.range(0.3, 2.0));
        let axis = ["x", "y", "z"][(rng.next_u64() % 3) as usize];
        let angle = rng.range(0.0, 360.0);
        let t = [0; 3].map(|_| rng.range(-9.0, 9.0));
        let _ = writeln!(
            lua,
            "n = {ctor} n:scale({}, {}, {}) n:rotate('{axis}', {angle}) n:translate({}, {}, {}) n:set_material(m) root:add_child(n)",
            s[0], s[1], s[2], t[0], t[1], t[2]
        );
    }
    lua + "gr.render(root, 'probe.png', 64, 64, {0, 0, 30}, {0, 0, -1}, {0, 1, 0}, 50, {0.1, 0.1, 0.1}, {})\n"
}

fn scene(seed: u64, cone: bool, count: usize, grid: GridMode) -> PackedScene {
    let overrides = OptionOverrides {
        grid: Some(grid),
        ..OptionOverrides::default()
    };
    packed_from_source(&random_scene(seed, cone, count), &overrides).remove(0)
}

#[test]
fn probes_cylinders() {
    let Some(ctx) = gpu_context() else { return };
    let s = scene(11, false, 60, GridMode::Off);
    assert_eq!(s.features, SceneFeatures::CYLINDER);
    check(&ctx, "cylinders", &s, 111);
    let s = scene(11, false, 60, GridMode::Auto);
    check(&ctx, "cylinders, grid", &s, 112);
}

#[test]
fn probes_cones() {
    let Some(ctx) = gpu_context() else { return };
    let s = scene(12, true, 60, GridMode::Off);
    assert_eq!(s.features, SceneFeatures::CONE);
    check(&ctx, "cones", &s, 121);
    let s = scene(12, true, 60, GridMode::Auto);
    check(&ctx, "cones, grid", &s, 122);
}

#[test]
fn columns_scene_matches() {
    let Some(ctx) = gpu_context() else { return };
    let overrides = OptionOverrides {
        width: Some(128),
        height: Some(128),
        ..OptionOverrides::default()
    };
    let scene = packed_from_file(&root().join("scenes/columns.lua"), &overrides).remove(0);
    for f in [SceneFeatures::CYLINDER, SceneFeatures::CONE] {
        assert!(scene.features.contains(f), "{}", scene.features);
    }
    let (gpu, info) = render_gpu_with_info(&ctx, &scene, &|_, _| {}).expect("gpu render");
    let cpu = glint::cpu::render(&scene, &|_, _| {});
    let out = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu_images");
    let report = assert_images_match("columns", &gpu, &cpu, 0.01, 0.999, &out)
        .unwrap_or_else(|message| panic!("{message}"));
    eprintln!(
        "columns: features [{}], FLIP mean {:.5}, {:.3}% within 2/255, {} CPU-fallback pixels",
        info.features,
        report.flip_mean,
        report.share_within(2.0 / 255.0) * 100.0,
        info.cpu_fallback_pixels
    );
}
