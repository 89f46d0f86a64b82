//! Procedural textures on the GPU against the CPU reference (tier 4): scenes/procedural.lua
//! (checker floor to the horizon, noise, marble, wood, a noise bump), and a checker and
//! noise on every primitive kind (a mesh among them) with a mirror, as colour only and
//! as bump only, each compared with `diff::assert_images_match` at the thresholds of the
//! image textures' parity (tests/gpu/gpu_textures.rs: FLIP mean < 0.01, ≥ 99.9% of
//! pixels within 2/255). Failures write actual, expected and heat-map PNGs to
//! `<target tmp>/gpu_procedural/`.

use crate::common;

use common::{gpu_context, packed_from_file, root, temp_dir};
use glint::pack::SceneFeatures;
use glint::scene::{AaMode, OptionOverrides};

/// scenes/procedural.lua at 128×72, without AA and with its default adaptive AA.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn procedural_scene_matches() {
    let Some(ctx) = gpu_context() else { return };
    let path = root().join("scenes/procedural.lua");
    for (name, aa) in [
        ("procedural", Some(AaMode::None)),
        ("procedural-adaptive", None),
    ] {
        let options = OptionOverrides {
            width: Some(128),
            height: Some(72),
            aa,
            ..OptionOverrides::default()
        };
        let scene = packed_from_file(&path, &options).remove(0);
        let features =
            common::assert_gpu_matches_cpu(&ctx, "gpu_procedural", name, &scene, 0.01).features;
        for f in [
            SceneFeatures::PROCEDURAL,
            SceneFeatures::TEXTURE,
            SceneFeatures::BUMP,
        ] {
            assert!(features.contains(f), "{name}: {features}");
        }
    }
}

/// Procedural colour only and procedural bump only, on every primitive kind and a mesh,
/// with a mirror that reflects them (the cone carried on).
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn procedural_colour_only_and_bump_only_match() {
    let Some(ctx) = gpu_context() else { return };
    let dir = temp_dir("gpu-procedural");
    for (name, set, feature) in [
        (
            "procedural-colour",
            "m:set_diffuse(gr.checker({1, 0.9, 0.2}, {0.1, 0.2, 0.8}, 0.4)) \
             m:set_specular(gr.wood({0.6, 0.6, 0.6}, {0.1, 0.1, 0.1}, 3))",
            SceneFeatures::TEXTURE,
        ),
        (
            "procedural-bump",
            "m:set_bump(gr.marble({0, 0, 0}, {1, 1, 1}, 2, 2, 3), 0.2)",
            SceneFeatures::BUMP,
        ),
    ] {
        let source = common::every_primitive_lua(set);
        let path = dir.join(format!("{name}.lua"));
        std::fs::write(&path, source).unwrap();
        let scene = packed_from_file(&path, &OptionOverrides::default()).remove(0);
        let features =
            common::assert_gpu_matches_cpu(&ctx, "gpu_procedural", name, &scene, 0.01).features;
        assert!(
            features.contains(SceneFeatures::PROCEDURAL),
            "{name}: {features}"
        );
        assert!(features.contains(feature), "{name}: {features}");
    }
}
