// rng.wgsl — stateless random numbers: a hash of (pixel, sample, dimension), identical in
// Rust and WGSL, so both tracers draw the same samples (PCG hash, Jarzynski & Olano 2020).

// PCG-RXS-M-XS 32-bit hash.
// Mirror of src/cpu/rng.rs::pcg_hash — change both.
fn pcg_hash(x: u32) -> u32 {
    let state = x * PCG_MULTIPLIER + PCG_INCREMENT;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * PCG_WORD_MULTIPLIER;
    return (word >> 22u) ^ word;
}

// Uniform float in [0, 1) for (pixel, sample, dimension): the top 24 bits of a chained
// hash, so every value is exactly representable in f32.
// Mirror of src/cpu/rng.rs::random_unit — change both.
fn random_unit(pixel: u32, sample: u32, dimension: u32) -> f32 {
    let h = pcg_hash(pixel ^ pcg_hash(sample ^ pcg_hash(dimension)));
    return f32(h >> 8u) * RANDOM_UNIT_SCALE;
}
