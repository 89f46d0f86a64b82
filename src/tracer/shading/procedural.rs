//! Procedural (solid) textures: `gr.checker`, `gr.noise`, `gr.marble` and `gr.wood`,
//! evaluated at the hit point in the primitive's own coordinates (`Surface::p_object`),
//! so the pattern moves, turns and scales with the object. The parameter blocks and
//! Perlin's permutation table are `pack::procedural`'s, in `texels`.
//!
//! **Noise** is Ken Perlin's improved noise (2002) as his reference `ImprovedNoise.java`
//! defines it: his permutation table (`constants::PERLIN_PERMUTATION`), his 12 gradient
//! directions picked by `hash & 15`, the fade 6t⁵ − 15t⁴ + 10t³, trilinear blending, in
//! f32; 0 at every lattice point. [`perlin_noise`] also returns its analytic gradient:
//! the trilinear blend of the corner gradients plus each fade's slope times the blend's
//! derivative along that axis. [`fbm`] sums octaves with lacunarity 2 and gain ½, divided
//! by the sum of the gains, so it stays in about [−1, 1].
//!
//! **Antialiasing** by the pixel's footprint (the ray cone of image textures, as a width
//! in object units, `object_frame`): octave o, whose lattice cells are 2⁻ᵒ wide, is kept
//! whole while the footprint spans at most half a cell and faded to its mean (0) by the
//! time it spans a whole one (its Nyquist limit); the checker is box-filtered over the
//! footprint in closed form (the integral of a square wave is a triangle wave), per axis
//! over the footprint disc's extent along that axis (none along the surface normal, so a
//! face lying on a cell boundary does not turn grey); marble's veins and wood's rings
//! fade to their mean colour between a quarter and half a period per footprint.

use super::surface::Surface;
use crate::constants::{
    PROCEDURAL_CHECKER, PROCEDURAL_CHECKER_MIN_WIDTH, PROCEDURAL_MARBLE, PROCEDURAL_MAX_OCTAVES,
    PROCEDURAL_NOISE, PROCEDURAL_TEXTURE, TWO_PI,
};
use crate::pack::layout::{load_instance, texel_word};
use crate::pack::{PackedInstance, PackedMaterial, PackedScene};
use glam::{Vec3, Vec4};

/// Perlin's fade curve, 6t⁵ − 15t⁴ + 10t³, in his reference code's form.
// Mirror of src/tracer/shading/procedural.wgsl::fade — change both.
fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

/// The fade's derivative, 30t²(t − 1)².
// Mirror of src/tracer/shading/procedural.wgsl::fade_slope — change both.
fn fade_slope(t: f32) -> f32 {
    let s = t * (t - 1.0);
    30.0 * s * s
}

/// `a + t·(b − a)`, the reference code's `lerp`.
// Mirror of src/tracer/shading/procedural.wgsl::lerp — change both.
fn lerp(t: f32, a: f32, b: f32) -> f32 {
    a + t * (b - a)
}

/// [`lerp`] of vectors.
// Mirror of src/tracer/shading/procedural.wgsl::lerp_vec3 — change both.
fn lerp_vec3(t: f32, a: Vec3, b: Vec3) -> Vec3 {
    a + (b - a) * t
}

/// The gradient direction Perlin's `grad(hash, x, y, z)` dots with (x, y, z): with
/// h = hash & 15, u is x for h < 8 else y, v is y for h < 4, x for h = 12 or 14, else z,
/// and the value ±u ± v (bit 0 the sign of u, bit 1 of v): one of the 12 midpoints of
/// the cube's edges, four of them twice. Its components are 0 and ±1, so the dot
/// product is the reference value exactly.
// Mirror of src/tracer/shading/procedural.wgsl::gradient_direction — change both.
fn gradient_direction(hash: u32) -> Vec3 {
    let h = hash & 15;
    let su = if h & 1 == 0 { 1.0 } else { -1.0 };
    let sv = if h & 2 == 0 { 1.0 } else { -1.0 };
    let mut g = Vec3::ZERO;
    if h < 8 {
        g.x = su;
    } else {
        g.y = su;
    }
    if h < 4 {
        g.y = sv;
    } else if h == 12 || h == 14 {
        g.x = sv;
    } else {
        g.z = sv;
    }
    g
}

/// Perlin's improved noise at `p` (the permutation table at word `table` of `texels`)
/// and its gradient: (n, ∂n/∂x, ∂n/∂y, ∂n/∂z). Lattice coordinates wrap every 256 cells
/// as in the reference code (|p| below 2³¹).
// Mirror of src/tracer/shading/procedural.wgsl::perlin_noise — change both.
pub fn perlin_noise(texels: &[u32], table: u32, p: Vec3) -> Vec4 {
    let cell = p.floor();
    let f = p - cell;
    let x = (cell.x as i32 & 255) as u32;
    let y = (cell.y as i32 & 255) as u32;
    let z = (cell.z as i32 & 255) as u32;
    let a = texel_word(texels, table + x) + y;
    let aa = texel_word(texels, table + a) + z;
    let ab = texel_word(texels, table + a + 1) + z;
    let b = texel_word(texels, table + x + 1) + y;
    let ba = texel_word(texels, table + b) + z;
    let bb = texel_word(texels, table + b + 1) + z;
    let g000 = gradient_direction(texel_word(texels, table + aa));
    let g100 = gradient_direction(texel_word(texels, table + ba));
    let g010 = gradient_direction(texel_word(texels, table + ab));
    let g110 = gradient_direction(texel_word(texels, table + bb));
    let g001 = gradient_direction(texel_word(texels, table + aa + 1));
    let g101 = gradient_direction(texel_word(texels, table + ba + 1));
    let g011 = gradient_direction(texel_word(texels, table + ab + 1));
    let g111 = gradient_direction(texel_word(texels, table + bb + 1));
    let n000 = g000.dot(f);
    let n100 = g100.dot(Vec3::new(f.x - 1.0, f.y, f.z));
    let n010 = g010.dot(Vec3::new(f.x, f.y - 1.0, f.z));
    let n110 = g110.dot(Vec3::new(f.x - 1.0, f.y - 1.0, f.z));
    let n001 = g001.dot(Vec3::new(f.x, f.y, f.z - 1.0));
    let n101 = g101.dot(Vec3::new(f.x - 1.0, f.y, f.z - 1.0));
    let n011 = g011.dot(Vec3::new(f.x, f.y - 1.0, f.z - 1.0));
    let n111 = g111.dot(Vec3::new(f.x - 1.0, f.y - 1.0, f.z - 1.0));
    let u = fade(f.x);
    let v = fade(f.y);
    let w = fade(f.z);
    let x00 = lerp(u, n000, n100);
    let x10 = lerp(u, n010, n110);
    let x01 = lerp(u, n001, n101);
    let x11 = lerp(u, n011, n111);
    let y0 = lerp(v, x00, x10);
    let y1 = lerp(v, x01, x11);
    let value = lerp(w, y0, y1);
    // d/dp of the blend: the blended corner gradients, plus each fade's slope times the
    // blend's derivative in that fade.
    let blended = lerp_vec3(
        w,
        lerp_vec3(v, lerp_vec3(u, g000, g100), lerp_vec3(u, g010, g110)),
        lerp_vec3(v, lerp_vec3(u, g001, g101), lerp_vec3(u, g011, g111)),
    );
    let d_u = lerp(
        w,
        lerp(v, n100 - n000, n110 - n010),
        lerp(v, n101 - n001, n111 - n011),
    );
    let d_v = lerp(w, x10 - x00, x11 - x01);
    let d_w = y1 - y0;
    let slope = Vec3::new(
        fade_slope(f.x) * d_u,
        fade_slope(f.y) * d_v,
        fade_slope(f.z) * d_w,
    );
    let gradient = blended + slope;
    Vec4::new(value, gradient.x, gradient.y, gradient.z)
}

/// Fractal Brownian motion of [`perlin_noise`] at `p`, with its gradient: octave o at
/// 2ᵒ·p weighs 2⁻ᵒ (lacunarity 2, gain ½), the sum divided by the sum of the weights.
/// An octave whose cells are under twice `footprint` (a width in p's units) fades to
/// its mean, 0 (see the module header).
// Mirror of src/tracer/shading/procedural.wgsl::fbm — change both.
pub fn fbm(texels: &[u32], table: u32, p: Vec3, octaves: u32, footprint: f32) -> Vec4 {
    let mut sum = Vec4::ZERO;
    let mut weights = 0.0;
    let mut amplitude = 1.0;
    let mut frequency = 1.0;
    for _ in 0..octaves.min(PROCEDURAL_MAX_OCTAVES) {
        weights += amplitude;
        let keep = (2.0 - 2.0 * footprint * frequency).clamp(0.0, 1.0);
        if keep > 0.0 {
            let n = perlin_noise(texels, table, p * frequency);
            let scaled = Vec4::new(n.x, n.y * frequency, n.z * frequency, n.w * frequency);
            sum += scaled * (amplitude * keep);
        }
        amplitude *= 0.5;
        frequency *= 2.0;
    }
    sum / weights
}

/// ∫₀ˣ s, s the square wave that is +1 on [0, 1) and −1 on [1, 2) (period 2): the
/// triangle wave rising on [0, 1) and falling on [1, 2).
// Mirror of src/tracer/shading/procedural.wgsl::square_wave_integral — change both.
fn square_wave_integral(x: f32) -> f32 {
    let m = x - 2.0 * (x * 0.5).floor();
    if m < 1.0 {
        m
    } else {
        2.0 - m
    }
}

/// The square wave (+1 where ⌊x⌋ is even, −1 where odd) box-filtered over a width
/// `width` centred on x; the wave itself where the width is below
/// `PROCEDURAL_CHECKER_MIN_WIDTH` (where the difference of integrals would lose its
/// digits) or holds no cell edge (where it is exactly the wave, which the difference
/// would round).
// Mirror of src/tracer/shading/procedural.wgsl::filtered_square_wave — change both.
fn filtered_square_wave(x: f32, width: f32) -> f32 {
    let half = 0.5 * width;
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    if !(width > PROCEDURAL_CHECKER_MIN_WIDTH) || (x - half).floor() == (x + half).floor() {
        let cell = x.floor();
        return if cell - 2.0 * (cell * 0.5).floor() == 0.0 {
            1.0
        } else {
            -1.0
        };
    }
    let filtered = (square_wave_integral(x + half) - square_wave_integral(x - half)) / width;
    filtered.clamp(-1.0, 1.0)
}

/// How much of a periodic pattern's contrast a footprint `width` (in the units of its
/// `period`) keeps: all up to a quarter period, none from half a period (its Nyquist
/// limit), linear between.
// Mirror of src/tracer/shading/procedural.wgsl::pattern_contrast — change both.
fn pattern_contrast(width: f32, period: f32) -> f32 {
    (2.0 - 4.0 * width / period).clamp(0.0, 1.0)
}

/// The extent along an axis of a footprint disc `width` wide whose unit normal has the
/// component `n` along that axis: width·√(1 − n²) (0 along the normal itself).
// Mirror of src/tracer/shading/procedural.wgsl::footprint_along_axis — change both.
fn footprint_along_axis(width: f32, n: f32) -> f32 {
    width * (1.0 - n * n).max(0.0).sqrt()
}

/// What a lookup knows about the object at the hit: the unit normal in object space,
/// and how many object units one world unit along the surface is.
// Mirror of src/tracer/shading/procedural.wgsl::ObjectFrame — change both.
pub struct ObjectFrame {
    pub normal: Vec3,
    pub scale: f32,
}

/// The object frame of `inst` where the world normal is `n`: the object normal is
/// ∝ (object→world)ᵀ·n, and the surface's area shrinks from world to object space by
/// |det world→object|·|(object→world)ᵀ·n|, whose square root is the scale (exact for
/// uniform scales, the geometric mean of the two in-surface scales otherwise: a cube
/// scaled to a floor gets the floor's scale, not the thin axis's). Scale 0 where the map
/// is degenerate.
// Mirror of src/tracer/shading/procedural.wgsl::object_frame — change both.
pub fn object_frame(inst: &PackedInstance, n: Vec3) -> ObjectFrame {
    let o2w = &inst.object_to_world;
    let r0 = Vec3::new(o2w[0][0], o2w[0][1], o2w[0][2]);
    let r1 = Vec3::new(o2w[1][0], o2w[1][1], o2w[1][2]);
    let r2 = Vec3::new(o2w[2][0], o2w[2][1], o2w[2][2]);
    let m = r0 * n.x + r1 * n.y + r2 * n.z;
    let len = m.length();
    let det = r0.dot(r1.cross(r2)).abs();
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    if !(len > 0.0 && det > 0.0) {
        return ObjectFrame {
            normal: n,
            scale: 0.0,
        };
    }
    ObjectFrame {
        normal: m / len,
        scale: (len / det).sqrt(),
    }
}

/// The pattern of the procedural texture whose block is at word `block`, at the object
/// point `p` with unit object normal `normal`, filtered over `footprint` (object units):
/// (t, ∂t/∂p) with t ∈ [0, 1] the blend from c1 to c2.
// Mirror of src/tracer/shading/procedural.wgsl::procedural_pattern — change both.
pub fn procedural_pattern(
    texels: &[u32],
    block: u32,
    p: Vec3,
    normal: Vec3,
    footprint: f32,
) -> Vec4 {
    let kind = texel_word(texels, block);
    let table = texel_word(texels, block + 1);
    let scale = f32::from_bits(texel_word(texels, block + 8));
    let octaves = texel_word(texels, block + 9);
    let strength = f32::from_bits(texel_word(texels, block + 10));
    if kind == PROCEDURAL_CHECKER {
        // scale is the cube side; the pattern's gradient is 0 (flat steps).
        let q = p / scale;
        let w = footprint / scale;
        let c = filtered_square_wave(q.x, footprint_along_axis(w, normal.x))
            * filtered_square_wave(q.y, footprint_along_axis(w, normal.y))
            * filtered_square_wave(q.z, footprint_along_axis(w, normal.z));
        return Vec4::new(0.5 - 0.5 * c, 0.0, 0.0, 0.0);
    }
    let q = p * scale;
    let w = footprint * scale;
    let n = fbm(texels, table, q, octaves, w);
    if kind == PROCEDURAL_NOISE {
        let t = 0.5 + 0.5 * n.x;
        let inside = if t > 0.0 && t < 1.0 { 0.5 * scale } else { 0.0 };
        return Vec4::new(t.clamp(0.0, 1.0), n.y * inside, n.z * inside, n.w * inside);
    }
    if kind == PROCEDURAL_MARBLE {
        // Veins across object x, two units of q apart, bent by the noise.
        let k = pattern_contrast(w, 2.0);
        let phase = (0.5 * TWO_PI) * (q.x + strength * n.x);
        let slope = 0.5 * k * (0.5 * TWO_PI) * phase.cos() * scale;
        let d = Vec3::new(1.0 + strength * n.y, strength * n.z, strength * n.w) * slope;
        return Vec4::new(0.5 + 0.5 * k * phase.sin(), d.x, d.y, d.z);
    }
    // Wood: rings around object z, one unit of q apart, bent by the noise.
    let k = pattern_contrast(w, 1.0);
    let rho = (q.x * q.x + q.y * q.y).sqrt();
    let radial = if rho > 0.0 {
        Vec3::new(q.x / rho, q.y / rho, 0.0)
    } else {
        Vec3::ZERO
    };
    let r = rho + strength * n.x;
    let ring = r - r.floor();
    let d = (radial + Vec3::new(n.y, n.z, n.w) * strength) * (k * scale);
    Vec4::new(0.5 + k * (ring - 0.5), d.x, d.y, d.z)
}

/// Whether the material's texture index `texture` (not `NO_TEXTURE`) is a procedural's.
// Mirror of src/tracer/shading/procedural.wgsl::is_procedural — change both.
pub fn is_procedural(texture: u32) -> bool {
    texture & PROCEDURAL_TEXTURE != 0
}

/// A procedural texture's pattern at a hit (t, ∂t/∂p in object units) and the object
/// frame it was looked up in.
// Mirror of src/tracer/shading/procedural.wgsl::ProceduralLookup — change both.
pub struct ProceduralLookup {
    pub pattern: Vec4,
    pub frame: ObjectFrame,
}

/// The pattern of procedural texture `texture` at `s` for a footprint `world_footprint`
/// wide in world units.
// Mirror of src/tracer/shading/procedural.wgsl::procedural_lookup — change both.
fn procedural_lookup(
    scene: &PackedScene,
    texture: u32,
    s: &Surface,
    world_footprint: f32,
) -> ProceduralLookup {
    let frame = object_frame(load_instance(scene, s.instance), s.normal);
    let block = texture & !PROCEDURAL_TEXTURE;
    let pattern = procedural_pattern(
        &scene.texels,
        block,
        s.p_object,
        frame.normal,
        world_footprint * frame.scale,
    );
    ProceduralLookup { pattern, frame }
}

/// The colour stored as three f32 words from word `at` of `texels`.
// Mirror of src/tracer/shading/procedural.wgsl::procedural_colour_word — change both.
fn procedural_colour_word(texels: &[u32], at: u32) -> Vec3 {
    Vec3::new(
        f32::from_bits(texel_word(texels, at)),
        f32::from_bits(texel_word(texels, at + 1)),
        f32::from_bits(texel_word(texels, at + 2)),
    )
}

/// The colour of procedural texture `texture` at `s`, filtered over `world_footprint`
/// (world units): c1 + t·(c2 − c1).
// Mirror of src/tracer/shading/procedural.wgsl::procedural_colour — change both.
pub fn procedural_colour(
    scene: &PackedScene,
    texture: u32,
    s: &Surface,
    world_footprint: f32,
) -> Vec3 {
    let lookup = procedural_lookup(scene, texture, s, world_footprint);
    let block = texture & !PROCEDURAL_TEXTURE;
    let c1 = procedural_colour_word(&scene.texels, block + 2);
    let c2 = procedural_colour_word(&scene.texels, block + 5);
    lerp_vec3(lookup.pattern.x, c1, c2)
}

/// The normal of `s` bumped by material `m`'s procedural bump texture: the pattern's
/// gradient taken to world space ((world→object)ᵀ·∇t, divided by the object frame's
/// scale so that the look does not change with the object's size), its part along the
/// surface subtracted from the normal times the strength (the normal leans away from
/// where the pattern rises). `s.normal` where the object map is degenerate.
// Mirror of src/tracer/shading/procedural.wgsl::procedural_bump_normal — change both.
pub fn procedural_bump_normal(scene: &PackedScene, m: &PackedMaterial, s: &Surface) -> Vec3 {
    let n = s.normal;
    let lookup = procedural_lookup(scene, m.bump_texture, s, s.world_footprint);
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    if !(lookup.frame.scale > 0.0) {
        return n;
    }
    let w2o = &load_instance(scene, s.instance).world_to_object;
    let g = lookup.pattern;
    let world = (Vec3::new(w2o[0][0], w2o[0][1], w2o[0][2]) * g.y
        + Vec3::new(w2o[1][0], w2o[1][1], w2o[1][2]) * g.z
        + Vec3::new(w2o[2][0], w2o[2][1], w2o[2][2]) * g.w)
        / lookup.frame.scale;
    let along = world - n * world.dot(n);
    let bumped = n - along * m.bump_strength;
    // along ⟂ n, so the sum is at least as long as n: never zero.
    bumped.normalize()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pack::procedural::pack_procedurals;

    /// The permutation table alone, at word 0.
    fn table() -> Vec<u32> {
        pack_procedurals(&[], 0)
    }

    /// Values of Perlin's reference `ImprovedNoise.noise` (Java, f64), computed by hand
    /// from its definition (tools/oracle/perlin_reference.py prints them).
    // 3.14 is the point the reference's documentation evaluates, not an approximate π.
    #[allow(clippy::approx_constant)]
    const REFERENCE: [([f32; 3], f64); 6] = [
        ([3.14, 42.0, 7.0], 0.13691995878400012),
        ([0.5, 0.5, 0.5], -0.25),
        ([1.25, -2.75, 0.125], -0.050499878358095884),
        ([-7.3, 11.9, 0.01], -0.04686566928643829),
        ([100.5, 200.25, -300.75], 0.20992088317871094),
        ([0.1, 0.2, 0.3], 0.35122924878110723),
    ];

    #[test]
    fn noise_matches_perlins_reference_values() {
        let texels = table();
        let mut worst = 0.0f64;
        for (p, expected) in REFERENCE {
            let n = perlin_noise(&texels, 0, Vec3::from(p)).x;
            worst = worst.max((f64::from(n) - expected).abs());
        }
        // f32 against the reference's f64: the points themselves round to f32 (3.14 by
        // 1e-7, 300.75 exactly), the sums by a few ulps.
        eprintln!("worst error against the reference: {worst:e}");
        assert!(worst < 2e-6, "worst error {worst:e}");
    }

    #[test]
    fn noise_is_zero_with_zero_gradient_slope_terms_at_lattice_points() {
        let texels = table();
        for p in [
            [0.0, 0.0, 0.0],
            [1.0, 2.0, 3.0],
            [-5.0, 17.0, 255.0],
            [256.0, -1.0, 9.0],
        ] {
            let n = perlin_noise(&texels, 0, Vec3::from(p));
            assert_eq!(n.x, 0.0, "{p:?}");
            // At a corner the gradient is that corner's direction.
            let g = Vec3::new(n.y, n.z, n.w);
            assert_eq!(g.abs().element_sum(), 2.0, "{p:?}: {g}");
        }
    }

    #[test]
    fn the_gradient_is_the_noise_derivative() {
        let texels = table();
        let h = 1.0 / 1024.0;
        for (p, _) in REFERENCE {
            let p = Vec3::from(p) + Vec3::splat(0.3);
            let n = perlin_noise(&texels, 0, p);
            for axis in 0..3 {
                let mut d = Vec3::ZERO;
                d[axis] = h;
                let numeric = (perlin_noise(&texels, 0, p + d).x
                    - perlin_noise(&texels, 0, p - d).x)
                    / (2.0 * h);
                let analytic = [n.y, n.z, n.w][axis];
                assert!(
                    (numeric - analytic).abs() < 2e-3,
                    "{p} axis {axis}: analytic {analytic}, numeric {numeric}"
                );
            }
        }
    }

    #[test]
    fn fbm_sums_octaves_with_gain_half_and_fades_them_by_the_footprint() {
        let texels = table();
        let p = Vec3::new(0.37, 1.71, -2.29);
        let n = |q: Vec3| perlin_noise(&texels, 0, q).x;
        let expected = (n(p) + 0.5 * n(2.0 * p) + 0.25 * n(4.0 * p)) / 1.75;
        assert!((fbm(&texels, 0, p, 3, 0.0).x - expected).abs() < 1e-6);
        // Footprint ¼: octave 2 (cells ¼ wide) is gone, octave 1 (½) kept whole.
        let faded = (n(p) + 0.5 * n(2.0 * p)) / 1.75;
        assert!((fbm(&texels, 0, p, 3, 0.25).x - faded).abs() < 1e-6);
        // Far past every octave's limit: the mean.
        assert_eq!(fbm(&texels, 0, p, 3, 10.0).x, 0.0);
    }

    #[test]
    fn the_filtered_square_wave_is_the_box_filtered_mean() {
        for (x, width) in [(0.3, 0.5), (0.9, 0.4), (1.7, 1.0), (-0.2, 0.3), (5.5, 3.0)] {
            let steps = 20000;
            let mut sum = 0.0f64;
            for i in 0..steps {
                let t = x - 0.5 * width + width * (i as f32 + 0.5) / steps as f32;
                sum += if t.floor().rem_euclid(2.0) == 0.0 {
                    1.0
                } else {
                    -1.0
                };
            }
            let mean = sum / f64::from(steps);
            let filtered = f64::from(filtered_square_wave(x, width));
            assert!(
                (filtered - mean).abs() < 1e-3,
                "{x} {width}: {filtered} vs {mean}"
            );
        }
        assert_eq!(filtered_square_wave(0.5, 0.0), 1.0);
        assert_eq!(filtered_square_wave(1.5, 0.0), -1.0);
        assert_eq!(filtered_square_wave(-0.5, 0.0), -1.0);
    }

    #[test]
    fn the_object_frame_scale_is_the_surface_scale() {
        let mut inst = PackedInstance {
            world_to_object: [[0.0; 4]; 3],
            object_to_world: [[0.0; 4]; 3],
            kind: 0,
            material: 0,
            params: [0.0; 2],
        };
        // A unit cube scaled to a floor (20, 0.1, 20), seen from above.
        inst.object_to_world = [
            [20.0, 0.0, 0.0, 3.0],
            [0.0, 0.1, 0.0, -1.0],
            [0.0, 0.0, 20.0, 0.0],
        ];
        let frame = object_frame(&inst, Vec3::Y);
        assert!((frame.scale - 0.05).abs() < 1e-7, "{}", frame.scale);
        assert_eq!(frame.normal, Vec3::Y);
        // Its side (normal x): scaled 0.1 by 20, the geometric mean √(1/2).
        let side = object_frame(&inst, Vec3::X);
        assert!((side.scale - (1.0f32 / 2.0).sqrt()).abs() < 1e-6);
    }
}
