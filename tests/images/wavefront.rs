//! The wavefront passes (`cpu::wavefront`) against the megakernel form (`trace_ray`) on
//! the CPU: every scene of scenes/ and the CS488 corpus without refraction, at a small
//! size, renders to the same bits through both — AA none and uniform AA as whole films
//! (with the traversal counters' totals: the same rays traced), adaptive AA as every
//! point of the finest lattice (its colour and its hint), since the adaptive passes
//! sample nothing but lattice points.

use crate::common;

use glint::cpu::pixel_sample::lattice_sample;
use glint::cpu::render::render_pixel;
use glint::cpu::traverse::Counters;
use glint::cpu::wavefront::{render_film, trace_batch, SampleSource};
use glint::film::Film;
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::{AaDepth, AaMode, AaSamples, DebugView, OptionOverrides};
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

/// The megakernel form's film, pixel by pixel as `cpu::render` computes them.
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
            p as u32 % W,
            p as u32 / W,
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
