//! The environment map's layout at the end of `PackedScene::texels`, defined here once
//! (both tracers read it through `tracer::shading::environment` and
//! `src/tracer/shading/environment.wgsl`):
//!
//! ```text
//! word e + 0    width w
//! word e + 1    height h
//! then          3·w·h words: each texel's r, g, b as f32 bits, row-major from the
//!               image's top row (the direction straight up)
//! ```
//! where e = `PackedGlobals::environment`, the length of the texture table and texels
//! before it (0 without textures). Full f32: the map's HDR values reach the image
//! unrounded (no half floats or shared exponents, so no error to state).

use crate::scene::environment::Environment;

/// Appends `environment` to `texels` in the layout above; returns where it starts.
pub fn append_environment(texels: &mut Vec<u32>, environment: &Environment) -> u32 {
    let start = texels.len() as u32;
    texels.reserve(2 + 3 * environment.rgb.len());
    texels.extend([environment.width, environment.height]);
    texels.extend(environment.rgb.iter().flatten().map(|c| c.to_bits()));
    start
}

/// cos and sin of a turn of `degrees` about +y, computed in f64 and rounded once.
pub fn rotation_cos_sin(degrees: f32) -> (f32, f32) {
    let radians = f64::from(degrees).to_radians();
    (radians.cos() as f32, radians.sin() as f32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn environment_follows_the_texture_words_as_f32_bits() {
        let env = Environment {
            path: "sky.exr".into(),
            width: 2,
            height: 1,
            rgb: vec![[1.0, 2.0, 3.0], [0.5, 65504.0, 1e-3]],
        };
        let mut texels = vec![7, 8, 9];
        assert_eq!(append_environment(&mut texels, &env), 3);
        assert_eq!(&texels[..5], &[7, 8, 9, 2, 1]);
        let floats: Vec<f32> = texels[5..].iter().map(|&w| f32::from_bits(w)).collect();
        assert_eq!(floats, vec![1.0, 2.0, 3.0, 0.5, 65504.0, 1e-3]);
    }

    #[test]
    fn rotations_are_exact_at_quarter_turns() {
        assert_eq!(rotation_cos_sin(0.0), (1.0, 0.0));
        let (c, s) = rotation_cos_sin(90.0);
        assert!(c.abs() < 1e-7 && s == 1.0, "{c} {s}");
        let (c, s) = rotation_cos_sin(-180.0);
        assert!(c == -1.0 && s.abs() < 1e-7, "{c} {s}");
    }
}
