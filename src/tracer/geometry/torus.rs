//! The torus in f32: ray intersection by a bracketed polynomial root finder, and the
//! surface (refined point, normal, UV, tangent frame) at a hit.
//!
//! Object space: centred at the origin in the XY plane, axis z; `rin` from the centre to
//! the middle of the tube, `rout` the tube's radius. `rout > rin` is a self-intersecting
//! "spindle" torus: the quartic then also has the inner "lemon" sheet, which the normal
//! and the UV follow (see `torus_surface`).
//!
//! Why not the textbook closed form (Ferrari's resolvent cubic): in f32 its square roots
//! of nearly cancelling terms lose most digits for far origins, thin tubes and grazing
//! rays (`glint bench --torus` measures it). Instead, after Yuksel, "High-Performance
//! Polynomial Root Finding for Graphics" (HPG 2022):
//! 1. work in units of the bounding radius rin + rout, and move the ray origin to where
//!    the ray enters the bounding sphere ∩ the slab |z| ≤ rout (so the quartic's
//!    coefficients are O(1) and its interval of interest is at most ~2 long);
//! 2. split that interval where the quartic's derivative (a cubic) vanishes — found the
//!    same way from its own derivative, a quadratic solved in closed form — so every
//!    piece is monotonic;
//! 3. in the first piece whose ends differ in sign, Newton's method with a bisection
//!    fallback (the bracket only shrinks), at most `TORUS_NEWTON_ITERATIONS` steps.
//!
//! The degree recursion is unrolled by hand (quadratic → cubic → quartic): WGSL has no
//! recursion, and the twin in `src/tracer/geometry/torus.wgsl` follows this file step for step.

use super::uv::ObjectSurface;
use crate::constants::{
    TORUS_BOUND_MARGIN, TORUS_NEWTON_ITERATIONS, TORUS_ROOT_TOLERANCE, TWO_PI, T_MISS,
};
use crate::tracer::base::math::safe_rcp;
use glam::{Vec2, Vec3, Vec4};

/// (p(x), p′(x)) for p(x) = a4·x⁴ + a.w·x³ + a.z·x² + a.y·x + a.x (Horner).
// Mirror of src/tracer/geometry/torus.wgsl::poly_eval — change both.
pub fn poly_eval(a: Vec4, a4: f32, x: f32) -> Vec2 {
    let f = (((a4 * x + a.w) * x + a.z) * x + a.y) * x + a.x;
    let df = ((4.0 * a4 * x + 3.0 * a.w) * x + 2.0 * a.z) * x + a.y;
    Vec2::new(f, df)
}

/// The root of p (as in [`poly_eval`]) between `x0` and `x1`, where p(x0) has the sign of
/// `f0` and p(x1) the other: Newton steps from the midpoint, a bisection step wherever
/// Newton would leave the bracket (which shrinks every step).
// Mirror of src/tracer/geometry/torus.wgsl::newton_bisect — change both.
pub fn newton_bisect(a: Vec4, a4: f32, x0: f32, x1: f32, f0: f32) -> f32 {
    let negative_at_lo = f0 < 0.0;
    let mut lo = x0;
    let mut hi = x1;
    let mut x = 0.5 * (x0 + x1);
    for _ in 0..TORUS_NEWTON_ITERATIONS {
        let p = poly_eval(a, a4, x);
        if p.x == 0.0 {
            return x;
        }
        // Shrink the bracket to the side where the sign changes.
        if (p.x < 0.0) == negative_at_lo {
            lo = x;
        } else {
            hi = x;
        }
        // Take the Newton step if it stays inside the bracket, else bisect.
        let mut next = 0.5 * (lo + hi);
        if p.y != 0.0 {
            let newton = x - p.x / p.y;
            if newton > lo.min(hi) && newton < lo.max(hi) {
                next = newton;
            }
        }
        let step = (next - x).abs();
        x = next;
        if step <= TORUS_ROOT_TOLERANCE * x.abs() {
            break;
        }
    }
    x
}

/// Knots that split [0, `len`] into pieces where the monic quartic
/// s⁴ + c.w·s³ + c.z·s² + c.y·s + c.x is monotonic: `knots[0..=count]`, from 0 to `len`.
#[derive(Clone, Copy, Debug, PartialEq)]
// Mirror of src/tracer/geometry/torus.wgsl::QuarticKnots — change both.
pub struct QuarticKnots {
    pub knots: [f32; 5],
    pub count: u32,
}

/// The monotonic pieces of the monic quartic `c` on [0, `len`] (see [`QuarticKnots`]).
// Mirror of src/tracer/geometry/torus.wgsl::quartic_knots — change both.
pub fn quartic_knots(c: Vec4, len: f32) -> QuarticKnots {
    // Compute the roots of the quartic's second derivative 12s² + 6c₃s + 2c₂ (halved:
    // 6s² + 3c₃s + c₂) in closed form; they split [0, len] into pieces where the cubic
    // (the first derivative) is monotonic.
    let qa = 6.0;
    let qb = 3.0 * c.w;
    let qc = c.z;
    let discriminant = qb * qb - 4.0 * qa * qc;
    let mut k1 = len;
    let mut k2 = len;
    if discriminant > 0.0 {
        let q = -0.5 * (qb + discriminant.sqrt().copysign(qb));
        if q != 0.0 {
            let r0 = q / qa;
            let r1 = qc / q;
            k1 = r0.min(r1).clamp(0.0, len);
            k2 = r0.max(r1).clamp(0.0, len);
        }
    }
    // Find the cubic's roots 4s³ + 3c₃s² + 2c₂s + c₁ in each monotonic piece: they split
    // [0, len] into pieces where the quartic is monotonic.
    let cubic = Vec4::new(c.y, 2.0 * c.z, 3.0 * c.w, 4.0);
    let cubic_knots = [0.0, k1, k2, len];
    let mut knots = [0.0, len, len, len, len];
    let mut count = 1;
    let mut y0 = poly_eval(cubic, 0.0, 0.0).x;
    for i in 0..3 {
        let (x0, x1) = (cubic_knots[i], cubic_knots[i + 1]);
        let y1 = poly_eval(cubic, 0.0, x1).x;
        if x0 < x1 && (y0 < 0.0) != (y1 < 0.0) {
            knots[count] = newton_bisect(cubic, 0.0, x0, x1, y0);
            count += 1;
        }
        y0 = y1;
    }
    knots[count] = len;
    QuarticKnots {
        knots,
        count: count as u32,
    }
}

/// Smallest root in [0, `len`] of the monic quartic s⁴ + c.w·s³ + c.z·s² + c.y·s + c.x,
/// or −1 when it has none there (no sign change between monotonic pieces; a double root
/// that only touches zero counts as none).
// Mirror of src/tracer/geometry/torus.wgsl::first_quartic_root — change both.
pub fn first_quartic_root(c: Vec4, len: f32) -> f32 {
    let k = quartic_knots(c, len);
    // Find the quartic's first root: in the first monotonic piece whose ends differ in
    // sign.
    let quartic = c;
    let mut y0 = poly_eval(quartic, 1.0, 0.0).x;
    for i in 0..k.count as usize {
        let (x0, x1) = (k.knots[i], k.knots[i + 1]);
        let y1 = poly_eval(quartic, 1.0, x1).x;
        if x0 < x1 && (y0 < 0.0) != (y1 < 0.0) {
            return newton_bisect(quartic, 1.0, x0, x1, y0);
        }
        y0 = y1;
    }
    -1.0
}

/// The part of a ray inside the torus's bounds, set up for the root finder: the ray
/// enters the bounds at `t_near`; s = (t − t_near)·`speed` runs over [0, `len`], where
/// the torus is the monic quartic `c` in s ≤ 0. `valid` is false when the ray misses the
/// bounds between `t_min` and `t_max`.
#[derive(Clone, Copy, Debug, PartialEq)]
// Mirror of src/tracer/geometry/torus.wgsl::TorusChord — change both.
pub struct TorusChord {
    pub t_near: f32,
    pub speed: f32,
    pub len: f32,
    pub c: Vec4,
    pub valid: bool,
}

/// The chord of `o + t·d` (object space, unnormalised d) through the bounds of the torus
/// (`rin`, `rout`), clipped to [`t_min`, `t_max`], and the quartic along it.
// Mirror of src/tracer/geometry/torus.wgsl::torus_chord — change both.
pub fn torus_chord(o: Vec3, d: Vec3, rin: f32, rout: f32, t_min: f32, t_max: f32) -> TorusChord {
    let mut chord = TorusChord {
        t_near: 0.0,
        speed: 1.0,
        len: 0.0,
        c: Vec4::ZERO,
        valid: false,
    };
    // Work in units of the bounding radius rin + rout (t is unchanged).
    let inv_size = 1.0 / (rin + rout);
    let o1 = o * inv_size;
    let d1 = d * inv_size;
    let r_mid = rin * inv_size;
    let r_tube = rout * inv_size;
    // Clip the ray to the bounding sphere (stable quadratic, as in intersect_sphere) ...
    let bound = 1.0 + TORUS_BOUND_MARGIN;
    let a = d1.dot(d1);
    let b = o1.dot(d1);
    let l = o1 - d1 * (b / a);
    let discriminant = a * (bound * bound - l.dot(l));
    if discriminant < 0.0 {
        return chord;
    }
    let q = -b - discriminant.sqrt().copysign(b);
    if q == 0.0 {
        return chord;
    }
    let r0 = (o1.dot(o1) - bound * bound) / q;
    let r1 = q / a;
    // ... and to the slab |z| ≤ tube radius.
    let half_height = r_tube + TORUS_BOUND_MARGIN;
    let inv_dz = safe_rcp(d1.z);
    let z0 = (-half_height - o1.z) * inv_dz;
    let z1 = (half_height - o1.z) * inv_dz;
    let t_near = r0.min(r1).max(z0.min(z1)).max(t_min);
    let t_far = r0.max(r1).min(z0.max(z1)).min(t_max);
    if t_near >= t_far {
        return chord;
    }
    // Move the origin to the entry point and make the direction unit: s = (t − t_near)·|d|.
    let p = o1 + d1 * t_near;
    let speed = a.sqrt();
    let dn = d1 / speed;
    let len = (t_far - t_near) * speed;
    // Compute the quartic's coefficients: (|p + s·dn|² + R² − r²)² − 4R²·ρ(s)² = 0.
    let k = p.dot(p) + (r_mid - r_tube) * (r_mid + r_tube);
    let bd = p.dot(dn);
    let rr4 = 4.0 * r_mid * r_mid;
    let c3 = 4.0 * bd;
    let c2 = 4.0 * bd * bd + 2.0 * k - rr4 * (dn.x * dn.x + dn.y * dn.y);
    let c1 = 4.0 * bd * k - 2.0 * rr4 * (p.x * dn.x + p.y * dn.y);
    // c₀ = K² − 4R²ρ² as ((ρ−R)² + z² − r²)·((ρ+R)² + z² − r²), the first factor as
    // (q − r)(q + r): no cancellation when p lies near the surface.
    let rho = Vec2::new(p.x, p.y).length();
    let tube_dist = Vec2::new(rho - r_mid, p.z).length();
    let near = (tube_dist - r_tube) * (tube_dist + r_tube);
    let far = (rho + r_mid) * (rho + r_mid) + p.z * p.z - r_tube * r_tube;
    let c0 = near * far;
    chord.t_near = t_near;
    chord.speed = speed;
    chord.len = len;
    chord.c = Vec4::new(c0, c1, c2, c3);
    chord.valid = true;
    chord
}

/// Nearest t in (0, t_max) where `o + t·d` (object space, unnormalised d) meets the torus
/// (`rin`, `rout`), else [`T_MISS`].
// Mirror of src/tracer/geometry/torus.wgsl::intersect_torus — change both.
pub fn intersect_torus(o: Vec3, d: Vec3, rin: f32, rout: f32, t_max: f32) -> f32 {
    let chord = torus_chord(o, d, rin, rout, 0.0, t_max);
    if !chord.valid {
        return T_MISS;
    }
    let s = first_quartic_root(chord.c, chord.len);
    if s < 0.0 {
        return T_MISS;
    }
    let t = chord.t_near + s / chord.speed;
    if t > 0.0 && t < t_max {
        t
    } else {
        T_MISS
    }
}

/// The t-intervals where `o + t·d` (object space, unnormalised d) is inside the torus
/// (`rin`, `rout`) — where its quartic is ≤ 0, so for a spindle torus the apple minus the
/// lemon, whose boundary is both drawn sheets: [x, y] and [z, w], each empty when its
/// lo > hi, the second after the first. The whole line is searched: it enters the bounds
/// outside the torus (they are grown by `TORUS_BOUND_MARGIN`), and every sign change of
/// the quartic between its monotonic pieces is a crossing, at most four. An unpaired last
/// crossing (a tangent's rounding) is closed where the line leaves the bounds.
// Mirror of src/tracer/geometry/torus.wgsl::torus_intervals — change both.
pub fn torus_intervals(o: Vec3, d: Vec3, rin: f32, rout: f32) -> Vec4 {
    let empty = Vec4::new(T_MISS, -T_MISS, T_MISS, -T_MISS);
    let chord = torus_chord(o, d, rin, rout, -T_MISS, T_MISS);
    if !chord.valid {
        return empty;
    }
    let k = quartic_knots(chord.c, chord.len);
    // Every piece whose ends differ in sign holds one crossing.
    let quartic = chord.c;
    let mut ends = [chord.len; 4];
    let mut count = 0;
    let mut y0 = poly_eval(quartic, 1.0, 0.0).x;
    for i in 0..k.count as usize {
        let (x0, x1) = (k.knots[i], k.knots[i + 1]);
        let y1 = poly_eval(quartic, 1.0, x1).x;
        if x0 < x1 && (y0 < 0.0) != (y1 < 0.0) {
            ends[count] = newton_bisect(quartic, 1.0, x0, x1, y0);
            count += 1;
        }
        y0 = y1;
    }
    let t = |s: f32| chord.t_near + s / chord.speed;
    let mut out = empty;
    if count > 0 {
        out.x = t(ends[0]);
        out.y = t(ends[1]);
    }
    if count > 2 {
        out.z = t(ends[2]);
        out.w = t(ends[3]);
    }
    out
}

/// Point, normal, UV and tangent frame at the torus point nearest `p`: `p` moves onto
/// the tube circle around the nearest point of the centre circle. On a spindle torus's
/// inner sheet (`rout > rin`) the tube circle is the far one (the sheet is part of the
/// tube around the opposite centre point), and the normal points into the lemon.
// Mirror of src/tracer/geometry/torus.wgsl::torus_surface — change both.
pub fn torus_surface(p: Vec3, rin: f32, rout: f32) -> ObjectSurface {
    // Compute the radial direction (any one on the axis).
    let rho = Vec2::new(p.x, p.y).length();
    let radial = if rho > 0.0 {
        Vec2::new(p.x, p.y) / rho
    } else {
        Vec2::new(1.0, 0.0)
    };
    // Pick the tube circle: the near one, but the far one on a spindle's inner sheet.
    let near = (rho - rin) * (rho - rin) + p.z * p.z - rout * rout;
    let far = (rho + rin) * (rho + rin) + p.z * p.z - rout * rout;
    let side = if far.abs() < near.abs() { -1.0 } else { 1.0 };
    let centre = (radial * (side * rin)).extend(0.0);
    // Normal from the tube's centre, and the point projected onto the tube.
    let offset = p - centre;
    let dist = offset.length();
    let normal = if dist > 0.0 {
        offset / dist
    } else {
        (radial * side).extend(0.0)
    };
    let on_surface = centre + normal * rout;
    // UV: θ around the axis, φ around the tube from the outward radial direction.
    let cos_phi = normal.x * radial.x + normal.y * radial.y;
    let sin_phi = normal.z;
    let mut u = on_surface.y.atan2(on_surface.x) / TWO_PI;
    if u < 0.0 {
        u += 1.0;
    }
    let mut v = sin_phi.atan2(cos_phi) / TWO_PI;
    if v < 0.0 {
        v += 1.0;
    }
    // Tangent frame: ∂p/∂θ = (−y, x, 0), ∂p/∂φ = r·(−sin φ·radial, cos φ).
    let dpdu = Vec3::new(-on_surface.y, on_surface.x, 0.0) * TWO_PI;
    let dpdv = (radial * -sin_phi).extend(cos_phi) * (TWO_PI * rout);
    ObjectSurface {
        p: on_surface,
        normal,
        uv: Vec2::new(u, v),
        dpdu,
        dpdv,
    }
}
