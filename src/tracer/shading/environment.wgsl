// environment.wgsl — the HDR environment map a ray that escapes the scene sees when the
// scene has one (ENVIRONMENT), in place of the background gradient. The layout in the
// texel table is src/pack/environment.rs's; the orientation and filtering (Mitsuba 3's
// envmap: u = atan2(d.x, −d.z)/2π mod 1, v = acos(d.y)/π, columns centred at (i + ½)/w and
// wrapping, row j at v = j/(h − 1), clamped) are derived in
// src/tracer/shading/environment.rs.

// #if ENVIRONMENT
// dir in the map's own frame: turned by −θ about +y (the map turns by θ).
// Mirror of src/tracer/shading/environment.rs::environment_direction — change both.
fn environment_direction(dir: vec3<f32>) -> vec3<f32> {
    let c = globals.environment_cos;
    let s = globals.environment_sin;
    return vec3<f32>(c * dir.x - s * dir.z, dir.y, s * dir.x + c * dir.z);
}

// The map's (u, v) of the unit direction d in its frame.
// Mirror of src/tracer/shading/environment.rs::environment_uv — change both.
fn environment_uv(d: vec3<f32>) -> vec2<f32> {
    // 1/2π and 1/π as constant expressions (rounded once, at compile time); θ = acos(d.y)
    // as atan2(√(x² + z²), y) (why: the Rust twin).
    let u = atan2(d.x, -d.z) * (1.0 / TWO_PI);
    let v = atan2(sqrt(d.x * d.x + d.z * d.z), d.y) * (2.0 / TWO_PI);
    return vec2<f32>(wrap_unit(u), v);
}

// Texel (x, y) of the map that starts at word `start` of the texel table.
// Mirror of src/tracer/shading/environment.rs::environment_texel — change both.
fn environment_texel(start: u32, x: u32, y: u32) -> vec3<f32> {
    let width = texel_word(start);
    let i = start + 2u + 3u * (y * width + x);
    return vec3<f32>(
        bitcast<f32>(texel_word(i)),
        bitcast<f32>(texel_word(i + 1u)),
        bitcast<f32>(texel_word(i + 2u)),
    );
}

// Bilinear lookup of the map at uv (u in [0, 1), v in [0, 1]): columns wrap, rows clamp.
// Mirror of src/tracer/shading/environment.rs::sample_environment — change both.
fn sample_environment(start: u32, uv: vec2<f32>) -> vec3<f32> {
    let width = texel_word(start);
    let height = texel_word(start + 1u);
    let last_row = f32(height - 1u);
    let x = uv.x * f32(width) - 0.5;
    let y = min(max(uv.y * last_row, 0.0), last_row);
    let x_floor = floor(x);
    let y_floor = floor(y);
    let fx = x - x_floor;
    let fy = y - y_floor;
    // x_floor ≥ −1: adding the width once wraps both columns.
    let w = i32(width);
    let x0 = u32((i32(x_floor) + w) % w);
    let x1 = u32((i32(x_floor) + 1 + w) % w);
    let y0 = u32(y_floor);
    let y1 = min(y0 + 1u, height - 1u);
    let top = environment_texel(start, x0, y0) * (1.0 - fx)
        + environment_texel(start, x1, y0) * fx;
    let bottom = environment_texel(start, x0, y1) * (1.0 - fx)
        + environment_texel(start, x1, y1) * fx;
    return top * (1.0 - fy) + bottom * fy;
}

// What a ray leaving the scene along the unit direction dir sees of the environment map.
// Mirror of src/tracer/shading/environment.rs::environment — change both.
fn environment(dir: vec3<f32>) -> vec3<f32> {
    let uv = environment_uv(environment_direction(dir));
    return sample_environment(globals.environment, uv);
}
// #endif
