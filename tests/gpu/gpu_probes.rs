//! Tier 3 of GPU parity: kernel probes. For each primitive kind, and for a mixed scene
//! through the grid and by brute force, ≥ 4096 seeded rays are traced by the GPU's
//! `closest_hit` + `surface_at` (the test-only `probe` entry point) and by the CPU's;
//! ≥ 99.9% of rays must agree on hit/miss and item with |Δt|/t ≤ 1e-4 and normals within
//! 1e-4 (f32 on both sides; the GPU's sqrt/division/normalize may differ by a few ulps,
//! which moves grazing hits only). Seeds are in the messages.

use crate::common;

use common::probes::{check, random_placed};
use common::{gpu_context, packed_from_source, Rng};
use glint::mailboxes::Mailboxes;
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::{GridMode, OptionOverrides};
use std::fmt::Write;

/// Lua for a random scene in [-10, 10]³: spheres and cubes with random non-uniform scale,
/// rotation and translation, and a random triangle soup of `triangles` triangles.
fn random_scene(seed: u64, spheres: usize, cubes: usize, triangles: usize) -> String {
    let mut rng = Rng(seed);
    let mut lua = String::from(
        "m = gr.material({0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, 25)\nroot = gr.node('root')\n",
    );
    for (kind, count) in [("sphere", spheres), ("cube", cubes)] {
        for i in 0..count {
            let s = [0; 3].map(|_| rng.range(0.3, 2.0));
            let axis = ["x", "y", "z"][(rng.next_u64() % 3) as usize];
            let angle = rng.range(0.0, 360.0);
            let t = [0; 3].map(|_| rng.range(-9.0, 9.0));
            let _ = writeln!(
                lua,
                "n = gr.{kind}('{kind}{i}') n:scale({}, {}, {}) n:rotate('{axis}', {angle}) n:translate({}, {}, {}) n:set_material(m) root:add_child(n)",
                s[0], s[1], s[2], t[0], t[1], t[2]
            );
        }
    }
    if triangles > 0 {
        let mut vertices = Vec::new();
        let mut faces = Vec::new();
        for i in 0..triangles {
            let centre = [0; 3].map(|_| rng.range(-9.0, 9.0));
            for _ in 0..3 {
                let v = [0, 1, 2].map(|k| centre[k] + rng.range(-2.0, 2.0));
                vertices.push(format!("{{{}, {}, {}}}", v[0], v[1], v[2]));
            }
            faces.push(format!("{{{}, {}, {}}}", 3 * i, 3 * i + 1, 3 * i + 2));
        }
        let _ = writeln!(
            lua,
            "t = gr.mesh('soup', {{{}}}, {{{}}}) t:set_material(m) root:add_child(t)",
            vertices.join(", "),
            faces.join(", ")
        );
    }
    lua + "gr.render(root, 'probe.png', 64, 64, {0, 0, 30}, {0, 0, -1}, {0, 1, 0}, 50, {0.1, 0.1, 0.1}, {})\n"
}

fn grid(mode: GridMode) -> OptionOverrides {
    OptionOverrides {
        grid: Some(mode),
        ..OptionOverrides::default()
    }
}

fn scene(seed: u64, spheres: usize, cubes: usize, triangles: usize, mode: GridMode) -> PackedScene {
    packed_from_source(&random_scene(seed, spheres, cubes, triangles), &grid(mode)).remove(0)
}

/// Lua for `count` random tori (ring and spindle, thin to fat tubes) in [-10, 10]³.
fn torus_scene(seed: u64, count: usize) -> String {
    let mut rng = Rng(seed);
    let mut lua = String::from(
        "m = gr.material({0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, 25)\nroot = gr.node('root')\n",
    );
    for i in 0..count {
        let rin = rng.range(0.5, 2.5);
        let rout = rin * rng.range(0.05, 1.3);
        let ctor = format!("gr.torus('torus{i}', {rin}, {rout})");
        lua += &random_placed(&mut rng, &ctor, (0.6, 1.5), 8.0);
        lua.push('\n');
    }
    lua + "gr.render(root, 'probe.png', 64, 64, {0, 0, 30}, {0, 0, -1}, {0, 1, 0}, 50, {0.1, 0.1, 0.1}, {})\n"
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn probes_tori() {
    let Some(ctx) = gpu_context() else { return };
    for (mode, has_grid) in [(GridMode::Off, false), (GridMode::Auto, true)] {
        let s = packed_from_source(&torus_scene(5, 30), &grid(mode)).remove(0);
        assert!(s.features.contains(SceneFeatures::TORUS));
        assert_eq!(s.features.contains(SceneFeatures::GRID), has_grid);
        check(&ctx, &format!("tori, grid {has_grid}"), &s, 105);
    }
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn probes_spheres() {
    let Some(ctx) = gpu_context() else { return };
    let s = scene(1, 40, 0, 0, GridMode::Off);
    assert_eq!(s.features, SceneFeatures::SPHERE);
    check(&ctx, "spheres", &s, 101);
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn probes_cubes() {
    let Some(ctx) = gpu_context() else { return };
    let s = scene(2, 0, 80, 0, GridMode::Off);
    assert_eq!(s.features, SceneFeatures::CUBE);
    check(&ctx, "cubes", &s, 102);
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn probes_triangles() {
    let Some(ctx) = gpu_context() else { return };
    let s = scene(3, 0, 0, 300, GridMode::Off);
    assert_eq!(s.features, SceneFeatures::MESH);
    check(&ctx, "triangles", &s, 103);
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn probes_mixed_grid_and_brute_force() {
    let Some(ctx) = gpu_context() else { return };
    let with_grid = scene(4, 60, 60, 600, GridMode::Auto);
    assert!(
        with_grid.features.contains(SceneFeatures::GRID),
        "{}",
        with_grid.features
    );
    check(&ctx, "mixed, grid", &with_grid, 104);
    let brute = scene(4, 60, 60, 600, GridMode::Off);
    assert!(!brute.features.contains(SceneFeatures::GRID));
    check(&ctx, "mixed, brute force", &brute, 104);
}

/// Lua for one random triangle soup of `triangles` triangles (around the origin, ±2)
/// placed `instances` times by random scale, rotation and translation, with a sphere
/// among them: the soup is stored once, in its own space, with its own grid.
fn instanced_scene(seed: u64, triangles: usize, instances: usize) -> String {
    let mut rng = Rng(seed);
    let mut lua = String::from(
        "m = gr.material({0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, 25)\nroot = gr.node('root')\n",
    );
    let (mut vertices, mut faces) = (Vec::new(), Vec::new());
    for i in 0..triangles {
        let centre = [0; 3].map(|_| rng.range(-2.0, 2.0));
        for _ in 0..3 {
            let v = [0, 1, 2].map(|k| centre[k] + rng.range(-0.4, 0.4));
            vertices.push(format!("{{{}, {}, {}}}", v[0], v[1], v[2]));
        }
        faces.push(format!("{{{}, {}, {}}}", 3 * i, 3 * i + 1, 3 * i + 2));
    }
    let _ = writeln!(
        lua,
        "soup = gr.mesh('soup', {{{}}}, {{{}}}) soup:set_material(m)",
        vertices.join(", "),
        faces.join(", ")
    );
    for i in 0..instances {
        let s = [0; 3].map(|_| rng.range(0.5, 2.0));
        let axis = ["x", "y", "z"][(rng.next_u64() % 3) as usize];
        let angle = rng.range(0.0, 360.0);
        let t = [0; 3].map(|_| rng.range(-7.0, 7.0));
        let _ = writeln!(
            lua,
            "n = gr.node('place{i}') n:scale({}, {}, {}) n:rotate('{axis}', {angle}) n:translate({}, {}, {}) n:add_child(soup) root:add_child(n)",
            s[0], s[1], s[2], t[0], t[1], t[2]
        );
    }
    lua += "b = gr.sphere('ball') b:scale(2, 2, 2) b:set_material(m) root:add_child(b)\n";
    lua + "gr.render(root, 'probe.png', 64, 64, {0, 0, 30}, {0, 0, -1}, {0, 1, 0}, 50, {0.1, 0.1, 0.1}, {})\n"
}

/// Instanced meshes through both levels of grid (and by brute force): every ray agrees
/// on hit or miss, instance and triangle; closest-hit and any-hit rays alike; with the
/// traversal's full mailboxes, with one item slot (every adapter's choice) and without,
/// on both tracers, in the kernel variant this adapter chose and in the hardware variant
/// (per-ray lists in storage, no loop guard: the kernels a GPU runs, here on lavapipe),
/// and the CPU's answers are the same bit for bit each way.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn probes_instanced_meshes() {
    use common::probes::{agree, random_rays};
    use glint::constants::{PROBE_ANY_HIT, T_MISS};
    use glint::gpu::{KernelConfig, KernelVariant};
    use glint::testing::probe::{gpu_probe, probe, ProbeRay};
    let Some(mut ctx) = gpu_context() else { return };
    let chosen = ctx.kernel;
    let mut kernels = vec![chosen];
    let hardware = KernelConfig::for_variant(KernelVariant::Hardware, &ctx.limits);
    if hardware != chosen {
        kernels.push(hardware);
    }
    for (mode, grid_name) in [(GridMode::Auto, "grid"), (GridMode::Off, "brute force")] {
        let mut s = packed_from_source(&instanced_scene(11, 400, 8), &grid(mode)).remove(0);
        assert_eq!(s.meshes.len(), 1, "the soup is stored once");
        assert_eq!(s.triangles.len(), 400);
        let mut rays = random_rays(111);
        for (i, r) in rays.iter_mut().enumerate() {
            r.mode = if i % 4 == 3 { PROBE_ANY_HIT } else { 0 };
            if i % 8 == 1 || i % 8 == 7 {
                // Past T_MISS: a triangle missed (t = T_MISS) must not count as a hit.
                r.t_max = f32::INFINITY;
            }
        }
        s.mailboxes = Mailboxes::Full;
        let with_mailboxes: Vec<_> = rays.iter().map(|r| probe(&s, r)).collect();
        for (kernel, mailboxes) in kernels.iter().flat_map(|k| Mailboxes::ALL.map(|m| (*k, m))) {
            ctx.kernel = KernelConfig {
                mailboxes,
                ..kernel
            };
            let name = format!("{grid_name}, {}", ctx.kernel);
            s.mailboxes = mailboxes;
            let gpu = gpu_probe(&ctx, &s, &rays).unwrap_or_else(|e| panic!("{name}: {e}"));
            let (mut hits, mut worst_dt) = (0, 0.0f32);
            for (i, (ray, g)) in rays.iter().zip(&gpu).enumerate() {
                let c = probe(&s, ray);
                assert_eq!(
                    format!("{c:?}"),
                    format!("{:?}", with_mailboxes[i]),
                    "{name}: the CPU's mailboxes changed ray {i}'s answer"
                );
                hits += c.hit;
                if ray.mode == PROBE_ANY_HIT {
                    assert_eq!(g.hit, c.hit, "{name}: any-hit ray {i} {ray:?}");
                    if ray.t_max == f32::INFINITY {
                        let closest = probe(&s, &ProbeRay { mode: 0, ..*ray });
                        assert_eq!(c.hit, closest.hit, "{name}: any-hit ray {i} past T_MISS");
                    }
                    continue;
                }
                if ray.t_max == f32::INFINITY {
                    let below_t_miss = probe(
                        &s,
                        &ProbeRay {
                            t_max: T_MISS,
                            ..*ray
                        },
                    );
                    assert_eq!(c, below_t_miss, "{name}: ray {i} past T_MISS");
                }
                let (ok, dt, _) = agree(g, &c);
                assert!(
                    ok && g.part == c.part,
                    "{name}: ray {i} {ray:?}: gpu {g:?} cpu {c:?}"
                );
                worst_dt = worst_dt.max(dt);
            }
            eprintln!(
                "instanced meshes, {name}: {hits}/{} CPU hits, 100% agreement (hit, instance, triangle), worst |Δt|/t {worst_dt:.2e}",
                rays.len()
            );
            assert!(hits as usize > rays.len() / 8, "{name}: too few hits");
        }
    }
}

/// Smooth shading normals (the probe's PROBE_SHADING_NORMAL mode, `smooth_normal`): an
/// inline torus with vertex normals placed six times by random non-uniform scale,
/// rotation and translation (stored once, normals through world→object) and a smooth
/// sphere placed once (baked into world space), among flat triangles: both tracers give
/// the same hit and the same interpolated normal within 10⁻⁴ on every ray, and the
/// normals are not the flat ones.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn probes_smooth_normals() {
    use common::probes::{agree, random_rays};
    use glint::constants::PROBE_SHADING_NORMAL;
    use glint::testing::probe::{gpu_probe, probe, ProbeRay};
    let Some(ctx) = gpu_context() else { return };
    let mut rng = Rng(37);
    let (around, tube) = (24, 12);
    let (mut verts, mut normals, mut faces) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..around {
        let theta = std::f64::consts::TAU * i as f64 / around as f64;
        for j in 0..tube {
            let phi = std::f64::consts::TAU * j as f64 / tube as f64;
            let n = [phi.cos() * theta.cos(), phi.cos() * theta.sin(), phi.sin()];
            let ring = 2.0 + 0.7 * phi.cos();
            let p = [ring * theta.cos(), ring * theta.sin(), 0.7 * phi.sin()];
            verts.push(format!("{{{}, {}, {}}}", p[0], p[1], p[2]));
            normals.push(format!("{{{}, {}, {}}}", n[0], n[1], n[2]));
            let (a, b) = (i * tube + j, ((i + 1) % around) * tube + j);
            let (c, d) = (
                ((i + 1) % around) * tube + (j + 1) % tube,
                i * tube + (j + 1) % tube,
            );
            faces.push(format!("{{{a}, {b}, {c}, {d}}}"));
        }
    }
    let mut lua = format!(
        "m = gr.material({{0.5, 0.5, 0.5}}, {{0.5, 0.5, 0.5}}, 25)\nroot = gr.node('root')\n\
         torus = gr.mesh('torus', {{{}}}, {{{}}}, nil, {{{}}}) torus:set_material(m)\n",
        verts.join(", "),
        faces.join(", "),
        normals.join(", ")
    );
    for i in 0..6 {
        let s = [0; 3].map(|_| rng.range(0.5, 2.0));
        let angle = rng.range(0.0, 360.0);
        let t = [0; 3].map(|_| rng.range(-7.0, 7.0));
        let _ = writeln!(
            lua,
            "n = gr.node('place{i}') n:scale({}, {}, {}) n:rotate('x', {angle}) n:rotate('y', {}) n:translate({}, {}, {}) n:add_child(torus) root:add_child(n)",
            s[0], s[1], s[2], angle * 0.7, t[0], t[1], t[2]
        );
    }
    lua += "ball = gr.mesh('ball', {{0, 0, 3}, {3, 0, -1}, {-2, 3, -1}, {-2, -3, -1}}, \
            {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}}, nil, \
            {{0, 0, 1}, {3, 0, -1}, {-2, 3, -1}, {-2, -3, -1}}) ball:set_material(m) \
            ball:scale(2, 1, 1.5) ball:translate(0, 0, 1) root:add_child(ball)\n";
    lua += "flat = gr.mesh('flat', {{-9, -9, -5}, {9, -9, -5}, {0, 9, -5}}, {{0, 1, 2}}) \
            flat:set_material(m) root:add_child(flat)\n";
    lua += "gr.render(root, 'probe.png', 64, 64, {0, 0, 30}, {0, 0, -1}, {0, 1, 0}, 50, {0.1, 0.1, 0.1}, {})\n";
    let scene = packed_from_source(&lua, &grid(GridMode::Auto)).remove(0);
    assert!(
        scene.features.contains(SceneFeatures::SMOOTH),
        "[{}]",
        scene.features
    );
    assert_eq!(
        scene.meshes.len(),
        3,
        "torus stored once, ball and flat baked"
    );
    let rays: Vec<ProbeRay> = random_rays(137)
        .into_iter()
        .map(|r| ProbeRay {
            mode: PROBE_SHADING_NORMAL,
            ..r
        })
        .collect();
    let gpu = gpu_probe(&ctx, &scene, &rays).unwrap_or_else(|e| panic!("{e}"));
    let (mut hits, mut bent, mut worst_dn) = (0, 0, 0.0f32);
    for (i, (ray, g)) in rays.iter().zip(&gpu).enumerate() {
        let c = probe(&scene, ray);
        let (ok, _, dn) = agree(g, &c);
        assert!(
            ok && g.part == c.part,
            "ray {i} {ray:?}: gpu {g:?} cpu {c:?}"
        );
        hits += c.hit;
        worst_dn = worst_dn.max(dn);
        let geometric = probe(&scene, &ProbeRay { mode: 0, ..*ray });
        let dot: f32 = (0..3).map(|k| c.normal[k] * geometric.normal[k]).sum();
        bent += (c.hit == 1 && dot < 0.9999) as u32;
    }
    eprintln!(
        "smooth normals: {hits}/{} CPU hits, {bent} shading normals off the geometric one, 100% agreement, worst |Δn| {worst_dn:.2e}",
        rays.len()
    );
    assert!(hits as usize > rays.len() / 8, "too few hits");
    assert!(
        bent as usize > rays.len() / 16,
        "too few smooth hits ({bent})"
    );
}

/// Rays along the stacked frames' axis (tests/common::stacked_frames_source) meet up to six
/// mesh instances before their hit, so the scene walk's list of pending instances fills
/// and the walk resumes after walking it: both tracers give the same answers (hit,
/// instance, triangle; any-hit rays under half the hit's t and beyond it), with every
/// mailbox variant.
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn probes_rays_past_many_mesh_instances() {
    use glint::constants::{PROBE_ANY_HIT, T_MISS};
    use glint::testing::probe::{gpu_probe, probe, ProbeRay};
    let Some(mut ctx) = gpu_context() else { return };
    let mut s =
        packed_from_source(&common::stacked_frames_source(), &grid(GridMode::Auto)).remove(0);
    assert!(s.features.contains(SceneFeatures::GRID) && s.features.contains(SceneFeatures::MESH));
    let mut rays = Vec::new();
    for origin in common::stacked_frames_origins() {
        let ray = ProbeRay {
            origin,
            t_max: T_MISS,
            dir: [0.0, 0.0, -1.0],
            mode: 0,
        };
        let t = probe(&s, &ray).t;
        rays.push(ray);
        for t_max in [0.5 * t, 1.001 * t] {
            rays.push(ProbeRay {
                t_max,
                mode: PROBE_ANY_HIT,
                ..ray
            });
        }
    }
    // Both forms of the any-hit walk (ANY_HIT_ONE_LOOP: the hardware variant's one loop).
    for (mailboxes, any_hit_one_loop) in Mailboxes::ALL
        .into_iter()
        .flat_map(|m| [(m, false), (m, true)])
    {
        ctx.kernel.mailboxes = mailboxes;
        ctx.kernel.any_hit_one_loop = any_hit_one_loop;
        s.mailboxes = mailboxes;
        let form = format!("{mailboxes}, any hit in one loop {any_hit_one_loop}");
        let gpu = gpu_probe(&ctx, &s, &rays).unwrap_or_else(|e| panic!("{form}: {e}"));
        let mut items = std::collections::BTreeSet::new();
        let (mut blocked, mut hits) = (0, 0);
        for (i, (ray, g)) in rays.iter().zip(&gpu).enumerate() {
            let c = probe(&s, ray);
            if ray.mode == PROBE_ANY_HIT {
                assert_eq!(g.hit, c.hit, "{form}: any-hit ray {i} {ray:?}");
                blocked += c.hit;
                continue;
            }
            assert_eq!(
                (g.hit, g.item, g.part),
                (c.hit, c.item, c.part),
                "{form}: ray {i} {ray:?}: gpu {g:?} cpu {c:?}"
            );
            items.insert(c.item);
            hits += c.hit;
        }
        assert_eq!(items.len(), 7, "{form}: items hit {items:?}");
        // Of each hit's two any-hit rays, the one that ends just past it is blocked.
        assert_eq!(blocked, hits, "{form}");
    }
}

/// Issue 37 at the kernel-probe tier: shadow rays (`shadow_blocked`, `shadow_reach`) from
/// random points of the room's floor, walls and ball to its point light in the ceiling's
/// lower face, at scales 1, 10⁻³ and 10³: GPU and CPU agree ray by ray on blocked or not
/// and on the reach, and the ceiling through the light blocks none of them (nothing else
/// is in their way; with the reach at the exact distance, rounding blocked 1442 of the
/// 4096 at scale 1).
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn probes_shadow_rays_to_a_light_in_a_face() {
    use common::light_on_surface::{light_on_surface_scene, LightOnSurface};
    use glint::testing::probe::{gpu_probe, probe, ProbeRay, SHADOW_RAY};
    let Some(ctx) = gpu_context() else { return };
    let room = light_on_surface_scene(LightOnSurface::Face, 0.0);
    for s in [1.0, 1e-3, 1e3] {
        let scene = glint::pipeline::pack_scene(&common::scaled_scene(&room, s)).unwrap();
        let light = glam::Vec3::from(scene.lights[0].position);
        let mut rng = common::Rng(0x5AD0);
        // Points just above the floor (y = 0), away from the ball and shelf's shadows
        // (x > 0), and on the right wall (x = 50) below the ceiling.
        let rays: Vec<ProbeRay> = (0..common::probes::RAYS)
            .map(|i| {
                let p = if i % 2 == 0 {
                    glam::DVec3::new(rng.range(0.0, 49.0), 1e-3, rng.range(-49.0, 49.0))
                } else {
                    glam::DVec3::new(50.0 - 1e-3, rng.range(0.0, 49.0), rng.range(-49.0, 49.0))
                };
                let origin = (p * s).as_vec3();
                ProbeRay {
                    origin: origin.to_array(),
                    t_max: origin.abs().max_element(),
                    dir: light.to_array(),
                    mode: SHADOW_RAY,
                }
            })
            .collect();
        let gpu = gpu_probe(&ctx, &scene, &rays).unwrap_or_else(|e| panic!("{e}"));
        let (mut agreeing, mut blocked) = (0, 0);
        for (ray, g) in rays.iter().zip(&gpu) {
            let c = probe(&scene, ray);
            blocked += c.hit as usize;
            agreeing += (g.hit == c.hit && (g.t - c.t).abs() <= 1e-5 * c.t) as usize;
        }
        eprintln!(
            "shadow rays to a light in a face at scale {s}: {agreeing}/{} agree, CPU blocks {blocked}",
            rays.len()
        );
        assert_eq!(agreeing, rays.len(), "scale {s}");
        assert_eq!(
            blocked, 0,
            "scale {s}: the ceiling through the light blocks shadow rays"
        );
    }
}

/// Lua for a row of `count` small things one unit apart along `axis` from the origin —
/// spheres of radius 0.3, or (`mesh`) triangles within 0.3 of it in one mesh — and beyond
/// both ends a target across the row (a sphere of radius 1.5, or a triangle) that rays
/// along the row, passing 0.6 off it, reach only by walking the whole row. Coordinates
/// are (along, off, across), permuted so that `along` is `axis`.
fn row_scene(axis: usize, count: usize, mesh: bool) -> String {
    let at = |along: f64, off: f64, across: f64| {
        let mut p = [0.0; 3];
        p[axis] = along;
        p[(axis + 1) % 3] = off;
        p[(axis + 2) % 3] = across;
        format!("{{{}, {}, {}}}", p[0], p[1], p[2])
    };
    let ends = [-20.0, count as f64 + 20.0];
    let mut lua = String::from(
        "m = gr.material({0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, 25)\nroot = gr.node('root')\n",
    );
    if mesh {
        let mut vertices = Vec::new();
        for i in 0..count {
            let x = i as f64;
            vertices.extend([at(x, -0.3, 0.0), at(x + 0.3, 0.3, 0.0), at(x, 0.0, 0.3)]);
        }
        for along in ends {
            vertices.extend([
                at(along, -1.0, -1.0),
                at(along, 2.0, -1.0),
                at(along, -1.0, 2.0),
            ]);
        }
        let faces: Vec<String> = (0..count + 2)
            .map(|f| format!("{{{}, {}, {}}}", 3 * f, 3 * f + 1, 3 * f + 2))
            .collect();
        let _ = writeln!(
            lua,
            "t = gr.mesh('row', {{{}}}, {{{}}}) t:set_material(m) root:add_child(t)",
            vertices.join(", "),
            faces.join(", ")
        );
    } else {
        for i in 0..count {
            let centre = at(i as f64, 0.0, 0.0);
            let _ = writeln!(
                lua,
                "n = gr.nh_sphere('s{i}', {centre}, 0.3) n:set_material(m) root:add_child(n)"
            );
        }
        for (k, along) in ends.into_iter().enumerate() {
            let centre = at(along, 0.0, 0.0);
            let _ = writeln!(
                lua,
                "n = gr.nh_sphere('end{k}', {centre}, 1.5) n:set_material(m) root:add_child(n)"
            );
        }
    }
    lua + "gr.render(root, 'probe.png', 64, 64, {0, 0, 30}, {0, 0, -1}, {0, 1, 0}, 50, {0.1, 0.1, 0.1}, {})\n"
}

/// The DDA's packed steps-left counters (`DDA_STEPS_BITS` an axis) at their largest: a
/// row of 2000 spheres along x, y or z gives the scene grid `MAX_AXIS_CELLS` cells along
/// it, a row of 2000 triangles the mesh's grid; rays along each row both ways (closest
/// and any hit, under each mailbox setting, with the any-hit walk in each form) pass over
/// it to the target beyond its far end:
/// GPU and CPU hit the same item and triangle, beyond the row. (With a counter a bit too
/// narrow the walk stops half-way and misses the target; with a wrong shift it stops at
/// once or runs off the grid.)
#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn probes_walks_across_the_largest_grids() {
    use glint::accel::grid::MAX_AXIS_CELLS;
    use glint::constants::{PROBE_ANY_HIT, T_MISS};
    use glint::testing::probe::{gpu_probe, probe, ProbeRay};
    let Some(mut ctx) = gpu_context() else { return };
    let count = 2000;
    for axis in 0..3 {
        for mesh in [false, true] {
            let mut s =
                packed_from_source(&row_scene(axis, count, mesh), &grid(GridMode::Auto)).remove(0);
            let dims = if mesh {
                s.meshes[0].grid_dims
            } else {
                s.globals.grid_dims
            };
            let name = format!("axis {axis}, mesh {mesh}");
            assert_eq!(dims[axis], MAX_AXIS_CELLS, "{name}: grid {dims:?}");
            let mut rays = Vec::new();
            for (sign, start) in [(1.0f32, -5.0f32), (-1.0, count as f32 + 5.0)] {
                let (mut origin, mut dir) = ([0.0; 3], [0.0; 3]);
                origin[axis] = start;
                origin[(axis + 1) % 3] = 0.6;
                dir[axis] = sign;
                let ray = ProbeRay {
                    origin,
                    t_max: T_MISS,
                    dir,
                    mode: 0,
                };
                rays.extend([
                    ray,
                    ProbeRay {
                        mode: PROBE_ANY_HIT,
                        ..ray
                    },
                ]);
            }
            // Both forms of the any-hit walk (ANY_HIT_ONE_LOOP: the hardware variant's).
            for (mailboxes, any_hit_one_loop) in Mailboxes::ALL
                .into_iter()
                .flat_map(|m| [(m, false), (m, true)])
            {
                ctx.kernel.mailboxes = mailboxes;
                ctx.kernel.any_hit_one_loop = any_hit_one_loop;
                s.mailboxes = mailboxes;
                let gpu = gpu_probe(&ctx, &s, &rays).unwrap_or_else(|e| panic!("{name}: {e}"));
                for (i, (ray, g)) in rays.iter().zip(&gpu).enumerate() {
                    let c = probe(&s, ray);
                    let what = format!(
                        "{name}, {mailboxes}, any hit in one loop {any_hit_one_loop}, ray {i} \
                         {ray:?}: gpu {g:?} cpu {c:?}"
                    );
                    assert_eq!((g.hit, c.hit), (1, 1), "{what}");
                    if ray.mode == PROBE_ANY_HIT {
                        continue;
                    }
                    assert_eq!((g.item, g.part), (c.item, c.part), "{what}");
                    assert!(c.t > count as f32 && g.t > count as f32, "{what}");
                }
            }
        }
    }
}
