//! GPU parity for CSG. Tier 3 (kernel probes): 4 096 seeded rays per operation and for
//! nested trees, through the grid and by brute force, traced by the GPU's `closest_hit` +
//! `surface_at` and the CPU's: 100% must agree on hit/miss, item and part (the leaf hit,
//! flipped or not), with |Δt|/t ≤ 1e-4 and normals within 1e-4. Tier 4 (images): one
//! scene per operation and `scenes/csg.lua` at 128×128 on both tracers (FLIP mean < 0.01
//! and ≥ 99.9% of pixels within 2/255, as in `gpu_images.rs`); and `scenes/csg.lua` scaled
//! by 1e-3 and 1e3 on the GPU gives the GPU's image at scale 1 (FLIP mean < 0.005), no
//! NaN, and no speckle in the glass.

use crate::common;

use common::probes::{agree, random_rays, RAYS};
use common::{gpu_context, packed_from_file, packed_from_source, root, Rng};
use glint::diff::assert_images_match;
use glint::gpu::{render_gpu, GpuContext, GpuRenderOptions};
use glint::pack::{pack, PackedScene, SceneFeatures};
use glint::scene::{GridMode, OptionOverrides};
use glint::testing::probe::{gpu_probe, probe};
use std::fmt::Write;

/// Lua statements making a random primitive (any kind CSG takes) of size about 1 near the
/// origin in `var`.
fn primitive(rng: &mut Rng, var: &str, name: &str) -> String {
    let (ctor, centre) = match rng.next_u64() % 5 {
        0 => (format!("gr.sphere('{name}')"), ""),
        1 => (format!("gr.cube('{name}')"), "translate(-0.5, -0.5, -0.5)"),
        2 => (format!("gr.cylinder('{name}')"), "translate(0, 0, -0.5)"),
        3 => {
            let (zmin, zmax) = match rng.next_u64() % 3 {
                0 => (0.0, rng.range(0.6, 1.2)),
                1 => (rng.range(0.1, 0.4), rng.range(0.6, 1.2)),
                _ => (-rng.range(0.4, 1.0), rng.range(0.4, 1.0)),
            };
            (format!("gr.cone('{name}', {zmin}, {zmax})"), "")
        }
        _ => (
            format!(
                "gr.torus('{name}', {}, {})",
                rng.range(0.5, 0.9),
                rng.range(0.1, 0.45)
            ),
            "",
        ),
    };
    let s = [0; 3].map(|_| rng.range(0.5, 1.3));
    let axis = ["x", "y", "z"][(rng.next_u64() % 3) as usize];
    let t = [0; 3].map(|_| rng.range(-0.5, 0.5));
    let centre = if centre.is_empty() {
        String::new()
    } else {
        format!("{var}:{centre} ")
    };
    format!(
        "{var} = {ctor} {centre}{var}:scale({}, {}, {}) {var}:rotate('{axis}', {}) {var}:translate({}, {}, {})\n",
        s[0],
        s[1],
        s[2],
        rng.range(0.0, 360.0),
        t[0],
        t[1],
        t[2]
    )
}

/// Lua statements making a random CSG tree `depth` levels deep in `var` (op None: random).
fn tree(rng: &mut Rng, var: &str, op: Option<char>, depth: u32, names: &mut usize) -> String {
    *names += 1;
    let id = *names;
    if depth == 0 {
        return primitive(rng, var, &format!("p{id}"));
    }
    let mut lua = tree(rng, &format!("{var}a"), op, depth - 1, names);
    lua += &tree(rng, &format!("{var}b"), op, depth - 1, names);
    let op = op.unwrap_or(['u', 'i', 'd'][(rng.next_u64() % 3) as usize]);
    let _ = writeln!(lua, "{var} = gr.csg('c{id}', '{op}', {var}a, {var}b)");
    if rng.next_u64().is_multiple_of(2) {
        let _ = writeln!(lua, "{var}:set_material(m{})", rng.next_u64() % 3);
    }
    lua
}

/// Lua for `count` random CSG objects in [-10, 10]³ (each `depth` operations deep).
fn random_scene(seed: u64, op: Option<char>, depth: u32, count: usize) -> String {
    let mut rng = Rng(seed);
    let mut lua = String::from(
        "m0 = gr.material({0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, 25)\n\
         m1 = gr.material({0.8, 0.2, 0.2}, {0.5, 0.5, 0.5}, 25)\n\
         m2 = gr.material({0.2, 0.3, 0.8}, {0.5, 0.5, 0.5}, 25)\n\
         root = gr.node('root')\n",
    );
    let mut names = 0;
    for i in 0..count {
        lua += &tree(&mut rng, "x", op, depth, &mut names);
        let s = rng.range(1.0, 2.5);
        let t = [0; 3].map(|_| rng.range(-9.0, 9.0));
        let _ = writeln!(
            lua,
            "x:scale({s}, {s}, {s}) x:rotate('y', {}) x:translate({}, {}, {}) root:add_child(x) -- {i}",
            rng.range(0.0, 360.0),
            t[0],
            t[1],
            t[2]
        );
    }
    lua + "gr.render(root, 'probe.png', 64, 64, {0, 0, 30}, {0, 0, -1}, {0, 1, 0}, 50, {0.1, 0.1, 0.1}, {})\n"
}

fn scene(seed: u64, op: Option<char>, depth: u32, grid: GridMode) -> PackedScene {
    let overrides = OptionOverrides {
        grid: Some(grid),
        ..OptionOverrides::default()
    };
    packed_from_source(&random_scene(seed, op, depth, 40), &overrides).remove(0)
}

/// All of `RAYS` seeded rays must agree on hit/miss, item and part, within the t and
/// normal tolerances of `common::probes`.
fn check_all(ctx: &GpuContext, name: &str, scene: &PackedScene, ray_seed: u64) {
    let rays = random_rays(ray_seed);
    let gpu = gpu_probe(ctx, scene, &rays).unwrap_or_else(|e| panic!("{name}: {e}"));
    let (mut hits, mut csg_hits, mut flipped) = (0, 0, 0);
    let (mut worst_dt, mut worst_dn) = (0.0f32, 0.0f32);
    let mut bad = Vec::new();
    for (i, (ray, g)) in rays.iter().zip(&gpu).enumerate() {
        let c = probe(scene, ray);
        hits += c.hit as usize;
        if c.hit == 1 && c.part != glint::constants::NO_ITEM {
            csg_hits += 1;
            flipped += (c.part & glint::constants::CSG_FLIP != 0) as usize;
        }
        let (ok, dt, dn) = agree(g, &c);
        if ok && g.part == c.part {
            worst_dt = worst_dt.max(dt);
            worst_dn = worst_dn.max(dn);
        } else {
            bad.push(format!("ray {i} {ray:?}:\n  gpu {g:?}\n  cpu {c:?}"));
        }
    }
    eprintln!(
        "{name}: features [{}], {hits}/{RAYS} CPU hits ({csg_hits} on CSG objects, {flipped} flipped), {} disagree, worst |Δt|/t {worst_dt:.2e}, |Δn| {worst_dn:.2e}",
        scene.features,
        bad.len()
    );
    assert!(
        scene.features.contains(SceneFeatures::CSG),
        "{}",
        scene.features
    );
    assert!(csg_hits > RAYS / 8, "{name}: too few CSG hits ({csg_hits})");
    assert!(
        bad.is_empty(),
        "{name} (ray seed {ray_seed}): {} of {RAYS} rays disagree; first:\n{}",
        bad.len(),
        bad[0]
    );
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn probes_union_intersection_difference() {
    let Some(ctx) = gpu_context() else { return };
    for (k, op) in ['u', 'i', 'd'].into_iter().enumerate() {
        let k = k as u64;
        check_all(
            &ctx,
            &format!("'{op}'"),
            &scene(100 + k, Some(op), 1, GridMode::Off),
            200 + k,
        );
        check_all(
            &ctx,
            &format!("'{op}', grid"),
            &scene(110 + k, Some(op), 1, GridMode::Auto),
            210 + k,
        );
    }
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn probes_nested() {
    let Some(mut ctx) = gpu_context() else { return };
    // The CSG lists as private arrays and in storage slots (src/gpu/compile/lists.rs), whichever
    // the adapter chose.
    let chosen = ctx.kernel;
    for lists_in_storage in [chosen.lists_in_storage, !chosen.lists_in_storage] {
        ctx.kernel.lists_in_storage = lists_in_storage;
        check_all(&ctx, "nested", &scene(120, None, 3, GridMode::Off), 220);
        check_all(
            &ctx,
            "nested, grid",
            &scene(121, None, 3, GridMode::Auto),
            221,
        );
    }
}

/// A row of CSG objects of one operation — sphere ○ cube, cylinder ○ cone, torus ○
/// double cone, cube ○ cylinder — on a floor, lit by two lights (shadow rays through CSG).
fn op_scene(op: char) -> String {
    format!(
        "gr.transform_order('pre')
        a = gr.material({{0.2, 0.35, 0.8}}, {{0.6, 0.6, 0.6}}, 50)
        b = gr.material({{0.8, 0.25, 0.15}}, {{0.6, 0.6, 0.6}}, 50)
        floor_m = gr.material({{0.7, 0.7, 0.7}}, {{0.1, 0.1, 0.1}}, 10)
        root = gr.node('root')
        floor = gr.cube('floor') floor:scale(12, 0.2, 8) floor:translate(-6, -0.2, -5) floor:set_material(floor_m)
        root:add_child(floor)
        function place(name, x, p, q)
          q:set_material(b)
          local c = gr.csg(name, '{op}', p, q)
          c:set_material(a)
          c:rotate('y', 30) c:rotate('x', -20) c:translate(x, 1.1, 0)
          root:add_child(c)
        end
        s = gr.sphere('s') c = gr.cube('c') c:translate(-0.5, -0.5, -0.5) c:scale(1.5, 1.5, 1.5)
        place('sphere-cube', -3.6, s, c)
        y = gr.cylinder('y') y:translate(0, 0, -0.5) y:scale(0.7, 0.7, 2)
        k = gr.cone('k', 0, 1) k:translate(0, 0, -0.6) k:scale(1, 1, 1.6) k:rotate('x', 90)
        place('cylinder-cone', -1.2, y, k)
        t = gr.torus('t', 0.8, 0.3)
        d = gr.cone('d', -1, 1) d:scale(0.5, 0.5, 1) d:rotate('y', 90)
        place('torus-cone', 1.2, t, d)
        e = gr.cube('e') e:translate(-0.5, -0.5, -0.5) e:scale(1.4, 1.4, 1.4)
        z = gr.cylinder('z') z:translate(0, 0, -0.5) z:scale(0.5, 0.5, 2) z:rotate('y', 90)
        place('cube-cylinder', 3.6, e, z)
        gr.render(root, 'op.png', 128, 128, {{0, 3.2, 8}}, {{0, -2.2, -8}}, {{0, 1, 0}}, 44,
          {{0.25, 0.25, 0.25}},
          {{gr.light({{-4, 8, 6}}, {{0.8, 0.8, 0.8}}, {{1, 0, 0}}),
           gr.light({{5, 3, 6}}, {{0.3, 0.3, 0.3}}, {{1, 0, 0}})}})
        "
    )
}

/// A CSG scene, GPU against CPU.
fn compare(ctx: &GpuContext, name: &str, scene: &PackedScene, max_flip: f64) {
    let info = common::assert_gpu_matches_cpu(ctx, "gpu_images", name, scene, max_flip);
    assert!(info.features.contains(SceneFeatures::CSG));
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn op_scenes_match() {
    let Some(ctx) = gpu_context() else { return };
    for op in ['u', 'i', 'd'] {
        let scene = packed_from_source(&op_scene(op), &OptionOverrides::default()).remove(0);
        compare(&ctx, &format!("csg-{op}"), &scene, 0.01);
    }
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn csg_scene_matches_and_is_scale_invariant() {
    let Some(ctx) = gpu_context() else { return };
    let overrides = OptionOverrides {
        width: Some(128),
        height: Some(80),
        ..OptionOverrides::default()
    };
    let path = root().join("scenes/csg.lua");
    let packed = packed_from_file(&path, &overrides).remove(0);
    compare(&ctx, "csg-scene", &packed, 0.01);
    // Scale invariance on the GPU: against its own image at scale 1.
    let scene = &common::load_scenes(&path, &overrides)[0];
    let reference = render_gpu(&ctx, &pack(scene).unwrap(), &GpuRenderOptions::default())
        .unwrap()
        .film;
    for s in [1.0, 1e-3, 1e3] {
        let scaled = common::scaled_scene(scene, s);
        let packed = pack(&scaled).unwrap();
        let probe = common::GlassProbe::new(&scaled, 4000);
        let results = gpu_probe(&ctx, &packed, &probe.rays).unwrap();
        assert!(
            results.iter().all(|r| r.hit == 1),
            "scale {s}: a ray missed the glass"
        );
        assert_eq!(
            probe.speckles(&results),
            0,
            "scale {s}: speckles in the glass"
        );
        if s == 1.0 {
            continue;
        }
        let film = render_gpu(&ctx, &packed, &GpuRenderOptions::default())
            .unwrap()
            .film;
        assert!(
            film.pixels.iter().flatten().all(|v| v.is_finite()),
            "NaN at scale {s}"
        );
        let out = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu_images");
        let report = assert_images_match(
            &format!("gpu-scale-{s}-csg"),
            &film,
            &reference,
            0.005,
            0.999,
            &out,
        )
        .unwrap_or_else(|message| panic!("{message}"));
        eprintln!("gpu scale {s}: FLIP mean {:.5}", report.flip_mean);
    }
}
