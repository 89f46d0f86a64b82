//! HDR environment maps on the GPU against the CPU reference (tier 4): a mirror sphere, a
//! glass sphere, a diffuse lit sphere (which the map must not light) and a textured one
//! (the map's words after the texture's) in the oracle's sky, turned 30°, under every AA
//! mode (FLIP mean ≤ 0.01, ≥ 99.9% of pixels within 2/255), and the hardware variant's
//! wavefront kernels against the megakernel. Failures write images to
//! `<target tmp>/gpu_environment/`.

use crate::common;
use crate::gpu_wavefront::assert_wavefront_matches;
use crate::texture_support;

use common::{gpu_context, packed_from_file, root, temp_dir};
use glint::gpu::KernelVariant;
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::{AaMode, OptionOverrides};

/// The spheres in the oracle's sky under `aa`, 64×40.
fn spheres(aa: AaMode) -> PackedScene {
    let dir = temp_dir("gpu-environment");
    std::fs::copy(
        root().join("tests/oracle/refs/environment/sky.exr"),
        dir.join("sky.exr"),
    )
    .unwrap();
    texture_support::save(&texture_support::uv_grid(), &dir.join("grid.png"));
    let source = "mirror = gr.material({0,0,0}, {0,0,0}, 1) mirror:set_reflection(0.9)
         glass = gr.material({0,0,0}, {0,0,0}, 1) glass:set_refraction(1.5)
         matte = gr.material({0.6,0.5,0.4}, {0.3,0.3,0.3}, 20)
         tex = gr.material({1,1,1}, {0,0,0}, 1) tex:set_diffuse('grid.png')
         root = gr.node('root')
         local function add(name, m, x, y)
             local s = gr.nh_sphere(name, {x, y, 0}, 0.9) s:set_material(m) root:add_child(s)
         end
         add('mirror', mirror, -1, 1) add('glass', glass, 1, 1)
         add('matte', matte, -1, -1) add('tex', tex, 1, -1)
         l = gr.light({3, 4, 6}, {0.9, 0.9, 0.9}, {1, 0, 0})
         gr.render(root, 'o.png', 64, 40, {0, 0.5, 7}, {0, -0.5, -7}, {0, 1, 0}, 45,
                   {0.1, 0.1, 0.1}, {l}, {environment='sky.exr', environment_rotation=30})";
    let path = dir.join("spheres.lua");
    std::fs::write(&path, source).unwrap();
    let overrides = OptionOverrides {
        aa: Some(aa),
        ..OptionOverrides::default()
    };
    packed_from_file(&path, &overrides).remove(0)
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn mirror_and_glass_in_an_environment_match_in_every_aa_mode() {
    let Some(ctx) = gpu_context() else { return };
    for (name, aa) in [
        ("none", AaMode::None),
        ("uniform", AaMode::Uniform),
        ("adaptive", AaMode::Adaptive),
    ] {
        let scene = spheres(aa);
        let info = common::assert_gpu_matches_cpu(&ctx, "gpu_environment", name, &scene, 0.01);
        for f in [
            SceneFeatures::ENVIRONMENT,
            SceneFeatures::REFRACTION,
            SceneFeatures::TEXTURE,
        ] {
            assert!(info.features.contains(f), "{name}: {}", info.features);
        }
    }
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn hardware_wavefront_renders_mains_image_in_an_environment() {
    let Some(mut ctx) = gpu_context() else { return };
    ctx.force_kernel_variant(KernelVariant::Hardware);
    assert_wavefront_matches(&mut ctx, "environment", &spheres(AaMode::None));
}

/// A ramp map (texel (i, j) = (i, j, 0): the lookup returns the continuous texel
/// coordinates x, y themselves) seen all round (fov 150° towards +z, away from the seam):
/// each pixel's difference is the difference in x and y, i.e. in the angles φ = 2π·x/w
/// and θ = π·y/(h − 1), that the two tracers' atan2 and acos give (the one place their
/// f32 operations are not specified to the bit). Pixels within a column of the seam, where
/// the ramp wraps, are left out.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn the_tracers_angles_differ_only_by_the_transcendentals() {
    let Some(ctx) = gpu_context() else { return };
    let dir = temp_dir("gpu-environment-ramp");
    let (w, h) = (64u32, 33u32);
    let mut ramp = glint::film::Film::new(w, h);
    for (k, p) in ramp.pixels.iter_mut().enumerate() {
        *p = [(k as u32 % w) as f32, (k as u32 / w) as f32, 0.0];
    }
    glint::image_io::write_image(&ramp, &dir.join("ramp.exr")).unwrap();
    let source = "root = gr.node('root')
         gr.render(root, 'o.png', 96, 96, {0, 0, 0}, {0.2, 0.3, 1}, {0, 1, 0}, 150,
                   {0, 0, 0}, {}, {aa = 'none', environment = 'ramp.exr'})";
    let path = dir.join("ramp.lua");
    std::fs::write(&path, source).unwrap();
    let scene = packed_from_file(&path, &OptionOverrides::default()).remove(0);
    let gpu = glint::gpu::render_gpu(&ctx, &scene, &Default::default())
        .unwrap()
        .film;
    let cpu = glint::tracer::render(&scene, &|_, _| {});
    let (mut dx, mut dy, mut differing, mut counted) = (0f32, 0f32, 0, 0);
    for (g, c) in gpu.pixels.iter().zip(&cpu.pixels) {
        if c[0] < 1.0 || c[0] > (w - 2) as f32 {
            continue;
        }
        counted += 1;
        differing += usize::from(g != c);
        dx = dx.max((g[0] - c[0]).abs());
        dy = dy.max((g[1] - c[1]).abs());
    }
    let (phi, theta) = (
        dx * std::f32::consts::TAU / w as f32,
        dy * std::f32::consts::PI / (h - 1) as f32,
    );
    eprintln!(
        "atan2/acos, Rust against lavapipe: {differing} of {counted} pixels differ; \
         at most {dx:e} texels in x ({phi:e} rad of φ), {dy:e} in y ({theta:e} rad of θ)"
    );
    // A thousandth of a texel: far below what a lookup can show.
    assert!(dx <= 1e-3 && dy <= 1e-3, "{dx} {dy}");
}
