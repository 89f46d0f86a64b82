//! The wavefront kernels (`shaders/wavefront.wgsl`, `KernelConfig::wavefront`: AA none in
//! the hardware variant; with refraction also `shaders/wavefront_tree.wgsl`, whose scenes
//! `gpu_wavefront_tree.rs` renders): naga validates them for every feature
//! set, the software variant's modules never include them, and rendered on
//! lavapipe with `--kernel-variant hardware` they give the megakernel's image bit for bit
//! (and so the CPU tracer's, within the GPU parity tolerance)
//! on scenes with mirrors (several generations), area lights, textures and bump maps,
//! smooth meshes, tori, meshes in grids and CSG.

use crate::common;

use common::{gpu_context, packed_from_file, packed_from_source};
use glint::gpu::shader::{all_feature_sets, assemble_with, validate, wavefront_kernels, Entry};
use glint::gpu::{render_gpu, GpuContext, GpuRenderOptions, KernelConfig, KernelVariant};
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::{AaMode, OptionOverrides};

/// Every feature set: the hardware variant's render module has the six wavefront entry
/// points, valid under naga, and with refraction the tree's four more (and its file) —
/// only then; the software variant's never mentions them (its modules are what they were
/// before the wavefront kernels: the files are not even appended).
#[test]
fn wavefront_kernels_validate_where_they_exist() {
    let limits = wgpu::Limits::default();
    let hardware = KernelConfig::for_variant(KernelVariant::Hardware, &limits);
    let software = KernelConfig::for_variant(KernelVariant::Software, &limits);
    let (mut validated, mut trees) = (0, 0);
    for features in all_feature_sets() {
        let tree = features.contains(SceneFeatures::REFRACTION);
        assert!(wavefront_kernels(hardware, features), "[{features}]");
        assert!(!wavefront_kernels(software, features), "[{features}]");
        let soft = assemble_with(features, Entry::Render, software);
        assert!(!soft.contains("wavefront"), "[{features}] software module");
        let hard = assemble_with(features, Entry::Render, hardware);
        assert!(hard.contains("shaders/wavefront.wgsl"), "[{features}]");
        assert_eq!(
            hard.contains("shaders/wavefront_tree.wgsl"),
            tree,
            "[{features}]"
        );
        let module = validate(&hard, features).unwrap_or_else(|e| panic!("{e}"));
        let entries = if tree {
            &Entry::WAVEFRONT_TREE[..]
        } else {
            &Entry::WAVEFRONT[..]
        };
        for entry in entries {
            assert!(
                module.entry_points.iter().any(|e| e.name == entry.name()),
                "[{features}] {entry:?}"
            );
            assert!(entry.exists_in(hardware, features) && !entry.exists_in(software, features));
        }
        for entry in Entry::ALL.into_iter().filter(|e| e.is_wavefront_tree()) {
            let exists = module.entry_points.iter().any(|e| e.name == entry.name());
            assert_eq!(exists, tree, "[{features}] {entry:?}");
            assert_eq!(entry.exists_in(hardware, features), tree);
        }
        validated += 1;
        trees += tree as u32;
    }
    assert!(validated > 20, "only {validated} feature sets validated");
    assert!(
        trees > 10,
        "only {trees} feature sets with refraction validated"
    );
}

fn small() -> OptionOverrides {
    OptionOverrides {
        width: Some(40),
        height: Some(30),
        aa: Some(AaMode::None),
        ..OptionOverrides::default()
    }
}

/// scenes/csg.lua with its glass a mirror (CSG without refraction; the repository has no
/// such scene).
fn mirrored_csg() -> PackedScene {
    let source = std::fs::read_to_string(common::root().join("scenes/csg.lua")).unwrap();
    assert!(source.contains("glass:set_refraction(1.5)"));
    let source = source.replace(
        "glass:set_refraction(1.5)",
        "glass:set_reflection(0.8, 0.8, 0.85)",
    );
    packed_from_source(&source, &small()).remove(0)
}

/// `scene` on the hardware variant: through the wavefront kernels (one camera pass and
/// five passes a generation per chunk; with refraction also the shadow rounds' 26 a
/// generation and the fold), the same bits as the hardware variant's
/// megakernel `main` (the same WGSL steps in the same order, on the same device), and the
/// CPU's image within the GPU parity tests' tolerance (lavapipe's `length`, `normalize`,
/// `exp2`… are not Rust's, so no GPU image is the CPU's bit for bit: tests/gpu/gpu_images.rs).
pub(crate) fn assert_wavefront_matches(ctx: &mut GpuContext, name: &str, scene: &PackedScene) {
    let tree = scene.features.contains(SceneFeatures::REFRACTION);
    let hardware = ctx.kernel;
    assert!(hardware.wavefront);
    let render = render_gpu(ctx, scene, &GpuRenderOptions::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let generations = if tree || scene.features.contains(SceneFeatures::REFLECTION) {
        scene.globals.max_depth as u64 + 1
    } else {
        1
    };
    // A tree's generation: 5 passes, 9 rounds of leg closest and crossing, 8 leg args.
    let (per_generation, fold) = if tree { (5 + 2 * 9 + 8, 1) } else { (5, 0) };
    assert_eq!(
        render.info.dispatches as u64,
        render.info.tiles * (1 + per_generation * generations + fold),
        "{name}: the wavefront's dispatches"
    );
    // main with lavapipe's loop limiter checked (ITERATION_GUARD, which changes no
    // arithmetic): a megakernel tracing a whole tree in one invocation can trip it
    // (csg.lua's glass), and the pixels it spoils are re-rendered by the CPU — those are
    // not main's, and are compared with the CPU's below instead.
    ctx.kernel = KernelConfig {
        wavefront: false,
        iteration_guard: true,
        ..hardware
    };
    let mega = render_gpu(ctx, scene, &GpuRenderOptions::default());
    ctx.kernel = hardware;
    let mega = mega.unwrap_or_else(|e| panic!("{name}: {e}"));
    let spoiled = mega.info.cpu_fallback_pixels;
    assert_eq!(
        render.info.cpu_fallback_pixels, 0,
        "{name}: pixels the queues had no room for"
    );
    assert_eq!(mega.info.dispatches as u64, mega.info.tiles, "{name}: main");
    if spoiled > 0 {
        eprintln!("{name}: {spoiled} of main's pixels spoiled by lavapipe's loop limiter");
    }
    let bits = |film: &glint::film::Film| -> Vec<[u32; 3]> {
        film.pixels.iter().map(|p| p.map(f32::to_bits)).collect()
    };
    let (wave, main) = (bits(&render.film), bits(&mega.film));
    // The pixels main's render took from the CPU tracer (at least its count of them).
    let cpu = match spoiled {
        0 => vec![[0; 3]; main.len()],
        _ => bits(&glint::cpu::render::render(scene, &|_, _| {})),
    };
    let taken = (0..main.len()).filter(|&p| main[p] == cpu[p]).count();
    assert!(
        spoiled == 0 || taken as u64 >= spoiled,
        "{name}: {spoiled} pixels re-rendered, {taken} found"
    );
    // Most of the image stays main's to compare (scrabble.lua at 24×16: 40 of 384).
    assert!(
        spoiled * 4 <= main.len() as u64,
        "{name}: {spoiled} spoiled"
    );
    let differing: Vec<usize> = (0..main.len())
        .filter(|&p| wave[p] != main[p] && (spoiled == 0 || main[p] != cpu[p]))
        .collect();
    if let Some(&p) = differing.first() {
        let w = scene.globals.width as usize;
        panic!(
            "{name}: {} pixels differ from main's; the first, ({}, {}), is {:?} through the wavefront, {:?} through main",
            differing.len(),
            p % w,
            p / w,
            render.film.pixels[p],
            mega.film.pixels[p]
        );
    }
    common::assert_gpu_matches_cpu(ctx, "gpu_wavefront", name, scene, 0.01);
}

/// The scenes of the issue without glass, and CSG with a mirror, on lavapipe with the
/// hardware variant: main's bits, and the CPU's image.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn hardware_wavefront_renders_mains_image() {
    let Some(mut ctx) = gpu_context() else { return };
    ctx.force_kernel_variant(KernelVariant::Hardware);
    let a4 = "scenes/cs488/a4-2021plus";
    let files = [
        format!("{a4}/simple.lua"),
        format!("{a4}/nonhier.lua"),
        format!("{a4}/macho-cows.lua"),
        "scenes/demo.lua".to_string(),
        "scenes/textures.lua".to_string(),
        "scenes/soft-shadows.lua".to_string(),
        "scenes/tori.lua".to_string(),
        "scenes/columns.lua".to_string(),
        "scenes/smooth.lua".to_string(),
    ];
    for file in &files {
        let scene = packed_from_file(&common::root().join(file), &small()).remove(0);
        assert_wavefront_matches(&mut ctx, file, &scene);
    }
    let csg = mirrored_csg();
    assert!(csg.features.contains(SceneFeatures::CSG));
    assert_wavefront_matches(&mut ctx, "csg.lua with a mirror for glass", &csg);
}
