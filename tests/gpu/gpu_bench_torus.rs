//! Parity of the torus benchmark's GPU kernel (shaders/bench/torus.wgsl) with its CPU
//! twins: glint's `intersect_torus` and the textbook Ferrari solver (`bench::ferrari`), on
//! the same seeded rays. The benchmark's GPU rows are only meaningful if the kernels
//! compute what the CPU rows compute.

use crate::common;

use common::gpu_context;
use glint::bench::ferrari::intersect_torus_ferrari;
use glint::bench::torus_gpu::{GpuTorusBench, GpuTorusSolver};
use glint::bench::torus_rays;
use glint::constants::T_MISS;
use glint::tracer::geometry::torus::intersect_torus;

/// Share of rays on which `a` and `b` agree: both miss, or both hit within `rel` of t.
fn agreement(a: &[f32], b: &[f32], rel: f32) -> f64 {
    let same = a
        .iter()
        .zip(b)
        .filter(|(&x, &y)| {
            (x == T_MISS && y == T_MISS)
                || (x != T_MISS && y != T_MISS && (x - y).abs() <= rel * x.abs().max(y.abs()))
        })
        .count();
    same as f64 / a.len() as f64
}

#[test]
#[cfg_attr(glint_skip_gpu, ignore = "needs a GPU adapter (GLINT_SKIP_GPU=1)")]
fn gpu_torus_kernels_match_their_cpu_twins() {
    let Some(ctx) = gpu_context() else { return };
    let bench = GpuTorusBench::new(ctx).expect("torus bench kernel");
    for (rin, rout) in [(1.0f32, 0.4f32), (1.0, 1.5)] {
        // The benchmark's own rays, 1.5–4 bounding radii away (where Ferrari in f32 is
        // still mostly right, so its twins can be compared).
        let rays = torus_rays::rays(4096, rin as f64, rout as f64, 1.5, 4.0, 0x7025_B3AC);
        let hits = rays
            .iter()
            .filter(|r| intersect_torus(r.o, r.d, rin, rout, T_MISS) != T_MISS)
            .count();
        assert!(
            hits > 400 && hits < 3700,
            "{hits} hits: the rays must mix hits and misses"
        );

        let cpu: Vec<f32> = rays
            .iter()
            .map(|r| intersect_torus(r.o, r.d, rin, rout, T_MISS))
            .collect();
        let (_, gpu) = bench
            .solve(&rays, rin, rout, GpuTorusSolver::Glint, 1)
            .unwrap();
        let glint_agreement = agreement(&cpu, &gpu, 1e-5);
        assert!(
            glint_agreement >= 0.999,
            "glint solver ({rin}, {rout}): GPU agrees with CPU on {:.3}%",
            100.0 * glint_agreement
        );

        let cpu: Vec<f32> = rays
            .iter()
            .map(|r| intersect_torus_ferrari(r.o, r.d, rin, rout))
            .collect();
        let (_, gpu) = bench
            .solve(&rays, rin, rout, GpuTorusSolver::Ferrari, 1)
            .unwrap();
        // Ferrari is ill-conditioned: the GPU's own rounding (fused multiply-adds, pow
        // for the cube root) moves some roots, so agree "mostly" — but a wrong formula
        // in either twin would disagree on most rays.
        let ferrari_agreement = agreement(&cpu, &gpu, 1e-2);
        assert!(
            ferrari_agreement >= 0.99,
            "Ferrari ({rin}, {rout}): GPU agrees with CPU on {:.3}%",
            100.0 * ferrari_agreement
        );
        println!(
            "torus ({rin}, {rout}): {hits} hits of 4096; GPU = CPU on {:.2}% (glint), {:.2}% (Ferrari)",
            100.0 * glint_agreement,
            100.0 * ferrari_agreement
        );
    }
}
