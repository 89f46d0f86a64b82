//! GPU kernel probes shared by `gpu_probes.rs` and `gpu_cylinder_cone.rs`: seeded rays,
//! traced by the GPU's `closest_hit` + `surface_at` (the test-only `probe` entry point)
//! and by the CPU's; ≥ 99.9% must agree on hit/miss and item with |Δt|/t ≤ 1e-4 and
//! normals within 1e-4.

use super::Rng;
use glam::DVec3;
use glint::constants::T_MISS;
use glint::gpu::GpuContext;
use glint::pack::PackedScene;
use glint::testing::probe::{gpu_probe, probe, ProbeRay, ProbeResult};

pub const RAYS: usize = 4096;

pub const REQUIRED_AGREEMENT: f64 = 0.999;

pub const T_TOLERANCE: f32 = 1e-4;

pub const NORMAL_TOLERANCE: f32 = 1e-4;

/// Rays from random points in [-15, 15]³ towards random points in [-10, 10]³, so that
/// most hit something; one in eight has a finite t_max.
pub fn random_rays(seed: u64) -> Vec<ProbeRay> {
    let mut rng = Rng(seed);
    (0..RAYS)
        .map(|i| {
            let origin = DVec3::new(
                rng.range(-15.0, 15.0),
                rng.range(-15.0, 15.0),
                rng.range(-15.0, 15.0),
            );
            let target = DVec3::new(
                rng.range(-10.0, 10.0),
                rng.range(-10.0, 10.0),
                rng.range(-10.0, 10.0),
            );
            let dir = (target - origin).normalize();
            ProbeRay {
                origin: origin.as_vec3().to_array(),
                t_max: if i % 8 == 0 {
                    rng.range(1.0, 30.0) as f32
                } else {
                    T_MISS
                },
                dir: dir.as_vec3().to_array(),
                mode: 0,
            }
        })
        .collect()
}

/// Whether GPU and CPU agree on one ray, and the relative t and normal errors.
pub fn agree(gpu: &ProbeResult, cpu: &ProbeResult) -> (bool, f32, f32) {
    if gpu.hit != cpu.hit {
        return (false, f32::INFINITY, f32::INFINITY);
    }
    if cpu.hit == 0 {
        return (true, 0.0, 0.0);
    }
    let dt = (gpu.t - cpu.t).abs() / cpu.t.abs();
    let dn = (0..3)
        .map(|k| (gpu.normal[k] - cpu.normal[k]).abs())
        .fold(0.0, f32::max);
    (
        gpu.item == cpu.item && dt <= T_TOLERANCE && dn <= NORMAL_TOLERANCE,
        dt,
        dn,
    )
}

pub fn check(ctx: &GpuContext, name: &str, scene: &PackedScene, ray_seed: u64) {
    let rays = random_rays(ray_seed);
    let gpu = gpu_probe(ctx, scene, &rays).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(gpu.len(), rays.len());
    let mut agreeing = 0;
    let mut hits = 0;
    let (mut worst_dt, mut worst_dn) = (0.0f32, 0.0f32);
    let mut first_bad = None;
    for (i, (ray, g)) in rays.iter().zip(&gpu).enumerate() {
        let c = probe(scene, ray);
        hits += c.hit as usize;
        let (ok, dt, dn) = agree(g, &c);
        if ok {
            agreeing += 1;
            worst_dt = worst_dt.max(dt);
            worst_dn = worst_dn.max(dn);
        } else if first_bad.is_none() {
            first_bad = Some(format!("ray {i} {ray:?}: gpu {g:?} cpu {c:?}"));
        }
    }
    let rate = agreeing as f64 / rays.len() as f64;
    eprintln!(
        "{name}: features [{}], {hits}/{} CPU hits, agreement {:.4}% ({agreeing}/{}), worst agreeing |Δt|/t {worst_dt:.2e}, |Δn| {worst_dn:.2e}",
        scene.features,
        rays.len(),
        rate * 100.0,
        rays.len()
    );
    assert!(
        hits > rays.len() / 8,
        "{name}: too few hits ({hits}) to test anything"
    );
    assert!(
        rate >= REQUIRED_AGREEMENT,
        "{name} (ray seed {ray_seed}): agreement {:.4}% < {}%; first disagreement: {}",
        rate * 100.0,
        REQUIRED_AGREEMENT * 100.0,
        first_bad.unwrap_or_default()
    );
}

/// One Lua line that adds `ctor` (a `gr` call) to `root` with material `m`, scaled by a
/// random factor in `scale` on each axis, rotated by a random angle about a random axis
/// and moved to a random point within ±`extent` on each axis.
pub fn random_placed(rng: &mut Rng, ctor: &str, scale: (f64, f64), extent: f64) -> String {
    let s = [0; 3].map(|_| rng.range(scale.0, scale.1));
    let axis = ["x", "y", "z"][(rng.next_u64() % 3) as usize];
    let angle = rng.range(0.0, 360.0);
    let t = [0; 3].map(|_| rng.range(-extent, extent));
    format!(
        "n = {ctor} n:scale({}, {}, {}) n:rotate('{axis}', {angle}) n:translate({}, {}, {}) n:set_material(m) root:add_child(n)",
        s[0], s[1], s[2], t[0], t[1], t[2]
    )
}
