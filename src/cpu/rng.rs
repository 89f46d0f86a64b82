//! Stateless random numbers: a hash of (pixel, sample, dimension), identical in Rust and
//! WGSL, so both tracers draw the same samples (PCG hash, Jarzynski & Olano 2020).

use crate::constants::{PCG_INCREMENT, PCG_MULTIPLIER, PCG_WORD_MULTIPLIER, RANDOM_UNIT_SCALE};

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
