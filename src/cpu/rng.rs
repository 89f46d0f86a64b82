//! Stateless random numbers: a hash of (pixel, sample, dimension), identical in Rust and
//! WGSL, so both tracers draw the same samples (PCG hash, Jarzynski & Olano 2020).

use crate::constants::{
    MAX_AA_DEPTH, PCG_INCREMENT, PCG_MULTIPLIER, PCG_WORD_MULTIPLIER, RANDOM_UNIT_SCALE,
    SHADOW_DIMENSION_BASE,
};

/// PCG-RXS-M-XS 32-bit hash.
// Mirror of shaders/rng.wgsl::pcg_hash — change both.
pub fn pcg_hash(x: u32) -> u32 {
    let state = x.wrapping_mul(PCG_MULTIPLIER).wrapping_add(PCG_INCREMENT);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(PCG_WORD_MULTIPLIER);
    (word >> 22) ^ word
}

/// Uniform float in [0, 1) for (pixel, sample, dimension): the top 24 bits of a chained
/// hash, so every value is exactly representable in f32.
// Mirror of shaders/rng.wgsl::random_unit — change both.
pub fn random_unit(pixel: u32, sample: u32, dimension: u32) -> f32 {
    let h = pcg_hash(pixel ^ pcg_hash(sample ^ pcg_hash(dimension)));
    (h >> 8) as f32 * RANDOM_UNIT_SCALE
}

/// Which camera sample a shading point belongs to, for the random numbers drawn there:
/// the pixel (or, under adaptive AA, a lattice coordinate), the camera sample's index,
/// and the bounce depth of the ray being shaded.
// Mirror of shaders/rng.wgsl::SampleSeed — change both.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SampleSeed {
    pub pixel: u32,
    pub sample: u32,
    pub depth: u32,
}

/// The seed of the adaptive-AA sample at film position (fx, fy): its coordinates on the
/// finest lattice (2^MAX_AA_DEPTH steps per pixel; exact, as every lattice position is a
/// dyadic fraction of at most MAX_AA_DEPTH bits), so a point shared by neighbouring pixels
/// or tiles draws the same numbers whichever pass traces it.
// Mirror of shaders/rng.wgsl::adaptive_seed — change both.
pub fn adaptive_seed(fx: f32, fy: f32) -> SampleSeed {
    let scale = (1u32 << MAX_AA_DEPTH) as f32;
    SampleSeed {
        pixel: (fx * scale) as u32,
        sample: (fy * scale) as u32,
        depth: 0,
    }
}

/// Jitter (`axis` 0 or 1) of stratum `stratum` of light `light`'s shadow samples at a
/// shading point of `seed`: depends on nothing else.
// Mirror of shaders/rng.wgsl::shadow_random — change both.
pub fn shadow_random(seed: SampleSeed, light: u32, stratum: u32, axis: u32) -> f32 {
    let sample = pcg_hash(seed.sample ^ pcg_hash(light ^ pcg_hash(seed.depth)));
    random_unit(
        seed.pixel,
        sample,
        SHADOW_DIMENSION_BASE + 2 * stratum + axis,
    )
}
