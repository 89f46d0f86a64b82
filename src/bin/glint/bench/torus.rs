//! `glint bench --torus`: ray–torus intersections per second on the CPU for glint's
//! solver (`tracer::geometry::torus`: rescaled, clipped quartic; derivative-split Newton–bisection)
//! against the textbook closed form (Ferrari via a resolvent cubic, Schwarze's
//! Graphics Gems I solver, in f32 — here for the comparison only), each with its
//! accuracy against an f64 oracle on the same rays: hit/miss disagreements (grazing rays
//! included, so a few are expected for both) and the worst and 99th-percentile |Δt|/t.
//! With a GPU adapter, both solvers also run on the GPU (`bench_torus_gpu`).

use super::common::BenchArgs;
use super::timing::fastest;
use glam::DVec3;
use glint::bench::ferrari::intersect_torus_ferrari;
use glint::bench::torus_gpu::{GpuTorusBench, GpuTorusSolver};
pub use glint::bench::torus_rays::{rays, TorusRay};
use glint::gpu::GpuContext;
use glint::tracer::geometry::torus::intersect_torus;
use rayon::prelude::*;

/// f64 oracle: first sign change of the factored torus function along the bounding
/// sphere's chord (1024 samples from the closest approach), bisected to the last bit.
fn oracle(r: &TorusRay, rin: f64, rout: f64) -> Option<f64> {
    let (o, d) = (r.o.as_dvec3(), r.d.as_dvec3().normalize());
    let f = |p: DVec3| {
        let rho = (p.x * p.x + p.y * p.y).sqrt();
        let q = ((rho - rin).powi(2) + p.z * p.z).sqrt();
        (q - rout) * (q + rout) * ((rho + rin).powi(2) + p.z * p.z - rout * rout)
    };
    let s_c = -o.dot(d);
    let c = o + d * s_c;
    let bound = (rin + rout) * 1.001;
    let h2 = bound * bound - c.length_squared();
    if h2 <= 0.0 {
        return None;
    }
    let h = h2.sqrt();
    let lo_u = (-h).max(-s_c);
    if lo_u >= h {
        return None;
    }
    const N: usize = 1024;
    let mut a = lo_u;
    let mut fa = f(c + d * a);
    for i in 1..=N {
        let b = lo_u + (h - lo_u) * (i as f64 / N as f64);
        let fb = f(c + d * b);
        if (fa < 0.0) != (fb < 0.0) {
            let (mut lo, mut hi) = (a, b);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                if (f(c + d * mid) < 0.0) == (fa < 0.0) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let t = s_c + 0.5 * (lo + hi);
            return (t > 0.0).then_some(t);
        }
        a = b;
        fa = fb;
    }
    None
}

/// (hit/miss disagreements, worst |Δt|/t, 99th percentile |Δt|/t) against the oracle.
fn accuracy(ts: &[f32], truth: &[Option<f64>]) -> (usize, f64, f64) {
    let mut wrong = 0;
    let mut errors = Vec::new();
    for (&t, &o) in ts.iter().zip(truth) {
        match (t < f32::MAX, o) {
            (true, Some(o)) => errors.push((t as f64 - o).abs() / o),
            (false, None) => {}
            _ => wrong += 1,
        }
    }
    errors.sort_by(f64::total_cmp);
    let worst = errors.last().copied().unwrap_or(0.0);
    let p99 = errors
        .get(errors.len().saturating_sub(1) * 99 / 100)
        .copied()
        .unwrap_or(0.0);
    (wrong, worst, p99)
}

/// A torus test on one ray: (ray, rin, rout) → t or `f32::MAX`.
type Solver = fn(&TorusRay, f32, f32) -> f32;

pub fn bench_torus(args: &BenchArgs) -> anyhow::Result<()> {
    let count = args.rays.min(200_000);
    // The GPU rows need an adapter (lavapipe counts); without one they are skipped.
    let gpu = match GpuContext::new(args.adapter.as_deref()).and_then(GpuTorusBench::new) {
        Ok(bench) => Some(bench),
        Err(e) => {
            println!("(GPU rows skipped: {e})");
            None
        }
    };
    println!(
        "\n## Ray–torus intersection, {count} rays per row (CPU: {} threads; GPU: {}; fastest of {})",
        rayon::current_num_threads(),
        gpu.as_ref().map_or("none", |g| g.adapter_name()),
        args.repeat
    );
    println!("| torus (rin, rout) | origins (sizes away) | solver | Mrays/s | hit/miss wrong | worst \\|Δt\\|/t | p99 \\|Δt\\|/t |");
    println!("| --- | --- | --- | ---: | ---: | ---: | ---: |");
    for (rin, rout) in [(1.0f32, 0.4f32), (1.0, 0.05), (1.0, 1.5)] {
        for (near, far) in [(1.0001, 3.0), (3.0, 1e2), (1e2, 1e4)] {
            let rays = rays(count, rin as f64, rout as f64, near, far, 17);
            let truth: Vec<Option<f64>> = rays
                .par_iter()
                .map(|r| oracle(r, rin as f64, rout as f64))
                .collect();
            let solvers: [(&str, Solver); 2] = [
                ("glint, CPU", |r, a, b| {
                    intersect_torus(r.o, r.d, a, b, f32::MAX)
                }),
                ("Ferrari, CPU", |r, a, b| {
                    intersect_torus_ferrari(r.o, r.d, a, b)
                }),
            ];
            for (name, solve) in solvers {
                let (time, ts) = fastest(args.repeat, || {
                    rays.par_iter()
                        .map(|r| solve(r, rin, rout))
                        .collect::<Vec<f32>>()
                });
                let (wrong, worst, p99) = accuracy(&ts, &truth);
                println!(
                    "| ({rin}, {rout}) | {near}–{far:e} | {name} | {:.1} | {wrong} | {worst:.1e} | {p99:.1e} |",
                    count as f64 / time.as_secs_f64() / 1e6
                );
            }
            if let Some(gpu) = &gpu {
                for (name, solver) in [
                    ("glint, GPU", GpuTorusSolver::Glint),
                    ("Ferrari, GPU", GpuTorusSolver::Ferrari),
                ] {
                    let (time, ts) = gpu.solve(&rays, rin, rout, solver, args.repeat)?;
                    let (wrong, worst, p99) = accuracy(&ts, &truth);
                    println!(
                        "| ({rin}, {rout}) | {near}–{far:e} | {name} | {:.1} | {wrong} | {worst:.1e} | {p99:.1e} |",
                        count as f64 / time.as_secs_f64() / 1e6
                    );
                }
            }
        }
    }
    Ok(())
}
