//! Texture lookups and bump mapping, by hand in both tracers (a hardware sampler would
//! make CPU and GPU differ). The texel layout is `pack::texture`'s.
//!
//! Filtering: bilinear with repeat. Texel (i, j) (column i, row j from the image's top)
//! has its centre at u = (i + ½)/w, v = 1 − (j + ½)/h: v = 0 is the image's bottom edge
//! (the OBJ convention), texel centres sit at half-integers of (u·w, (1 − v)·h), and a
//! lookup between centres blends the four nearest texels, wrapping around every edge.
//!
//! Bump mapping (Blinn 1978): the height h is the luminance of the bilinear height map;
//! its gradient comes from central differences one texel apart. With unit tangents
//! t_u = ∂p/∂u/|∂p/∂u|, t_v = ∂p/∂v/|∂p/∂v| and the unit normal N, the surface displaced
//! by s·h along N has tangents t_u + s·∂h/∂u·N and t_v + s·∂h/∂v·N, whose cross product is
//! (t_u × t_v) + s·∂h/∂u·(N × t_v) + s·∂h/∂v·(t_u × N) (the s² term is N × N = 0). Written
//! against N (σ = ±1 the side of t_u × t_v, g = |t_u × t_v|) and divided by σ·g:
//!   N' = normalize(N − s·(∂h/∂u·T_u + ∂h/∂v·T_v)),
//!   T_u = σ·(t_v × N)/g,   T_v = σ·(N × t_u)/g,
//! which for an orthonormal right-handed frame is T_u = t_u, T_v = t_v: the normal leans
//! away from the way the height rises (a ramp rising along u tilts it towards −u). The
//! proposal's N = ⟨Hs−Hy, Hs−Hx, 1⟩ pairs the x component with the v slope and the y
//! component with the u slope; here each slope goes with its own tangent. Scale: s is the
//! height per unit of texture space, so the look does not change when an object is scaled.

use super::surface::{Phong, Surface};
use crate::constants::{
    BUMP_MIN_FRAME_SINE, LUMINANCE_B, LUMINANCE_G, LUMINANCE_R, NO_TEXTURE, TEXTURE_HEADER_WORDS,
};
use crate::pack::{PackedMaterial, PackedScene};
use glam::{Vec2, Vec3};

/// Texel (x, y) of texture `texture` (x < width, y < height, y from the top row) as RGB
/// in [0, 1], as stored (/255, no gamma).
// Mirror of shaders/texture.wgsl::texel — change both.
fn texel(texels: &[u32], texture: u32, x: u32, y: u32) -> Vec3 {
    let header = (texture * TEXTURE_HEADER_WORDS) as usize;
    let offset = texels[header];
    let width = texels[header + 1];
    let word = texels[(offset + y * width + x) as usize];
    Vec3::new(
        (word & 0xff) as f32,
        ((word >> 8) & 0xff) as f32,
        ((word >> 16) & 0xff) as f32,
    ) / 255.0
}

/// `t − floor(t)`, the position within one period, with anything that is not a finite
/// number (or rounds up to 1) mapped to 0, so lookups never index out of range.
// Mirror of shaders/texture.wgsl::wrap_unit — change both.
fn wrap_unit(t: f32) -> f32 {
    let f = t - t.floor();
    if (0.0..1.0).contains(&f) {
        f
    } else {
        0.0
    }
}

/// Bilinear lookup of `texture` at `uv`, repeating (see the module header for where the
/// texel centres are).
// Mirror of shaders/texture.wgsl::sample_texture — change both.
pub fn sample_texture(texels: &[u32], texture: u32, uv: Vec2) -> Vec3 {
    let header = (texture * TEXTURE_HEADER_WORDS) as usize;
    let width = texels[header + 1];
    let height = texels[header + 2];
    // Continuous texel coordinates: centres at half-integers, v = 0 at the bottom row.
    let x = wrap_unit(uv.x) * width as f32 - 0.5;
    let y = (1.0 - wrap_unit(uv.y)) * height as f32 - 0.5;
    let x_floor = x.floor();
    let y_floor = y.floor();
    let fx = x - x_floor;
    let fy = y - y_floor;
    // x_floor ≥ −1 and y_floor ≥ −1: adding the size once wraps every index.
    let w = width as i32;
    let h = height as i32;
    let x0 = ((x_floor as i32 + w) % w) as u32;
    let x1 = ((x_floor as i32 + 1 + w) % w) as u32;
    let y0 = ((y_floor as i32 + h) % h) as u32;
    let y1 = ((y_floor as i32 + 1 + h) % h) as u32;
    let top = texel(texels, texture, x0, y0) * (1.0 - fx) + texel(texels, texture, x1, y0) * fx;
    let bottom = texel(texels, texture, x0, y1) * (1.0 - fx) + texel(texels, texture, x1, y1) * fx;
    top * (1.0 - fy) + bottom * fy
}

/// The bump height at `uv`: the luminance of the bilinear lookup.
// Mirror of shaders/texture.wgsl::texture_height — change both.
fn texture_height(texels: &[u32], texture: u32, uv: Vec2) -> f32 {
    let c = sample_texture(texels, texture, uv);
    c.x * LUMINANCE_R + c.y * LUMINANCE_G + c.z * LUMINANCE_B
}

/// (∂h/∂u, ∂h/∂v) of the height map `texture` at `uv`: central differences one texel
/// apart (so per unit of u and v: the difference over two texels times size/2).
// Mirror of shaders/texture.wgsl::height_gradient — change both.
pub fn height_gradient(texels: &[u32], texture: u32, uv: Vec2) -> Vec2 {
    let header = (texture * TEXTURE_HEADER_WORDS) as usize;
    let width = texels[header + 1] as f32;
    let height = texels[header + 2] as f32;
    let du = Vec2::new(1.0 / width, 0.0);
    let dv = Vec2::new(0.0, 1.0 / height);
    let h_u = (texture_height(texels, texture, uv + du) - texture_height(texels, texture, uv - du))
        * (0.5 * width);
    let h_v = (texture_height(texels, texture, uv + dv) - texture_height(texels, texture, uv - dv))
        * (0.5 * height);
    Vec2::new(h_u, h_v)
}

/// The bumped normal of `s` for material `m` (`s.normal` tilted by the height gradient,
/// see the module header); `s.normal` itself where the tangent frame is degenerate
/// (a pole, a cone tip, zero-area UVs).
// Mirror of shaders/texture.wgsl::bump_normal — change both.
pub fn bump_normal(texels: &[u32], m: &PackedMaterial, s: &Surface) -> Vec3 {
    let n = s.normal;
    let len_u = s.dpdu.length();
    let len_v = s.dpdv.length();
    // The negated tests also reject NaN.
    if !(len_u > 0.0 && len_v > 0.0) {
        return n;
    }
    let t_u = s.dpdu / len_u;
    let t_v = s.dpdv / len_v;
    let g = t_u.cross(t_v);
    let g_len = g.length();
    if g_len.is_nan() || g_len <= BUMP_MIN_FRAME_SINE {
        return n;
    }
    let sigma = if g.dot(n) < 0.0 { -1.0 } else { 1.0 };
    let gradient = height_gradient(texels, m.bump_texture, s.uv);
    let k = sigma * m.bump_strength / g_len;
    let tilt = t_v.cross(n) * (k * gradient.x) + n.cross(t_u) * (k * gradient.y);
    // tilt ⟂ n, so the sum is at least as long as n: never zero.
    (n - tilt).normalize()
}

/// The normal shading uses: `n` (the geometric normal facing the viewer) or, with a bump
/// map, the bumped normal turned to the same side.
// Mirror of shaders/texture.wgsl::shading_normal — change both.
pub fn shading_normal(scene: &PackedScene, s: &Surface, n: Vec3) -> Vec3 {
    let m = &scene.materials[s.material as usize];
    if m.bump_texture == NO_TEXTURE {
        return n;
    }
    let bumped = bump_normal(&scene.texels, m, s);
    if n.dot(s.normal) < 0.0 {
        -bumped
    } else {
        bumped
    }
}

/// (kd, ks) at `s`: the material's colours, or its textures' texels at the hit's UV.
// Mirror of shaders/texture.wgsl::surface_colours — change both.
pub fn surface_colours(scene: &PackedScene, m: &PackedMaterial, s: &Surface) -> Phong {
    let mut kd = Vec3::from(m.kd);
    let mut ks = Vec3::from(m.ks);
    if m.diffuse_texture != NO_TEXTURE {
        kd = sample_texture(&scene.texels, m.diffuse_texture, s.uv);
    }
    if m.specular_texture != NO_TEXTURE {
        ks = sample_texture(&scene.texels, m.specular_texture, s.uv);
    }
    Phong { kd, ks }
}
