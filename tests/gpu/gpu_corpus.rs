//! Tier 4 over everything: every CS488 sample scene (with its family's transform order)
//! and every scene in `scenes/`, with its own render options (adaptive anti-aliasing by
//! default), rendered by both tracers at 96×96 and compared: FLIP mean < 0.01 and ≥ 99.9%
//! of pixels within 2/255 (the GPU runs the CPU's f32 steps; only a few ulps of GPU
//! sqrt/division may differ). Prints every scene's figures and the worst. On failure the
//! actual (GPU), expected (CPU) and heat-map PNGs go to `target/test-failures/`.

use crate::common;

use common::{corpus_scenes, failure_dir, gpu_context, load_packed, own_scenes, scene_name};
use glint::diff::assert_images_match;
use glint::scene::OptionOverrides;

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn every_scene_matches_on_both_tracers() {
    let Some(ctx) = gpu_context() else { return };
    let overrides = OptionOverrides {
        width: Some(96),
        height: Some(96),
        ..OptionOverrides::default()
    };
    let mut failures = Vec::new();
    let mut worst: Option<(String, f64, f64)> = None;
    for path in corpus_scenes().into_iter().chain(own_scenes()) {
        let name = format!("gpu-{}", scene_name(&path));
        let packed = load_packed(&path, &overrides);
        let gpu = glint::gpu::render_gpu(&ctx, &packed, &Default::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"))
            .film;
        let cpu = common::render_cpu(&packed);
        match assert_images_match(&name, &gpu, &cpu, 0.01, 0.999, &failure_dir()) {
            Ok(report) => {
                let share = report.share_within(2.0 / 255.0);
                println!(
                    "{name}: FLIP mean {:.5}, {:.3}% within 2/255",
                    report.flip_mean,
                    100.0 * share
                );
                if worst.as_ref().is_none_or(|w| report.flip_mean >= w.1) {
                    worst = Some((name, report.flip_mean, share));
                }
            }
            Err(message) => failures.push(message),
        }
    }
    if let Some((name, flip, share)) = worst {
        println!(
            "worst: {name}, FLIP mean {flip:.5}, {:.3}% within 2/255",
            100.0 * share
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}
