//! The wavefront passes (`tracer::wavefront::wavefront`) against the megakernel form (`trace_ray`) on
//! the CPU: every scene of scenes/ and the CS488 corpus without refraction, at a small
//! size, renders to the same bits through both — AA none and uniform AA as whole films
//! (with the traversal counters' totals: the same rays traced), adaptive AA as every
//! point of the finest lattice (its colour and its hint), since the adaptive passes
//! sample nothing but lattice points, and as adaptive tiles whose corner and midpoint
//! passes go through the passes (`tracer::wavefront::wavefront_lattice`, the GPU's hardware variant's
//! form).

use crate::common;
use common::tree_scenes::{slab_scene, FULL_STACK_SCENE, UNDERWATER_SCENE};

use glam::Vec3;
use glint::constants::{MAX_SHADOW_CROSSINGS, RAY_STACK_SIZE};
use glint::film::Film;
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::{AaDepth, AaMode, AaSamples, DebugView, OptionOverrides, TraceDepth};
use glint::tiling::AdaptiveTile;
use glint::tracer::sampling::adaptive::{adaptive_tile, adaptive_tile_passes, Lattice};
use glint::tracer::sampling::pixel_sample::lattice_sample;
use glint::tracer::sampling::render::render_pixel;
use glint::tracer::shading::dielectric::{shadow_transmittance, MediumStack};
use glint::tracer::traversal::traverse::Counters;
use glint::tracer::wavefront::wavefront::{
    camera_pass, closest_pass, render_film, trace_batch, wavefront_args, Batch, SampleSource,
};
use glint::tracer::wavefront::wavefront_gather::{fold_pass, gather_pass};
use glint::tracer::wavefront::wavefront_lattice::trace_lattice_pass;
use glint::tracer::wavefront::wavefront_shade::shade_pass;
use glint::tracer::wavefront::wavefront_shadow::{glass_shadow_pass, shadow_pass};
use std::path::{Path, PathBuf};

const W: u32 = 20;
const H: u32 = 14;

/// Every scene file whose first render has no refraction (the passes trace chains).
fn chain_scenes() -> Vec<PathBuf> {
    let mut scenes = common::own_scenes();
    scenes.extend(common::corpus_scenes());
    scenes
}

fn packed(path: &Path, aa: AaMode, debug: DebugView) -> Vec<PackedScene> {
    packed_where(path, aa, debug, false)
}

/// The renders of `path` whose refraction is `refraction`, at W×H.
fn packed_where(path: &Path, aa: AaMode, debug: DebugView, refraction: bool) -> Vec<PackedScene> {
    let overrides = OptionOverrides {
        aa: Some(aa),
        samples: Some(AaSamples::constant(2)),
        aa_depth: Some(AaDepth::constant(2)),
        debug: Some(debug),
        width: Some(W),
        height: Some(H),
        ..OptionOverrides::default()
    };
    common::packed_from_file(path, &overrides)
        .into_iter()
        .filter(|s| s.features.contains(SceneFeatures::REFRACTION) == refraction)
        .collect()
}

/// The megakernel form's film, pixel by pixel as `tracer::render` computes them.
fn reference_film(scene: &PackedScene, counters: &mut Counters) -> Film {
    let g = &scene.globals;
    let mut film = Film::new(g.width, g.height);
    for y in 0..g.height {
        for x in 0..g.width {
            film.set(x, y, render_pixel(scene, x, y, counters).to_array());
        }
    }
    film
}

fn bits(film: &Film) -> Vec<[u32; 3]> {
    film.pixels.iter().map(|p| p.map(f32::to_bits)).collect()
}

fn assert_films_match(name: &str, scene: &PackedScene, batch_pixels: usize) {
    let mut mega = Counters::default();
    let mut wave = Counters::default();
    let expected = reference_film(scene, &mut mega);
    let actual = render_film(scene, batch_pixels, &mut wave);
    let (e, a) = (bits(&expected), bits(&actual));
    if let Some(p) = (0..e.len()).find(|&p| e[p] != a[p]) {
        panic!(
            "{name}: pixel ({}, {}) is {:?} through the passes, {:?} through trace_ray",
            p as u32 % scene.globals.width,
            p as u32 / scene.globals.width,
            actual.pixels[p],
            expected.pixels[p]
        );
    }
    assert_eq!(
        (wave.cells_visited, wave.items_tested),
        (mega.cells_visited, mega.items_tested),
        "{name}: traversal counters (cells, items)"
    );
}

/// Scenes the comparisons must include (mirrors over several generations, area lights,
/// textures, bump maps, smooth meshes, tori, CSG, meshes in grids): a filter or loader
/// that dropped one would otherwise pass unnoticed.
const REQUIRED: &[&str] = &[
    "scenes-demo",
    "scenes-textures",
    "scenes-soft-shadows",
    "scenes-tori",
    "scenes-columns",
    "scenes-smooth",
    "a4-2021plus-nonhier",
    "a4-2021plus-macho-cows",
    "a4-2021plus-simple",
];

/// Fails unless every [`REQUIRED`] scene is among `names` and there are at least
/// `at_least` of them (29 scene renders of the 33 files have no refraction).
fn assert_coverage(names: &[String], at_least: usize) {
    for required in REQUIRED {
        assert!(
            names.iter().any(|n| n.starts_with(required)),
            "{required} was not compared (compared: {names:?})"
        );
    }
    assert!(
        names.len() >= at_least,
        "only {} compared: {names:?}",
        names.len()
    );
}

#[test]
fn passes_render_every_chain_scene_as_trace_ray_does() {
    let mut checked = Vec::new();
    for path in chain_scenes() {
        for aa in [AaMode::None, AaMode::Uniform] {
            for scene in packed(&path, aa, DebugView::None) {
                let name = format!("{} {aa:?}", common::scene_name(&path));
                // Batches that do not divide the image, and one for all of it.
                assert_films_match(&name, &scene, 37);
                assert_films_match(&name, &scene, (W * H) as usize);
                checked.push(name);
            }
        }
    }
    assert_coverage(&checked, 2 * 29);
}

/// scenes/csg.lua with its glass a mirror: CSG objects (the tumbler, the classic, the
/// lens) with no refraction, reflecting each other over several generations.
pub fn mirrored_csg_source() -> String {
    let source = std::fs::read_to_string(common::root().join("scenes/csg.lua")).unwrap();
    assert!(source.contains("glass:set_refraction(1.5)"));
    source.replace(
        "glass:set_refraction(1.5)",
        "glass:set_reflection(0.8, 0.8, 0.85)",
    )
}

#[test]
fn passes_render_csg_without_refraction_as_trace_ray_does() {
    let overrides = |aa| OptionOverrides {
        aa: Some(aa),
        samples: Some(AaSamples::constant(2)),
        width: Some(W),
        height: Some(H),
        ..OptionOverrides::default()
    };
    for aa in [AaMode::None, AaMode::Uniform] {
        let scenes = common::packed_from_source(&mirrored_csg_source(), &overrides(aa));
        let scene = &scenes[0];
        assert!(scene.features.contains(SceneFeatures::CSG));
        assert!(scene.features.contains(SceneFeatures::REFLECTION));
        assert!(!scene.features.contains(SceneFeatures::REFRACTION));
        assert_films_match(&format!("mirrored csg {aa:?}"), scene, 64);
    }
}

#[test]
fn passes_render_the_uv_debug_view_as_trace_ray_does() {
    for file in ["scenes/textures.lua", "scenes/demo.lua"] {
        let path = common::root().join(file);
        for scene in packed(&path, AaMode::None, DebugView::Uv) {
            assert_films_match(&format!("{file} uv"), &scene, 50);
        }
    }
}

#[test]
fn passes_sample_every_lattice_point_as_lattice_sample_does() {
    let mut checked = Vec::new();
    for path in chain_scenes() {
        for scene in packed(&path, AaMode::Adaptive, DebugView::None) {
            let name = common::scene_name(&path);
            assert_lattice_matches(&name, &scene);
            checked.push(name);
        }
    }
    assert_coverage(&checked, 29);
}

/// Every point of `scene`'s finest lattice through the passes in one batch: the colour
/// and the hint of `lattice_sample` (trace_ray's), bit for bit.
fn assert_lattice_matches(name: &str, scene: &PackedScene) {
    {
        {
            let steps = 1u32 << scene.globals.aa_depth;
            let points: Vec<[f32; 2]> = (0..=H * steps)
                .flat_map(|y| (0..=W * steps).map(move |x| [x, y]))
                .map(|[x, y]| [x as f32 / steps as f32, y as f32 / steps as f32])
                .collect();
            let batch = trace_batch(
                scene,
                &SampleSource::Lattice { points: &points },
                &mut Counters::default(),
            );
            for (k, &[fx, fy]) in points.iter().enumerate() {
                let (colour, hint) = lattice_sample(scene, fx, fy, &mut Counters::default());
                let wave = batch.samples.colour[k];
                assert_eq!(
                    wave.to_array().map(f32::to_bits),
                    colour.to_array().map(f32::to_bits),
                    "{name}: lattice point ({fx}, {fy}): {wave:?} through the passes, {colour:?} through trace_ray"
                );
                assert_eq!(
                    batch.samples.hint(k),
                    hint,
                    "{name}: lattice point ({fx}, {fy})'s hint"
                );
            }
        }
    }
}

/// Every scene without refraction under adaptive AA (depth 2), in tiles of 8 pixels (the
/// last ones partial): the corner and midpoint passes through the wavefront passes
/// (`wavefront_lattice::trace_lattice_pass`) leave the megakernel passes' lattice (every
/// colour, hint and split flag) and pixels, bit for bit.
#[test]
fn adaptive_tiles_through_the_passes_are_the_megakernel_passes_tiles() {
    let mut checked = Vec::new();
    for path in chain_scenes() {
        for scene in packed(&path, AaMode::Adaptive, DebugView::None) {
            let name = common::scene_name(&path);
            assert_adaptive_tiles_match(&name, &scene);
            checked.push(name);
        }
    }
    assert_coverage(&checked, 29);
}

fn assert_adaptive_tiles_match(name: &str, scene: &PackedScene) {
    let g = &scene.globals;
    let side = 8;
    for ty in (0..g.height).step_by(side as usize) {
        for tx in (0..g.width).step_by(side as usize) {
            let tile = AdaptiveTile {
                origin: [tx, ty],
                size: [side.min(g.width - tx), side.min(g.height - ty)],
                side,
                depth: g.aa_depth,
            };
            let mut mega = Lattice::new(tile);
            let mut wave = Lattice::new(tile);
            let expected =
                adaptive_tile(scene, &mut mega, g.aa_threshold, &mut Counters::default());
            let mut counters = Counters::default();
            let actual = adaptive_tile_passes(&mut wave, g.aa_threshold, |lat, pass| {
                trace_lattice_pass(scene, lat, pass, &mut counters)
            });
            let at = format!("{name}: tile at ({tx}, {ty})");
            let point_bits = |l: &Lattice| -> Vec<[u32; 3]> {
                l.points
                    .iter()
                    .map(|p| p.to_array().map(f32::to_bits))
                    .collect()
            };
            assert!(
                point_bits(&wave) == point_bits(&mega),
                "{at}: lattice colours"
            );
            assert!(wave.hints == mega.hints, "{at}: lattice hints");
            assert!(wave.split == mega.split, "{at}: split flags");
            let pixel_bits = |p: &[(Vec3, u32)]| -> Vec<([u32; 3], u32)> {
                p.iter()
                    .map(|(c, n)| (c.to_array().map(f32::to_bits), *n))
                    .collect()
            };
            assert!(pixel_bits(&actual) == pixel_bits(&expected), "{at}: pixels");
        }
    }
}

/// The scene files whose renders have refraction (a sample's paths form a tree).
const TREE_SCENES: &[&str] = &["scenes-glass", "scenes-csg", "scenes-scrabble"];

/// Every render with refraction of scenes/ and the corpus, its name and the scene.
fn tree_scenes(aa: AaMode) -> Vec<(String, PackedScene)> {
    let mut scenes = Vec::new();
    for path in chain_scenes() {
        for scene in packed_where(&path, aa, DebugView::None, true) {
            scenes.push((common::scene_name(&path), scene));
        }
    }
    let names: Vec<&String> = scenes.iter().map(|(n, _)| n).collect();
    for required in TREE_SCENES {
        assert!(
            names.iter().any(|n| n.starts_with(required)),
            "{required} was not compared (compared: {names:?})"
        );
    }
    scenes
}

#[test]
fn passes_render_every_tree_scene_as_trace_ray_does() {
    for aa in [AaMode::None, AaMode::Uniform] {
        for (name, scene) in tree_scenes(aa) {
            assert_films_match(&format!("{name} {aa:?}"), &scene, 37);
        }
    }
}

#[test]
fn passes_sample_every_lattice_point_of_tree_scenes_as_lattice_sample_does() {
    for (name, scene) in tree_scenes(AaMode::Adaptive) {
        assert_lattice_matches(&name, &scene);
    }
}

/// What a batch's run through the passes reached: the largest pending count of a path
/// and the most glass shadow rounds of a generation.
#[derive(Debug, Default)]
struct Reach {
    pending: u32,
    rounds: u32,
}

/// `trace_batch`'s loop for a scene with refraction, pass by pass, noting its [`Reach`].
fn trace_tree_batch(scene: &PackedScene, source: &SampleSource) -> (Batch, Reach) {
    let mut counters = Counters::default();
    let mut batch = Batch::default();
    let mut reach = Reach::default();
    camera_pass(scene, source, &mut batch);
    loop {
        reach.pending = reach
            .pending
            .max(batch.paths.pending.iter().copied().max().unwrap_or(0));
        closest_pass(scene, &mut batch, &mut counters);
        shade_pass(scene, &mut batch, &mut counters);
        shadow_pass(scene, &mut batch, &mut counters);
        reach.rounds = reach
            .rounds
            .max(glass_shadow_pass(scene, &mut batch, &mut counters));
        gather_pass(scene, &mut batch, &mut counters);
        if !wavefront_args(&mut batch) {
            fold_pass(&mut batch);
            return (batch, reach);
        }
    }
}

fn overrides_at(max_depth: u32, w: u32, h: u32) -> OptionOverrides {
    OptionOverrides {
        aa: Some(AaMode::None),
        max_depth: Some(TraceDepth::constant(max_depth)),
        width: Some(w),
        height: Some(h),
        ..OptionOverrides::default()
    }
}

#[test]
fn passes_drop_the_rays_trace_ray_drops_when_its_stack_is_full() {
    let film_at = |max_depth: u32| {
        let scene =
            common::packed_from_source(FULL_STACK_SCENE, &overrides_at(max_depth, 8, 6)).remove(0);
        assert!(scene.features.contains(SceneFeatures::REFRACTION));
        let film = reference_film(&scene, &mut Counters::default());
        (scene, film)
    };
    // trace_ray drops: the reflected ray of the vertex at stack index RAY_STACK_SIZE − 1
    // (depth 15) is never traced, so depth 16 ends every path as deeper limits do — and
    // the depth limit still matters below it.
    let full = RAY_STACK_SIZE;
    let (scene, deep) = film_at(40);
    assert_eq!(
        bits(&film_at(full).1),
        bits(&deep),
        "max_depth {full} vs 40"
    );
    assert_ne!(
        bits(&film_at(full - 1).1),
        bits(&deep),
        "max_depth {}",
        full - 1
    );
    assert_films_match("full stack", &scene, 13);
    let pixels: Vec<[u32; 2]> = (0..6).flat_map(|y| (0..8).map(move |x| [x, y])).collect();
    let source = SampleSource::Strata {
        pixels: &pixels,
        n: 1,
        uniform: false,
    };
    let (_, reach) = trace_tree_batch(&scene, &source);
    assert_eq!(
        reach.pending,
        RAY_STACK_SIZE - 1,
        "the stack's last slot used"
    );
}

#[test]
fn passes_trace_shadow_rays_through_every_crossing_trace_ray_allows() {
    // Four slabs are MAX_SHADOW_CROSSINGS surfaces: the light gets through, after every
    // round the pass allows; five are more, and block it.
    assert_eq!(MAX_SHADOW_CROSSINGS, 8);
    for (slabs, lit) in [(4, true), (5, false)] {
        let scene =
            common::packed_from_source(&slab_scene(slabs), &overrides_at(8, 12, 8)).remove(0);
        let under = Vec3::new(-3.0, 0.001, 0.0);
        let light = Vec3::new(0.0, 12.0, 0.0);
        let t = shadow_transmittance(
            &scene,
            under,
            light,
            1.0,
            &MediumStack::default(),
            &mut Counters::default(),
        );
        assert_eq!(t > 0.0, lit, "{slabs} slabs: transmittance {t}");
        let name = format!("{slabs} slabs");
        assert_films_match(&name, &scene, 29);
        let pixels: Vec<[u32; 2]> = (0..8).flat_map(|y| (0..12).map(move |x| [x, y])).collect();
        let source = SampleSource::Strata {
            pixels: &pixels,
            n: 1,
            uniform: false,
        };
        let (_, reach) = trace_tree_batch(&scene, &source);
        assert_eq!(reach.rounds, MAX_SHADOW_CROSSINGS + 1, "{name}: rounds");
    }
}

#[test]
fn passes_start_camera_rays_in_the_media_around_the_camera() {
    let scene = common::packed_from_source(UNDERWATER_SCENE, &overrides_at(8, 12, 8)).remove(0);
    assert_eq!(
        scene.globals.camera_media_count, 1,
        "the camera is under water"
    );
    assert_films_match("under water", &scene, 29);
}

/// `glint view`'s frames through the passes (the Stratum source, the GPU wavefront
/// view's twin): every chain scene of scenes/ under uniform AA, frame s of each pixel
/// added to its sum as `view_sample` adds it, for every s of n², gives `view_sample`'s
/// sums bit for bit.
#[test]
fn passes_sample_the_views_frames_as_view_sample_does() {
    use glint::tracer::sampling::progressive::{view_sample, wavefront_view_store};
    let mut checked = 0;
    for path in common::own_scenes() {
        for scene in packed(&path, AaMode::Uniform, DebugView::None) {
            let g = scene.globals;
            let pixels: Vec<[u32; 2]> = (0..g.height)
                .flat_map(|y| (0..g.width).map(move |x| [x, y]))
                .collect();
            let mut expected = vec![[0.0f32; 4]; pixels.len()];
            let mut actual = expected.clone();
            for s in 0..g.aa_samples * g.aa_samples {
                let source = SampleSource::Stratum {
                    pixels: &pixels,
                    n: g.aa_samples,
                    uniform: true,
                    s,
                };
                let batch = trace_batch(&scene, &source, &mut Counters::default());
                for (k, &[x, y]) in pixels.iter().enumerate() {
                    expected[k] = view_sample(&scene, x, y, s, expected[k]);
                }
                wavefront_view_store(&mut actual, s, &batch.samples.colour);
            }
            let bits = |sums: &[[f32; 4]]| -> Vec<[u32; 4]> {
                sums.iter().map(|p| p.map(f32::to_bits)).collect()
            };
            assert_eq!(bits(&actual), bits(&expected), "{}", path.display());
            checked += 1;
        }
    }
    assert!(checked > 5, "only {checked} scenes");
}
