//! GPU parity for cylinders and cones. Tier 3 (kernel probes): ≥ 4096 seeded rays per
//! kind through the GPU's `closest_hit` + `surface_at` and the CPU's; ≥ 99.9% must agree
//! on hit/miss and item with |Δt|/t ≤ 1e-4 and normals within 1e-4 (the thresholds of
//! `gpu_probes.rs`). Tier 4 (images): `scenes/columns.lua` at 128×128 on both tracers,
//! FLIP mean < 0.01 and ≥ 99.9% of pixels within 2/255 (as in `gpu_images.rs`).

use crate::common;

use common::probes::{check, random_placed};
use common::{gpu_context, packed_from_file, packed_from_source, root, Rng};
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::{GridMode, OptionOverrides};

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
        lua += &random_placed(&mut rng, &ctor, (0.3, 2.0), 9.0);
        lua.push('\n');
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
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn probes_cylinders() {
    let Some(ctx) = gpu_context() else { return };
    let s = scene(11, false, 60, GridMode::Off);
    assert_eq!(s.features, SceneFeatures::CYLINDER);
    check(&ctx, "cylinders", &s, 111);
    let s = scene(11, false, 60, GridMode::Auto);
    check(&ctx, "cylinders, grid", &s, 112);
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn probes_cones() {
    let Some(ctx) = gpu_context() else { return };
    let s = scene(12, true, 60, GridMode::Off);
    assert_eq!(s.features, SceneFeatures::CONE);
    check(&ctx, "cones", &s, 121);
    let s = scene(12, true, 60, GridMode::Auto);
    check(&ctx, "cones, grid", &s, 122);
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
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
    common::assert_gpu_matches_cpu(&ctx, "gpu_images", "columns", &scene, 0.01);
}
