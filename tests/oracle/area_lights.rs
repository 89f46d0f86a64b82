//! Area lights (`gr.area_light`) on the CPU tracer: packing, a zero-size area light equals
//! a point light, the soft-shadow error falls as the n×n shadow samples grow, and an
//! adaptive-AA pixel centre's shadow jitter mirrors its corners'.
//! (CPU–GPU parity is in `gpu_images.rs`.)

use crate::common;
use crate::oracle_support::film_rmse as rmse;

use common::{area_lit_floor_source, packed_from_source, render_cpu};
use glint::constants::{LIGHT_AREA, LIGHT_POINT};
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::{AaDepth, AaMode, AaSamples, OptionOverrides, ShadowSamples};

/// A sphere over a floor, lit by `light` (a Lua expression).
fn scene(light: &str, overrides: &OptionOverrides) -> PackedScene {
    let source = format!(
        "
        grey = gr.material({{0.7, 0.7, 0.7}}, {{0.3, 0.3, 0.3}}, 25)
        red = gr.material({{0.8, 0.2, 0.2}}, {{0.5, 0.5, 0.5}}, 40)
        root = gr.node('root')
        floor = gr.cube('floor') floor:scale(10, 0.5, 10) floor:translate(-5, -1.5, -9)
        floor:set_material(grey) root:add_child(floor)
        s = gr.sphere('s') s:translate(0, 0, -4) s:set_material(red) root:add_child(s)
        l = {light}
        gr.render(root, 'area.png', 48, 48, {{0, 2, 3}}, {{0, -0.4, -1}}, {{0, 1, 0}}, 50,
                  {{0.1, 0.1, 0.1}}, {{l}})
        "
    );
    packed_from_source(&source, overrides).remove(0)
}

const AREA: &str =
    "gr.area_light({0, 4, -3}, {2.5, 0, 0}, {0, 0, 2.5}, {0.9, 0.9, 0.9}, {1, 0, 0})";

fn no_aa() -> OptionOverrides {
    OptionOverrides {
        aa: Some(AaMode::None),
        ..OptionOverrides::default()
    }
}

#[test]
fn area_lights_pack_with_their_samples_and_feature() {
    let packed = scene(AREA, &OptionOverrides::default());
    let l = &packed.lights[0];
    assert_eq!(l.kind, LIGHT_AREA);
    assert_eq!(l.samples, 4, "default n");
    assert_eq!(l.edge_u, [2.5, 0.0, 0.0]);
    assert_eq!(l.edge_v, [0.0, 0.0, 2.5]);
    assert!(packed.features.contains(SceneFeatures::AREA_LIGHT));
    let with_n = scene(&AREA.replace("{1, 0, 0})", "{1, 0, 0}, 7)"), &no_aa());
    assert_eq!(with_n.lights[0].samples, 7);
    let overridden = scene(
        AREA,
        &OptionOverrides {
            shadow_samples: Some(ShadowSamples::constant(2)),
            ..OptionOverrides::default()
        },
    );
    assert_eq!(
        overridden.lights[0].samples, 2,
        "shadow_samples overrides n"
    );
    let point = scene("gr.light({0, 4, -3}, {0.9, 0.9, 0.9}, {1, 0, 0})", &no_aa());
    assert_eq!(point.lights[0].kind, LIGHT_POINT);
    assert!(!point.features.contains(SceneFeatures::AREA_LIGHT));
}

/// A 1×1 area light of zero size is the point light, bit for bit; with n×n samples at one
/// point it is the mean of n² equal terms (equal up to rounding).
#[test]
fn zero_size_area_light_equals_point_light() {
    for aa in [AaMode::None, AaMode::Uniform, AaMode::Adaptive] {
        let overrides = OptionOverrides {
            aa: Some(aa),
            samples: Some(glint::scene::AaSamples::constant(2)),
            ..OptionOverrides::default()
        };
        let point = scene(
            "gr.light({0.3, 4, -3}, {0.9, 0.8, 0.7}, {1, 0.05, 0.01})",
            &overrides,
        );
        let reference = render_cpu(&point);
        for n in [1, 3] {
            let mut area = point.clone();
            area.lights[0].kind = LIGHT_AREA;
            area.lights[0].samples = n;
            area.lights[0].edge_u = [0.0; 3];
            area.lights[0].edge_v = [0.0; 3];
            let film = render_cpu(&area);
            let worst = film
                .pixels
                .iter()
                .zip(&reference.pixels)
                .flat_map(|(a, b)| (0..3).map(move |c| (a[c] - b[c]).abs()))
                .fold(0.0f32, f32::max);
            if n == 1 {
                assert_eq!(worst, 0.0, "{aa:?}: n = 1 differs by {worst}");
            } else {
                assert!(worst < 1e-5, "{aa:?}: n = {n} differs by {worst}");
            }
        }
    }
}

/// The soft shadow's error against n = 16 falls as n grows (1, 2, 4, 8).
#[test]
fn soft_shadow_error_falls_with_more_samples() {
    let with_n = |n: u32| {
        render_cpu(&scene(
            AREA,
            &OptionOverrides {
                shadow_samples: Some(ShadowSamples::constant(n)),
                ..no_aa()
            },
        ))
    };
    let reference = with_n(16);
    let errors: Vec<f64> = [1, 2, 4, 8]
        .iter()
        .map(|&n| rmse(&with_n(n), &reference))
        .collect();
    let ratios: Vec<f64> = errors.windows(2).map(|w| w[0] / w[1]).collect();
    eprintln!("RMSE against n = 16 for n = 1, 2, 4, 8: {errors:.5?}; ratios {ratios:.2?}");
    for w in errors.windows(2) {
        assert!(w[1] < w[0], "error did not fall: {errors:?}");
    }
}

/// `area_lit_floor_source` (a slightly shiny floor) with 2×2 shadow samples, rendered
/// with `overrides`.
fn lit_floor(overrides: &OptionOverrides) -> glint::film::Film {
    let overrides = OptionOverrides {
        shadow_samples: Some(ShadowSamples::constant(2)),
        ..overrides.clone()
    };
    let source = area_lit_floor_source(0.6, 0.4, 10.0);
    render_cpu(&packed_from_source(&source, &overrides).remove(0))
}

/// An unsplit adaptive pixel is the quincunx mean of its corners and centre, and its
/// centre's shadow jitter is its corners' mirrored through each stratum's centre, which
/// cancels their error where the light's contribution varies linearly across a stratum.
/// With no contrast and no penumbra to split anything, its five samples so err less
/// against a 16×16 reference than uniform 4×4's sixteen independent ones (RMSE 0.0045
/// against 0.0057 when written; with independent jitters the pixels erred 0.0134, as
/// the quincunx's variance is 0.31 of one sample's and 4×4's 0.06).
#[test]
fn pixel_centres_mirror_their_corners_shadow_jitter() {
    let uniform = |n: u32| {
        lit_floor(&OptionOverrides {
            aa: Some(AaMode::Uniform),
            samples: Some(AaSamples::constant(n)),
            ..OptionOverrides::default()
        })
    };
    let reference = uniform(16);
    let adaptive = lit_floor(&OptionOverrides {
        aa: Some(AaMode::Adaptive),
        aa_threshold: Some(f32::MAX),
        aa_depth: Some(AaDepth::constant(1)),
        ..OptionOverrides::default()
    });
    let none = lit_floor(&no_aa());
    let (adaptive, four, one) = (
        rmse(&adaptive, &reference),
        rmse(&uniform(4), &reference),
        rmse(&none, &reference),
    );
    eprintln!("RMSE against 16×16: adaptive {adaptive:.5}, uniform 4×4 {four:.5}, none {one:.5}");
    assert!(
        four < one,
        "4×4 ({four}) should err less than one sample ({one})"
    );
    assert!(adaptive < four, "adaptive {adaptive} vs uniform 4×4 {four}");
}
