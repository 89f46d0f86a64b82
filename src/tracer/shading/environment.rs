//! The HDR environment map: what a ray that escapes the scene sees when the scene has one
//! (`SceneFeatures::ENVIRONMENT`), in place of the background gradient. Its layout in
//! `texels` is `pack::environment`'s.
//!
//! Orientation and filtering are Mitsuba 3's `envmap` emitter's, so a scene can be checked
//! against it (tests/oracle/environment.rs): the direction d (y up), turned by −θ about +y
//! for the map's rotation θ, is at u = atan2(d.x, −d.z)/2π mod 1 and v = acos(d.y)/π, (0, 0)
//! being the image's top-left corner. Column i has its centre at u = (i + ½)/w and the
//! columns wrap (the seam at u = 0 blends the last column with the first); row j lies at
//! v = j/(h − 1), so the top row is the direction straight up and the bottom row straight
//! down, and v clamps there. Between them the lookup is bilinear.
//!
//! The angles come from `atan2` (θ too: atan2(√(x² + z²), y), which is acos(d.y) for a unit
//! d), the one place the twins call a transcendental function whose results are not
//! specified to the bit: Rust's is the platform libm's, WGSL's the driver's
//! (docs/environment.md gives what they differ by on lavapipe).

use crate::constants::TWO_PI;
use crate::pack::layout::texel_word;
use crate::pack::PackedGlobals;
use crate::tracer::shading::texture::wrap_unit;
use glam::{Vec2, Vec3};

/// `dir` in the map's own frame: turned by −θ about +y (the map turns by θ), from the
/// cos and sin of θ in the globals.
// Mirror of src/tracer/shading/environment.wgsl::environment_direction — change both.
fn environment_direction(g: &PackedGlobals, dir: Vec3) -> Vec3 {
    let c = g.environment_cos;
    let s = g.environment_sin;
    Vec3::new(c * dir.x - s * dir.z, dir.y, s * dir.x + c * dir.z)
}

/// The map's (u, v) of the unit direction `d` in its frame (see the module header).
// Mirror of src/tracer/shading/environment.wgsl::environment_uv — change both.
fn environment_uv(d: Vec3) -> Vec2 {
    // 1/2π and 1/π as constant expressions (rounded once, at compile time, on both
    // sides): multiplied rather than divided, so both tracers round alike. θ = acos(d.y)
    // is taken as atan2(√(x² + z²), y), the same angle for a unit d: acos is
    // ill-conditioned near the poles, and lavapipe's differs from libm's by up to 1.6·10⁻⁴
    // rad there, where the two atan2 agree to 4·10⁻⁶ (docs/environment.md).
    let u = d.x.atan2(-d.z) * (1.0 / TWO_PI);
    let v = (d.x * d.x + d.z * d.z).sqrt().atan2(d.y) * (2.0 / TWO_PI);
    Vec2::new(wrap_unit(u), v)
}

/// Texel (x, y) of the map that starts at word `start` of `texels`.
// Mirror of src/tracer/shading/environment.wgsl::environment_texel — change both.
fn environment_texel(texels: &[u32], start: u32, x: u32, y: u32) -> Vec3 {
    let width = texel_word(texels, start);
    let i = start + 2 + 3 * (y * width + x);
    Vec3::new(
        f32::from_bits(texel_word(texels, i)),
        f32::from_bits(texel_word(texels, i + 1)),
        f32::from_bits(texel_word(texels, i + 2)),
    )
}

/// Bilinear lookup of the map at `uv` (u in [0, 1), v in [0, 1]): columns wrap, rows
/// clamp (see the module header for where the texels lie).
// Mirror of src/tracer/shading/environment.wgsl::sample_environment — change both.
fn sample_environment(texels: &[u32], start: u32, uv: Vec2) -> Vec3 {
    let width = texel_word(texels, start);
    let height = texel_word(texels, start + 1);
    let last_row = (height - 1) as f32;
    let x = uv.x * width as f32 - 0.5;
    let y = (uv.y * last_row).max(0.0).min(last_row);
    let x_floor = x.floor();
    let y_floor = y.floor();
    let fx = x - x_floor;
    let fy = y - y_floor;
    // x_floor ≥ −1: adding the width once wraps both columns.
    let w = width as i32;
    let x0 = ((x_floor as i32 + w) % w) as u32;
    let x1 = ((x_floor as i32 + 1 + w) % w) as u32;
    let y0 = y_floor as u32;
    let y1 = (y0 + 1).min(height - 1);
    let top = environment_texel(texels, start, x0, y0) * (1.0 - fx)
        + environment_texel(texels, start, x1, y0) * fx;
    let bottom = environment_texel(texels, start, x0, y1) * (1.0 - fx)
        + environment_texel(texels, start, x1, y1) * fx;
    top * (1.0 - fy) + bottom * fy
}

/// What a ray leaving the scene along the unit direction `dir` sees of the environment
/// map (the scene has one: `SceneFeatures::ENVIRONMENT`).
// Mirror of src/tracer/shading/environment.wgsl::environment — change both.
pub fn environment(texels: &[u32], g: &PackedGlobals, dir: Vec3) -> Vec3 {
    let uv = environment_uv(environment_direction(g, dir));
    sample_environment(texels, g.environment, uv)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pack::environment::append_environment;
    use crate::scene::environment::Environment;

    /// A w×h map whose texel (x, y) is (x, y, 1).
    fn ramp(w: u32, h: u32) -> Vec<u32> {
        let rgb = (0..h)
            .flat_map(|y| (0..w).map(move |x| [x as f32, y as f32, 1.0]))
            .collect();
        let env = Environment {
            path: "ramp.exr".into(),
            width: w,
            height: h,
            rgb,
        };
        let mut texels = vec![0; 5];
        append_environment(&mut texels, &env);
        texels
    }

    #[test]
    fn texel_centres_columns_wrap_and_rows_clamp() {
        let texels = ramp(4, 3);
        let at = |u: f32, v: f32| sample_environment(&texels, 5, Vec2::new(u, v));
        // Column centres at (i + ½)/w, rows at j/(h − 1).
        assert_eq!(at(0.125, 0.0), Vec3::new(0.0, 0.0, 1.0));
        assert_eq!(at(0.625, 0.5), Vec3::new(2.0, 1.0, 1.0));
        assert_eq!(at(0.875, 1.0), Vec3::new(3.0, 2.0, 1.0));
        // Halfway between rows and columns: the mean.
        assert_eq!(at(0.5, 0.25), Vec3::new(1.5, 0.5, 1.0));
        // The seam: u = 0 is halfway between the last column and the first.
        assert_eq!(at(0.0, 0.0), Vec3::new(1.5, 0.0, 1.0));
    }

    #[test]
    fn directions_map_to_mitsubas_uv() {
        let g = PackedGlobals {
            environment_cos: 1.0,
            ..bytemuck::Zeroable::zeroed()
        };
        let uv = |d: Vec3| environment_uv(environment_direction(&g, d));
        // −z is u = 0 (the seam: wrap_unit keeps it in [0, 1)), +x a quarter, +z half.
        assert_eq!(uv(Vec3::new(0.0, 0.0, -1.0)), Vec2::new(0.0, 0.5));
        assert_eq!(uv(Vec3::new(1.0, 0.0, 0.0)), Vec2::new(0.25, 0.5));
        assert_eq!(uv(Vec3::new(0.0, 0.0, 1.0)), Vec2::new(0.5, 0.5));
        assert_eq!(uv(Vec3::new(-1.0, 0.0, 0.0)), Vec2::new(0.75, 0.5));
        assert_eq!(uv(Vec3::Y).y, 0.0);
        assert_eq!(uv(-Vec3::Y).y, 1.0);
        // A quarter turn of the map (+z towards +x) brings what was at +z (u = ½) to +x.
        let turned = PackedGlobals {
            environment_cos: 0.0,
            environment_sin: 1.0,
            ..g
        };
        let d = environment_direction(&turned, Vec3::X);
        assert_eq!(environment_uv(d), Vec2::new(0.5, 0.5));
    }
}
