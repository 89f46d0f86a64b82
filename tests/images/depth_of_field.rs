//! Depth of field on the CPU tracer in `glint view`'s progressive form: the view's n²
//! frames sum to `glint render`'s image bit for bit, each frame's stratum taking its
//! point of the pixel's lens sequence; and a pinhole packs without the feature.

use crate::common;

use glint::pack::SceneFeatures;
use glint::scene::{AaMode, AaSamples, OptionOverrides};
use glint::tracer::sampling::progressive::{accumulate_sample, film_of_sums};

fn scene(aa: AaMode, aperture: Option<f32>) -> glint::pack::PackedScene {
    let overrides = OptionOverrides {
        aa: Some(aa),
        samples: Some(AaSamples::constant(3)),
        aperture,
        width: Some(40),
        height: Some(25),
        ..OptionOverrides::default()
    };
    common::load_packed(
        &common::root().join("scenes/depth-of-field.lua"),
        &overrides,
    )
}

/// The view's frames (stratum s of every pixel, frame s) sum to the render, bit for bit.
#[test]
fn view_frames_sum_to_the_render() {
    let scene = scene(AaMode::Uniform, None);
    assert!(scene.features.contains(SceneFeatures::DEPTH_OF_FIELD));
    let g = scene.globals;
    let mut sums = vec![[0.0f32; 4]; (g.width * g.height) as usize];
    for s in 0..g.aa_samples * g.aa_samples {
        accumulate_sample(&scene, s, &mut sums);
    }
    let view = film_of_sums(&sums, g.width, g.height);
    assert_eq!(view.pixels, common::render_cpu(&scene).pixels);
}

/// `aperture = 0` (the flag over the scene's) is the pinhole: no DEPTH_OF_FIELD feature,
/// and the image differs from the lens's.
#[test]
fn zero_aperture_is_the_pinhole() {
    let pinhole = scene(AaMode::None, Some(0.0));
    assert!(!pinhole.features.contains(SceneFeatures::DEPTH_OF_FIELD));
    let lens = scene(AaMode::None, None);
    assert_ne!(
        common::render_cpu(&pinhole).pixels,
        common::render_cpu(&lens).pixels
    );
}
