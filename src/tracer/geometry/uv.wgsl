// uv.wgsl — UVs and tangent frames of the sphere, the box and mesh triangles (the
// cylinder, cone and torus have theirs in cylinder_cone.wgsl and torus.wgsl). The
// conventions are documented in src/tracer/geometry/uv.rs and docs/scene-language.md ("UV conventions").

// #if SPHERE|CUBE|CYLINDER|CONE|TORUS
// An analytic surface at a point, in object space: the point snapped onto it, its unit
// outward normal, UV and ∂p/∂u, ∂p/∂v. What every primitive's *_surface returns.
// Mirror of src/tracer/geometry/uv.rs::ObjectSurface — change both.
struct ObjectSurface {
    p: vec3<f32>,
    normal: vec3<f32>,
    uv: vec2<f32>,
    dpdu: vec3<f32>,
    dpdv: vec3<f32>,
}
// #endif

// #if SPHERE
// The unit sphere at p (reprojected onto the sphere). At the poles ∂p/∂u = 0 (bump
// mapping then leaves the normal alone); nothing divides by the distance to the axis.
// Mirror of src/tracer/geometry/uv.rs::sphere_surface — change both.
fn sphere_surface(p_in: vec3<f32>) -> ObjectSurface {
    // Reproject onto the unit sphere.
    let p = normalize(p_in);
    let r = sqrt(p.x * p.x + p.y * p.y);
    let phi = atan2(p.y, p.x);
    let latitude = atan2(p.z, r);
    var u = phi / TWO_PI;
    if u < 0.0 {
        u += 1.0;
    }
    let v = latitude / (0.5 * TWO_PI) + 0.5;
    return ObjectSurface(
        p,
        p,
        vec2<f32>(u, v),
        vec3<f32>(-p.y, p.x, 0.0) * TWO_PI,
        vec3<f32>(-p.z * cos(phi), -p.z * sin(phi), r) * (0.5 * TWO_PI),
    );
}
// #endif

// #if CUBE
// The box [0,1]³ at p: the face nearest the point, the point snapped onto it.
// Mirror of src/tracer/geometry/uv.rs::cube_surface — change both.
fn cube_surface(p_in: vec3<f32>) -> ObjectSurface {
    var p = p_in;
    // The face nearest the point: snap the point onto it.
    let dist = min(abs(p), abs(p - vec3<f32>(1.0)));
    var axis = 2u;
    if dist.x <= dist.y && dist.x <= dist.z {
        axis = 0u;
    } else if dist.y <= dist.z {
        axis = 1u;
    }
    let upper = p[axis] > 0.5;
    p[axis] = select(0.0, 1.0, upper);
    let sign = select(-1.0, 1.0, upper);
    var normal = vec3<f32>(0.0);
    normal[axis] = sign;
    // The face's right (∂p/∂u) and up (∂p/∂v) as seen from outside.
    var dpdu = vec3<f32>(sign, 0.0, 0.0);
    var dpdv = vec3<f32>(0.0, 1.0, 0.0);
    if axis == 0u {
        dpdu = vec3<f32>(0.0, 0.0, -sign);
    } else if axis == 1u {
        dpdu = vec3<f32>(1.0, 0.0, 0.0);
        dpdv = vec3<f32>(0.0, 0.0, -sign);
    }
    let centred = p - vec3<f32>(0.5);
    return ObjectSurface(p, normal, vec2<f32>(dot(dpdu, centred) + 0.5, dot(dpdv, centred) + 0.5), dpdu, dpdv);
}
// #endif

// #if MESH
// #if TEXTURE|BUMP
// (∂p/∂u, ∂p/∂v) of the triangle (p0, p1, p2) with corner UVs (uv0, uv1, uv2) and unit
// normal `normal`, as the two halves of a mat2x3 (columns dpdu, dpdv). When the UV
// triangle is degenerate (its doubled area at most TRIANGLE_FRAME_MIN_UV_SINE of the
// product of its edges — a scale-free test), an orthonormal frame around the normal.
// Mirror of src/tracer/geometry/uv.rs::triangle_frame — change both.
fn triangle_frame(p0: vec3<f32>, p1: vec3<f32>, p2: vec3<f32>, uv0: vec2<f32>, uv1: vec2<f32>, uv2: vec2<f32>, normal: vec3<f32>) -> mat2x3<f32> {
    let e1 = p1 - p0;
    let e2 = p2 - p0;
    let d1 = uv1 - uv0;
    let d2 = uv2 - uv0;
    let det = d1.x * d2.y - d1.y * d2.x;
    let scale = length(d1) * length(d2);
    if abs(det) > TRIANGLE_FRAME_MIN_UV_SINE * scale {
        let inv = 1.0 / det;
        return mat2x3<f32>((e1 * d2.y - e2 * d1.y) * inv, (e2 * d1.x - e1 * d2.x) * inv);
    }
    // Any axis not along the normal gives a perpendicular; dpdu × dpdv = normal.
    var axis = vec3<f32>(1.0, 0.0, 0.0);
    if abs(normal.x) > TRIANGLE_FRAME_AXIS_SWITCH {
        axis = vec3<f32>(0.0, 1.0, 0.0);
    }
    let dpdu = normalize(cross(normal, axis));
    return mat2x3<f32>(dpdu, cross(normal, dpdu));
}
// #endif
// #endif
