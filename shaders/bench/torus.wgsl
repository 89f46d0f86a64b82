// bench_torus.wgsl — the GPU half of `glint bench --torus` (src/bench/torus_gpu.rs):
// one ray per invocation through glint's torus test (src/tracer/geometry/torus.wgsl) or the textbook
// Ferrari closed form below, twin of src/bench/ferrari.rs. Not part of the tracer; it is
// appended to the common modules only by the benchmark.

// Mirror of src/bench/torus_gpu.rs::BenchTorusParams — change both.
struct BenchTorusParams {
    rin: f32,
    rout: f32,
    // BENCH_SOLVER_GLINT or BENCH_SOLVER_FERRARI.
    solver: u32,
    count: u32,
}

// Mirror of src/bench/torus_gpu.rs::BenchRay — change both.
struct BenchRay {
    o: vec3<f32>,
    _pad0: f32,
    d: vec3<f32>,
    _pad1: f32,
}

@group(0) @binding(20) var<uniform> bench_params: BenchTorusParams;
@group(0) @binding(21) var<storage, read> bench_rays: array<BenchRay>;
@group(0) @binding(22) var<storage, read_write> bench_t: array<f32>;

// Up to four real roots: the first `count` entries of `roots` are valid.
// Mirror of src/bench/ferrari.rs::Roots — change both.
struct Roots {
    roots: vec4<f32>,
    count: u32,
}

// Mirror of src/bench/ferrari.rs::ferrari_cbrt — change both.
fn ferrari_cbrt(x: f32) -> f32 {
    if x == 0.0 {
        return 0.0;
    }
    return sign(x) * pow(abs(x), 1.0 / 3.0);
}

// Mirror of src/bench/ferrari.rs::solve_cubic — change both.
fn solve_cubic(a: f32, b: f32, c: f32) -> Roots {
    let sq_a = a * a;
    let p = (1.0 / 3.0) * (-(1.0 / 3.0) * sq_a + b);
    let q = 0.5 * ((2.0 / 27.0) * a * sq_a - (1.0 / 3.0) * a * b + c);
    let cb_p = p * p * p;
    let disc = q * q + cb_p;
    var r = vec4<f32>(0.0);
    var count = 0u;
    if disc == 0.0 {
        if q == 0.0 {
            count = 1u;
        } else {
            let u = ferrari_cbrt(-q);
            r.x = 2.0 * u;
            r.y = -u;
            count = 2u;
        }
    } else if disc < 0.0 {
        let phi = (1.0 / 3.0) * acos(clamp(-q / sqrt(-cb_p), -1.0, 1.0));
        let t = 2.0 * sqrt(-p);
        r.x = t * cos(phi);
        r.y = -t * cos(phi + TWO_PI / 6.0);
        r.z = -t * cos(phi - TWO_PI / 6.0);
        count = 3u;
    } else {
        let sqrt_d = sqrt(disc);
        r.x = ferrari_cbrt(sqrt_d - q) - ferrari_cbrt(sqrt_d + q);
        count = 1u;
    }
    return Roots(r - vec4<f32>(a / 3.0), count);
}

// Mirror of src/bench/ferrari.rs::push_quadratic_roots — change both.
fn push_quadratic_roots(out_in: Roots, p: f32, q: f32, shift: f32) -> Roots {
    var out = out_in;
    let disc = 0.25 * p * p - q;
    if disc >= 0.0 {
        let s = sqrt(disc);
        out.roots[out.count] = -0.5 * p + s - shift;
        out.roots[out.count + 1u] = -0.5 * p - s - shift;
        out.count += 2u;
    }
    return out;
}

// Mirror of src/bench/ferrari.rs::solve_quartic — change both.
fn solve_quartic(a: f32, b: f32, c: f32, d: f32) -> Roots {
    let sq_a = a * a;
    // Substitute x = y − a/4: y⁴ + p·y² + q·y + r.
    let p = -(3.0 / 8.0) * sq_a + b;
    let q = (1.0 / 8.0) * sq_a * a - 0.5 * a * b + c;
    let r = -(3.0 / 256.0) * sq_a * sq_a + (1.0 / 16.0) * sq_a * b - 0.25 * a * c + d;
    let shift = 0.25 * a;
    var out = Roots(vec4<f32>(0.0), 0u);
    if r == 0.0 {
        // y·(y³ + p·y + q) = 0.
        let cubic = solve_cubic(0.0, p, q);
        out.roots.x = -shift;
        for (var i = 0u; i < cubic.count; i++) {
            out.roots[i + 1u] = cubic.roots[i] - shift;
        }
        out.count = cubic.count + 1u;
        return out;
    }
    // Solve the resolvent cubic and take one real root.
    let z = solve_cubic(-0.5 * p, -r, 0.5 * r * p - (1.0 / 8.0) * q * q).roots.x;
    var u = z * z - r;
    var v = 2.0 * z - p;
    if abs(u) < FERRARI_ZERO {
        u = 0.0;
    } else if u > 0.0 {
        u = sqrt(u);
    } else {
        return out;
    }
    if abs(v) < FERRARI_ZERO {
        v = 0.0;
    } else if v > 0.0 {
        v = sqrt(v);
    } else {
        return out;
    }
    var sv = v;
    if q < 0.0 {
        sv = -v;
    }
    out = push_quadratic_roots(out, sv, z - u, shift);
    return push_quadratic_roots(out, -sv, z + u, shift);
}

// Mirror of src/bench/ferrari.rs::intersect_torus_ferrari — change both.
fn intersect_torus_ferrari(o: vec3<f32>, d: vec3<f32>, rin: f32, rout: f32) -> f32 {
    let four_r2 = 4.0 * rin * rin;
    let e = dot(o, o) - rin * rin - rout * rout;
    let f = dot(o, d);
    let c3 = 4.0 * f;
    let c2 = 2.0 * e + 4.0 * f * f + four_r2 * d.z * d.z;
    let c1 = 4.0 * f * e + 2.0 * four_r2 * o.z * d.z;
    let c0 = e * e - four_r2 * (rout * rout - o.z * o.z);
    let roots = solve_quartic(c3, c2, c1, c0);
    var best = T_MISS;
    for (var i = 0u; i < roots.count; i++) {
        // NaN and infinities fail one of the comparisons.
        let t = roots.roots[i];
        if t > 0.0 && t < best {
            best = t;
        }
    }
    return best;
}

@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn bench_torus(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= bench_params.count {
        return;
    }
    let ray = bench_rays[i];
    if bench_params.solver == BENCH_SOLVER_GLINT {
        bench_t[i] = intersect_torus(ray.o, ray.d, bench_params.rin, bench_params.rout, T_MISS);
    } else {
        bench_t[i] = intersect_torus_ferrari(ray.o, ray.d, bench_params.rin, bench_params.rout);
    }
}
