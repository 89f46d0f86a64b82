// ray.wgsl — rays, camera rays and the self-intersection offset.

// Mirror of src/tracer/base/ray.rs::Ray — change both.
struct Ray {
    origin: vec3<f32>,
    // Unit direction in world space (object-space twins are not normalised).
    dir: vec3<f32>,
}

// Largest component (glam's max_element).
fn max_element(v: vec3<f32>) -> f32 {
    return max(v.x, max(v.y, v.z));
}

// Smallest component (glam's min_element).
fn min_element(v: vec3<f32>) -> f32 {
    return min(v.x, min(v.y, v.z));
}

// |x| with the sign of y, read from y's sign bit like Rust's f32::copysign (so -0.0
// counts as negative).
fn copysign(x: f32, y: f32) -> f32 {
    let sign_bit = bitcast<u32>(y) & 0x80000000u;
    return bitcast<f32>((bitcast<u32>(x) & 0x7fffffffu) | sign_bit);
}

// Primary ray through film position (fx, fy) in pixels (0,0 = top-left corner of the
// image, pixel centres at +0.5).
// Mirror of src/tracer/base/ray.rs::camera_ray — change both.
fn camera_ray(fx: f32, fy: f32) -> Ray {
    let g = globals;
    let ndc_x = 2.0 * fx / f32(g.width) - 1.0;
    let ndc_y = 1.0 - 2.0 * fy / f32(g.height);
    let dir = g.forward
        + g.right * (ndc_x * g.aspect * g.tan_half_fov)
        + g.up * (ndc_y * g.tan_half_fov);
    return Ray(g.eye, normalize(dir));
}

// #if DEPTH_OF_FIELD
// The point of the unit disk for u in [0, 1)²: Shirley & Chiu's concentric map.
// Mirror of src/tracer/base/ray.rs::concentric_disk — change both.
fn concentric_disk(u: vec2<f32>) -> vec2<f32> {
    let a = u * 2.0 - vec2<f32>(1.0);
    if a.x == 0.0 && a.y == 0.0 {
        return vec2<f32>(0.0);
    }
    let eighth = TWO_PI / 8.0;
    var radius = a.y;
    var angle = 2.0 * eighth - eighth * (a.x / a.y);
    if abs(a.x) > abs(a.y) {
        radius = a.x;
        angle = eighth * (a.y / a.x);
    }
    return vec2<f32>(cos(angle), sin(angle)) * radius;
}

// The thin-lens camera ray of the pinhole ray (camera_ray's) and lens position lens in
// [0, 1)²: from the lens disk's point (radius lens_radius, in the plane of right and up
// through the eye) towards where the pinhole ray meets the plane in focus, computed from
// the eye so that it loses no precision far from the origin.
// Mirror of src/tracer/base/ray.rs::thin_lens_ray — change both.
fn thin_lens_ray(pinhole: Ray, lens: vec2<f32>) -> Ray {
    let g = globals;
    let to_focus = pinhole.dir * (g.focus_distance / dot(pinhole.dir, g.forward));
    let disk = concentric_disk(lens) * g.lens_radius;
    let offset = g.right * disk.x + g.up * disk.y;
    return Ray(pinhole.origin + offset, normalize(to_focus - offset));
}
// #endif

// Moves a hit point off its surface along the unit normal n (pointing to the side the new
// ray leaves towards), by OFFSET_RELATIVE of magnitude, the largest coordinate magnitude
// that went into computing p.
// Mirror of src/tracer/base/ray.rs::offset_ray — change both.
fn offset_ray(p: vec3<f32>, n: vec3<f32>, magnitude: f32) -> vec3<f32> {
    return p + n * (max(magnitude, max_element(abs(p))) * OFFSET_RELATIVE);
}

// How far a shadow ray from origin looks for blockers on its way to a light at position,
// distance away: the distance less offset_ray's bound, taken at the largest coordinate
// magnitude of either end (and magnitude, the shaded surface's), so a surface through the
// light is never hit at t ≈ distance, where rounding would decide pixel by pixel.
// Mirror of src/tracer/base/ray.rs::shadow_reach — change both.
fn shadow_reach(origin: vec3<f32>, position: vec3<f32>, distance: f32, magnitude: f32) -> f32 {
    let ends = max(max_element(abs(origin)), max_element(abs(position)));
    return max(distance - max(magnitude, ends) * OFFSET_RELATIVE, 0.0);
}
