//! Tier 4 of GPU parity: scenes rendered by both tracers at 128×128 and compared with
//! `diff::assert_images_match` (FLIP mean < 0.01 and ≥ 99.9% of pixels within 2/255, the
//! thresholds of Vello's `compare_gpu_cpu`: both tracers run the same f32 steps, so only
//! a few ulps of GPU sqrt/division/normalize may differ). On failure the actual, expected
//! and heat-map PNGs land in `<target tmp>/gpu_images/`.

use crate::common;

use common::{
    area_lit_floor_source, corpus, gpu_context, packed_from_file, packed_from_source, root,
};
use glint::diff::assert_images_match;
use glint::gpu::{render_gpu, GpuContext, GpuRender, GpuRenderOptions};
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::{AaMode, OptionOverrides};
use glint::tracer::sampling::render::adaptive_leaf_counts;
use std::path::PathBuf;
use std::time::Instant;

const MAX_FLIP_MEAN: f64 = 0.01;
const MIN_SHARE_WITHIN_2_255: f64 = 0.999;

fn out_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu_images")
}

fn small(aa: Option<AaMode>) -> OptionOverrides {
    OptionOverrides {
        width: Some(128),
        height: Some(128),
        aa,
        ..OptionOverrides::default()
    }
}

fn compare(ctx: &GpuContext, name: &str, scene: &PackedScene) -> SceneFeatures {
    compare_render(ctx, name, scene).info.features
}

/// [`compare`], returning the GPU's render (its leaf counts for [`assert_same_splits`]).
fn compare_render(ctx: &GpuContext, name: &str, scene: &PackedScene) -> GpuRender {
    let start = Instant::now();
    let render = render_gpu(ctx, scene, &GpuRenderOptions::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let GpuRender {
        film: gpu, info, ..
    } = &render;
    let gpu_time = start.elapsed();
    let start = Instant::now();
    let cpu = glint::tracer::render(scene, &|_, _| {});
    let cpu_time = start.elapsed();
    let report = assert_images_match(
        name,
        gpu,
        &cpu,
        MAX_FLIP_MEAN,
        MIN_SHARE_WITHIN_2_255,
        &out_dir(),
    )
    .unwrap_or_else(|message| panic!("{message}"));
    eprintln!(
        "{name}: features [{}], FLIP mean {:.5}, {:.3}% within 2/255; GPU {:.1} ms (pipelines {:.1} ms, {} chunks of row stride {}, {} CPU-fallback pixels), CPU {:.1} ms",
        info.features,
        report.flip_mean,
        report.share_within(2.0 / 255.0) * 100.0,
        gpu_time.as_secs_f64() * 1e3,
        info.compile_time.as_secs_f64() * 1e3,
        info.tiles,
        info.tile_side,
        info.cpu_fallback_pixels,
        cpu_time.as_secs_f64() * 1e3
    );
    render
}

fn corpus_scene(file: &str, aa: Option<AaMode>) -> PackedScene {
    packed_from_file(&corpus().join("a4-2021plus").join(file), &small(aa)).remove(0)
}

/// scenes/tori.lua: linked rings, a mirror ring, a fat and a spindle torus.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn tori_scene_matches() {
    let Some(ctx) = gpu_context() else { return };
    let scene = packed_from_file(&common::root().join("scenes/tori.lua"), &small(None)).remove(0);
    let features = compare(&ctx, "tori", &scene);
    assert!(features.contains(SceneFeatures::TORUS), "{features}");
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn corpus_scenes_match() {
    let Some(ctx) = gpu_context() else { return };
    for file in ["simple.lua", "nonhier.lua", "hier.lua", "instance.lua"] {
        compare(
            &ctx,
            file.trim_end_matches(".lua"),
            &corpus_scene(file, None),
        );
    }
    let cows = corpus_scene("macho-cows.lua", Some(AaMode::None));
    compare(&ctx, "macho-cows-no-aa", &cows);
}

/// The default adaptive AA over 1 000+ triangles per grid cell: with lavapipe's loop
/// limiter (65 535 loop iterations per invocation, summed over all loops, after which the
/// loops end silently), an invocation that traced a pixel's every AA sample would come out
/// dark in whole workgroups; each invocation traces one sample, and this image shows it.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn macho_cows_adaptive_matches() {
    let Some(ctx) = gpu_context() else { return };
    compare(&ctx, "macho-cows", &corpus_scene("macho-cows.lua", None));
}

fn cows_with(size: u32, overrides: OptionOverrides) -> PackedScene {
    let o = OptionOverrides {
        width: Some(size),
        height: Some(size),
        ..overrides
    };
    packed_from_file(&corpus().join("a4-2021plus").join("macho-cows.lua"), &o).remove(0)
}

/// macho-cows at 512×512 with AA none, the size `glint bench --gpu` measures: its rays
/// cross more scene cells than those of the smaller renders, so the scene walk's list of
/// pending mesh instances fills more often (a walk that skipped the instance it stopped
/// on lost the central dome here: 8.5k pixels).
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn macho_cows_at_512_matches() {
    let Some(ctx) = gpu_context() else { return };
    let scene = cows_with(
        512,
        OptionOverrides {
            aa: Some(AaMode::None),
            ..OptionOverrides::default()
        },
    );
    compare(&ctx, "macho-cows-512", &scene);
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn macho_cows_uniform_4x4_matches() {
    let Some(ctx) = gpu_context() else { return };
    let scene = cows_with(
        64,
        OptionOverrides {
            aa: Some(AaMode::Uniform),
            samples: Some(glint::scene::AaSamples::constant(4)),
            ..OptionOverrides::default()
        },
    );
    compare(&ctx, "macho-cows-uniform-4", &scene);
}

/// Adaptive AA at depths 1 and 3: the images, and the split decisions (leaf squares per
/// pixel), which must be the same on both tracers but for a few pixels whose corners
/// differ by the threshold within a few ulps.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn macho_cows_adaptive_depths_match() {
    let Some(ctx) = gpu_context() else { return };
    for depth in [1, 3] {
        let scene = cows_with(
            64,
            OptionOverrides {
                aa: Some(AaMode::Adaptive),
                aa_depth: Some(glint::scene::AaDepth::constant(depth)),
                ..OptionOverrides::default()
            },
        );
        compare(&ctx, &format!("macho-cows-adaptive-d{depth}"), &scene);
        let gpu = render_gpu(&ctx, &scene, &GpuRenderOptions::default())
            .unwrap()
            .leaf_counts;
        let cpu = adaptive_leaf_counts(&scene);
        let differ = gpu.iter().zip(&cpu).filter(|(a, b)| a != b).count();
        let split = cpu.iter().filter(|&&l| l > 1).count();
        eprintln!(
            "d={depth}: {split} of {} pixels split; {differ} differ",
            cpu.len()
        );
        assert!(split > 0);
        assert!(
            differ * 1000 <= cpu.len(),
            "d={depth}: {differ} pixels split differently"
        );
    }
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn anti_aliasing_matches() {
    let Some(ctx) = gpu_context() else { return };
    compare(
        &ctx,
        "nonhier-uniform-aa",
        &corpus_scene("nonhier.lua", Some(AaMode::Uniform)),
    );
    compare(
        &ctx,
        "nonhier-adaptive-aa",
        &corpus_scene("nonhier.lua", Some(AaMode::Adaptive)),
    );
}

/// Mirrors (the REFLECTION specialisation) over a cube floor, with a triangle.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn reflections_match() {
    let Some(ctx) = gpu_context() else { return };
    let source = "
        mirror = gr.material({0.1, 0.1, 0.1}, {0.8, 0.8, 0.8}, 80)
        mirror:set_reflection(0.7, 0.7, 0.7)
        red = gr.material({0.8, 0.2, 0.2}, {0.3, 0.3, 0.3}, 20)
        root = gr.node('root')
        floor = gr.cube('floor') floor:scale(20, 0.5, 20) floor:translate(-10, -2.5, -15)
        floor:set_material(mirror) root:add_child(floor)
        a = gr.sphere('a') a:translate(-1.5, 0, -6) a:set_material(mirror) root:add_child(a)
        b = gr.sphere('b') b:scale(0.7, 0.7, 0.7) b:translate(1.2, -0.5, -4) b:set_material(red) root:add_child(b)
        t = gr.mesh('t', {{-4, -1, -9}, {4, -1, -9}, {0, 4, -10}}, {{0, 1, 2}})
        t:set_material(red) root:add_child(t)
        l = gr.light({5, 8, 5}, {0.9, 0.9, 0.9}, {1, 0, 0})
        gr.render(root, 'mirror.png', 128, 128, {0, 1, 3}, {0, -0.1, -1}, {0, 1, 0}, 60, {0.2, 0.2, 0.2}, {l})
    ";
    let scene = packed_from_source(source, &small(None)).remove(0);
    let features = compare(&ctx, "reflections", &scene);
    assert!(features.contains(SceneFeatures::REFLECTION), "{features}");
}

/// A hall of mirrors (two parallel mirror walls, a sphere between): chains of up to
/// `max_depth` = 24 reflections. Without dielectrics the GPU's ray stack has one entry
/// (a shading point pushes at most its reflection, after its own entry was popped),
/// where the CPU's has RAY_STACK_SIZE: the images must still agree.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn deep_reflection_chains_match() {
    let Some(ctx) = gpu_context() else { return };
    let source = "
        mirror = gr.material({0.05, 0.05, 0.05}, {0.5, 0.5, 0.5}, 60)
        mirror:set_reflection(0.9, 0.9, 0.85)
        red = gr.material({0.8, 0.2, 0.2}, {0.3, 0.3, 0.3}, 20)
        blue = gr.material({0.2, 0.3, 0.8}, {0.3, 0.3, 0.3}, 20)
        root = gr.node('root')
        left = gr.cube('left') left:scale(0.2, 8, 40) left:translate(-3.2, -4, -30)
        left:set_material(mirror) root:add_child(left)
        right = gr.cube('right') right:scale(0.2, 8, 40) right:translate(3, -4, -30)
        right:set_material(mirror) root:add_child(right)
        s = gr.sphere('s') s:translate(0.8, 0, -6) s:set_material(red) root:add_child(s)
        c = gr.cube('c') c:translate(-1.5, -1.5, -9) c:set_material(blue) root:add_child(c)
        l = gr.light({0, 3, 0}, {0.9, 0.9, 0.9}, {1, 0, 0})
        gr.render(root, 'hall.png', 96, 64, {0, 0.5, 2}, {0.6, -0.05, -1}, {0, 1, 0}, 70,
                  {0.2, 0.2, 0.2}, {l}, {max_depth = 24, min_weight = 0.001})
    ";
    let scene = packed_from_source(source, &small(None)).remove(0);
    assert_eq!(scene.globals.max_depth, 24);
    let features = compare(&ctx, "hall of mirrors", &scene);
    assert!(features.contains(SceneFeatures::REFLECTION), "{features}");
    assert!(!features.contains(SceneFeatures::REFRACTION), "{features}");
    // The chains are long: cut at 8 reflections, the image changes.
    let shallow = OptionOverrides {
        max_depth: glint::scene::TraceDepth::new(8),
        ..small(None)
    };
    let cut = packed_from_source(source, &shallow).remove(0);
    assert_eq!(cut.globals.max_depth, 8);
    assert_ne!(
        common::render_cpu(&scene).pixels,
        common::render_cpu(&cut).pixels,
        "no chain is longer than 8 reflections: the test proves nothing"
    );
}

/// The loop-limit guard end to end: asking the limiter check for more iterations than
/// lavapipe's limit (65 535) trips the limiter in every invocation, so on a software
/// adapter every pixel is flagged and re-rendered on the CPU — and the image is still
/// right. (On a hardware adapter the check never trips and nothing is re-rendered.)
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn loop_limit_guard_falls_back_to_the_cpu() {
    let Some(ctx) = gpu_context() else { return };
    for aa in [AaMode::None, AaMode::Uniform, AaMode::Adaptive] {
        let overrides = OptionOverrides {
            width: Some(24),
            height: Some(20),
            aa: Some(aa),
            samples: Some(glint::scene::AaSamples::constant(2)),
            aa_depth: Some(glint::scene::AaDepth::constant(2)),
            ..OptionOverrides::default()
        };
        let scene = packed_from_file(
            &corpus().join("a4-2021plus").join("nonhier.lua"),
            &overrides,
        )
        .remove(0);
        let tripping = GpuRenderOptions {
            limiter_sentinel: 70_000,
            ..GpuRenderOptions::default()
        };
        let GpuRender {
            film: gpu, info, ..
        } = render_gpu(&ctx, &scene, &tripping).unwrap();
        let expected = if info.kernel.iteration_guard {
            24 * 20
        } else {
            0
        };
        eprintln!(
            "{aa:?}: guard {}, {} pixels re-rendered",
            info.kernel.iteration_guard, info.cpu_fallback_pixels
        );
        assert_eq!(info.cpu_fallback_pixels, expected, "{aa:?}");
        let cpu = glint::tracer::render(&scene, &|_, _| {});
        assert_images_match(
            &format!("guard-{aa:?}"),
            &gpu,
            &cpu,
            MAX_FLIP_MEAN,
            MIN_SHARE_WITHIN_2_255,
            &out_dir(),
        )
        .unwrap_or_else(|message| panic!("{message}"));
    }
}

/// Leaf squares per pixel of adaptive AA in `gpu` (the GPU tracer's render of `scene`) and
/// on the CPU tracer: identical, and some pixels split.
fn assert_same_splits(name: &str, scene: &PackedScene, gpu: &GpuRender) {
    let gpu = &gpu.leaf_counts;
    let cpu = adaptive_leaf_counts(scene);
    let differ: Vec<usize> = (0..cpu.len()).filter(|&k| gpu[k] != cpu[k]).collect();
    let split = cpu.iter().filter(|&&l| l > 1).count();
    eprintln!(
        "{name}: {split} of {} pixels split; {} differ",
        cpu.len(),
        differ.len()
    );
    let w = scene.globals.width as usize;
    for &k in differ.iter().take(10) {
        eprintln!(
            "  pixel ({}, {}): GPU {} leaves, CPU {}",
            k % w,
            k / w,
            gpu[k],
            cpu[k]
        );
    }
    assert!(split > 0, "{name}: nothing split");
    assert!(
        differ.is_empty(),
        "{name}: {} pixels split differently",
        differ.len()
    );
}

/// Penumbra splits (a lattice sample whose area light was partly occluded among its
/// shadow samples splits its squares down to AA_FINE_DETAIL_DEPTH) on the soft-shadow
/// scene: the same samples-per-pixel map on both tracers, with the scene's threshold and
/// with one no contrast exceeds (penumbrae alone split).
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn soft_shadows_split_the_same() {
    let Some(ctx) = gpu_context() else { return };
    for (name, threshold) in [
        ("soft-shadows-adaptive", None),
        ("soft-shadows-penumbrae", Some(f32::MAX)),
    ] {
        let overrides = OptionOverrides {
            width: Some(64),
            height: Some(64),
            aa: Some(AaMode::Adaptive),
            aa_threshold: threshold,
            ..OptionOverrides::default()
        };
        let scene = packed_from_file(&root().join("scenes/soft-shadows.lua"), &overrides).remove(0);
        let gpu = compare_render(&ctx, name, &scene);
        assert_same_splits(name, &scene, &gpu);
    }
}

/// Item-edge splits (squares whose samples hit different items split down to
/// AA_ITEM_EDGE_DEPTH whatever their contrast): two walls of the same colour, and
/// macho-cows with a threshold no contrast exceeds (only its silhouettes and the edges
/// between its objects split): the same samples-per-pixel maps on both tracers.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn item_edge_splits_match() {
    let Some(ctx) = gpu_context() else { return };
    let overrides = OptionOverrides {
        aa: Some(AaMode::Adaptive),
        aa_threshold: Some(f32::MAX),
        ..OptionOverrides::default()
    };
    let walls =
        common::packed_from_source(&common::two_walls_source(1.0, 1.0), &overrides).remove(0);
    let gpu = compare_render(&ctx, "same-colour-walls", &walls);
    assert_same_splits("same-colour-walls", &walls, &gpu);
    let cows = cows_with(
        48,
        OptionOverrides {
            aa_depth: Some(glint::scene::AaDepth::constant(3)),
            ..overrides
        },
    );
    let gpu = compare_render(&ctx, "macho-cows-item-edges", &cows);
    assert_same_splits("macho-cows-item-edges", &cows, &gpu);
}

/// Splits from what a mirror shows (the item its reflected ray hits keys a sample too:
/// mirrored walls of one colour, a threshold no contrast exceeds) and from texture detail
/// at the pixel's scale (thin lines on a quad, `striped_quad`): the same images and the
/// same samples-per-pixel maps on both tracers (a twin that keys by the mirror alone, or
/// does not look at the texture, splits nothing or fewer pixels there).
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn mirror_and_texture_detail_splits_match() {
    let Some(ctx) = gpu_context() else { return };
    let overrides = OptionOverrides {
        aa: Some(AaMode::Adaptive),
        aa_threshold: Some(f32::MAX),
        ..OptionOverrides::default()
    };
    let mirror = packed_from_source(&common::mirrored_walls_source(), &overrides).remove(0);
    let gpu = compare_render(&ctx, "mirrored-walls", &mirror);
    assert_same_splits("mirrored-walls", &mirror, &gpu);
    let dir = common::temp_dir("gpu-texture-detail");
    let stripes = common::striped_quad(
        &dir,
        &OptionOverrides {
            aa_threshold: Some(0.15),
            aa_depth: Some(glint::scene::AaDepth::constant(3)),
            ..overrides
        },
    );
    let gpu = compare_render(&ctx, "striped-quad", &stripes);
    assert_same_splits("striped-quad", &stripes, &gpu);
}

/// A pixel centre's shadow jitter mirrors its pixel's corners' (shadow_stream,
/// shadow_random): a shiny floor under a large area light with one shadow sample and
/// nothing to split, so each pixel is the quincunx mean and its colour moves with where
/// the centre's one sample falls on the light. Both tracers must draw the same points (a
/// centre mirrored from other corners, or not at all, moves most pixels by more than
/// 2/255).
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn mirrored_shadow_jitter_matches() {
    let Some(ctx) = gpu_context() else { return };
    let source = area_lit_floor_source(0.6, 0.6, 20.0);
    let overrides = OptionOverrides {
        aa: Some(AaMode::Adaptive),
        aa_threshold: Some(f32::MAX),
        aa_depth: Some(glint::scene::AaDepth::constant(1)),
        shadow_samples: Some(glint::scene::ShadowSamples::constant(1)),
        ..OptionOverrides::default()
    };
    let scene = packed_from_source(&source, &overrides).remove(0);
    let features = compare(&ctx, "mirrored-shadow-jitter", &scene);
    assert!(features.contains(SceneFeatures::AREA_LIGHT), "{features}");
}

/// An area light's soft shadows (the AREA_LIGHT specialisation) under the default
/// adaptive AA and under uniform AA: both tracers draw the same shadow samples, and
/// adaptive AA splits the same squares (penumbrae included) on both.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn area_light_matches() {
    let Some(ctx) = gpu_context() else { return };
    let source = "
        grey = gr.material({0.7, 0.7, 0.7}, {0.3, 0.3, 0.3}, 25)
        red = gr.material({0.8, 0.2, 0.2}, {0.5, 0.5, 0.5}, 40)
        mirror = gr.material({0.1, 0.1, 0.1}, {0.8, 0.8, 0.8}, 80)
        mirror:set_reflection(0.6, 0.6, 0.6)
        root = gr.node('root')
        floor = gr.cube('floor') floor:scale(10, 0.5, 10) floor:translate(-5, -1.5, -9)
        floor:set_material(grey) root:add_child(floor)
        s = gr.sphere('s') s:translate(-0.8, 0, -4) s:set_material(red) root:add_child(s)
        m = gr.sphere('m') m:scale(0.6, 0.6, 0.6) m:translate(1.2, -0.4, -3.5)
        m:set_material(mirror) root:add_child(m)
        a = gr.area_light({0, 4, -3}, {2.5, 0, 0}, {0, 0, 2.5}, {0.8, 0.8, 0.8}, {1, 0, 0})
        p = gr.light({-4, 3, 2}, {0.3, 0.3, 0.3}, {1, 0, 0})
        gr.render(root, 'area.png', 96, 96, {0, 2, 3}, {0, -0.4, -1}, {0, 1, 0}, 50,
                  {0.1, 0.1, 0.1}, {a, p})
    ";
    for (name, aa) in [
        ("area-light-adaptive", None),
        ("area-light-uniform", Some(AaMode::Uniform)),
    ] {
        let overrides = OptionOverrides {
            width: Some(96),
            height: Some(96),
            aa,
            samples: Some(glint::scene::AaSamples::constant(2)),
            ..OptionOverrides::default()
        };
        let scene = packed_from_source(source, &overrides).remove(0);
        let gpu = compare_render(&ctx, name, &scene);
        let features = gpu.info.features;
        assert!(features.contains(SceneFeatures::AREA_LIGHT), "{features}");
        if aa.is_none() {
            assert_same_splits(name, &scene, &gpu);
        }
    }
}

/// Issue 37 on the GPU: a light lying in a surface (a ceiling's face, also through glass;
/// a shelf's edge; inside a panel thinner than the shadow-ray bound; an area light in the
/// ceiling's plane) at scales 1, 10⁻³ and 10³ leaves no pixel more than 16/255 darker
/// than the light moved 0.01 off it (the CPU's limit, tests/oracle/shading.rs), and each
/// matches the CPU's image (src/tracer/base/ray.wgsl::shadow_reach is the twin of the CPU's).
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn light_on_a_surface_does_not_speckle_on_the_gpu() {
    use common::light_on_surface::{light_on_surface_scene, speckle, LightOnSurface};
    let Some(ctx) = gpu_context() else { return };
    let gpu = |scene: &PackedScene| {
        render_gpu(&ctx, scene, &GpuRenderOptions::default())
            .unwrap_or_else(|e| panic!("{e}"))
            .film
    };
    let mut failures = Vec::new();
    for case in LightOnSurface::ALL {
        let (on, off) = (
            light_on_surface_scene(case, 0.0),
            light_on_surface_scene(case, 0.01),
        );
        for s in [1.0, 1e-3, 1e3] {
            let pack =
                |scene| glint::pipeline::pack_scene(&common::scaled_scene(scene, s)).unwrap();
            let packed = pack(&on);
            let (darker, isolated) = speckle(&gpu(&packed), &gpu(&pack(&off)));
            eprintln!(
                "GPU {case:?} at scale {s}: {:.3}% of pixels darker by 16/255, {:.3}% isolated",
                darker * 100.0,
                isolated * 100.0
            );
            if darker > 0.001 {
                failures.push(format!("{case:?} at scale {s}: {:.3}%", darker * 100.0));
            }
            if s == 1.0 {
                compare(&ctx, &format!("light-on-surface-{case:?}"), &packed);
            }
        }
    }
    assert!(failures.is_empty(), "speckle on the GPU: {failures:?}");
}

/// Smooth meshes (interpolated vertex normals, the terminator rule): scenes/smooth.lua
/// (the OBJ torus smooth and, through `readobj`, flat; the same OBJ instanced as a smooth
/// mirror; an inline mesh with normals and UVs, smooth and bump-mapped on top) and the
/// POV-Ray comparison torus, and a smooth glass ball, on both tracers; and scenes/smooth.lua under
/// `shading = 'flat'`, which packs no normals and compiles no smooth code.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn smooth_meshes_match() {
    use glint::scene::Shading;
    let Some(ctx) = gpu_context() else { return };
    let smooth = root().join("scenes/smooth.lua");
    let scene = packed_from_file(&smooth, &small(Some(AaMode::None))).remove(0);
    let features = compare(&ctx, "smooth", &scene);
    for feature in [
        SceneFeatures::SMOOTH,
        SceneFeatures::BUMP,
        SceneFeatures::REFLECTION,
    ] {
        assert!(features.contains(feature), "{features}");
    }
    let torus = root().join("scenes/meshes/torus-povray.lua");
    let scene = packed_from_file(&torus, &OptionOverrides::default()).remove(0);
    assert!(compare(&ctx, "smooth-torus", &scene).contains(SceneFeatures::SMOOTH));
    let flat = OptionOverrides {
        shading: Some(Shading::Flat),
        ..small(Some(AaMode::None))
    };
    let scene = packed_from_file(&smooth, &flat).remove(0);
    assert!(scene.triangle_normals.is_empty());
    assert!(!compare(&ctx, "smooth-flat", &scene).contains(SceneFeatures::SMOOTH));
    // A smooth glass ball (refraction by the interpolated normals) over a floor.
    let glass = format!(
        "m = gr.material({{0, 0, 0}}, {{0.8, 0.8, 0.8}}, 80) m:set_refraction(1.5)\n\
         f = gr.material({{0.7, 0.6, 0.4}}, {{0, 0, 0}}, 1)\nroot = gr.node('root')\n{}\
         floor = gr.cube('floor') floor:set_material(f) floor:scale(8, 0.1, 8) floor:translate(-4, -1.2, -4) root:add_child(floor)\n\
         gr.render(root, 'x.png', 128, 128, {{0, 1, 4}}, {{0, -0.25, -1}}, {{0, 1, 0}}, 40, {{0.2, 0.2, 0.2}}, \
         {{gr.light({{-3, 5, 4}}, {{0.9, 0.9, 0.9}}, {{1, 0, 0}})}})\n",
        common::smooth_sphere_lua("ball", 24, 12, 1.0, glam::DVec3::ZERO)
    );
    let scene = packed_from_source(&glass, &small(Some(AaMode::None))).remove(0);
    let features = compare(&ctx, "smooth-glass", &scene);
    for feature in [SceneFeatures::SMOOTH, SceneFeatures::REFRACTION] {
        assert!(features.contains(feature), "{features}");
    }
}
