//! The textbook ray–torus test, for `glint bench --torus` only: the quartic's
//! coefficients straight from the ray (Suffern, "Ray Tracing from the Ground Up", 19.4),
//! solved in closed form by Ferrari's method through a resolvent cubic (Schwarze's
//! solver, Graphics Gems I), in f32. The tracer never uses it: it is the accuracy and
//! speed baseline glint's solver (`tracer::geometry::torus`) is measured against. Written without
//! closures or out-parameters so that its WGSL twin (shaders/bench/torus.wgsl) can
//! follow it step for step.

use crate::constants::{TWO_PI, T_MISS};
use glam::{Vec3, Vec4};

/// |u| or |v| of the resolvent's factorisation below this counts as zero (a double
/// root). Emitted into the benchmark kernel's own prelude (`torus_gpu::bench_prelude`).
pub const FERRARI_ZERO: f32 = 1.0e-12;

/// Up to four real roots: the first `count` entries of `roots` are valid.
// Mirror of shaders/bench/torus.wgsl::Roots — change both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Roots {
    pub roots: Vec4,
    pub count: u32,
}

/// Real cube root (sign-preserving; WGSL has no `cbrt`, so both twins use `pow`).
// Mirror of shaders/bench/torus.wgsl::ferrari_cbrt — change both.
pub fn ferrari_cbrt(x: f32) -> f32 {
    if x == 0.0 {
        0.0
    } else {
        x.abs().powf(1.0 / 3.0).copysign(x)
    }
}

/// Real roots of x³ + a·x² + b·x + c (Cardano, or the trigonometric form for three).
// Mirror of shaders/bench/torus.wgsl::solve_cubic — change both.
pub fn solve_cubic(a: f32, b: f32, c: f32) -> Roots {
    let sq_a = a * a;
    let p = (1.0 / 3.0) * (-(1.0 / 3.0) * sq_a + b);
    let q = 0.5 * ((2.0 / 27.0) * a * sq_a - (1.0 / 3.0) * a * b + c);
    let cb_p = p * p * p;
    let disc = q * q + cb_p;
    let mut r = Vec4::ZERO;
    let count;
    if disc == 0.0 {
        if q == 0.0 {
            count = 1;
        } else {
            let u = ferrari_cbrt(-q);
            r.x = 2.0 * u;
            r.y = -u;
            count = 2;
        }
    } else if disc < 0.0 {
        let phi = (1.0 / 3.0) * (-q / (-cb_p).sqrt()).clamp(-1.0, 1.0).acos();
        let t = 2.0 * (-p).sqrt();
        r.x = t * phi.cos();
        r.y = -t * (phi + TWO_PI / 6.0).cos();
        r.z = -t * (phi - TWO_PI / 6.0).cos();
        count = 3;
    } else {
        let sqrt_d = disc.sqrt();
        r.x = ferrari_cbrt(sqrt_d - q) - ferrari_cbrt(sqrt_d + q);
        count = 1;
    }
    Roots {
        roots: r - Vec4::splat(a / 3.0),
        count,
    }
}

/// Appends the real roots of x² + p·x + q (shifted by `shift`) to `out`.
// Mirror of shaders/bench/torus.wgsl::push_quadratic_roots — change both.
fn push_quadratic_roots(out: Roots, p: f32, q: f32, shift: f32) -> Roots {
    let mut out = out;
    let disc = 0.25 * p * p - q;
    if disc >= 0.0 {
        let s = disc.sqrt();
        out.roots[out.count as usize] = -0.5 * p + s - shift;
        out.roots[out.count as usize + 1] = -0.5 * p - s - shift;
        out.count += 2;
    }
    out
}

/// Real roots of x⁴ + a·x³ + b·x² + c·x + d by Ferrari's method.
// Mirror of shaders/bench/torus.wgsl::solve_quartic — change both.
pub fn solve_quartic(a: f32, b: f32, c: f32, d: f32) -> Roots {
    let sq_a = a * a;
    // Substitute x = y − a/4: y⁴ + p·y² + q·y + r.
    let p = -(3.0 / 8.0) * sq_a + b;
    let q = (1.0 / 8.0) * sq_a * a - 0.5 * a * b + c;
    let r = -(3.0 / 256.0) * sq_a * sq_a + (1.0 / 16.0) * sq_a * b - 0.25 * a * c + d;
    let shift = 0.25 * a;
    let mut out = Roots {
        roots: Vec4::ZERO,
        count: 0,
    };
    if r == 0.0 {
        // y·(y³ + p·y + q) = 0.
        let cubic = solve_cubic(0.0, p, q);
        out.roots.x = -shift;
        for i in 0..cubic.count as usize {
            out.roots[i + 1] = cubic.roots[i] - shift;
        }
        out.count = cubic.count + 1;
        return out;
    }
    // Solve the resolvent cubic and take one real root.
    let z = solve_cubic(-0.5 * p, -r, 0.5 * r * p - (1.0 / 8.0) * q * q)
        .roots
        .x;
    let mut u = z * z - r;
    let mut v = 2.0 * z - p;
    if u.abs() < FERRARI_ZERO {
        u = 0.0;
    } else if u > 0.0 {
        u = u.sqrt();
    } else {
        return out;
    }
    if v.abs() < FERRARI_ZERO {
        v = 0.0;
    } else if v > 0.0 {
        v = v.sqrt();
    } else {
        return out;
    }
    let sv = if q < 0.0 { -v } else { v };
    out = push_quadratic_roots(out, sv, z - u, shift);
    push_quadratic_roots(out, -sv, z + u, shift)
}

/// The smallest t > 0 where `o + t·d` meets the torus (`rin`, `rout`) in the XY plane,
/// else [`T_MISS`].
// Mirror of shaders/bench/torus.wgsl::intersect_torus_ferrari — change both.
pub fn intersect_torus_ferrari(o: Vec3, d: Vec3, rin: f32, rout: f32) -> f32 {
    let four_r2 = 4.0 * rin * rin;
    let e = o.dot(o) - rin * rin - rout * rout;
    let f = o.dot(d);
    let c3 = 4.0 * f;
    let c2 = 2.0 * e + 4.0 * f * f + four_r2 * d.z * d.z;
    let c1 = 4.0 * f * e + 2.0 * four_r2 * o.z * d.z;
    let c0 = e * e - four_r2 * (rout * rout - o.z * o.z);
    let roots = solve_quartic(c3, c2, c1, c0);
    let mut best = T_MISS;
    for i in 0..roots.count as usize {
        // NaN and infinities fail one of the comparisons.
        let t = roots.roots[i];
        if t > 0.0 && t < best {
            best = t;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quartic_with_four_known_roots() {
        // (x − 1)(x − 2)(x + 3)(x − 0.5) = x⁴ − 0.5x³ − 7x² + 9.5x − 3.
        let r = solve_quartic(-0.5, -7.0, 9.5, -3.0);
        assert_eq!(r.count, 4);
        let mut found: Vec<f32> = (0..4).map(|i| r.roots[i]).collect();
        found.sort_by(f32::total_cmp);
        for (f, want) in found.iter().zip([-3.0, 0.5, 1.0, 2.0]) {
            assert!((f - want).abs() < 1e-3, "{found:?}");
        }
    }

    #[test]
    fn ray_through_the_tube_hits_at_the_near_side() {
        // From x = 5 towards −x along the axis of the tube's centre circle at y = 0:
        // the torus (1, 0.25) is met first at x = 1.25, t = 3.75.
        let t = intersect_torus_ferrari(Vec3::new(5.0, 0.0, 0.0), Vec3::NEG_X, 1.0, 0.25);
        assert!((t - 3.75).abs() < 1e-3, "{t}");
        let miss = intersect_torus_ferrari(Vec3::new(5.0, 0.0, 2.0), Vec3::NEG_X, 1.0, 0.25);
        assert_eq!(miss, T_MISS);
    }
}
