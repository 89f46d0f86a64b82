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

// #if DEPTH_OF_FIELD
// Point `index` of the Sobol' (0,2)-sequence in base 2 (the van der Corput sequence and
// Sobol's second dimension), as 32-bit binary fractions: its first 2^m points are
// stratified in x, in y and jointly.
// Mirror of src/tracer/base/rng.rs::sobol_02 — change both.
fn sobol_02(index: u32) -> vec2<u32> {
    var y = 0u;
    var direction = 1u << 31u;
    var bits = index;
    while bits != 0u {
        if (bits & 1u) != 0u {
            y ^= direction;
        }
        bits >>= 1u;
        direction ^= direction >> 1u;
    }
    return vec2<u32>(reverseBits(index), y);
}

// Element i of a permutation of 0..count chosen by key (i < count): a keyed bijection of
// the bits-bit integers applied again until the value falls below count (cycle walking).
// Mirror of src/tracer/base/rng.rs::shuffled_index — change both.
fn shuffled_index(i: u32, count: u32, key: u32) -> u32 {
    if count <= 1u {
        return 0u;
    }
    let bits = 32u - countLeadingZeros(count - 1u);
    let mask = 0xffffffffu >> (32u - bits);
    let shift = (bits + 1u) / 2u;
    let mixed = pcg_hash(key);
    var j = i;
    loop {
        // Each step maps 0..2^bits onto itself one to one.
        j = (j ^ key) & mask;
        j = (j * (mixed | 1u)) & mask;
        j ^= j >> shift;
        j = (j ^ (mixed >> 16u)) & mask;
        j = (j * ((key >> 16u) | 1u)) & mask;
        j ^= j >> shift;
        if j < count {
            break;
        }
    }
    return j;
}

// Point `index` of the 2D sequence of dimensions (dimension, dimension + 1) of the pixel
// key: sobol_02's point with each coordinate's bits xored with a hash of the pixel and
// dimension (a random digital shift), as floats in [0, 1) from its top 24 bits.
// Mirror of src/tracer/base/rng.rs::sequence_pair — change both.
fn sequence_pair(key: u32, index: u32, dimension: u32) -> vec2<f32> {
    let point = sobol_02(index);
    let shift_x = pcg_hash(key ^ pcg_hash(dimension));
    let shift_y = pcg_hash(key ^ pcg_hash(dimension + 1u));
    return vec2<f32>(
        f32((point.x ^ shift_x) >> 8u) * RANDOM_UNIT_SCALE,
        f32((point.y ^ shift_y) >> 8u) * RANDOM_UNIT_SCALE,
    );
}

// The index in its pixel's sequence of the adaptive-AA lattice point at (x, y), its
// coordinates within the pixel on the finest lattice: each one's bits reversed, then
// interleaved (x's in the even places), so a pixel's points of levels 0..L take the
// sequence's first 4^L indices.
// Mirror of src/tracer/base/rng.rs::lattice_sequence_index — change both.
fn lattice_sequence_index(x: u32, y: u32) -> u32 {
    let reversed_x = reverseBits(x) >> (32u - MAX_AA_DEPTH);
    let reversed_y = reverseBits(y) >> (32u - MAX_AA_DEPTH);
    var index = 0u;
    for (var bit = 0u; bit < MAX_AA_DEPTH; bit++) {
        index |= ((reversed_x >> bit) & 1u) << (2u * bit);
        index |= ((reversed_y >> bit) & 1u) << (2u * bit + 1u);
    }
    return index;
}
// #endif
