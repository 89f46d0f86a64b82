// texture.wgsl — texture lookups and bump mapping by hand (a hardware sampler would make
// CPU and GPU differ). The texel layout is src/pack/texture.rs's; filtering (bilinear,
// repeat, texel centres at half-integers, v = 0 at the image's bottom) and the bump
// formula are derived in src/cpu/texture.rs.

// #if TEXTURE|BUMP
// Texel (x, y) of texture `texture` (x < width, y < height, y from the top row) as RGB in
// [0, 1], as stored (/255, no gamma).
// Mirror of src/cpu/texture.rs::texel — change both.
fn texel(texture: u32, x: u32, y: u32) -> vec3<f32> {
    let header = texture * TEXTURE_HEADER_WORDS;
    let offset = texels[header];
    let width = texels[header + 1u];
    let word = texels[offset + y * width + x];
    return vec3<f32>(f32(word & 0xffu), f32((word >> 8u) & 0xffu), f32((word >> 16u) & 0xffu)) / 255.0;
}

// t − floor(t), the position within one period, with anything that is not a finite
// number (or rounds up to 1) mapped to 0, so lookups never index out of range.
// Mirror of src/cpu/texture.rs::wrap_unit — change both.
fn wrap_unit(t: f32) -> f32 {
    let f = t - floor(t);
    if f >= 0.0 && f < 1.0 {
        return f;
    }
    return 0.0;
}

// Bilinear lookup of `texture` at uv, repeating.
// Mirror of src/cpu/texture.rs::sample_texture — change both.
fn sample_texture(texture: u32, uv: vec2<f32>) -> vec3<f32> {
    let header = texture * TEXTURE_HEADER_WORDS;
    let width = texels[header + 1u];
    let height = texels[header + 2u];
    // Continuous texel coordinates: centres at half-integers, v = 0 at the bottom row.
    let x = wrap_unit(uv.x) * f32(width) - 0.5;
    let y = (1.0 - wrap_unit(uv.y)) * f32(height) - 0.5;
    let x_floor = floor(x);
    let y_floor = floor(y);
    let fx = x - x_floor;
    let fy = y - y_floor;
    // x_floor ≥ −1 and y_floor ≥ −1: adding the size once wraps every index.
    let w = i32(width);
    let h = i32(height);
    let x0 = u32((i32(x_floor) + w) % w);
    let x1 = u32((i32(x_floor) + 1 + w) % w);
    let y0 = u32((i32(y_floor) + h) % h);
    let y1 = u32((i32(y_floor) + 1 + h) % h);
    let top = texel(texture, x0, y0) * (1.0 - fx) + texel(texture, x1, y0) * fx;
    let bottom = texel(texture, x0, y1) * (1.0 - fx) + texel(texture, x1, y1) * fx;
    return top * (1.0 - fy) + bottom * fy;
}
// #endif

// #if BUMP
// The bump height at uv: the luminance of the bilinear lookup.
// Mirror of src/cpu/texture.rs::texture_height — change both.
fn texture_height(texture: u32, uv: vec2<f32>) -> f32 {
    let c = sample_texture(texture, uv);
    return c.x * LUMINANCE_R + c.y * LUMINANCE_G + c.z * LUMINANCE_B;
}

// (∂h/∂u, ∂h/∂v) of the height map `texture` at uv: central differences one texel apart.
// Mirror of src/cpu/texture.rs::height_gradient — change both.
fn height_gradient(texture: u32, uv: vec2<f32>) -> vec2<f32> {
    let header = texture * TEXTURE_HEADER_WORDS;
    let width = f32(texels[header + 1u]);
    let height = f32(texels[header + 2u]);
    let du = vec2<f32>(1.0 / width, 0.0);
    let dv = vec2<f32>(0.0, 1.0 / height);
    let h_u = (texture_height(texture, uv + du) - texture_height(texture, uv - du)) * (0.5 * width);
    let h_v = (texture_height(texture, uv + dv) - texture_height(texture, uv - dv)) * (0.5 * height);
    return vec2<f32>(h_u, h_v);
}

// The bumped normal of s for material m (s.normal tilted by the height gradient);
// s.normal itself where the tangent frame is degenerate (a pole, a cone tip, zero-area
// UVs).
// Mirror of src/cpu/texture.rs::bump_normal — change both.
fn bump_normal(m: PackedMaterial, s: Surface) -> vec3<f32> {
    let n = s.normal;
    let len_u = length(s.dpdu);
    let len_v = length(s.dpdv);
    // The negated tests also reject NaN.
    if !(len_u > 0.0 && len_v > 0.0) {
        return n;
    }
    let t_u = s.dpdu / len_u;
    let t_v = s.dpdv / len_v;
    let g = cross(t_u, t_v);
    let g_len = length(g);
    // The negated test also rejects NaN, like Rust's is_nan check.
    if !(g_len > BUMP_MIN_FRAME_SINE) {
        return n;
    }
    let sigma = select(1.0, -1.0, dot(g, n) < 0.0);
    let gradient = height_gradient(m.bump_texture, s.uv);
    let k = sigma * m.bump_strength / g_len;
    let tilt = cross(t_v, n) * (k * gradient.x) + cross(n, t_u) * (k * gradient.y);
    // tilt ⟂ n, so the sum is at least as long as n: never zero.
    return normalize(n - tilt);
}

// The normal shading uses: n (the geometric normal facing the viewer) or, with a bump
// map, the bumped normal turned to the same side.
// Mirror of src/cpu/texture.rs::shading_normal — change both.
fn shading_normal(s: Surface, n: vec3<f32>) -> vec3<f32> {
    let m = materials[s.material];
    if m.bump_texture == NO_TEXTURE {
        return n;
    }
    let bumped = bump_normal(m, s);
    if dot(n, s.normal) < 0.0 {
        return -bumped;
    }
    return bumped;
}
// #endif

// #if TEXTURE
// (kd, ks) at s: the material's colours, or its textures' texels at the hit's UV.
// Mirror of src/cpu/texture.rs::surface_colours — change both.
fn surface_colours(m: PackedMaterial, s: Surface) -> Phong {
    var kd = m.kd;
    var ks = m.ks;
    if m.diffuse_texture != NO_TEXTURE {
        kd = sample_texture(m.diffuse_texture, s.uv);
    }
    if m.specular_texture != NO_TEXTURE {
        ks = sample_texture(m.specular_texture, s.uv);
    }
    return Phong(kd, ks);
}
// #endif
