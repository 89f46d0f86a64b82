// sample_source.wgsl — the sample sources: where a camera sample lies on the film, and its
// seed. A pixel's n×n strata (stratum_position: AA none's centre at n = 1, uniform AA's
// jittered strata, glint view's frame s taking stratum s) and adaptive AA's lattice
// points (lattice_jitter of a point the lattice passes enumerate: adaptive.wgsl's
// corner_to_trace and midpoint_to_trace, at lattice_position). Each is written once
// here, and every kernel that starts camera samples takes it: the megakernels
// (render.wgsl's uniform_sample for main, uniform_samples and progressive.wgsl's
// view_sample; pixel_sample.wgsl's lattice_sample for adaptive_corners and
// adaptive_midpoints) and the hardware variant's camera kernels (its strata's and its
// lattice passes').

// A camera sample: its film position (fx, fy) in pixels and its seed.
// Mirror of src/tracer/sampling/sample_source.rs::CameraSample — change both.
struct CameraSample {
    fx: f32,
    fy: f32,
    seed: SampleSeed,
}

// Stratum s of pixel (x, y)'s n×n strata, (s mod n, s div n): a point jittered within it
// when `uniform`, else its centre; its seed names the pixel and the stratum.
// Mirror of src/tracer/sampling/sample_source.rs::stratum_position — change both.
fn stratum_position(x: u32, y: u32, s: u32, n: u32, uniform: bool) -> CameraSample {
    let pixel = y * globals.width + x;
    let i = s % n;
    let j = s / n;
    var jx = 0.5;
    var jy = 0.5;
    if uniform {
        jx = random_unit(pixel, s, PIXEL_DIMENSION);
        jy = random_unit(pixel, s, PIXEL_DIMENSION + 1u);
    }
    let fx = f32(x) + (f32(i) + jx) / f32(n);
    let fy = f32(y) + (f32(j) + jy) / f32(n);
    return CameraSample(fx, fy, SampleSeed(pixel, s, 0u, false));
}

// Adaptive AA's sample of lattice point (fx, fy), a dyadic film position (exact): the
// point jittered, by hashes of its seed, within a square AA_LATTICE_JITTER steps of the
// finest lattice (2^aa_depth per pixel) wide around it, with the point's own seed. The
// jitter depends only on the point, so a point shared by neighbouring squares, pixels or
// chunks is the same sample whichever pass traces it.
// Mirror of src/tracer/sampling/sample_source.rs::lattice_jitter — change both.
fn lattice_jitter(fx: f32, fy: f32) -> CameraSample {
    let seed = adaptive_seed(fx, fy);
    // A power of two: the products below are exact, so a fused multiply-add rounds the
    // sums as the CPU's separate operations do.
    let width = AA_LATTICE_JITTER * ldexp(1.0, -i32(globals.aa_depth));
    let jx = (random_unit(seed.pixel, seed.sample, PIXEL_DIMENSION) - 0.5) * width;
    let jy = (random_unit(seed.pixel, seed.sample, PIXEL_DIMENSION + 1u) - 0.5) * width;
    return CameraSample(fx + jx, fy + jy, seed);
}

// #if DEPTH_OF_FIELD
// Where camera sample seed lies in its pixel's stratified sequence for the effect of
// `dimension`: (the pixel's key, the sample's index). A pixel's n×n strata take the
// indices 0..n² shuffled per pixel and dimension; adaptive AA's lattice points take
// lattice_sequence_index of their place in their pixel. See the twin for why.
// Mirror of src/tracer/sampling/sample_source.rs::sequence_index — change both.
fn sequence_index(seed: SampleSeed, dimension: u32) -> vec2<u32> {
    if globals.aa_mode == AA_ADAPTIVE {
        let within = (1u << MAX_AA_DEPTH) - 1u;
        let key = (seed.sample >> MAX_AA_DEPTH) * globals.width + (seed.pixel >> MAX_AA_DEPTH);
        return vec2<u32>(key, lattice_sequence_index(seed.pixel & within, seed.sample & within));
    }
    let n = select(1u, globals.aa_samples, globals.aa_mode == AA_UNIFORM);
    let shuffle = pcg_hash(seed.pixel ^ pcg_hash(~dimension));
    return vec2<u32>(seed.pixel, shuffled_index(seed.sample, n * n, shuffle));
}

// Camera sample seed's position on the lens, in [0, 1)² (the dimensions LENS_DIMENSION
// and the next): its point of its pixel's sequence.
// Mirror of src/tracer/sampling/sample_source.rs::lens_position — change both.
fn lens_position(seed: SampleSeed) -> vec2<f32> {
    let at = sequence_index(seed, LENS_DIMENSION);
    return sequence_pair(at.x, at.y, LENS_DIMENSION);
}
// #endif
