//! Dielectrics, CPU against GPU (tier 4): scenes/glass.lua and small scenes for each
//! material feature with glass (glass alone, glass and mirror on one material, glass with
//! area-light shadows, nested media with the camera inside glass), compared as in
//! `gpu_images.rs`: FLIP mean < 0.01 and ≥ 99.9% of pixels within 2/255. Refraction
//! magnifies the last-ulp differences of GPU sqrt/normalize wherever a ray grazes, so
//! these also show that the WGSL twins of refract_direction, schlick_reflectance, the
//! medium stack and shadow_transmittance agree with the CPU's.

use crate::common;

use common::{gpu_context, packed_from_file, packed_from_source};
use glint::gpu::GpuContext;
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::{AaMode, OptionOverrides};

/// A dielectric scene, GPU against CPU.
fn compare(ctx: &GpuContext, name: &str, scene: &PackedScene) {
    assert!(scene.features.contains(SceneFeatures::REFRACTION), "{name}");
    common::assert_gpu_matches_cpu(ctx, "gpu_refraction", name, scene, 0.01);
}

fn small(size: u32, aa: AaMode) -> OptionOverrides {
    OptionOverrides {
        width: Some(size),
        height: Some(size),
        aa: Some(aa),
        ..OptionOverrides::default()
    }
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn glass_scene_matches() {
    let Some(ctx) = gpu_context() else { return };
    let scene = packed_from_file(
        &common::root().join("scenes/glass.lua"),
        &small(96, AaMode::None),
    )
    .remove(0);
    compare(&ctx, "glass", &scene);
}

/// A checker of boxes under two balls and a ring, with `material` set up by `setup`.
fn material_scene(setup: &str, eye: &str, lights: &str) -> String {
    format!(
        r#"
white = gr.material({{0.8, 0.8, 0.8}}, {{0.2, 0.2, 0.2}}, 20)
dark = gr.material({{0.2, 0.2, 0.3}}, {{0.2, 0.2, 0.2}}, 20)
glass = gr.material({{0, 0, 0}}, {{0.5, 0.5, 0.5}}, 100)
{setup}
root = gr.node('root')
for i = 0, 5 do
  for j = 0, 5 do
    local t = gr.cube('t' .. i .. j)
    t:set_material(((i + j) % 2 == 0) and white or dark)
    t:scale(1, 0.2, 1)
    t:translate(i - 3, -0.2, j - 3)
    root:add_child(t)
  end
end
b = gr.nh_sphere('b', {{-1, 0.8, 0}}, 0.8)
b:set_material(glass)
root:add_child(b)
r = gr.torus('r', 0.6, 0.2)
r:set_material(glass)
r:translate(1, 0.8, 0)
root:add_child(r)
gr.render(root, 'x.png', 64, 64, {eye}, {{0, -0.4, -1}}, {{0, 1, 0}}, 50,
          {{0.3, 0.3, 0.3}}, {lights})
"#
    )
}

const POINT_LIGHT: &str = "{gr.light({-3, 6, 4}, {0.8, 0.8, 0.8}, {1, 0, 0})}";

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn material_features_match() {
    let Some(ctx) = gpu_context() else { return };
    let cases = [
        (
            "glass",
            "glass:set_refraction(1.5)",
            "{0, 2, 4}",
            POINT_LIGHT,
        ),
        (
            "glass-and-mirror",
            "glass:set_refraction(1.5)\nglass:set_reflection(0.3)",
            "{0, 2, 4}",
            POINT_LIGHT,
        ),
        (
            "glass-area-light",
            "glass:set_refraction(1.5)",
            "{0, 2, 4}",
            "{gr.area_light({-3, 6, 4}, {1, 0, 0}, {0, 0, 1}, {0.8, 0.8, 0.8}, {1, 0, 0}, 2)}",
        ),
        (
            // The eye inside the glass ball, which sits in a water ball.
            "camera-inside-glass-in-water",
            "glass:set_refraction(1.5)\nwater = gr.material({0, 0, 0}, {0.3, 0.3, 0.3}, 50)\n\
             water:set_refraction(1.33)\nw = gr.nh_sphere('w', {-1, 0.8, 0}, 1.6)\n\
             w:set_material(water)",
            "{-1, 0.9, 0.3}",
            POINT_LIGHT,
        ),
    ];
    for (name, setup, eye, lights) in cases {
        let mut source = material_scene(setup, eye, lights);
        if name.starts_with("camera") {
            source = source.replace("root:add_child(b)", "root:add_child(b)\nroot:add_child(w)");
        }
        let scene = packed_from_source(&source, &small(64, AaMode::None)).remove(0);
        if name.starts_with("camera") {
            assert_eq!(scene.globals.camera_media_count, 2, "{name}");
        }
        compare(&ctx, name, &scene);
    }
    // Uniform AA over glass (the uniform kernels' path).
    let scene = packed_from_source(
        &material_scene("glass:set_refraction(1.5)", "{0, 2, 4}", POINT_LIGHT),
        &OptionOverrides {
            samples: Some(glint::scene::AaSamples::constant(2)),
            ..small(48, AaMode::Uniform)
        },
    )
    .remove(0);
    compare(&ctx, "glass-uniform-aa", &scene);
}
