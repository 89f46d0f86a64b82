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

// Which camera sample a shading point belongs to, for the random numbers drawn there: the
// pixel (or, under adaptive AA, a lattice coordinate), the camera sample's index, and the
// bounce depth of the ray being shaded.
// Mirror of src/cpu/rng.rs::SampleSeed — change both.
struct SampleSeed {
    pixel: u32,
    sample: u32,
    depth: u32,
}

// The seed of the adaptive-AA sample at film position (fx, fy): its coordinates on the
// finest lattice (2^MAX_AA_DEPTH steps per pixel, exact).
// Mirror of src/cpu/rng.rs::adaptive_seed — change both.
fn adaptive_seed(fx: f32, fy: f32) -> SampleSeed {
    let scale = f32(1u << MAX_AA_DEPTH);
    return SampleSeed(u32(fx * scale), u32(fy * scale), 0u);
}

// #if AREA_LIGHT
// Jitter (axis 0 or 1) of stratum `stratum` of light `light`'s shadow samples at a
// shading point of `seed`: depends on nothing else.
// Mirror of src/cpu/rng.rs::shadow_random — change both.
fn shadow_random(seed: SampleSeed, light: u32, stratum: u32, axis: u32) -> f32 {
    let sample = pcg_hash(seed.sample ^ pcg_hash(light ^ pcg_hash(seed.depth)));
    return random_unit(seed.pixel, sample, SHADOW_DIMENSION_BASE + 2u * stratum + axis);
}
// #endif
