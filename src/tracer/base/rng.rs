//! Stateless random numbers: a hash of (pixel, sample, dimension), identical in Rust and
//! WGSL, so both tracers draw the same samples (PCG hash, Jarzynski & Olano 2020).

use crate::constants::{
    MAX_AA_DEPTH, PCG_INCREMENT, PCG_MULTIPLIER, PCG_WORD_MULTIPLIER, RANDOM_UNIT_SCALE,
    SHADOW_DIMENSION_BASE,
};

/// PCG-RXS-M-XS 32-bit hash.
// Mirror of src/tracer/base/rng.wgsl::pcg_hash — change both.
pub fn pcg_hash(x: u32) -> u32 {
    let state = x.wrapping_mul(PCG_MULTIPLIER).wrapping_add(PCG_INCREMENT);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(PCG_WORD_MULTIPLIER);
    (word >> 22) ^ word
}

/// Uniform float in [0, 1) for (pixel, sample, dimension): the top 24 bits of a chained
/// hash, so every value is exactly representable in f32.
// Mirror of src/tracer/base/rng.wgsl::random_unit — change both.
pub fn random_unit(pixel: u32, sample: u32, dimension: u32) -> f32 {
    let h = pcg_hash(pixel ^ pcg_hash(sample ^ pcg_hash(dimension)));
    (h >> 8) as f32 * RANDOM_UNIT_SCALE
}

/// Which camera sample a shading point belongs to, for the random numbers drawn there:
/// the pixel (or, under adaptive AA, a lattice coordinate), the camera sample's index,
/// the bounce depth of the ray being shaded, and whether the sample is the centre of an
/// adaptive-AA square (a pixel or a smaller one), whose shadow jitter mirrors its
/// square's corners' ([`shadow_random`]).
// Mirror of src/tracer/base/rng.wgsl::SampleSeed — change both.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SampleSeed {
    pub pixel: u32,
    pub sample: u32,
    pub depth: u32,
    pub mirrors_corners: bool,
}

/// The seed of the adaptive-AA sample at film position (fx, fy): its coordinates on the
/// finest lattice (2^MAX_AA_DEPTH steps per pixel; exact, as every lattice position is a
/// dyadic fraction of at most MAX_AA_DEPTH bits), so a point shared by neighbouring pixels
/// or tiles draws the same numbers whichever pass traces it. A point whose two
/// coordinates are odd multiples of the same power of two 2^t below a pixel (t <
/// MAX_AA_DEPTH) is the centre of a square 2^(t+1) steps wide: a pixel's at t =
/// MAX_AA_DEPTH − 1, else a smaller square's.
// Mirror of src/tracer/base/rng.wgsl::adaptive_seed — change both.
pub fn adaptive_seed(fx: f32, fy: f32) -> SampleSeed {
    let steps = 1u32 << MAX_AA_DEPTH;
    let (pixel, sample) = ((fx * steps as f32) as u32, (fy * steps as f32) as u32);
    let t = pixel.trailing_zeros();
    SampleSeed {
        pixel,
        sample,
        depth: 0,
        mirrors_corners: t == sample.trailing_zeros() && t < MAX_AA_DEPTH,
    }
}

/// The random streams of light `light`'s shadow jitters at a shading point of `seed`
/// ([`shadow_stream`]): hashed once per light, so that each jitter costs three hashes.
// Mirror of src/tracer/base/rng.wgsl::ShadowStream — change both.
#[derive(Clone, Copy, Debug)]
pub struct ShadowStream {
    /// The seed's sample index hashed with the light and depth; for a mirrored stream,
    /// those of its square's top and bottom corners.
    rows: [u32; 2],
    /// The seed's pixel coordinate; for a mirrored stream, its square's left and right
    /// corners'.
    columns: [u32; 2],
    mirrored: bool,
}

/// Light `light`'s shadow-jitter streams at `seed`. They are drawn independently for
/// every seed but one kind: at the first hit of an adaptive-AA square's centre
/// (`mirrors_corners`) the jitters are its square's four corners' mirrored through each
/// stratum's centre ([`shadow_random`]); the corners are half the square's side away, as
/// many finest-lattice steps as the lowest set bit of the centre's coordinates.
// Mirror of src/tracer/base/rng.wgsl::shadow_stream — change both.
pub fn shadow_stream(seed: SampleSeed, light: u32) -> ShadowStream {
    let light_hash = pcg_hash(light ^ pcg_hash(seed.depth));
    if seed.mirrors_corners && seed.depth == 0 {
        let half = 1u32 << seed.pixel.trailing_zeros();
        ShadowStream {
            rows: [
                pcg_hash((seed.sample - half) ^ light_hash),
                pcg_hash((seed.sample + half) ^ light_hash),
            ],
            columns: [seed.pixel - half, seed.pixel + half],
            mirrored: true,
        }
    } else {
        let row = pcg_hash(seed.sample ^ light_hash);
        ShadowStream {
            rows: [row, row],
            columns: [seed.pixel, seed.pixel],
            mirrored: false,
        }
    }
}

/// Jitter (`axis` 0 or 1) of stratum `stratum` of a light's shadow samples from its
/// `stream`: `random_unit`'s hash chain, the sample index hashed with light and depth.
/// A mirrored stream's jitter is 2^24 − 1 minus the mean of its four corners' 24-bit
/// jitters (integers: exact on both tracers), 1 − their mean. Why: an unsplit square is
/// the quincunx mean (centre 1/2, corners 1/8 each), so where a light's contribution
/// varies linearly across a stratum the centre's jitter cancels the corners' error
/// exactly; with independent jitters that noise set adaptive AA's error over evenly lit
/// areas. Each corner's own jitter stays uniform in its stratum.
// Mirror of src/tracer/base/rng.wgsl::shadow_random — change both.
pub fn shadow_random(stream: &ShadowStream, stratum: u32, axis: u32) -> f32 {
    let dimension_hash = pcg_hash(SHADOW_DIMENSION_BASE + 2 * stratum + axis);
    let top = pcg_hash(stream.rows[0] ^ dimension_hash);
    let [left, right] = stream.columns;
    let bits = if stream.mirrored {
        let bottom = pcg_hash(stream.rows[1] ^ dimension_hash);
        let sum = (pcg_hash(left ^ top) >> 8)
            + (pcg_hash(right ^ top) >> 8)
            + (pcg_hash(left ^ bottom) >> 8)
            + (pcg_hash(right ^ bottom) >> 8);
        0x00ff_ffff - (sum >> 2)
    } else {
        pcg_hash(left ^ top) >> 8
    };
    bits as f32 * RANDOM_UNIT_SCALE
}

/// Point `index` of the Sobol' (0,2)-sequence in base 2 (its first two dimensions: the
/// van der Corput sequence and Sobol's second), as 32-bit binary fractions. Its first 2^m
/// points (and every aligned block of 2^m) put one point in each of the 2^m boxes of
/// every shape 2^−a × 2^−(m−a): stratified in x, in y and jointly, at once.
// Mirror of src/tracer/base/rng.wgsl::sobol_02 — change both.
pub fn sobol_02(index: u32) -> [u32; 2] {
    // Sobol's second dimension: direction number k is v_{k+1} = v_k ^ (v_k >> 1), from 2^31.
    let (mut y, mut direction, mut bits) = (0u32, 1u32 << 31, index);
    while bits != 0 {
        if bits & 1 != 0 {
            y ^= direction;
        }
        bits >>= 1;
        direction ^= direction >> 1;
    }
    [index.reverse_bits(), y]
}

/// Element `i` of a permutation of 0..`count` chosen by `key` (i < count): a keyed
/// bijection of the `bits`-bit integers (`bits` enough for count − 1), applied again
/// until the value falls below count (cycle walking: it does, as the start does, and in
/// fewer than two steps on average, since 2^bits < 2·count).
// Mirror of src/tracer/base/rng.wgsl::shuffled_index — change both.
pub fn shuffled_index(i: u32, count: u32, key: u32) -> u32 {
    if count <= 1 {
        return 0;
    }
    let bits = 32 - (count - 1).leading_zeros();
    let mask = u32::MAX >> (32 - bits);
    let shift = bits.div_ceil(2);
    let mixed = pcg_hash(key);
    let mut j = i;
    loop {
        // Each step maps 0..2^bits onto itself one to one: xor with a constant, an odd
        // multiplier modulo 2^bits, a right xorshift.
        j = (j ^ key) & mask;
        j = j.wrapping_mul(mixed | 1) & mask;
        j ^= j >> shift;
        j = (j ^ (mixed >> 16)) & mask;
        j = j.wrapping_mul((key >> 16) | 1) & mask;
        j ^= j >> shift;
        if j < count {
            break;
        }
    }
    j
}

/// Point `index` of the 2D sequence of dimensions (`dimension`, `dimension` + 1) of the
/// pixel `key`: [`sobol_02`]'s point with each coordinate's bits xored with a hash of the
/// pixel and dimension (a random digital shift, which keeps every stratification above),
/// as floats in [0, 1) from its top 24 bits.
// Mirror of src/tracer/base/rng.wgsl::sequence_pair — change both.
pub fn sequence_pair(key: u32, index: u32, dimension: u32) -> [f32; 2] {
    let [x, y] = sobol_02(index);
    let shift_x = pcg_hash(key ^ pcg_hash(dimension));
    let shift_y = pcg_hash(key ^ pcg_hash(dimension + 1));
    [
        ((x ^ shift_x) >> 8) as f32 * RANDOM_UNIT_SCALE,
        ((y ^ shift_y) >> 8) as f32 * RANDOM_UNIT_SCALE,
    ]
}

/// The index in its pixel's sequence of the adaptive-AA lattice point at (x, y), its
/// coordinates within the pixel on the finest lattice (0..2^MAX_AA_DEPTH each): the bits
/// of each reversed, then interleaved (x's in the even places). A point of level L (its
/// coordinates multiples of 2^(MAX_AA_DEPTH − L)) then takes an index below 4^L, and the
/// 4^L points of a pixel split to level L are exactly the sequence's first 4^L: a pixel's
/// lattice samples are as stratified as its first samples of [`sobol_02`], level by level.
// Mirror of src/tracer/base/rng.wgsl::lattice_sequence_index — change both.
pub fn lattice_sequence_index(x: u32, y: u32) -> u32 {
    let reversed_x = x.reverse_bits() >> (32 - MAX_AA_DEPTH);
    let reversed_y = y.reverse_bits() >> (32 - MAX_AA_DEPTH);
    let mut index = 0;
    for bit in 0..MAX_AA_DEPTH {
        index |= ((reversed_x >> bit) & 1) << (2 * bit);
        index |= ((reversed_y >> bit) & 1) << (2 * bit + 1);
    }
    index
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constants::LENS_DIMENSION;

    /// The 24-bit jitter of `seed`'s stratum `stratum`, axis `axis`, for light 2.
    fn jitter_bits(seed: SampleSeed, stratum: u32, axis: u32) -> u32 {
        (shadow_random(&shadow_stream(seed, 2), stratum, axis) / RANDOM_UNIT_SCALE) as u32
    }

    /// The centre of an adaptive square of every level (not only a pixel's) mirrors the
    /// shadow jitter of that square's four corners: 2^24 − 1 minus the mean of the
    /// jitters their own streams draw. Its edge midpoints draw their own.
    #[test]
    fn square_centres_mirror_their_own_squares_corners() {
        for level in 0..MAX_AA_DEPTH {
            let side = 1.0 / (1u32 << level) as f32;
            let (x0, y0) = (3.0 + 2.0 * side, 5.0 + 3.0 * side);
            let centre = adaptive_seed(x0 + side / 2.0, y0 + side / 2.0);
            assert!(centre.mirrors_corners, "level {level}");
            for (mx, my) in [(0.5, 0.0), (0.0, 0.5), (1.0, 0.5), (0.5, 1.0)] {
                let midpoint = adaptive_seed(x0 + mx * side, y0 + my * side);
                assert!(!midpoint.mirrors_corners, "level {level} ({mx}, {my})");
            }
            let corners =
                [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)].map(|(cx, cy)| SampleSeed {
                    mirrors_corners: false,
                    ..adaptive_seed(x0 + cx * side, y0 + cy * side)
                });
            for stratum in 0..4 {
                for axis in 0..2 {
                    let sum: u32 = corners.iter().map(|&c| jitter_bits(c, stratum, axis)).sum();
                    assert_eq!(
                        jitter_bits(centre, stratum, axis),
                        0x00ff_ffff - sum / 4,
                        "level {level}, stratum {stratum}, axis {axis}"
                    );
                }
            }
        }
        // Pixel corners are no square's centre.
        assert!(!adaptive_seed(7.0, 9.0).mirrors_corners);
        assert!(!adaptive_seed(0.0, 0.0).mirrors_corners);
    }

    /// The first 2^m points of the scrambled sequence put one point in each box of every
    /// shape 2^−a × 2^−(m−a) (a (0, m, 2)-net), for every pixel key and both dimensions'
    /// shifts; so does the second block of 2^m.
    #[test]
    fn sequence_blocks_are_nets() {
        for key in [0, 1, 77, 123_456] {
            for m in 0..=8u32 {
                for block in 0..2u32 {
                    for a in 0..=m {
                        let mut boxes = vec![false; 1 << m];
                        for i in 0..1u32 << m {
                            let [x, y] = sequence_pair(key, (block << m) + i, LENS_DIMENSION);
                            let bx = (x * (1u32 << a) as f32) as u32;
                            let by = (y * (1u32 << (m - a)) as f32) as u32;
                            let b = (by << a | bx) as usize;
                            assert!(!boxes[b], "key {key}, m {m}, block {block}, a {a}");
                            boxes[b] = true;
                        }
                    }
                }
            }
        }
    }

    /// `shuffled_index` permutes 0..count, differently for different keys.
    #[test]
    fn shuffled_indices_are_permutations() {
        for count in [1, 2, 3, 4, 5, 9, 16, 17, 100, 4096] {
            let mut orders = std::collections::HashSet::new();
            for key in 0..8u32 {
                let order: Vec<u32> = (0..count)
                    .map(|i| shuffled_index(i, count, pcg_hash(key)))
                    .collect();
                let mut sorted = order.clone();
                sorted.sort_unstable();
                assert_eq!(sorted, (0..count).collect::<Vec<_>>(), "count {count}");
                orders.insert(order);
            }
            assert!(
                orders.len() > 4 || count < 4,
                "count {count}: {}",
                orders.len()
            );
        }
    }

    /// A pixel's lattice points of levels 0..=L (its top-left corner, then each level's
    /// new points) take exactly the sequence indices 0..4^L.
    #[test]
    fn lattice_levels_take_sequence_prefixes() {
        for level in 0..=MAX_AA_DEPTH {
            let step = 1u32 << (MAX_AA_DEPTH - level);
            let mut indices: Vec<u32> = (0..1u32 << level)
                .flat_map(|j| (0..1u32 << level).map(move |i| (i * step, j * step)))
                .map(|(x, y)| lattice_sequence_index(x, y))
                .collect();
            indices.sort_unstable();
            assert_eq!(
                indices,
                (0..1u32 << (2 * level)).collect::<Vec<_>>(),
                "level {level}"
            );
        }
        // The pixel's centre is the fourth point; its top-left corner the first.
        let half = 1 << (MAX_AA_DEPTH - 1);
        assert_eq!(lattice_sequence_index(half, half), 3);
        assert_eq!(lattice_sequence_index(0, 0), 0);
    }
}
