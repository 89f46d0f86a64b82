// cylinder_cone.wgsl — capped cylinder and capped cone in f32: ray intersection in object
// space (unnormalised direction, so t is the world-space t) and the surface at a hit
// (point snapped onto the surface, outward normal, UV and tangent frame).
//
// Both solids are a quadric region intersected with the slab between their cap planes:
// cylinder x² + y² ≤ 1, 0 ≤ z ≤ 1; cone x² + y² ≤ z², zmin ≤ z ≤ zmax (with
// zmin < 0 < zmax the double cone: both nappes, each capped, touching at the tip). The
// ray's inside is the quadric's t-interval(s) clipped to the slab's, and the hit is the
// nearest end of those in (0, t_max). UVs and the frame: see src/tracer/geometry/cylinder_cone.rs.

// #if CYLINDER|CONE
// The nearer of best and the ends of [lo, hi] that lie in (0, t_max), each shifted by
// t_shift (empty when lo > hi).
// Mirror of src/tracer/geometry/cylinder_cone.rs::nearest_interval_end — change both.
fn nearest_interval_end(lo: f32, hi: f32, t_shift: f32, t_max: f32, best: f32) -> f32 {
    if lo > hi {
        return best;
    }
    let t_lo = t_shift + lo;
    let t_hi = t_shift + hi;
    if t_lo > 0.0 && t_lo < t_max && t_lo < best {
        return t_lo;
    } else if t_hi > 0.0 && t_hi < t_max && t_hi < best {
        return t_hi;
    }
    return best;
}

// u = angle of (x, y) around the z axis / 2π, in [0, 1) (0 on the axis itself).
// Mirror of src/tracer/geometry/cylinder_cone.rs::cylinder_cone_angle_u — change both.
fn cylinder_cone_angle_u(x: f32, y: f32) -> f32 {
    if x == 0.0 && y == 0.0 {
        return 0.0;
    }
    let u = atan2(y, x) / TWO_PI;
    if u < 0.0 {
        return u + 1.0;
    }
    return u;
}
// #endif

// #if CYLINDER
// The t-interval [lo, hi] where o + t·d is inside the solid cylinder x² + y² ≤ 1,
// 0 ≤ z ≤ 1, as (lo, hi); empty (lo > hi) when the line misses it.
// Mirror of src/tracer/geometry/cylinder_cone.rs::cylinder_interval — change both.
fn cylinder_interval(o: vec3<f32>, d: vec3<f32>) -> vec2<f32> {
    let miss = vec2<f32>(T_MISS, -T_MISS);
    // Compute the side quadratic a·t² + 2b·t + c of x² + y² − 1 (intersect_sphere's
    // stable form, in xy).
    let a = d.x * d.x + d.y * d.y;
    let b = o.x * d.x + o.y * d.y;
    let c = o.x * o.x + o.y * o.y - 1.0;
    var side_lo = -T_MISS;
    var side_hi = T_MISS;
    if a > 0.0 {
        // Compute the discriminant as a·(1 − |l|²), l the line's point nearest the axis.
        let lx = o.x - d.x * (b / a);
        let ly = o.y - d.y * (b / a);
        let discriminant = a * (1.0 - (lx * lx + ly * ly));
        if discriminant < 0.0 {
            return miss;
        }
        // Compute both roots without cancellation.
        let q = -b - copysign(sqrt(discriminant), b);
        if q == 0.0 {
            side_lo = 0.0;
            side_hi = 0.0;
        } else {
            let r0 = c / q;
            let r1 = q / a;
            side_lo = min(r0, r1);
            side_hi = max(r0, r1);
        }
    } else if c > 0.0 {
        // Parallel to the axis, outside the side.
        return miss;
    }
    // Clip to the slab between the caps.
    let inv_dz = safe_rcp(d.z);
    let tz0 = (0.0 - o.z) * inv_dz;
    let tz1 = (1.0 - o.z) * inv_dz;
    return vec2<f32>(max(side_lo, min(tz0, tz1)), min(side_hi, max(tz0, tz1)));
}

// Nearest t in (0, t_max) where o + t·d meets the solid cylinder x² + y² ≤ 1, 0 ≤ z ≤ 1,
// else T_MISS (from inside, the exit point).
// Mirror of src/tracer/geometry/cylinder_cone.rs::intersect_cylinder — change both.
fn intersect_cylinder(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> f32 {
    let interval = cylinder_interval(o, d);
    return nearest_interval_end(interval.x, interval.y, 0.0, t_max, T_MISS);
}

// The cylinder's surface at the object-space point p (near the surface): the nearest of
// side and caps, with p snapped onto it.
// Mirror of src/tracer/geometry/cylinder_cone.rs::cylinder_surface — change both.
fn cylinder_surface(p: vec3<f32>) -> ObjectSurface {
    let r = sqrt(p.x * p.x + p.y * p.y);
    let d_side = abs(r - 1.0);
    let d_bottom = abs(p.z);
    let d_top = abs(p.z - 1.0);
    if d_side <= d_bottom && d_side <= d_top {
        // Side: snap radially onto r = 1, z into [0, 1].
        var cx = 1.0;
        var cy = 0.0;
        if r > 0.0 {
            cx = p.x / r;
            cy = p.y / r;
        }
        let z = clamp(p.z, 0.0, 1.0);
        return ObjectSurface(
            vec3<f32>(cx, cy, z),
            vec3<f32>(cx, cy, 0.0),
            vec2<f32>(cylinder_cone_angle_u(cx, cy), z),
            vec3<f32>(-cy, cx, 0.0) * TWO_PI,
            vec3<f32>(0.0, 0.0, 1.0),
        );
    }
    // Cap: snap onto its plane, into the unit disc.
    let top = d_top < d_bottom;
    var s = 1.0;
    if r > 1.0 {
        s = 1.0 / r;
    }
    let x = p.x * s;
    let y = p.y * s;
    return ObjectSurface(
        vec3<f32>(x, y, select(0.0, 1.0, top)),
        vec3<f32>(0.0, 0.0, select(-1.0, 1.0, top)),
        vec2<f32>(0.5 * (x + 1.0), 0.5 * (y + 1.0)),
        vec3<f32>(2.0, 0.0, 0.0),
        vec3<f32>(0.0, 2.0, 0.0),
    );
}
// #endif

// #if CONE
// Where a line is inside a cone: t = t_shift + t′ over the t′-intervals
// [spans.x, spans.y] and [spans.z, spans.w] (each empty when its lo > hi; the second after
// the first).
// Mirror of src/tracer/geometry/cylinder_cone.rs::ConeIntervals — change both.
struct ConeIntervals {
    t_shift: f32,
    spans: vec4<f32>,
}

// The intervals where o + t·d is inside the solid cone x² + y² ≤ z², zmin ≤ z ≤ zmax (two
// only for a double cone).
// Mirror of src/tracer/geometry/cylinder_cone.rs::cone_intervals — change both.
fn cone_intervals(o: vec3<f32>, d: vec3<f32>, zmin: f32, zmax: f32) -> ConeIntervals {
    let empty = vec4<f32>(T_MISS, -T_MISS, T_MISS, -T_MISS);
    // Move the origin to the line's point nearest the tip: the quadratic's coefficients
    // are then of the size of the hit's distance from the tip, not of the origin's (no
    // catastrophic b² − ac for far origins, and rays passing near the tip keep their
    // precision). t = t_shift + t', t' the parameter from the moved origin.
    let t_shift = -dot(o, d) / dot(d, d);
    let os = o + d * t_shift;
    // Compute the quadratic a·t'² + 2b·t' + c of x² + y² − z².
    let a = d.x * d.x + d.y * d.y - d.z * d.z;
    let b = os.x * d.x + os.y * d.y - os.z * d.z;
    let c = os.x * os.x + os.y * os.y - os.z * os.z;
    let discriminant = b * b - a * c;
    // The t'-intervals where x² + y² ≤ z²: [lo0, hi0] and [lo1, hi1] (empty: lo > hi).
    var lo0 = -T_MISS;
    var hi0 = T_MISS;
    var lo1 = 1.0;
    var hi1 = 0.0;
    if a == 0.0 {
        // Parallel to a generator: 2b·t' + c ≤ 0 on a half-line (or everywhere/nowhere).
        if b > 0.0 {
            hi0 = -c / (2.0 * b);
        } else if b < 0.0 {
            lo0 = -c / (2.0 * b);
        } else if c > 0.0 {
            return ConeIntervals(t_shift, empty);
        }
    } else if a < 0.0 && discriminant <= 0.0 {
        // Steeper than the cone: inside for every t' (through the tip when Δ = 0).
    } else {
        if discriminant < 0.0 {
            return ConeIntervals(t_shift, empty);
        }
        // Compute both roots without cancellation.
        let q = -b - copysign(sqrt(discriminant), b);
        var r0 = 0.0;
        var r1 = 0.0;
        if q != 0.0 {
            let s0 = c / q;
            let s1 = q / a;
            r0 = min(s0, s1);
            r1 = max(s0, s1);
        }
        if a > 0.0 {
            // Flatter than the cone: inside between the roots.
            lo0 = r0;
            hi0 = r1;
        } else {
            // Steeper: inside before the first root (one nappe) and after the second.
            hi0 = r0;
            lo1 = r1;
            hi1 = T_MISS;
        }
    }
    // Clip to the slab between the caps.
    let inv_dz = safe_rcp(d.z);
    let tz0 = (zmin - os.z) * inv_dz;
    let tz1 = (zmax - os.z) * inv_dz;
    let slab_lo = min(tz0, tz1);
    let slab_hi = max(tz0, tz1);
    return ConeIntervals(
        t_shift,
        vec4<f32>(max(lo0, slab_lo), min(hi0, slab_hi), max(lo1, slab_lo), min(hi1, slab_hi)),
    );
}

// Nearest t in (0, t_max) where o + t·d meets the solid cone x² + y² ≤ z²,
// zmin ≤ z ≤ zmax, else T_MISS (from inside, the exit point). With zmin < 0 < zmax, the
// double cone.
// Mirror of src/tracer/geometry/cylinder_cone.rs::intersect_cone — change both.
fn intersect_cone(o: vec3<f32>, d: vec3<f32>, zmin: f32, zmax: f32, t_max: f32) -> f32 {
    let c = cone_intervals(o, d, zmin, zmax);
    let s = c.spans;
    let best = nearest_interval_end(s.x, s.y, c.t_shift, t_max, T_MISS);
    return nearest_interval_end(s.z, s.w, c.t_shift, t_max, best);
}

// The cone's surface at the object-space point p (near the surface): the nearest of side
// and caps (a cap of radius 0, at a tip, is never chosen), with p snapped onto it.
// Mirror of src/tracer/geometry/cylinder_cone.rs::cone_surface — change both.
fn cone_surface(p: vec3<f32>, zmin: f32, zmax: f32) -> ObjectSurface {
    let r = sqrt(p.x * p.x + p.y * p.y);
    // Distances to the side (in the (r, z) half-plane, from the generator r = |z|) and to
    // the caps.
    let d_side = abs((r - abs(p.z)) / sqrt(2.0));
    var d_bottom = T_MISS;
    if zmin != 0.0 {
        d_bottom = abs(p.z - zmin);
    }
    var d_top = T_MISS;
    if zmax != 0.0 {
        d_top = abs(p.z - zmax);
    }
    var cx = 1.0;
    var cy = 0.0;
    if r > 0.0 {
        cx = p.x / r;
        cy = p.y / r;
    }
    if d_side <= d_bottom && d_side <= d_top {
        // Side: project (r, z) onto the nappe's generator r = s·z, z into [zmin, zmax].
        let s = select(-1.0, 1.0, p.z >= 0.0);
        let z = clamp(s * 0.5 * (r + abs(p.z)), zmin, zmax);
        let rs = abs(z);
        let height = zmax - zmin;
        return ObjectSurface(
            vec3<f32>(cx * rs, cy * rs, z),
            // ∇(x² + y² − z²) ∝ (cx, cy, −s) on the nappe.
            normalize(vec3<f32>(cx, cy, -s)),
            vec2<f32>(cylinder_cone_angle_u(cx, cy), (z - zmin) / height),
            vec3<f32>(-cy * rs, cx * rs, 0.0) * TWO_PI,
            vec3<f32>(s * cx, s * cy, 1.0) * height,
        );
    }
    // Cap: snap onto its plane, into its disc of radius |z_cap|.
    let top = d_top < d_bottom;
    let z = select(zmin, zmax, top);
    let radius = abs(z);
    var k = 1.0;
    if r > radius {
        k = radius / r;
    }
    let x = p.x * k;
    let y = p.y * k;
    return ObjectSurface(
        vec3<f32>(x, y, z),
        vec3<f32>(0.0, 0.0, select(-1.0, 1.0, top)),
        vec2<f32>(0.5 * (x / radius + 1.0), 0.5 * (y / radius + 1.0)),
        vec3<f32>(2.0 * radius, 0.0, 0.0),
        vec3<f32>(0.0, 2.0 * radius, 0.0),
    );
}
// #endif
