// intersect.wgsl — ray–primitive intersection in f32: sphere (stable quadratic), box
// (slabs), triangle (watertight). Analytic primitives are intersected in object space
// with an unnormalised direction, so t is the world-space t.

// #if SPHERE
// The t-interval [t0, t1] where o + t·d is inside the unit sphere at the origin, as
// (t0, t1); empty (t0 > t1) when the line misses it. Haines et al., Ray Tracing Gems
// ch. 7: the discriminant from the distance of the centre to the line (no catastrophic
// b² − ac), and the root pair from q = −b − sign(b)·√Δ, t = c/q and q/a (no cancellation
// in either root).
// Mirror of src/tracer/geometry/intersect.rs::sphere_interval — change both.
fn sphere_interval(o: vec3<f32>, d: vec3<f32>) -> vec2<f32> {
    // Compute the quadratic a·t² + 2b·t + c with f = o (centre at the origin).
    let a = dot(d, d);
    let b = dot(o, d);
    let c = dot(o, o) - 1.0;
    // Compute the discriminant as a·(r² − |f − (b/a)·d|²).
    let l = o - d * (b / a);
    let discriminant = a * (1.0 - dot(l, l));
    if discriminant < 0.0 {
        return vec2<f32>(T_MISS, -T_MISS);
    }
    // Compute both roots without cancellation.
    let q = -b - copysign(sqrt(discriminant), b);
    if q == 0.0 {
        return vec2<f32>(0.0);
    }
    let r0 = c / q;
    let r1 = q / a;
    return vec2<f32>(min(r0, r1), max(r0, r1));
}

// Nearest t in (0, t_max) where o + t·d meets the unit sphere at the origin, else T_MISS
// (the nearer end of sphere_interval in range; from inside, the exit).
// Mirror of src/tracer/geometry/intersect.rs::intersect_sphere — change both.
fn intersect_sphere(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> f32 {
    let interval = sphere_interval(o, d);
    if interval.x > interval.y {
        return T_MISS;
    }
    let t0 = interval.x;
    let t1 = interval.y;
    if t0 > 0.0 && t0 < t_max {
        return t0;
    } else if t1 > 0.0 && t1 < t_max {
        return t1;
    }
    return T_MISS;
}
// #endif

// #if CUBE
// The slab interval [t_near, t_far] of o + t·d through the box [0,1]³ (empty:
// t_near > t_far).
// Mirror of src/tracer/geometry/intersect.rs::box_interval — change both.
fn box_interval(o: vec3<f32>, d: vec3<f32>) -> vec2<f32> {
    let inv = safe_rcp3(d);
    let t0 = (vec3<f32>(0.0) - o) * inv;
    let t1 = (vec3<f32>(1.0) - o) * inv;
    return vec2<f32>(max_element(min(t0, t1)), min_element(max(t0, t1)));
}

// Nearest t in (0, t_max) where o + t·d meets the box [0,1]³, else T_MISS (slab test;
// from inside, the exit point).
// Mirror of src/tracer/geometry/intersect.rs::intersect_box — change both.
fn intersect_box(o: vec3<f32>, d: vec3<f32>, t_max: f32) -> f32 {
    let interval = box_interval(o, d);
    let t_near = interval.x;
    let t_far = interval.y;
    if t_near > t_far {
        return T_MISS;
    }
    var t = t_far;
    if t_near > 0.0 {
        t = t_near;
    }
    if t > 0.0 && t < t_max {
        return t;
    }
    return T_MISS;
}
// #endif

// Per-ray set-up of the watertight triangle test (Woop, Benthin & Wald, JCGT 2013): the
// dominant axis of the direction becomes z, and a shear maps the direction to +z. (The
// struct stays in every specialisation: traversal passes one even when it is unused.)
// Mirror of src/tracer/geometry/intersect.rs::TriangleRay — change both.
struct TriangleRay {
    origin: vec3<f32>,
    kx: u32,
    ky: u32,
    kz: u32,
    shear: vec3<f32>,
}

// #if MESH
// The triangle's vertices as vectors.
// Mirror of src/tracer/geometry/intersect.rs::triangle_vertices — change both.
fn triangle_vertices(index: u32) -> array<vec3<f32>, 3> {
    // The triangle's three texels in the table: p0.xyz p1.x | p1.yz p2.xy | p2.z.
    let base = index * TRIANGLE_TABLE_TEXELS;
    let a = bitcast<vec4<f32>>(table_at(triangle_table, base));
    let b = bitcast<vec4<f32>>(table_at(triangle_table, base + 1u));
    let c = bitcast<f32>(table_at(triangle_table, base + 2u).x);
    return array<vec3<f32>, 3>(a.xyz, vec3<f32>(a.w, b.xy), vec3<f32>(b.zw, c));
}

// Mirror of src/tracer/geometry/intersect.rs::triangle_ray_setup — change both.
fn triangle_ray_setup(origin: vec3<f32>, d: vec3<f32>) -> TriangleRay {
    // Calculate the dimension where the ray direction is maximal.
    let ad = abs(d);
    var kz = 2u;
    if ad.x >= ad.y && ad.x >= ad.z {
        kz = 0u;
    } else if ad.y >= ad.z {
        kz = 1u;
    }
    var kx = (kz + 1u) % 3u;
    var ky = (kx + 1u) % 3u;
    // Swap kx and ky to preserve the winding direction of triangles.
    if d[kz] < 0.0 {
        let swap = kx;
        kx = ky;
        ky = swap;
    }
    // Calculate the shear constants.
    let shear = vec3<f32>(d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]);
    return TriangleRay(origin, kx, ky, kz, shear);
}

// p.x·q.y − p.y·q.x for the directed edge (p, q) in the sheared plane, always evaluated
// with the endpoints in one canonical order and negated when they come swapped, so the two
// triangles sharing an edge compute exactly opposite values (watertightness) even where
// the shader compiler fuses one of the products into an FMA (llvmpipe does). Selects, as
// on the CPU (where they spare an unpredictable branch): one expression, so any fusion is
// the same for both triangles.
// Mirror of src/tracer/geometry/intersect.rs::edge_function — change both.
fn edge_function(px: f32, py: f32, qx: f32, qy: f32) -> f32 {
    let canonical = px < qx || (px == qx && py < qy);
    let s = select(vec2<f32>(qx, qy), vec2<f32>(px, py), canonical);
    let e = select(vec2<f32>(px, py), vec2<f32>(qx, qy), canonical);
    let r = s.x * e.y - s.y * e.x;
    return select(-r, r, canonical);
}

// The triangle vertex p relative to the ray origin, sheared: (x, y) in the plane where
// the ray is the +z axis, and the unscaled z (a[kz]).
// Mirror of src/tracer/geometry/intersect.rs::shear_vertex — change both.
fn shear_vertex(r: TriangleRay, p: vec3<f32>) -> vec3<f32> {
    let a = p - r.origin;
    let az = a[r.kz];
    return vec3<f32>(a[r.kx] - r.shear.x * az, a[r.ky] - r.shear.y * az, az);
}

// (t, b1, b2) of the hit with the triangle (p0, p1, p2) in (0, t_max), b1 and b2 the
// barycentric weights of p1 and p2; t = T_MISS on a miss. Two-sided. Edges shared by two
// triangles are never missed by both: the edge functions are computed identically from
// the shared vertices, and a zero counts as inside.
// Mirror of src/tracer/geometry/intersect.rs::intersect_triangle — change both.
fn intersect_triangle(r: TriangleRay, p0: vec3<f32>, p1: vec3<f32>, p2: vec3<f32>, t_max: f32) -> vec3<f32> {
    let miss = vec3<f32>(T_MISS, 0.0, 0.0);
    // Calculate the vertices relative to the ray origin, and perform the shear and scale
    // of the vertices.
    let a = shear_vertex(r, p0);
    let b = shear_vertex(r, p1);
    let c = shear_vertex(r, p2);
    // Calculate the scaled barycentric coordinates.
    let u = edge_function(c.x, c.y, b.x, b.y);
    let v = edge_function(a.x, a.y, c.x, c.y);
    let w = edge_function(b.x, b.y, a.x, a.y);
    // Perform the edge tests.
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return miss;
    }
    // Calculate the determinant.
    let det = u + v + w;
    if det == 0.0 {
        return miss;
    }
    // Calculate the scaled z-coordinates of the vertices and the scaled hit distance.
    let az = r.shear.z * a.z;
    let bz = r.shear.z * b.z;
    let cz = r.shear.z * c.z;
    let t_scaled = u * az + v * bz + w * cz;
    let t = t_scaled / det;
    if !(t > 0.0 && t < t_max) {
        return miss;
    }
    return vec3<f32>(t, v / det, w / det);
}
// #endif

// #if SPHERE|CUBE|CYLINDER|CONE|TORUS|MESH
// Object-space ray of an instance: origin and (unnormalised) direction through the
// world→object rows.
// Mirror of src/tracer/geometry/intersect.rs::to_object_space — change both.
fn to_object_space(inst: PackedInstance, o: vec3<f32>, d: vec3<f32>) -> Ray {
    let rows = inst.world_to_object;
    let oo = vec3<f32>(
        dot(rows[0].xyz, o) + rows[0].w,
        dot(rows[1].xyz, o) + rows[1].w,
        dot(rows[2].xyz, o) + rows[2].w,
    );
    let od = vec3<f32>(dot(rows[0].xyz, d), dot(rows[1].xyz, d), dot(rows[2].xyz, d));
    return Ray(oo, od);
}

// t of the nearest hit in (0, t_max) with an analytic instance, else T_MISS (KIND_CSG
// instances: see intersect_item).
// Mirror of src/tracer/geometry/intersect.rs::intersect_instance — change both.
fn intersect_instance(inst: PackedInstance, o: vec3<f32>, d: vec3<f32>, t_max: f32) -> f32 {
    let local = to_object_space(inst, o, d);
// #if SPHERE
    if inst.kind == KIND_SPHERE {
        return intersect_sphere(local.origin, local.dir, t_max);
    }
// #endif
// #if CUBE
    if inst.kind == KIND_CUBE {
        return intersect_box(local.origin, local.dir, t_max);
    }
// #endif
// #if CYLINDER
    if inst.kind == KIND_CYLINDER {
        return intersect_cylinder(local.origin, local.dir, t_max);
    }
// #endif
// #if CONE
    if inst.kind == KIND_CONE {
        return intersect_cone(local.origin, local.dir, inst.params.x, inst.params.y, t_max);
    }
// #endif
// #if TORUS
    if inst.kind == KIND_TORUS {
        return intersect_torus(local.origin, local.dir, inst.params.x, inst.params.y, t_max);
    }
// #endif
    return T_MISS;
}
// #endif
