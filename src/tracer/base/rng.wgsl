// rng.wgsl — stateless random numbers: a hash of (pixel, sample, dimension), identical in
// Rust and WGSL, so both tracers draw the same samples (PCG hash, Jarzynski & Olano 2020).

// PCG-RXS-M-XS 32-bit hash.
// Mirror of src/tracer/base/rng.rs::pcg_hash — change both.
fn pcg_hash(x: u32) -> u32 {
    let state = x * PCG_MULTIPLIER + PCG_INCREMENT;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * PCG_WORD_MULTIPLIER;
    return (word >> 22u) ^ word;
}

// Uniform float in [0, 1) for (pixel, sample, dimension): the top 24 bits of a chained
// hash, so every value is exactly representable in f32.
// Mirror of src/tracer/base/rng.rs::random_unit — change both.
fn random_unit(pixel: u32, sample: u32, dimension: u32) -> f32 {
    let h = pcg_hash(pixel ^ pcg_hash(sample ^ pcg_hash(dimension)));
    return f32(h >> 8u) * RANDOM_UNIT_SCALE;
}

// Which camera sample a shading point belongs to, for the random numbers drawn there: the
// pixel (or, under adaptive AA, a lattice coordinate), the camera sample's index, the
// bounce depth of the ray being shaded, and whether the sample is an adaptive-AA pixel
// centre, whose shadow jitter mirrors its pixel's corners' (shadow_random).
// Mirror of src/tracer/base/rng.rs::SampleSeed — change both.
struct SampleSeed {
    pixel: u32,
    sample: u32,
    depth: u32,
    mirrors_corners: bool,
}

// The seed of the adaptive-AA sample at film position (fx, fy): its coordinates on the
// finest lattice (2^MAX_AA_DEPTH steps per pixel, exact). A point whose two coordinates
// are odd multiples of the same power of two 2^t (t < MAX_AA_DEPTH) is the centre of a
// square 2^(t+1) steps wide (a pixel's, or a smaller square's).
// Mirror of src/tracer/base/rng.rs::adaptive_seed — change both.
fn adaptive_seed(fx: f32, fy: f32) -> SampleSeed {
    let steps = 1u << MAX_AA_DEPTH;
    let pixel = u32(fx * f32(steps));
    let sample = u32(fy * f32(steps));
    let t = countTrailingZeros(pixel);
    let centre = t == countTrailingZeros(sample) && t < MAX_AA_DEPTH;
    return SampleSeed(pixel, sample, 0u, centre);
}

// #if AREA_LIGHT
// The random streams of light `light`'s shadow jitters at a shading point of `seed`
// (shadow_stream): hashed once per light, so that each jitter costs three hashes. rows:
// the seed's sample index hashed with the light and depth (a mirrored stream: its
// square's top and bottom corners'); columns: the seed's pixel coordinate (the left and
// right corners').
// Mirror of src/tracer/base/rng.rs::ShadowStream — change both.
struct ShadowStream {
    rows: vec2<u32>,
    columns: vec2<u32>,
    mirrored: bool,
}

// Light `light`'s shadow-jitter streams at `seed`: independent for every seed but an
// adaptive-AA square centre's first hit, whose jitters mirror its square's corners'.
// Mirror of src/tracer/base/rng.rs::shadow_stream — change both.
fn shadow_stream(seed: SampleSeed, light: u32) -> ShadowStream {
    let light_hash = pcg_hash(light ^ pcg_hash(seed.depth));
    if seed.mirrors_corners && seed.depth == 0u {
        // Half the square's side: the lowest set bit of the centre's coordinates.
        let half = 1u << countTrailingZeros(seed.pixel);
        let rows = vec2<u32>(
            pcg_hash((seed.sample - half) ^ light_hash),
            pcg_hash((seed.sample + half) ^ light_hash),
        );
        return ShadowStream(rows, vec2<u32>(seed.pixel - half, seed.pixel + half), true);
    }
    let row = pcg_hash(seed.sample ^ light_hash);
    return ShadowStream(vec2<u32>(row), vec2<u32>(seed.pixel), false);
}

// Jitter (`axis` 0 or 1) of stratum `stratum` of a light's shadow samples from its
// `stream`; a mirrored stream's is 2^24 − 1 minus the mean of its four corners' 24-bit
// jitters (integers: exact on both tracers). See the twin for why.
// Mirror of src/tracer/base/rng.rs::shadow_random — change both.
fn shadow_random(stream: ShadowStream, stratum: u32, axis: u32) -> f32 {
    let dimension_hash = pcg_hash(SHADOW_DIMENSION_BASE + 2u * stratum + axis);
    let top = pcg_hash(stream.rows.x ^ dimension_hash);
    let left = stream.columns.x;
    let right = stream.columns.y;
    var bits = pcg_hash(left ^ top) >> 8u;
    if stream.mirrored {
        let bottom = pcg_hash(stream.rows.y ^ dimension_hash);
        let sum = bits
            + (pcg_hash(right ^ top) >> 8u)
            + (pcg_hash(left ^ bottom) >> 8u)
            + (pcg_hash(right ^ bottom) >> 8u);
        bits = 0x00ffffffu - (sum >> 2u);
    }
    return f32(bits) * RANDOM_UNIT_SCALE;
}
// #endif
