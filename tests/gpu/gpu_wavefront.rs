//! The wavefront kernels (`src/tracer/wavefront/wavefront.wgsl`, `KernelConfig::wavefront`: AA none and
//! uniform AA in the hardware variant, scenes without refraction): naga validates them for
//! every feature set that has them (where the megakernel entries they replace are gone),
//! the software variant's modules never include them, and rendered on lavapipe with
//! `--kernel-variant hardware` they give the megakernel's image bit for bit (and so the
//! CPU tracer's, within the GPU parity tolerance) on scenes with mirrors (several
//! generations), area lights, textures and bump maps, smooth meshes, tori, meshes in
//! grids and CSG. Under adaptive AA the hardware variant traces the corner and midpoint
//! passes through them (`src/tracer/wavefront/wavefront_lattice.wgsl`), with the same lattice, and so
//! image, as the megakernel passes, bit for bit; `glint view`'s frames go through them
//! too, with `view_sample`'s sums. With refraction AA none runs them with
//! `src/tracer/wavefront/wavefront_tree.wgsl`'s (whose scenes `gpu_wavefront_tree.rs` renders), and the
//! other AA modes and the view keep their megakernels.

use crate::common;

use common::{gpu_context, packed_from_file, packed_from_source};
use glint::constants::{AA_ADAPTIVE, AA_UNIFORM};
use glint::gpu::compile::lists::LaneLists;
use glint::gpu::compile::shader::{
    all_feature_sets, assemble_with, validate, wavefront_kernels, Entry,
};
use glint::gpu::view::progressive::{Progressive, SumBuffer};
use glint::gpu::{render_gpu, GpuContext, GpuRenderOptions, KernelConfig, KernelVariant};
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::bounded::AaSamples;
use glint::scene::{AaDepth, AaMode, OptionOverrides};
use glint::tracer::wavefront::batch::light_points;

/// Every feature set: the hardware variant's render module has the wavefront entry points
/// (the renders' and the view's), valid under naga, exactly where the scene has no
/// refraction, and then not the megakernel entries they replace (uniform AA's two passes,
/// `view_sample`), and with refraction AA none's and the tree's four more (and its file),
/// keeping the megakernel entries of the other AA modes; the software variant's never
/// mentions them (its modules are what they were before the wavefront kernels: the files
/// are not even appended) and keeps every megakernel entry.
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
        assert!(
            hard.contains("src/tracer/wavefront/wavefront.wgsl"),
            "[{features}]"
        );
        assert_eq!(
            hard.contains("src/tracer/wavefront/wavefront_tree.wgsl"),
            tree,
            "[{features}]"
        );
        let module = validate(&hard, features).unwrap_or_else(|e| panic!("{e}"));
        let entries: Vec<Entry> = if tree {
            Entry::WAVEFRONT_TREE
                .into_iter()
                .chain(Entry::ADAPTIVE_WAVEFRONT_TREE)
                .chain(Entry::WAVEFRONT_VIEW_TREE)
                .collect()
        } else {
            Entry::WAVEFRONT
                .into_iter()
                .chain(Entry::WAVEFRONT_VIEW)
                .chain(Entry::ADAPTIVE_WAVEFRONT)
                .collect()
        };
        for entry in entries {
            assert!(
                module.entry_points.iter().any(|e| e.name == entry.name()),
                "[{features}] {entry:?}"
            );
            assert!(entry.exists_in(hardware, features));
            assert_eq!(
                entry.exists_in(software, features),
                !entry.is_wavefront(),
                "{entry:?}"
            );
        }
        for entry in Entry::REPLACED_BY_WAVEFRONT {
            assert!(
                !module.entry_points.iter().any(|e| e.name == entry.name()),
                "[{features}] {entry:?} is replaced"
            );
            assert!(!entry.exists_in(hardware, features));
            assert!(entry.exists_in(software, features));
            assert!(
                soft.contains(&format!("fn {}(", entry.name())),
                "[{features}]"
            );
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

/// `small` under uniform n×n AA, smaller (n² samples a pixel).
fn small_uniform(n: u32) -> OptionOverrides {
    OptionOverrides {
        width: Some(24),
        height: Some(18),
        aa: Some(AaMode::Uniform),
        samples: Some(AaSamples::new(n.into()).unwrap()),
        ..OptionOverrides::default()
    }
}

/// scenes/csg.lua with its glass a mirror (CSG without refraction, as in
/// scenes/machined.lua, with csg.lua's objects and two point lights).
fn mirrored_csg(options: &OptionOverrides) -> PackedScene {
    let source = std::fs::read_to_string(common::root().join("scenes/csg.lua")).unwrap();
    assert!(source.contains("glass:set_refraction(1.5)"));
    let source = source.replace(
        "glass:set_refraction(1.5)",
        "glass:set_reflection(0.8, 0.8, 0.85)",
    );
    packed_from_source(&source, options).remove(0)
}

/// `scene` on the hardware variant: through the wavefront kernels (one camera pass and
/// five passes a generation per chunk, with CSG a shadow dispatch per light point; with
/// refraction also the shadow rounds' 26 a generation and the fold), the same bits as the hardware variant's
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
    let adaptive = scene.globals.aa_mode == AA_ADAPTIVE;
    // AA none and uniform AA: the camera pass, five passes a generation (uniform AA: then
    // the resolve pass; its megakernel: two passes). Adaptive AA: per lattice pass (the
    // corner pass, a midpoint pass a level) the camera pass, five passes a generation and
    // the store pass; decide and work args a level; integrate.
    let depth = scene.globals.aa_depth as u64;
    let uniform = (scene.globals.aa_mode == AA_UNIFORM) as u64;
    // With CSG (no glass) a chain's shadow pass is a dispatch per light point (its
    // slices: one request an invocation, at most one a sample each).
    let slices = match !tree && scene.features.contains(SceneFeatures::CSG) {
        true => light_points(scene) as u64,
        false => 1,
    };
    // A tree's generation: 5 passes, 9 rounds of leg closest and crossing, 8 leg args;
    // then its fold.
    let (per_generation, fold) = if tree {
        (5 + 2 * 9 + 8, 1)
    } else {
        (4 + slices, 0)
    };
    let per_tile = match adaptive {
        false => 1 + per_generation * generations + fold + uniform,
        true => (2 + fold + per_generation * generations) * (1 + depth) + 2 * depth + 1,
    };
    assert_eq!(
        render.info.dispatches as u64,
        render.info.tiles * per_tile,
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
    // main (uniform AA: its two passes), or adaptive AA's corners, decide + work args +
    // midpoints a level, integrate.
    let mega_per_tile = if adaptive { 2 + 3 * depth } else { 1 + uniform };
    assert_eq!(
        mega.info.dispatches as u64,
        mega.info.tiles * mega_per_tile,
        "{name}: the megakernels"
    );
    let spoiled = mega.info.cpu_fallback_pixels;
    assert_eq!(
        render.info.cpu_fallback_pixels, 0,
        "{name}: pixels the queues had no room for"
    );
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
        _ => bits(&glint::tracer::sampling::render::render(scene, &|_, _| {})),
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
            "{name}: {} pixels differ from the megakernels'; the first, ({}, {}), is {:?} through the wavefront, {:?} through the megakernels",
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
/// hardware variant: main's bits, and the CPU's image. machined.lua is CSG without glass
/// under an area light: its shadow pass is 10 slices, not csg.lua's 2.
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
        "scenes/machined.lua".to_string(),
    ];
    for file in &files {
        let scene = packed_from_file(&common::root().join(file), &small()).remove(0);
        assert_wavefront_matches(&mut ctx, file, &scene);
    }
    let csg = mirrored_csg(&small());
    assert!(csg.features.contains(SceneFeatures::CSG));
    assert_wavefront_matches(&mut ctx, "csg.lua with a mirror for glass", &csg);
}

fn adaptive(depth: u32) -> OptionOverrides {
    OptionOverrides {
        aa: Some(AaMode::Adaptive),
        aa_depth: Some(AaDepth::constant(depth)),
        ..small()
    }
}

/// Adaptive AA at depths 1 and 2 on lavapipe with the hardware variant: its corner and
/// midpoint passes through the wavefront kernels give the megakernel passes' image bit
/// for bit, and the CPU's within the tolerance — on scenes whose splits read every hint:
/// textures (fine detail), mirrors (the mirrored item), area lights (penumbrae: fine
/// detail from the gather pass), CSG with a mirror, and plain item edges.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn hardware_wavefront_traces_adaptive_aa_as_its_megakernels() {
    let Some(mut ctx) = gpu_context() else { return };
    ctx.force_kernel_variant(KernelVariant::Hardware);
    let a4 = "scenes/cs488/a4-2021plus";
    let files = [
        (format!("{a4}/nonhier.lua"), 2),
        ("scenes/demo.lua".to_string(), 1),
        ("scenes/textures.lua".to_string(), 2),
        ("scenes/soft-shadows.lua".to_string(), 2),
    ];
    for (file, depth) in &files {
        let scene = packed_from_file(&common::root().join(file), &adaptive(*depth)).remove(0);
        assert_eq!(scene.globals.aa_mode, AA_ADAPTIVE);
        assert_wavefront_matches(&mut ctx, &format!("{file} at depth {depth}"), &scene);
    }
    let csg = mirrored_csg(&adaptive(2));
    assert_wavefront_matches(&mut ctx, "csg.lua with a mirror, adaptive AA", &csg);
}

/// Uniform AA (n = 1, 2, 3) on lavapipe with the hardware variant: the wavefront's
/// strata, generations and resolve give the megakernel's uniform_samples +
/// uniform_resolve image bit for bit, and the CPU's within the tolerance, on scenes with
/// mirrors, area lights, textures and bump maps, smooth meshes and CSG (machined.lua: with
/// an area light, 10 shadow slices).
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn hardware_wavefront_renders_uniform_aa_as_the_megakernel() {
    let Some(mut ctx) = gpu_context() else { return };
    ctx.force_kernel_variant(KernelVariant::Hardware);
    let files = [
        ("scenes/cs488/a4-2021plus/nonhier.lua", 2),
        ("scenes/demo.lua", 2),
        ("scenes/textures.lua", 3),
        ("scenes/soft-shadows.lua", 3),
        ("scenes/smooth.lua", 1),
        ("scenes/machined.lua", 2),
    ];
    for (file, n) in files {
        let options = small_uniform(n);
        let scene = packed_from_file(&common::root().join(file), &options).remove(0);
        assert_eq!(scene.globals.aa_mode, AA_UNIFORM);
        assert_eq!(scene.globals.aa_samples, n);
        assert_wavefront_matches(&mut ctx, &format!("{file} at {n}×{n}"), &scene);
    }
    let csg = mirrored_csg(&small_uniform(2));
    assert_wavefront_matches(&mut ctx, "csg.lua with a mirror for glass at 2×2", &csg);
}

/// `frames` frames of `glint view`'s progressive sums of `scene` on `ctx` (in bands
/// where `ctx`'s binding limit asks for them), after a frame of a preview at a third of
/// the size (the view's narrower rows: bands of more pixels), read back; and whether they
/// went through the wavefront kernels, in how many bands.
pub(crate) fn view_sums(
    ctx: &GpuContext,
    scene: &PackedScene,
    frames: u32,
) -> (Vec<[f32; 4]>, bool, usize) {
    let g = scene.globals;
    let pixels = u64::from(g.width * g.height);
    let sums = SumBuffer::new(ctx, pixels).unwrap();
    let mut view = Progressive::new(ctx, scene, &sums).unwrap();
    let preview = glint::pack::PackedGlobals {
        width: g.width.div_ceil(3),
        height: g.height.div_ceil(3),
        ..g
    };
    view.set_globals(ctx, &preview);
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    view.encode_sample(ctx, &mut encoder, 0);
    ctx.queue.submit([encoder.finish()]);
    view.set_globals(ctx, &g);
    for s in 0..frames {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        view.encode_sample(ctx, &mut encoder, s);
        ctx.queue.submit([encoder.finish()]);
    }
    let read = sums.read(ctx, pixels).unwrap();
    (read, view.runs_wavefront(), view.bands().len())
}

/// `glint view` on lavapipe with the hardware variant, where `view_sample` is not in the
/// module: each frame's band after band through the wavefront kernels (the camera pass
/// takes the frame's stratum of each pixel, the store adds each sample to its pixel's
/// sum), and after n² frames (AA none: one) the sums are the megakernel `view_sample`'s
/// bit for bit — uniform AA at 2×2 and 3×3 and AA none, on scenes with mirrors, area
/// lights, textures and bump maps, and CSG. The binding limit is lowered to three rows'
/// queues or lists, so that the window is many bands (each band's pixels at their own
/// rows of the image's sums).
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn hardware_wavefront_view_sums_are_view_samples() {
    let Some(mut ctx) = gpu_context() else { return };
    ctx.force_kernel_variant(KernelVariant::Hardware);
    let hardware = ctx.kernel;
    let none = OptionOverrides {
        width: Some(24),
        height: Some(18),
        ..small()
    };
    let scenes = [
        ("scenes/demo.lua", small_uniform(2)),
        ("scenes/demo.lua", none.clone()),
        ("scenes/textures.lua", small_uniform(2)),
        ("scenes/soft-shadows.lua", small_uniform(3)),
    ];
    let mut cases: Vec<(String, PackedScene)> = scenes
        .iter()
        .map(|(file, o)| {
            let scene = packed_from_file(&common::root().join(file), o).remove(0);
            (file.to_string(), scene)
        })
        .collect();
    cases.push((
        "csg.lua with a mirror".into(),
        mirrored_csg(&small_uniform(2)),
    ));
    for (name, scene) in &cases {
        let g = scene.globals;
        let frames = if g.aa_mode == AA_UNIFORM {
            g.aa_samples * g.aa_samples
        } else {
            1
        };
        let name = format!("{name}, {frames} frames");
        // Three rows' queues (14 + 2L vec4s a sample, L light points) or per-ray lists
        // a binding, whichever is more.
        let queues = (14 + 2 * u64::from(light_points(scene))) * 16;
        let lists = 4 * u64::from(LaneLists::of(scene.features, hardware).words());
        ctx.limits.max_storage_buffer_binding_size = 3 * u64::from(g.width) * queues.max(lists);
        assert!(
            !Entry::ViewSample.exists_in(hardware, scene.features),
            "{name}"
        );
        let (wave, through_wavefront, bands) = view_sums(&ctx, scene, frames);
        assert!(through_wavefront, "{name}");
        assert!(bands > 1, "{name}: {bands} bands");
        ctx.kernel = KernelConfig {
            wavefront: false,
            ..hardware
        };
        let (mega, through_wavefront, _) = view_sums(&ctx, scene, frames);
        ctx.kernel = hardware;
        assert!(!through_wavefront, "{name}: view_sample");
        let bits = |sums: &[[f32; 4]]| -> Vec<[u32; 4]> {
            sums.iter().map(|p| p.map(f32::to_bits)).collect()
        };
        let (wave, mega) = (bits(&wave), bits(&mega));
        let differing: Vec<usize> = (0..mega.len()).filter(|&p| wave[p] != mega[p]).collect();
        if let Some(&p) = differing.first() {
            let w = g.width as usize;
            panic!(
                "{name}: {} sums differ from view_sample's; the first, ({}, {}), is {:?} through the wavefront, {:?} through view_sample",
                differing.len(),
                p % w,
                p / w,
                wave[p].map(f32::from_bits),
                mega[p].map(f32::from_bits)
            );
        }
        assert!(
            wave.iter().all(|s| f32::from_bits(s[3]) == frames as f32),
            "{name}"
        );
    }
}
