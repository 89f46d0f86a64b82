// texture.wgsl — texture lookups and bump mapping by hand (a hardware sampler would make
// CPU and GPU differ). The texel layout (mip chain included) is src/pack/texture.rs's;
// filtering (trilinear over the mip chain, each level bilinear with repeat, texel centres
// at half-integers, v = 0 at the image's bottom), the ray cone that picks the level and
// the bump formula are derived in src/tracer/shading/texture.rs.

// #if TEXTURE|BUMP
// Texel (x, y) of texture `texture` (x < width, y < height, y from the top row) as RGB in
// [0, 1], as stored (/255, no gamma).
// Mirror of src/tracer/shading/texture.rs::texel — change both.
fn texel(texture: u32, x: u32, y: u32) -> vec3<f32> {
    let header = texture * TEXTURE_HEADER_WORDS;
    let offset = texel_word(header);
    let width = texel_word(header + 1u);
    let word = texel_word(offset + y * width + x);
    return vec3<f32>(f32(word & 0xffu), f32((word >> 8u) & 0xffu), f32((word >> 16u) & 0xffu)) / 255.0;
}
// #endif

// #if TEXTURE|BUMP|ENVIRONMENT
// t − floor(t), the position within one period, with anything that is not a finite
// number (or rounds up to 1) mapped to 0, so lookups never index out of range (the
// environment map's u too).
// Mirror of src/tracer/shading/texture.rs::wrap_unit — change both.
fn wrap_unit(t: f32) -> f32 {
    let f = t - floor(t);
    if f >= 0.0 && f < 1.0 {
        return f;
    }
    return 0.0;
}
// #endif

// #if TEXTURE|BUMP
// Bilinear lookup of `texture` at uv, repeating.
// Mirror of src/tracer/shading/texture.rs::sample_texture — change both.
fn sample_texture(texture: u32, uv: vec2<f32>) -> vec3<f32> {
    let header = texture * TEXTURE_HEADER_WORDS;
    let width = texel_word(header + 1u);
    let height = texel_word(header + 2u);
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

// Number of levels of a width×height texture's chain: 1 + floor(log2 max(w, h)).
// Mirror of src/pack/texture.rs::texture_levels — change both.
fn texture_levels(width: u32, height: u32) -> u32 {
    return 32u - countLeadingZeros(max(max(width, height), 1u));
}

// Header index of mip level `level` of `texture` (level 0 is the texture's own header).
// Mirror of src/tracer/shading/texture.rs::texture_level — change both.
fn texture_level(texture: u32, level: u32) -> u32 {
    if level == 0u {
        return texture;
    }
    return texel_word(texture * TEXTURE_HEADER_WORDS + 3u) + level - 1u;
}

// The fractional mip level at which `footprint` (a width in uv) spans one texel of
// `texture`: from 0 (magnified, or no footprint) to the coarsest level.
// Mirror of src/tracer/shading/texture.rs::texture_lod — change both.
fn texture_lod(texture: u32, footprint: f32) -> f32 {
    let header = texture * TEXTURE_HEADER_WORDS;
    let width = texel_word(header + 1u);
    let height = texel_word(header + 2u);
    let spanned = footprint * sqrt(f32(width) * f32(height));
    // The negated test also rejects NaN.
    if !(spanned > 1.0) {
        return 0.0;
    }
    return min(log2(spanned), f32(texture_levels(width, height) - 1u));
}

// The two mip levels around texture_lod of `footprint`: `level` and the next, and how
// far towards the next to blend (0: `level` alone).
struct MipBlend {
    level: u32,
    blend: f32,
}

// The mip levels the filtered lookups blend for a footprint `footprint` wide (in uv).
// Mirror of src/tracer/shading/texture.rs::mip_blend — change both.
fn mip_blend(texture: u32, footprint: f32) -> MipBlend {
    let lod = texture_lod(texture, footprint);
    let level = floor(lod);
    return MipBlend(u32(level), lod - level);
}

// Trilinear lookup of `texture` at uv for a footprint `footprint` wide (in uv): the
// bilinear lookups of the two levels around texture_lod, blended.
// Mirror of src/tracer/shading/texture.rs::sample_texture_filtered — change both.
fn sample_texture_filtered(texture: u32, uv: vec2<f32>, footprint: f32) -> vec3<f32> {
    let mip = mip_blend(texture, footprint);
    let fine = sample_texture(texture_level(texture, mip.level), uv);
    if mip.blend <= 0.0 {
        return fine;
    }
    let coarse = sample_texture(texture_level(texture, mip.level + 1u), uv);
    return fine * (1.0 - mip.blend) + coarse * mip.blend;
}

// The width, in uv, of the patch of surface s that one pixel covers, for a ray along the
// unit dir whose cone (width at its origin, spread per unit length) is `cone` and which
// hit s after t; 0 (level 0) where the tangent frame gives no finite width.
// Mirror of src/tracer/shading/texture.rs::texture_footprint — change both.
fn texture_footprint(s: Surface, dir: vec3<f32>, cone: vec2<f32>, t: f32) -> f32 {
    let width = cone.x + cone.y * t;
    let cosine = max(abs(dot(s.normal, dir)), TEXTURE_FOOTPRINT_MIN_COSINE);
    let uv_scale = sqrt(length(s.dpdu) * length(s.dpdv));
    let footprint = width / (sqrt(cosine) * uv_scale);
    // The test also rejects NaN and infinity.
    if footprint < 3.40282347e38 {
        return footprint;
    }
    return 0.0;
}

// s with its footprint (texture_footprint) for a hit t along the unit dir of a ray whose
// cone is `cone` (compiled only into scenes with textures or bump maps).
// Mirror of src/tracer/shading/texture.rs::with_footprint — change both.
fn with_footprint(s: Surface, dir: vec3<f32>, cone: vec2<f32>, t: f32) -> Surface {
    var filtered = s;
    filtered.footprint = texture_footprint(s, dir, cone, t);
// #if PROCEDURAL
    filtered.world_footprint = pixel_footprint(s, dir, cone, t);
// #endif
    return filtered;
}

// #if PROCEDURAL
// The width, in world units, of the patch of surface s that one pixel covers: the
// footprint of procedural textures.
// Mirror of src/tracer/shading/texture.rs::pixel_footprint — change both.
fn pixel_footprint(s: Surface, dir: vec3<f32>, cone: vec2<f32>, t: f32) -> f32 {
    let width = cone.x + cone.y * t;
    let cosine = max(abs(dot(s.normal, dir)), TEXTURE_FOOTPRINT_MIN_COSINE);
    let footprint = width / sqrt(cosine);
    // The test also rejects NaN and infinity.
    if footprint < F32_MAX {
        return footprint;
    }
    return 0.0;
}
// #endif

// The cone t along a ray whose cone is `cone` (width at its origin, spread): what a
// secondary ray leaving from there starts with.
// Mirror of src/tracer/shading/texture.rs::cone_at — change both.
fn cone_at(cone: vec2<f32>, t: f32) -> vec2<f32> {
    return vec2<f32>(cone.x + cone.y * t, cone.y);
}

// The cone a camera ray starts with: width 0 at the eye, spread one pixel's angle
// (2·tan(fov/2)/height) times cos^1.5 of the ray's angle to the view axis.
// Mirror of src/tracer/shading/texture.rs::camera_cone — change both.
fn camera_cone(primary: Ray) -> vec2<f32> {
    let axis = max(dot(primary.dir, globals.forward), 0.0);
    let pixel = 2.0 * globals.tan_half_fov / f32(globals.height);
    return vec2<f32>(0.0, pixel * axis * sqrt(axis));
}
// #endif

// #if BUMP
// The bump height at uv: the luminance of the bilinear lookup.
// Mirror of src/tracer/shading/texture.rs::texture_height — change both.
fn texture_height(texture: u32, uv: vec2<f32>) -> f32 {
    let c = sample_texture(texture, uv);
    return c.x * LUMINANCE_R + c.y * LUMINANCE_G + c.z * LUMINANCE_B;
}

// (∂h/∂u, ∂h/∂v) of the height map `texture` at uv: central differences one texel apart.
// Mirror of src/tracer/shading/texture.rs::height_gradient — change both.
fn height_gradient(texture: u32, uv: vec2<f32>) -> vec2<f32> {
    let header = texture * TEXTURE_HEADER_WORDS;
    let width = f32(texel_word(header + 1u));
    let height = f32(texel_word(header + 2u));
    let du = vec2<f32>(1.0 / width, 0.0);
    let dv = vec2<f32>(0.0, 1.0 / height);
    let h_u = (texture_height(texture, uv + du) - texture_height(texture, uv - du)) * (0.5 * width);
    let h_v = (texture_height(texture, uv + dv) - texture_height(texture, uv - dv)) * (0.5 * height);
    return vec2<f32>(h_u, h_v);
}

// height_gradient blended between the two mip levels around texture_lod of `footprint`
// (each level's differences one of its own texels apart).
// Mirror of src/tracer/shading/texture.rs::filtered_height_gradient — change both.
fn filtered_height_gradient(texture: u32, uv: vec2<f32>, footprint: f32) -> vec2<f32> {
    let mip = mip_blend(texture, footprint);
    let fine = height_gradient(texture_level(texture, mip.level), uv);
    if mip.blend <= 0.0 {
        return fine;
    }
    let coarse = height_gradient(texture_level(texture, mip.level + 1u), uv);
    return fine * (1.0 - mip.blend) + coarse * mip.blend;
}

// The bumped normal of s for material m (s.normal tilted by the height gradient);
// s.normal itself where the tangent frame is degenerate (a pole, a cone tip, zero-area
// UVs).
// Mirror of src/tracer/shading/texture.rs::bump_normal — change both.
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
    let gradient = filtered_height_gradient(m.bump_texture, s.uv, s.footprint);
    let k = sigma * m.bump_strength / g_len;
    let tilt = cross(t_v, n) * (k * gradient.x) + cross(n, t_u) * (k * gradient.y);
    // tilt ⟂ n, so the sum is at least as long as n: never zero.
    return normalize(n - tilt);
}

// The normal shading uses: n (the normal facing the viewer: the geometric one, or on a
// smooth mesh the interpolated one, which s.normal then holds) or, with a bump map,
// s.normal bumped and turned to n's side.
// Mirror of src/tracer/shading/texture.rs::shading_normal — change both.
fn shading_normal(s: Surface, n: vec3<f32>) -> vec3<f32> {
    let m = load_material(s.material);
    if m.bump_texture == NO_TEXTURE {
        return n;
    }
// #if PROCEDURAL
    var bumped: vec3<f32>;
    if is_procedural(m.bump_texture) {
        bumped = procedural_bump_normal(m, s);
    } else {
        bumped = bump_normal(m, s);
    }
// #else
    let bumped = bump_normal(m, s);
// #endif
    if dot(n, s.normal) < 0.0 {
        return -bumped;
    }
    return bumped;
}
// #endif

// #if TEXTURE
// The texture detail at the pixel's scale that hit s shows: the largest per-channel
// difference between its material's diffuse texture filtered over the hit's footprint and
// filtered over twice that (0 without a diffuse texture). Adaptive AA's hint for detail
// that a pixel's few samples alias (trace.wgsl's note_texture_detail).
// Mirror of src/tracer/shading/texture.rs::texture_detail — change both.
fn texture_detail(s: Surface) -> f32 {
    let m = load_material(s.material);
    if m.diffuse_texture == NO_TEXTURE {
        return 0.0;
    }
// #if PROCEDURAL
    if is_procedural(m.diffuse_texture) {
        let at_pixel = procedural_colour(m.diffuse_texture, s, s.world_footprint);
        let coarser = procedural_colour(m.diffuse_texture, s, 2.0 * s.world_footprint);
        return max_element(abs(at_pixel - coarser));
    }
// #endif
    let at_pixel = sample_texture_filtered(m.diffuse_texture, s.uv, s.footprint);
    let coarser = sample_texture_filtered(m.diffuse_texture, s.uv, 2.0 * s.footprint);
    return max_element(abs(at_pixel - coarser));
}

// (kd, ks) at s: the material's colours, or its textures' at the hit's UV, filtered over
// the hit's footprint.
// Mirror of src/tracer/shading/texture.rs::surface_colours — change both.
fn surface_colours(m: PackedMaterial, s: Surface) -> Phong {
    var kd = m.kd;
    var ks = m.ks;
    if m.diffuse_texture != NO_TEXTURE {
        kd = texture_colour(m.diffuse_texture, s);
    }
    if m.specular_texture != NO_TEXTURE {
        ks = texture_colour(m.specular_texture, s);
    }
    return Phong(kd, ks);
}

// The colour texture `texture` gives at s: a procedural's at the hit's object point,
// filtered over its footprint in object units; an image's at the hit's UV, filtered over
// its footprint in uv.
// Mirror of src/tracer/shading/texture.rs::texture_colour — change both.
fn texture_colour(texture: u32, s: Surface) -> vec3<f32> {
// #if PROCEDURAL
    if is_procedural(texture) {
        return procedural_colour(texture, s, s.world_footprint);
    }
// #endif
    return sample_texture_filtered(texture, s.uv, s.footprint);
}
// #endif
