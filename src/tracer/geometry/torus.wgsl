// torus.wgsl — the torus in f32: ray intersection by a bracketed polynomial root finder,
// and the surface (refined point, normal, UV, tangent frame) at a hit. The method and
// its reasons are in src/tracer/geometry/torus.rs, which this file follows step for step: work in
// units of rin + rout from where the ray enters the bounding sphere ∩ slab, split the
// interval at the roots of the derivatives (quadratic → cubic → quartic, unrolled: WGSL
// has no recursion), then Newton with bisection fallback in the first bracketing piece.
// Loops are capped by TORUS_NEWTON_ITERATIONS (lavapipe counts every loop iteration).

// #if TORUS
// (p(x), p′(x)) for p(x) = a4·x⁴ + a.w·x³ + a.z·x² + a.y·x + a.x (Horner).
// Mirror of src/tracer/geometry/torus.rs::poly_eval — change both.
fn poly_eval(a: vec4<f32>, a4: f32, x: f32) -> vec2<f32> {
    let f = (((a4 * x + a.w) * x + a.z) * x + a.y) * x + a.x;
    let df = ((4.0 * a4 * x + 3.0 * a.w) * x + 2.0 * a.z) * x + a.y;
    return vec2<f32>(f, df);
}

// The root of p (as in poly_eval) between x0 and x1, where p(x0) has the sign of f0 and
// p(x1) the other: Newton steps from the midpoint, a bisection step wherever Newton would
// leave the bracket (which shrinks every step).
// Mirror of src/tracer/geometry/torus.rs::newton_bisect — change both.
fn newton_bisect(a: vec4<f32>, a4: f32, x0: f32, x1: f32, f0: f32) -> f32 {
    let negative_at_lo = f0 < 0.0;
    var lo = x0;
    var hi = x1;
    var x = 0.5 * (x0 + x1);
    for (var i = 0u; i < TORUS_NEWTON_ITERATIONS; i++) {
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
        var next = 0.5 * (lo + hi);
        if p.y != 0.0 {
            let newton = x - p.x / p.y;
            if newton > min(lo, hi) && newton < max(lo, hi) {
                next = newton;
            }
        }
        let step = abs(next - x);
        x = next;
        if step <= TORUS_ROOT_TOLERANCE * abs(x) {
            break;
        }
    }
    return x;
}

// Knots that split [0, len] into pieces where the monic quartic
// s⁴ + c.w·s³ + c.z·s² + c.y·s + c.x is monotonic: knots[0..=count], from 0 to len.
// Mirror of src/tracer/geometry/torus.rs::QuarticKnots — change both.
struct QuarticKnots {
    knots: array<f32, 5>,
    count: u32,
}

// The monotonic pieces of the monic quartic c on [0, len] (see QuarticKnots).
// Mirror of src/tracer/geometry/torus.rs::quartic_knots — change both.
fn quartic_knots(c: vec4<f32>, len: f32) -> QuarticKnots {
    // Compute the roots of the quartic's second derivative 12s² + 6c₃s + 2c₂ (halved:
    // 6s² + 3c₃s + c₂) in closed form; they split [0, len] into pieces where the cubic
    // (the first derivative) is monotonic.
    let qa = 6.0;
    let qb = 3.0 * c.w;
    let qc = c.z;
    let discriminant = qb * qb - 4.0 * qa * qc;
    var k1 = len;
    var k2 = len;
    if discriminant > 0.0 {
        let q = -0.5 * (qb + copysign(sqrt(discriminant), qb));
        if q != 0.0 {
            let r0 = q / qa;
            let r1 = qc / q;
            k1 = clamp(min(r0, r1), 0.0, len);
            k2 = clamp(max(r0, r1), 0.0, len);
        }
    }
    // Find the cubic's roots 4s³ + 3c₃s² + 2c₂s + c₁ in each monotonic piece: they split
    // [0, len] into pieces where the quartic is monotonic.
    let cubic = vec4<f32>(c.y, 2.0 * c.z, 3.0 * c.w, 4.0);
    let cubic_knots = array<f32, 4>(0.0, k1, k2, len);
    var knots = array<f32, 5>(0.0, len, len, len, len);
    var count = 1u;
    var y0 = poly_eval(cubic, 0.0, 0.0).x;
    for (var i = 0u; i < 3u; i++) {
        let x0 = cubic_knots[i];
        let x1 = cubic_knots[i + 1u];
        let y1 = poly_eval(cubic, 0.0, x1).x;
        if x0 < x1 && (y0 < 0.0) != (y1 < 0.0) {
            knots[count] = newton_bisect(cubic, 0.0, x0, x1, y0);
            count += 1u;
        }
        y0 = y1;
    }
    knots[count] = len;
    return QuarticKnots(knots, count);
}

// Smallest root in [0, len] of the monic quartic s⁴ + c.w·s³ + c.z·s² + c.y·s + c.x, or
// −1 when it has none there (no sign change between monotonic pieces; a double root that
// only touches zero counts as none).
// Mirror of src/tracer/geometry/torus.rs::first_quartic_root — change both.
fn first_quartic_root(c: vec4<f32>, len: f32) -> f32 {
    let k = quartic_knots(c, len);
    // Find the quartic's first root: in the first monotonic piece whose ends differ in
    // sign.
    let quartic = c;
    var z0 = poly_eval(quartic, 1.0, 0.0).x;
    for (var i = 0u; i < k.count; i++) {
        let x0 = k.knots[i];
        let x1 = k.knots[i + 1u];
        let z1 = poly_eval(quartic, 1.0, x1).x;
        if x0 < x1 && (z0 < 0.0) != (z1 < 0.0) {
            return newton_bisect(quartic, 1.0, x0, x1, z0);
        }
        z0 = z1;
    }
    return -1.0;
}

// The part of a ray inside the torus's bounds, set up for the root finder: the ray enters
// the bounds at t_near; s = (t − t_near)·speed runs over [0, len], where the torus is the
// monic quartic c in s ≤ 0. valid is false when the ray misses the bounds between t_min
// and t_max.
// Mirror of src/tracer/geometry/torus.rs::TorusChord — change both.
struct TorusChord {
    t_near: f32,
    speed: f32,
    len: f32,
    c: vec4<f32>,
    valid: bool,
}

// The chord of o + t·d (object space, unnormalised d) through the bounds of the torus
// (rin, rout), clipped to [t_min, t_max], and the quartic along it.
// Mirror of src/tracer/geometry/torus.rs::torus_chord — change both.
fn torus_chord(o: vec3<f32>, d: vec3<f32>, rin: f32, rout: f32, t_min: f32, t_max: f32) -> TorusChord {
    var chord = TorusChord(0.0, 1.0, 0.0, vec4<f32>(0.0), false);
    // Work in units of the bounding radius rin + rout (t is unchanged).
    let inv_size = 1.0 / (rin + rout);
    let o1 = o * inv_size;
    let d1 = d * inv_size;
    let r_mid = rin * inv_size;
    let r_tube = rout * inv_size;
    // Clip the ray to the bounding sphere (stable quadratic, as in intersect_sphere) ...
    let bound = 1.0 + TORUS_BOUND_MARGIN;
    let a = dot(d1, d1);
    let b = dot(o1, d1);
    let l = o1 - d1 * (b / a);
    let discriminant = a * (bound * bound - dot(l, l));
    if discriminant < 0.0 {
        return chord;
    }
    let q = -b - copysign(sqrt(discriminant), b);
    if q == 0.0 {
        return chord;
    }
    let r0 = (dot(o1, o1) - bound * bound) / q;
    let r1 = q / a;
    // ... and to the slab |z| ≤ tube radius.
    let half_height = r_tube + TORUS_BOUND_MARGIN;
    let inv_dz = safe_rcp(d1.z);
    let z0 = (-half_height - o1.z) * inv_dz;
    let z1 = (half_height - o1.z) * inv_dz;
    let t_near = max(max(min(r0, r1), min(z0, z1)), t_min);
    let t_far = min(min(max(r0, r1), max(z0, z1)), t_max);
    if t_near >= t_far {
        return chord;
    }
    // Move the origin to the entry point and make the direction unit: s = (t − t_near)·|d|.
    let p = o1 + d1 * t_near;
    let speed = sqrt(a);
    let dn = d1 / speed;
    let len = (t_far - t_near) * speed;
    // Compute the quartic's coefficients: (|p + s·dn|² + R² − r²)² − 4R²·ρ(s)² = 0.
    let k = dot(p, p) + (r_mid - r_tube) * (r_mid + r_tube);
    let bd = dot(p, dn);
    let rr4 = 4.0 * r_mid * r_mid;
    let c3 = 4.0 * bd;
    let c2 = 4.0 * bd * bd + 2.0 * k - rr4 * (dn.x * dn.x + dn.y * dn.y);
    let c1 = 4.0 * bd * k - 2.0 * rr4 * (p.x * dn.x + p.y * dn.y);
    // c₀ = K² − 4R²ρ² as ((ρ−R)² + z² − r²)·((ρ+R)² + z² − r²), the first factor as
    // (q − r)(q + r): no cancellation when p lies near the surface.
    let rho = length(p.xy);
    let tube_dist = length(vec2<f32>(rho - r_mid, p.z));
    let near = (tube_dist - r_tube) * (tube_dist + r_tube);
    let far = (rho + r_mid) * (rho + r_mid) + p.z * p.z - r_tube * r_tube;
    let c0 = near * far;
    chord.t_near = t_near;
    chord.speed = speed;
    chord.len = len;
    chord.c = vec4<f32>(c0, c1, c2, c3);
    chord.valid = true;
    return chord;
}

// Nearest t in (0, t_max) where o + t·d (object space, unnormalised d) meets the torus
// (rin, rout), else T_MISS.
// Mirror of src/tracer/geometry/torus.rs::intersect_torus — change both.
fn intersect_torus(o: vec3<f32>, d: vec3<f32>, rin: f32, rout: f32, t_max: f32) -> f32 {
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
        return t;
    }
    return T_MISS;
}

// #if CSG
// The t-intervals where o + t·d (object space, unnormalised d) is inside the torus
// (rin, rout) — where its quartic is ≤ 0: [x, y] and [z, w], each empty when its lo > hi,
// the second after the first (see the CPU twin).
// Mirror of src/tracer/geometry/torus.rs::torus_intervals — change both.
fn torus_intervals(o: vec3<f32>, d: vec3<f32>, rin: f32, rout: f32) -> vec4<f32> {
    let empty = vec4<f32>(T_MISS, -T_MISS, T_MISS, -T_MISS);
    let chord = torus_chord(o, d, rin, rout, -T_MISS, T_MISS);
    if !chord.valid {
        return empty;
    }
    let k = quartic_knots(chord.c, chord.len);
    // Every piece whose ends differ in sign holds one crossing.
    let quartic = chord.c;
    var ends = array<f32, 4>(chord.len, chord.len, chord.len, chord.len);
    var count = 0u;
    var y0 = poly_eval(quartic, 1.0, 0.0).x;
    for (var i = 0u; i < k.count; i++) {
        let x0 = k.knots[i];
        let x1 = k.knots[i + 1u];
        let y1 = poly_eval(quartic, 1.0, x1).x;
        if x0 < x1 && (y0 < 0.0) != (y1 < 0.0) {
            ends[count] = newton_bisect(quartic, 1.0, x0, x1, y0);
            count += 1u;
        }
        y0 = y1;
    }
    var out = empty;
    if count > 0u {
        out.x = chord.t_near + ends[0] / chord.speed;
        out.y = chord.t_near + ends[1] / chord.speed;
    }
    if count > 2u {
        out.z = chord.t_near + ends[2] / chord.speed;
        out.w = chord.t_near + ends[3] / chord.speed;
    }
    return out;
}
// #endif

// Point, normal, UV and tangent frame at the torus point nearest p (see the CPU twin for
// the spindle torus's inner sheet).
// Mirror of src/tracer/geometry/torus.rs::torus_surface — change both.
fn torus_surface(p: vec3<f32>, rin: f32, rout: f32) -> ObjectSurface {
    // Compute the radial direction (any one on the axis).
    let rho = length(p.xy);
    var radial = vec2<f32>(1.0, 0.0);
    if rho > 0.0 {
        radial = p.xy / rho;
    }
    // Pick the tube circle: the near one, but the far one on a spindle's inner sheet.
    let near = (rho - rin) * (rho - rin) + p.z * p.z - rout * rout;
    let far = (rho + rin) * (rho + rin) + p.z * p.z - rout * rout;
    var side = 1.0;
    if abs(far) < abs(near) {
        side = -1.0;
    }
    let centre = vec3<f32>(radial * (side * rin), 0.0);
    // Normal from the tube's centre, and the point projected onto the tube.
    let offset = p - centre;
    let dist = length(offset);
    var normal = vec3<f32>(radial * side, 0.0);
    if dist > 0.0 {
        normal = offset / dist;
    }
    let on_surface = centre + normal * rout;
    // UV: θ around the axis, φ around the tube from the outward radial direction.
    let cos_phi = normal.x * radial.x + normal.y * radial.y;
    let sin_phi = normal.z;
    var u = atan2(on_surface.y, on_surface.x) / TWO_PI;
    if u < 0.0 {
        u += 1.0;
    }
    var v = atan2(sin_phi, cos_phi) / TWO_PI;
    if v < 0.0 {
        v += 1.0;
    }
    // Tangent frame: ∂p/∂θ = (−y, x, 0), ∂p/∂φ = r·(−sin φ·radial, cos φ).
    let dpdu = vec3<f32>(-on_surface.y, on_surface.x, 0.0) * TWO_PI;
    let dpdv = vec3<f32>(radial * -sin_phi, cos_phi) * (TWO_PI * rout);
    return ObjectSurface(on_surface, normal, vec2<f32>(u, v), dpdu, dpdv);
}
// #endif
