//! The wavefront kernels of scenes with refraction (`src/tracer/wavefront/wavefront_tree.wgsl` with
//! `src/tracer/wavefront/wavefront.wgsl`: pending counts, the vertex tree and its fold, glass shadow
//! rounds), rendered on lavapipe with the hardware variant: the megakernel `main`'s image
//! bit for bit and the CPU's within the GPU parity tolerance
//! (`gpu_wavefront::assert_wavefront_matches`), on the repository's glass scenes and on
//! the CPU twin's test scenes (tests/images/wavefront.rs): a scene that fills the ray
//! stack, a floor under 4 and 5 glass slabs, the camera under water.

use crate::common;
use crate::gpu_wavefront::{assert_wavefront_matches, view_sums};

use common::tree_scenes::{slab_scene, FULL_STACK_SCENE, UNDERWATER_SCENE};
use common::{gpu_context, packed_from_file, packed_from_source};
use glint::gpu::KernelVariant;
use glint::pack::SceneFeatures;
use glint::scene::bounded::AaSamples;
use glint::scene::{AaDepth, AaMode, OptionOverrides, TraceDepth};

fn overrides_at(max_depth: Option<u32>, w: u32, h: u32) -> OptionOverrides {
    OptionOverrides {
        aa: Some(AaMode::None),
        max_depth: max_depth.map(TraceDepth::constant),
        width: Some(w),
        height: Some(h),
        ..OptionOverrides::default()
    }
}

/// scenes/glass.lua, csg.lua and scrabble.lua (small) through the tree's wavefront.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn hardware_wavefront_renders_mains_image_of_glass_scenes() {
    let Some(mut ctx) = gpu_context() else { return };
    ctx.force_kernel_variant(KernelVariant::Hardware);
    for (file, w, h) in [
        ("scenes/glass.lua", 40, 30),
        ("scenes/csg.lua", 40, 30),
        ("scenes/scrabble.lua", 24, 16),
    ] {
        let scene =
            packed_from_file(&common::root().join(file), &overrides_at(None, w, h)).remove(0);
        assert!(scene.features.contains(SceneFeatures::REFRACTION), "{file}");
        assert_wavefront_matches(&mut ctx, file, &scene);
    }
}

/// The CPU twin's tree scenes: the full ray stack (max_depth 40: pending counts up to
/// 15, the rays trace_ray drops), 4 and 5 slabs (every shadow round), under water.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn hardware_wavefront_renders_mains_image_of_tree_edge_cases() {
    let Some(mut ctx) = gpu_context() else { return };
    ctx.force_kernel_variant(KernelVariant::Hardware);
    let mut scenes = vec![
        (
            "full stack".to_string(),
            packed_from_source(FULL_STACK_SCENE, &overrides_at(Some(40), 8, 6)).remove(0),
        ),
        (
            "under water".to_string(),
            packed_from_source(UNDERWATER_SCENE, &overrides_at(Some(8), 12, 8)).remove(0),
        ),
    ];
    for slabs in [4, 5] {
        let scene = packed_from_source(&slab_scene(slabs), &overrides_at(Some(8), 12, 8));
        scenes.push((format!("{slabs} slabs"), scene.into_iter().next().unwrap()));
    }
    assert_eq!(scenes[1].1.globals.camera_media_count, 1, "under water");
    for (name, scene) in &scenes {
        assert!(scene.features.contains(SceneFeatures::REFRACTION), "{name}");
        assert_wavefront_matches(&mut ctx, name, scene);
    }
}

/// The camera inside a glass shell (index 1.5 and a 0.9 mirror) around a glass ball: a
/// ray that meets the ball splits in two at every surface and both halves stay inside,
/// so a sample's tree grows toward 2^9 vertices at max_depth 8 — more than the queues'
/// room (TREE_PATHS_PER_SAMPLE paths a generation, TREE_VERTICES_PER_SAMPLE vertices a
/// sample). A white box fills the lower right of the view: its pixels spawn no rays.
const BUSHY_SCENE: &str = r#"
glass = gr.material({0.1, 0.1, 0.1}, {0.5, 0.5, 0.5}, 50)
glass:set_reflection(0.9, 0.9, 0.9)
glass:set_refraction(1.5)
root = gr.node('root')
shell = gr.nh_sphere('shell', {0, 0, 0}, 10)
shell:set_material(glass)
root:add_child(shell)
ball = gr.nh_sphere('ball', {0, 0, -4}, 3)
ball:set_material(glass)
root:add_child(ball)
white = gr.material({0.8, 0.8, 0.8}, {0.2, 0.2, 0.2}, 20)
wall = gr.nh_box('wall', {0.5, -4, -1}, 4)
wall:set_material(white)
root:add_child(wall)
gr.render(root, 'bushy.png', 8, 6, {0, 0, 5}, {0, 0, -1}, {0, 1, 0}, 50,
          {0.3, 0.3, 0.3}, {gr.light({0, 5, 0}, {0.8, 0.8, 0.8}, {1, 0, 0})})
"#;

/// Where a tree outgrows the queues, no ray is lost: the children without room set their
/// pixel's guard flag and the host renders those pixels with the CPU tracer (its bits);
/// the image is the CPU's within the parity tolerance.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn hardware_wavefront_hands_pixels_without_room_to_the_cpu() {
    let Some(mut ctx) = gpu_context() else { return };
    ctx.force_kernel_variant(KernelVariant::Hardware);
    let scene = packed_from_source(BUSHY_SCENE, &overrides_at(Some(8), 8, 6)).remove(0);
    let render = glint::gpu::render_gpu(&ctx, &scene, &glint::gpu::GpuRenderOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let handed = render.info.cpu_fallback_pixels;
    eprintln!("bushy: {handed} of 48 pixels handed to the CPU");
    assert!(handed > 0, "no pixel outgrew the queues");
    assert!(
        handed < 48,
        "the box's pixels spawn no rays: traced on the GPU"
    );
    let cpu = glint::tracer::sampling::render::render(&scene, &|_, _| {});
    let bits = |p: &[f32; 3]| p.map(f32::to_bits);
    let cpu_bits = render
        .film
        .pixels
        .iter()
        .zip(&cpu.pixels)
        .filter(|(g, c)| bits(g) == bits(c))
        .count();
    assert!(
        cpu_bits as u64 >= handed,
        "{handed} pixels handed to the CPU, {cpu_bits} with its bits"
    );
    common::assert_gpu_matches_cpu(&ctx, "gpu_wavefront", "bushy", &scene, 0.01);
}

/// `overrides_at` under uniform n×n AA.
fn uniform_at(n: u32, w: u32, h: u32) -> OptionOverrides {
    OptionOverrides {
        aa: Some(AaMode::Uniform),
        samples: Some(AaSamples::new(n.into()).unwrap()),
        ..overrides_at(None, w, h)
    }
}

/// scenes/glass.lua and csg.lua (small) under uniform 2×2 AA through the tree's
/// wavefront (the strata of the camera pass, the generations and rounds, the fold into
/// each sample's record, the resolve pass): the megakernel passes' (uniform_samples +
/// uniform_resolve) image bit for bit where their pixel is their own, the CPU's within
/// the tolerance.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn hardware_wavefront_renders_uniform_aa_of_glass_scenes() {
    let Some(mut ctx) = gpu_context() else { return };
    ctx.force_kernel_variant(KernelVariant::Hardware);
    for (file, w, h) in [("scenes/glass.lua", 20, 15), ("scenes/csg.lua", 20, 15)] {
        let scene = packed_from_file(&common::root().join(file), &uniform_at(2, w, h)).remove(0);
        assert!(scene.features.contains(SceneFeatures::REFRACTION), "{file}");
        assert_eq!(scene.globals.aa_mode, glint::constants::AA_UNIFORM);
        assert_wavefront_matches(&mut ctx, &format!("{file} at 2×2"), &scene);
    }
}

/// scenes/glass.lua and csg.lua (small) under adaptive AA at depths 1 and 2 through the
/// tree's wavefront (per lattice pass the lattice camera pass with the camera's media,
/// the generations and rounds, the fold into each traced point's record, the store): the
/// megakernel passes' (adaptive_corners, adaptive_midpoints) image bit for bit where
/// their pixel is their own, the CPU's within the tolerance.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn hardware_wavefront_traces_adaptive_aa_of_glass_scenes() {
    let Some(mut ctx) = gpu_context() else { return };
    ctx.force_kernel_variant(KernelVariant::Hardware);
    for (file, depth) in [
        ("scenes/glass.lua", 1),
        ("scenes/glass.lua", 2),
        ("scenes/csg.lua", 2),
    ] {
        let options = OptionOverrides {
            aa: Some(AaMode::Adaptive),
            aa_depth: Some(AaDepth::constant(depth)),
            ..overrides_at(None, 20, 15)
        };
        let scene = packed_from_file(&common::root().join(file), &options).remove(0);
        assert!(scene.features.contains(SceneFeatures::REFRACTION), "{file}");
        assert_eq!(scene.globals.aa_mode, glint::constants::AA_ADAPTIVE);
        assert_wavefront_matches(&mut ctx, &format!("{file} at depth {depth}"), &scene);
    }
}

/// `glint view` of scenes/glass.lua (uniform 2×2: four frames; and AA none) on lavapipe with
/// the hardware variant, where `view_sample` is not in the module: each frame through the
/// tree's wavefront (camera pass of the frame's stratum, generations and rounds, the fold
/// into each sample's record, the store into the sums) gives `view_sample`'s sums bit
/// for bit.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn hardware_wavefront_view_sums_of_glass_are_view_samples() {
    let Some(mut ctx) = gpu_context() else { return };
    ctx.force_kernel_variant(KernelVariant::Hardware);
    let hardware = ctx.kernel;
    for (options, frames) in [(uniform_at(2, 16, 12), 4), (overrides_at(None, 16, 12), 1)] {
        let file = "scenes/glass.lua";
        let scene = packed_from_file(&common::root().join(file), &options).remove(0);
        assert!(scene.features.contains(SceneFeatures::REFRACTION));
        assert!(!glint::gpu::compile::shader::Entry::ViewSample.exists_in(hardware, scene.features));
        let (wave, through_wavefront, _) = view_sums(&ctx, &scene, frames);
        assert!(through_wavefront, "{file}");
        ctx.kernel = glint::gpu::KernelConfig {
            wavefront: false,
            ..hardware
        };
        let (mega, through_wavefront, _) = view_sums(&ctx, &scene, frames);
        ctx.kernel = hardware;
        assert!(!through_wavefront, "{file}: view_sample");
        let bits = |sums: &[[f32; 4]]| -> Vec<[u32; 4]> {
            sums.iter().map(|p| p.map(f32::to_bits)).collect()
        };
        let (wave, mega) = (bits(&wave), bits(&mega));
        let differing = (0..mega.len()).filter(|&p| wave[p] != mega[p]).count();
        assert_eq!(
            differing, 0,
            "{file}, {frames} frames: sums differ from view_sample's"
        );
        assert!(wave.iter().all(|s| f32::from_bits(s[3]) == frames as f32));
    }
}

/// scenes/glass.lua at 96×80 — several chunks, each generation's shadow pass several
/// workgroups — rendered `RUNS` times in each AA mode by `glint render --kernel-variant
/// hardware` in a process of its own with 16 llvmpipe worker threads (more threads than
/// cores, so the workgroups of one dispatch interleave): every run the same pixels (the
/// determinism rule) and the CPU's image within the parity tolerance. A pass must not
/// read a counter that its own invocations write: the tree's light points, once written
/// by the shadow pass's invocation 0 and read by every invocation's `store_leg`, put the
/// legs of the workgroups that ran first at the wrong place (a chunk's lower rows
/// garbage) in 5 of 12 runs under AA none with 16 threads; the camera pass writes them
/// now.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn hardware_wavefront_renders_glass_the_same_every_run_over_several_chunks() {
    const RUNS: usize = 5;
    if gpu_context().is_none() {
        return;
    }
    let dir = common::temp_dir("glass_every_run");
    let file = common::root().join("scenes/glass.lua");
    let adaptive = OptionOverrides {
        aa: Some(AaMode::Adaptive),
        aa_depth: Some(AaDepth::constant(1)),
        ..overrides_at(None, 96, 80)
    };
    for (mode, flags, options) in [
        ("none", vec!["--aa", "none"], overrides_at(None, 96, 80)),
        (
            "uniform",
            vec!["--aa", "uniform", "--samples", "2"],
            uniform_at(2, 96, 80),
        ),
        (
            "adaptive",
            vec!["--aa", "adaptive", "--aa-depth", "1"],
            adaptive,
        ),
    ] {
        let render = |run: usize| {
            let out = dir.join(format!("{mode}-{run}.exr"));
            let status = std::process::Command::new(env!("CARGO_BIN_EXE_glint"))
                .args([
                    "render",
                    file.to_str().unwrap(),
                    "-o",
                    out.to_str().unwrap(),
                ])
                .args(["--width", "96", "--height", "80", "--backend", "gpu"])
                .args(["--kernel-variant", "hardware", "--stats"])
                .args(&flags)
                .env(glint::gpu::device::context::LLVMPIPE_THREADS_VAR, "16")
                .output()
                .expect("glint runs");
            let stderr = String::from_utf8_lossy(&status.stderr);
            assert!(status.status.success(), "{mode}, run {run}: {stderr}");
            assert!(!stderr.contains(" 1 chunks"), "{mode}: one chunk: {stderr}");
            let film = glint::image_io::read_image(&out).unwrap();
            film.pixels
                .iter()
                .map(|p| p.map(f32::to_bits))
                .collect::<Vec<_>>()
        };
        let first = render(0);
        for run in 1..RUNS {
            let again = render(run);
            let differing = (0..first.len()).filter(|&p| again[p] != first[p]).count();
            assert_eq!(
                differing, 0,
                "glass.lua, AA {mode}: run {run}'s pixels differ from run 0's"
            );
        }
        let gpu = glint::image_io::read_image(&dir.join(format!("{mode}-0.exr"))).unwrap();
        let scene = packed_from_file(&file, &options).remove(0);
        let cpu = glint::tracer::render(&scene, &|_, _| {});
        let out = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu_wavefront");
        glint::diff::assert_images_match(
            &format!("glass AA {mode}"),
            &gpu,
            &cpu,
            0.01,
            0.999,
            &out,
        )
        .unwrap_or_else(|message| panic!("{message}"));
    }
}
