//! Texture lookups and bump mapping, by hand in both tracers (a hardware sampler would
//! make CPU and GPU differ). The texel layout is `pack::texture`'s.
//!
//! Filtering: trilinear over the mip chain (`pack::texture`), each level bilinear with
//! repeat. Texel (i, j) (column i, row j from the image's top) has its centre at
//! u = (i + ½)/w, v = 1 − (j + ½)/h: v = 0 is the image's bottom edge (the OBJ
//! convention), texel centres sit at half-integers of (u·w, (1 − v)·h), and a lookup
//! between centres blends the four nearest texels, wrapping around every edge.
//!
//! The level comes from the hit's footprint ([`texture_footprint`]): the width of the
//! patch of surface that one pixel covers, carried as a ray cone (Amanatides 1984; Akenine-
//! Möller et al., "Texture level of detail strategies for real-time ray tracing", Ray
//! Tracing Gems ch. 20). A camera ray's cone opens by one pixel's angle (2·tan(fov/2)/height,
//! times cos^1.5 of the ray's angle off the view axis: a pixel's solid angle shrinks as
//! cos³ away from it); mirrors and dielectrics pass the cone on unchanged in angle, as flat
//! surfaces do (curved ones would widen or focus it; that is not modelled). At a hit t
//! along the ray the cone is w = w₀ + spread·t wide; the surface, seen at cosine c to the
//! ray, stretches it to an ellipse with axes w and w/c, and glint filters isotropically
//! over their geometric mean, w/√c (c clamped at `TEXTURE_FOOTPRINT_MIN_COSINE`). Divided
//! by √(|∂p/∂u|·|∂p/∂v|) it is a width in uv; times √(texture width · height) a number of
//! texels, whose log2 is the level (level 0 where it is below one texel: magnified
//! textures stay bilinear). The footprint is one pixel's whatever the anti-aliasing: the
//! image glint converges to is the one with these filtered textures, and few samples per
//! pixel do not alias the texture's detail into moiré.
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

use super::procedural::{is_procedural, procedural_bump_normal, procedural_colour};
use super::surface::{Phong, Surface};
use crate::constants::{
    BUMP_MIN_FRAME_SINE, LUMINANCE_B, LUMINANCE_G, LUMINANCE_R, NO_TEXTURE,
    TEXTURE_FOOTPRINT_MIN_COSINE, TEXTURE_HEADER_WORDS,
};
use crate::pack::layout::{load_material, texel_word};
use crate::pack::{texture_levels, PackedGlobals, PackedMaterial, PackedScene, SceneFeatures};
use crate::tracer::base::ray::Ray;
use glam::{Vec2, Vec3};

/// Texel (x, y) of texture `texture` (x < width, y < height, y from the top row) as RGB
/// in [0, 1], as stored (/255, no gamma).
// Mirror of src/tracer/shading/texture.wgsl::texel — change both.
fn texel(texels: &[u32], texture: u32, x: u32, y: u32) -> Vec3 {
    let header = texture * TEXTURE_HEADER_WORDS;
    let offset = texel_word(texels, header);
    let width = texel_word(texels, header + 1);
    let word = texel_word(texels, offset + y * width + x);
    Vec3::new(
        (word & 0xff) as f32,
        ((word >> 8) & 0xff) as f32,
        ((word >> 16) & 0xff) as f32,
    ) / 255.0
}

/// `t − floor(t)`, the position within one period, with anything that is not a finite
/// number (or rounds up to 1) mapped to 0, so lookups never index out of range.
// Mirror of src/tracer/shading/texture.wgsl::wrap_unit — change both.
pub(crate) fn wrap_unit(t: f32) -> f32 {
    let f = t - t.floor();
    if (0.0..1.0).contains(&f) {
        f
    } else {
        0.0
    }
}

/// Bilinear lookup of `texture` at `uv`, repeating (see the module header for where the
/// texel centres are).
// Mirror of src/tracer/shading/texture.wgsl::sample_texture — change both.
pub fn sample_texture(texels: &[u32], texture: u32, uv: Vec2) -> Vec3 {
    let header = texture * TEXTURE_HEADER_WORDS;
    let width = texel_word(texels, header + 1);
    let height = texel_word(texels, header + 2);
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

/// Header index of mip level `level` of `texture` (level 0 is the texture's own header).
// Mirror of src/tracer/shading/texture.wgsl::texture_level — change both.
fn texture_level(texels: &[u32], texture: u32, level: u32) -> u32 {
    if level == 0 {
        texture
    } else {
        texel_word(texels, texture * TEXTURE_HEADER_WORDS + 3) + level - 1
    }
}

/// The fractional mip level at which `footprint` (a width in uv) spans one texel of
/// `texture`: log2 of the texels it spans at level 0, from 0 (magnified, or no footprint)
/// to the coarsest level.
// Mirror of src/tracer/shading/texture.wgsl::texture_lod — change both.
fn texture_lod(texels: &[u32], texture: u32, footprint: f32) -> f32 {
    let header = texture * TEXTURE_HEADER_WORDS;
    let width = texel_word(texels, header + 1);
    let height = texel_word(texels, header + 2);
    let spanned = footprint * (width as f32 * height as f32).sqrt();
    // The negated test also rejects NaN.
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    if !(spanned > 1.0) {
        return 0.0;
    }
    spanned
        .log2()
        .min((texture_levels(width, height) - 1) as f32)
}

/// The two mip levels around [`texture_lod`] of a footprint: `level` and the next, and
/// how far towards the next to blend (0: `level` alone).
struct MipBlend {
    level: u32,
    blend: f32,
}

/// The mip levels the filtered lookups blend for a footprint `footprint` wide (in uv).
// Mirror of src/tracer/shading/texture.wgsl::mip_blend — change both.
fn mip_blend(texels: &[u32], texture: u32, footprint: f32) -> MipBlend {
    let lod = texture_lod(texels, texture, footprint);
    let level = lod.floor();
    MipBlend {
        level: level as u32,
        blend: lod - level,
    }
}

/// Trilinear lookup of `texture` at `uv` for a footprint `footprint` wide (in uv): the
/// bilinear lookups of the two levels around [`texture_lod`], blended.
// Mirror of src/tracer/shading/texture.wgsl::sample_texture_filtered — change both.
pub fn sample_texture_filtered(texels: &[u32], texture: u32, uv: Vec2, footprint: f32) -> Vec3 {
    blend_mip_levels(texels, texture, footprint, |level| {
        sample_texture(texels, texture_level(texels, texture, level), uv)
    })
}

/// `lookup` of the mip level (a texture number, from [`texture_level`]) around
/// [`texture_lod`] of `footprint` and, where the footprint falls between two levels, of
/// the next, blended: the steps [`sample_texture_filtered`] and
/// [`filtered_height_gradient`] share. (The WGSL writes them out in each: it has no
/// generics; the same operations in the same order.)
#[inline(always)]
fn blend_mip_levels<T>(texels: &[u32], texture: u32, footprint: f32, lookup: impl Fn(u32) -> T) -> T
where
    T: std::ops::Mul<f32, Output = T> + std::ops::Add<Output = T>,
{
    let mip = mip_blend(texels, texture, footprint);
    let fine = lookup(mip.level);
    if mip.blend <= 0.0 {
        return fine;
    }
    let coarse = lookup(mip.level + 1);
    fine * (1.0 - mip.blend) + coarse * mip.blend
}

/// The width, in uv, of the patch of surface `s` that one pixel covers, for a ray along
/// the unit `dir` whose cone (width at its origin, spread per unit length) is `cone` and
/// which hit `s` after `t` (see the module header); 0 (level 0) where the tangent frame
/// gives no finite width (zero ∂p/∂u or ∂p/∂v).
// Mirror of src/tracer/shading/texture.wgsl::texture_footprint — change both.
pub fn texture_footprint(s: &Surface, dir: Vec3, cone: Vec2, t: f32) -> f32 {
    let width = cone.x + cone.y * t;
    let cosine = s.normal.dot(dir).abs().max(TEXTURE_FOOTPRINT_MIN_COSINE);
    let uv_scale = (s.dpdu.length() * s.dpdv.length()).sqrt();
    let footprint = width / (cosine.sqrt() * uv_scale);
    // The test also rejects NaN and ∞.
    if footprint < f32::MAX {
        footprint
    } else {
        0.0
    }
}

/// `s` with its footprint ([`texture_footprint`]) for a hit `t` along the unit `dir` of a
/// ray whose cone is `cone`, in scenes with textures or bump maps (no other reads it).
// Mirror of src/tracer/shading/texture.wgsl::with_footprint — change both.
pub fn with_footprint(scene: &PackedScene, s: Surface, dir: Vec3, cone: Vec2, t: f32) -> Surface {
    if !scene.features.uses_textures() {
        return s;
    }
    let mut filtered = Surface {
        footprint: texture_footprint(&s, dir, cone, t),
        ..s
    };
    if scene.features.contains(SceneFeatures::PROCEDURAL) {
        filtered.world_footprint = pixel_footprint(&s, dir, cone, t);
    }
    filtered
}

/// The width, in world units, of the patch of surface `s` that one pixel covers (see
/// [`texture_footprint`], before its division by the uv scale): the footprint of
/// procedural textures, which `tracer::shading::procedural` takes to object units.
// Mirror of src/tracer/shading/texture.wgsl::pixel_footprint — change both.
fn pixel_footprint(s: &Surface, dir: Vec3, cone: Vec2, t: f32) -> f32 {
    let width = cone.x + cone.y * t;
    let cosine = s.normal.dot(dir).abs().max(TEXTURE_FOOTPRINT_MIN_COSINE);
    let footprint = width / cosine.sqrt();
    // The test also rejects NaN and ∞.
    if footprint < f32::MAX {
        footprint
    } else {
        0.0
    }
}

/// The cone `t` along a ray whose cone is `cone` (width at its origin, spread): what a
/// secondary ray leaving from there starts with.
// Mirror of src/tracer/shading/texture.wgsl::cone_at — change both.
pub fn cone_at(cone: Vec2, t: f32) -> Vec2 {
    Vec2::new(cone.x + cone.y * t, cone.y)
}

/// The cone a camera ray starts with: width 0 at the eye, spread one pixel's angle
/// (2·tan(fov/2)/height) times cos^1.5 of the ray's angle to the view axis.
// Mirror of src/tracer/shading/texture.wgsl::camera_cone — change both.
pub fn camera_cone(g: &PackedGlobals, primary: &Ray) -> Vec2 {
    let axis = primary.dir.dot(Vec3::from(g.forward)).max(0.0);
    let pixel = 2.0 * g.tan_half_fov / g.height as f32;
    Vec2::new(0.0, pixel * axis * axis.sqrt())
}

/// The bump height at `uv`: the luminance of the bilinear lookup.
// Mirror of src/tracer/shading/texture.wgsl::texture_height — change both.
fn texture_height(texels: &[u32], texture: u32, uv: Vec2) -> f32 {
    let c = sample_texture(texels, texture, uv);
    c.x * LUMINANCE_R + c.y * LUMINANCE_G + c.z * LUMINANCE_B
}

/// (∂h/∂u, ∂h/∂v) of the height map `texture` at `uv`: central differences one texel
/// apart (so per unit of u and v: the difference over two texels times size/2).
// Mirror of src/tracer/shading/texture.wgsl::height_gradient — change both.
pub fn height_gradient(texels: &[u32], texture: u32, uv: Vec2) -> Vec2 {
    let header = texture * TEXTURE_HEADER_WORDS;
    let width = texel_word(texels, header + 1) as f32;
    let height = texel_word(texels, header + 2) as f32;
    let du = Vec2::new(1.0 / width, 0.0);
    let dv = Vec2::new(0.0, 1.0 / height);
    let h_u = (texture_height(texels, texture, uv + du) - texture_height(texels, texture, uv - du))
        * (0.5 * width);
    let h_v = (texture_height(texels, texture, uv + dv) - texture_height(texels, texture, uv - dv))
        * (0.5 * height);
    Vec2::new(h_u, h_v)
}

/// [`height_gradient`] blended between the two mip levels around [`texture_lod`] of
/// `footprint` (each level's differences one of its own texels apart).
// Mirror of src/tracer/shading/texture.wgsl::filtered_height_gradient — change both.
fn filtered_height_gradient(texels: &[u32], texture: u32, uv: Vec2, footprint: f32) -> Vec2 {
    blend_mip_levels(texels, texture, footprint, |level| {
        height_gradient(texels, texture_level(texels, texture, level), uv)
    })
}

/// The bumped normal of `s` for material `m` (`s.normal` tilted by the height gradient,
/// see the module header); `s.normal` itself where the tangent frame is degenerate
/// (a pole, a cone tip, zero-area UVs).
// Mirror of src/tracer/shading/texture.wgsl::bump_normal — change both.
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
    let gradient = filtered_height_gradient(texels, m.bump_texture, s.uv, s.footprint);
    let k = sigma * m.bump_strength / g_len;
    let tilt = t_v.cross(n) * (k * gradient.x) + n.cross(t_u) * (k * gradient.y);
    // tilt ⟂ n, so the sum is at least as long as n: never zero.
    (n - tilt).normalize()
}

/// The normal shading uses: `n` (the normal facing the viewer: the geometric one, or on a
/// smooth mesh the interpolated one, which `s.normal` then holds) or, with a bump map,
/// `s.normal` bumped and turned to `n`'s side.
// Mirror of src/tracer/shading/texture.wgsl::shading_normal — change both.
pub fn shading_normal(scene: &PackedScene, s: &Surface, n: Vec3) -> Vec3 {
    let m = load_material(scene, s.material);
    if m.bump_texture == NO_TEXTURE {
        return n;
    }
    let bumped = if is_procedural(m.bump_texture) {
        procedural_bump_normal(scene, m, s)
    } else {
        bump_normal(&scene.texels, m, s)
    };
    if n.dot(s.normal) < 0.0 {
        -bumped
    } else {
        bumped
    }
}

/// The texture detail at the pixel's scale that hit `s` shows: the largest per-channel
/// difference between its material's diffuse texture filtered over the hit's footprint
/// and filtered over twice that (0 without a diffuse texture). Adaptive AA's hint for
/// detail that a pixel's few samples alias (`trace::note_texture_detail`).
// Mirror of src/tracer/shading/texture.wgsl::texture_detail — change both.
pub fn texture_detail(scene: &PackedScene, s: &Surface) -> f32 {
    let m = load_material(scene, s.material);
    if m.diffuse_texture == NO_TEXTURE {
        return 0.0;
    }
    let texels = &scene.texels;
    if is_procedural(m.diffuse_texture) {
        let at_pixel = procedural_colour(scene, m.diffuse_texture, s, s.world_footprint);
        let coarser = procedural_colour(scene, m.diffuse_texture, s, 2.0 * s.world_footprint);
        return (at_pixel - coarser).abs().max_element();
    }
    let at_pixel = sample_texture_filtered(texels, m.diffuse_texture, s.uv, s.footprint);
    let coarser = sample_texture_filtered(texels, m.diffuse_texture, s.uv, 2.0 * s.footprint);
    (at_pixel - coarser).abs().max_element()
}

/// (kd, ks) at `s`: the material's colours, or its textures' at the hit's UV (a
/// procedural's at its object point), filtered over the hit's footprint.
// Mirror of src/tracer/shading/texture.wgsl::surface_colours — change both.
pub fn surface_colours(scene: &PackedScene, m: &PackedMaterial, s: &Surface) -> Phong {
    let mut kd = Vec3::from(m.kd);
    let mut ks = Vec3::from(m.ks);
    if m.diffuse_texture != NO_TEXTURE {
        kd = texture_colour(scene, m.diffuse_texture, s);
    }
    if m.specular_texture != NO_TEXTURE {
        ks = texture_colour(scene, m.specular_texture, s);
    }
    Phong { kd, ks }
}

/// The colour texture `texture` gives at `s`: a procedural's at the hit's object point,
/// filtered over its footprint in object units; an image's at the hit's UV, filtered over
/// its footprint in uv.
// Mirror of src/tracer/shading/texture.wgsl::texture_colour — change both.
fn texture_colour(scene: &PackedScene, texture: u32, s: &Surface) -> Vec3 {
    if is_procedural(texture) {
        return procedural_colour(scene, texture, s, s.world_footprint);
    }
    sample_texture_filtered(&scene.texels, texture, s.uv, s.footprint)
}
