//! Textures, UVs and bump maps on the GPU against the CPU reference (tier 4): the texture
//! scene (every primitive textured, a bump-mapped sphere, a specular map), its UV debug
//! view, and the TEXTURE-only and BUMP-only specialisations, each compared with
//! `diff::assert_images_match` at the thresholds of tests/gpu/gpu_images.rs (FLIP mean < 0.01,
//! ≥ 99.9% of pixels within 2/255). Failures write actual, expected and heat-map PNGs to
//! `<target tmp>/gpu_textures/`.

use crate::common;
use crate::texture_support;

use common::{gpu_context, packed_from_file, root, temp_dir};
use glint::gpu::GpuContext;
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::{AaMode, DebugView, OptionOverrides};

/// A textured scene, GPU against CPU (FLIP mean ≤ 0.01); the features it compiled.
fn compare(ctx: &GpuContext, name: &str, scene: &PackedScene) -> SceneFeatures {
    common::assert_gpu_matches_cpu(ctx, "gpu_textures", name, scene, 0.01).features
}

fn small(aa: Option<AaMode>, debug: Option<DebugView>) -> OptionOverrides {
    OptionOverrides {
        width: Some(128),
        height: Some(128),
        aa,
        debug,
        ..OptionOverrides::default()
    }
}

/// scenes/textures.lua under its default (adaptive) AA: diffuse and specular textures,
/// UVs of every primitive and of meshes with and without UVs, a bump map.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn texture_scene_matches() {
    let Some(ctx) = gpu_context() else { return };
    let path = root().join("scenes/textures.lua");
    let scene = packed_from_file(&path, &small(None, None)).remove(0);
    let features = compare(&ctx, "textures", &scene);
    for f in [
        SceneFeatures::TEXTURE,
        SceneFeatures::BUMP,
        SceneFeatures::MESH,
    ] {
        assert!(features.contains(f), "{features}");
    }
}

/// The UV debug view of the same scene: every primitive's UVs, pixel by pixel.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn uv_debug_view_matches() {
    let Some(ctx) = gpu_context() else { return };
    let path = root().join("scenes/textures.lua");
    let scene = packed_from_file(&path, &small(Some(AaMode::None), Some(DebugView::Uv))).remove(0);
    compare(&ctx, "textures-uv-view", &scene);
}

/// Textures without bump maps, and bump maps without textures (each specialisation
/// alone), on every primitive kind, with a mirror reflecting them.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn texture_only_and_bump_only_match() {
    let Some(ctx) = gpu_context() else { return };
    let dir = temp_dir("gpu-textures");
    texture_support::save(&texture_support::uv_grid(), &dir.join("grid.png"));
    texture_support::save(&texture_support::bumps(), &dir.join("bumps.png"));
    for (name, set, feature) in [
        (
            "texture-only",
            "m:set_diffuse('grid.png') m:set_specular('bumps.png')",
            SceneFeatures::TEXTURE,
        ),
        (
            "bump-only",
            "m:set_bump('bumps.png', 0.02)",
            SceneFeatures::BUMP,
        ),
    ] {
        let source = common::every_primitive_lua(set);
        let path = dir.join(format!("{name}.lua"));
        std::fs::write(&path, source).unwrap();
        let scene = packed_from_file(&path, &OptionOverrides::default()).remove(0);
        let features = compare(&ctx, name, &scene);
        assert!(features.contains(feature), "{name}: {features}");
        let other = if feature == SceneFeatures::TEXTURE {
            SceneFeatures::BUMP
        } else {
            SceneFeatures::TEXTURE
        };
        assert!(!features.contains(other), "{name}: {features}");
    }
}

/// Texture filtering: a floor tiled 24 times with a fine noise texture and its bump map,
/// receding to the horizon (every mip level, blended, down to the grazing clamp), and a
/// mirror sphere whose reflected rays carry the cone on; textured only, bump-mapped only,
/// and both.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn minified_textures_match_across_mip_levels() {
    let Some(ctx) = gpu_context() else { return };
    let dir = temp_dir("gpu-textures-minified");
    texture_support::save(&texture_support::noise(64, 64, 5), &dir.join("noise.png"));
    for (name, set) in [
        ("minified-texture", "m:set_diffuse('noise.png')"),
        ("minified-bump", "m:set_bump('noise.png', 0.001)"),
        (
            "minified-both",
            "m:set_diffuse('noise.png') m:set_bump('noise.png', 0.001)",
        ),
    ] {
        let source = format!(
            "m = gr.material({{0.7, 0.5, 0.3}}, {{0.5, 0.5, 0.5}}, 30) {set}
             mirror = gr.material({{0.1, 0.1, 0.1}}, {{0, 0, 0}}, 1)
             mirror:set_reflection(0.6, 0.6, 0.6)
             root = gr.node('root')
             floor = gr.mesh('floor', {{{{-50,0,-50}},{{50,0,-50}},{{50,0,50}},{{-50,0,50}}}},
                             {{{{0,1,2,3}}}}, {{{{0,0}},{{24,0}},{{24,24}},{{0,24}}}})
             floor:set_material(m) root:add_child(floor)
             ball = gr.sphere('ball') ball:set_material(mirror) ball:translate(0, 1, -2)
             root:add_child(ball)
             l = gr.light({{3, 8, 6}}, {{0.9, 0.9, 0.9}}, {{1, 0, 0}})
             gr.render(root, 'o.png', 96, 64, {{0, 1.5, 6}}, {{0, -0.15, -1}}, {{0, 1, 0}}, 60,
                       {{0.3, 0.3, 0.3}}, {{l}}, {{aa='none'}})"
        );
        let path = dir.join(format!("{name}.lua"));
        std::fs::write(&path, source).unwrap();
        let scene = packed_from_file(&path, &OptionOverrides::default()).remove(0);
        compare(&ctx, name, &scene);
    }
}
