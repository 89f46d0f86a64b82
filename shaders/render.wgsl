// render.wgsl — pixels and chunks: the render kernels for AA none (`main`) and uniform AA,
// each invocation tracing one sample (Mesa's lavapipe caps the loop iterations of one
// invocation, see loop_limiter_tripped), and what shaders/adaptive.wgsl shares. Every
// sample depends only on (pixel, sample) hashes or its film position, as on the CPU.

@group(0) @binding(7) var<uniform> tile: GpuTile;
// One RGBA pixel per tile pixel, row-major (tile.side wide); alpha is unused, except by
// adaptive AA, which puts there the pixel's number of leaf squares.
@group(0) @binding(8) var<storage, read_write> output: array<vec4<f32>>;
// Per-sample colours: uniform AA's n² per pixel, or adaptive AA's lattice.
@group(0) @binding(11) var<storage, read_write> samples: array<vec4<f32>>;
// Adaptive AA's split flags, level after level (see adaptive.wgsl::split_offset).
@group(0) @binding(12) var<storage, read_write> split: array<u32>;
// 1 where a tile pixel must be re-rendered on the CPU (loop_limiter_tripped).
@group(0) @binding(13) var<storage, read_write> guard: array<u32>;

// Colour at film position (fx, fy) in pixels; seed names the camera sample.
// Mirror of src/cpu/pixel_sample.rs::sample — change both.
fn sample(fx: f32, fy: f32, seed: SampleSeed) -> vec3<f32> {
    return trace_ray(camera_ray(fx, fy), seed);
}

// What adaptive AA's split decisions read from a lattice sample beside its colour: whether
// its first surface showed fine detail that the colours of a few samples may not show (an
// area light reaching it through some of its shadow samples but not all, or a texture's
// detail at the pixel's scale: fine_detail_seen), and the item its camera ray hit first,
// as sample_item_key (camera_item; mirrored_item where that is a mirror).
// Mirror of src/cpu/pixel_sample.rs::SampleHint — change both.
struct SampleHint {
    fine_detail: bool,
    item: u32,
}

// The part of item number `item` (NO_ITEM: none) that a SampleHint keeps: its low
// AA_ITEM_KEY_MASK bits, which encode_hint's float holds exactly.
// Mirror of src/cpu/pixel_sample.rs::item_key — change both.
fn item_key(item: u32) -> u32 {
    return item & AA_ITEM_KEY_MASK;
}

// A hint as a lattice sample's fourth component: ±(item + 1), negative for fine detail (an
// integer of at most 2^24, so the float is exact and decode_hint gives it back).
fn encode_hint(hint: SampleHint) -> f32 {
    return select(1.0, -1.0, hint.fine_detail) * f32(hint.item + 1u);
}

// The hint encode_hint stored in w.
fn decode_hint(w: f32) -> SampleHint {
    return SampleHint(w < 0.0, u32(abs(w)) - 1u);
}

// What the split decision of a square reads beside its samples' contrast: whether one of
// its samples saw fine detail, and whether they hit different items.
// Mirror of src/cpu/pixel_sample.rs::SquareHints — change both.
struct SquareHints {
    fine_detail: bool,
    items_differ: bool,
}

// hints with sample hint h added (first: the square's first sample's hint).
// Mirror of src/cpu/pixel_sample.rs::add_sample_hint — change both.
fn add_sample_hint(hints: SquareHints, first: SampleHint, h: SampleHint) -> SquareHints {
    return SquareHints(hints.fine_detail || h.fine_detail, hints.items_differ || h.item != first.item);
}

// item_key of a sample whose camera ray hit item `camera` first and, where that is a
// mirror, whose reflected ray hit item `mirrored` first (NO_ITEM: not a mirror, or the
// reflected ray hit nothing): the camera item's key mixed with a hash of the mirrored one.
// Mirror of src/cpu/pixel_sample.rs::sample_item_key — change both.
fn sample_item_key(camera: u32, mirrored: u32) -> u32 {
    if mirrored == NO_ITEM {
        return item_key(camera);
    }
    return item_key(camera ^ ((mirrored + 1u) * 0x9e3779b1u));
}

// sample, and in w its SampleHint (encode_hint). Adaptive AA's lattice samples.
// Mirror of src/cpu/pixel_sample.rs::hinted_sample — change both.
fn hinted_sample(fx: f32, fy: f32, seed: SampleSeed) -> vec4<f32> {
    fine_detail_seen = false;
    camera_item = NO_ITEM;
    mirrored_item = NO_ITEM;
    let colour = sample(fx, fy, seed);
    let key = sample_item_key(camera_item, mirrored_item);
    return vec4<f32>(colour, encode_hint(SampleHint(fine_detail_seen, key)));
}

// Adaptive AA's sample at lattice point (fx, fy), a dyadic film position (exact): the
// point jittered, by hashes of its seed, within a square AA_LATTICE_JITTER steps of the
// finest lattice (2^aa_depth per pixel) wide around it, then hinted_sample there with
// the point's own seed. The jitter depends only on the point, so a point shared by
// neighbouring squares, pixels or chunks is the same sample whichever pass traces it.
// Mirror of src/cpu/pixel_sample.rs::lattice_sample — change both.
fn lattice_sample(fx: f32, fy: f32) -> vec4<f32> {
    let seed = adaptive_seed(fx, fy);
    // A power of two: the products below are exact, so a fused multiply-add rounds the
    // sums as the CPU's separate operations do.
    let width = AA_LATTICE_JITTER * ldexp(1.0, -i32(globals.aa_depth));
    let jx = (random_unit(seed.pixel, seed.sample, 0u) - 0.5) * width;
    let jy = (random_unit(seed.pixel, seed.sample, 1u) - 0.5) * width;
    return hinted_sample(fx + jx, fy + jy, seed);
}

// Largest per-channel spread of a square's four corner samples and its centre sample:
// what the split decision of adaptive AA weighs.
// Mirror of src/cpu/pixel_sample.rs::square_contrast_of — change both.
fn square_contrast_of(c: array<vec3<f32>, 4>, centre: vec3<f32>) -> f32 {
    let lo = min(min(min(min(c[0], c[1]), c[2]), c[3]), centre);
    let hi = max(max(max(max(c[0], c[1]), c[2]), c[3]), centre);
    return max_element(hi - lo);
}

// Colour of a square that adaptive AA did not split, from its corner samples and its
// centre sample: the centre weighs AA_CENTRE_WEIGHT, the corners share the rest.
// Mirror of src/cpu/pixel_sample.rs::quincunx_mean — change both.
fn quincunx_mean(c: array<vec3<f32>, 4>, centre: vec3<f32>) -> vec3<f32> {
    let corner_weight = 0.25 * (1.0 - AA_CENTRE_WEIGHT);
    return (c[0] + c[1] + c[2] + c[3]) * corner_weight + centre * AA_CENTRE_WEIGHT;
}

// Sample s of pixel (x, y) under n×n stratification: stratum (s mod n, s div n),
// jittered when `uniform`, else its centre.
// Mirror of src/cpu/render.rs::uniform_sample — change both.
fn uniform_sample(x: u32, y: u32, s: u32, n: u32, uniform: bool) -> vec3<f32> {
    let pixel = y * globals.width + x;
    let i = s % n;
    let j = s / n;
    var jx = 0.5;
    var jy = 0.5;
    if uniform {
        jx = random_unit(pixel, s, 0u);
        jy = random_unit(pixel, s, 1u);
    }
    let fx = f32(x) + (f32(i) + jx) / f32(n);
    let fy = f32(y) + (f32(j) + jy) / f32(n);
    return sample(fx, fy, SampleSeed(pixel, s, 0u, false));
}

// Index of a one-dimensional kernel's invocation: a dispatch wider than the adapter's
// workgroups per dimension continues in y (src/gpu/plan.rs::linear_workgroups).
fn linear_index(id: vec3<u32>, groups: vec3<u32>) -> u32 {
    return id.y * groups.x * LINEAR_WORKGROUP_SIZE + id.x;
}

// #if ITERATION_GUARD
// Whether Mesa's loop limiter has tripped in this invocation (software adapters only).
// gallivm counts loop iterations per invocation, summed over every loop of the inlined
// shader, and past LP_MAX_TGSI_LOOP_ITERATIONS (65 535) ends every loop at the end of
// its current iteration — silently, so results come out wrong. A loop asked for
// tile.sentinel = 2 iterations (a uniform, so nothing unrolls it) then stops after one.
// The host re-renders the pixels so flagged with the CPU tracer.
fn loop_limiter_tripped() -> bool {
    var n = 0u;
    loop {
        n += 1u;
        if n >= tile.sentinel {
            break;
        }
    }
    return n < tile.sentinel;
}
// #endif

// The chunk pixel invocation gid traces in `main`: the same square of pixels as its
// workgroup, but each run of 8 consecutive invocations (local index order, x fastest)
// takes a 4×2 block instead of 8 pixels of one row. llvmpipe runs 8 invocations in the 8
// lanes of one AVX2 instruction stream, as long as the slowest of them, and a 4×2 block's
// rays stay together longer than a row's (measured on lavapipe, docs/journal/2026-11-29-gpu-kernel-variant-measured.md: 5–8% less
// GPU time on average on nonhier, macho-cows and demo, none on hier). A hardware GPU's
// 32-lane warp gets an 8×4 block either way. Workgroup sides not a multiple of 4 keep the
// row order. GPU-only: which invocation traces a pixel changes nothing in the pixel.
fn block_pixel(gid: vec3<u32>) -> vec2<u32> {
    let side = WORKGROUP_SIZE;
    if side % 4u != 0u {
        return gid.xy;
    }
    let corner = gid.xy - gid.xy % side;
    let lane = (gid.y % side) * side + gid.x % side;
    let block = lane / 8u;
    let blocks_per_row = side / 4u;
    let x = (block % blocks_per_row) * 4u + lane % 4u;
    let y = (block / blocks_per_row) * 2u + (lane / 4u) % 2u;
    return corner + vec2<u32>(x, y);
}

// AA none: pixel block_pixel(gid) of the chunk at tile.origin, its centre; invocations
// outside the chunk (its ragged edge) do nothing. (Both AA modes take one sample per
// invocation too, in passes: uniform_samples and uniform_resolve below, and
// shaders/adaptive.wgsl.)
// Mirror of the AA-none case of src/cpu/render.rs::render_pixel — change both.
@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let id = block_pixel(gid);
    if id.x >= tile.size.x || id.y >= tile.size.y {
        return;
    }
    let p = id.y * tile.side + id.x;
    begin_lane(p);
    output[p] = vec4<f32>(uniform_sample(tile.origin.x + id.x, tile.origin.y + id.y, 0u, 1u, false), 1.0);
// #if ITERATION_GUARD
    if loop_limiter_tripped() {
        guard[p] = 1u;
    }
// #endif
}

// Uniform AA, pass 1: sample (idx mod n², idx div n² as a tile pixel, row-major over the
// tile's size) of the tile into samples[(pixel's row-major index at stride tile.side)·n²
// + s].
// Mirror of the sample loop of src/cpu/render.rs::render_pixel — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn uniform_samples(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let idx = linear_index(id, groups);
    if idx >= tile.items {
        return;
    }
    let n = globals.aa_samples;
    let nn = n * n;
    let p = idx / nn;
    let s = idx % nn;
    let tx = p % tile.size.x;
    let ty = p / tile.size.x;
    let q = ty * tile.side + tx;
    begin_lane(idx);
    samples[q * nn + s] = vec4<f32>(uniform_sample(tile.origin.x + tx, tile.origin.y + ty, s, n, true), 1.0);
// #if ITERATION_GUARD
    if loop_limiter_tripped() {
        guard[q] = 1u;
    }
// #endif
}

// Uniform AA, pass 2: each pixel's mean, summed in sample order as the CPU does.
// Mirror of the sum of src/cpu/render.rs::render_pixel — change both.
@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE)
fn uniform_resolve(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= tile.size.x || id.y >= tile.size.y {
        return;
    }
    let nn = globals.aa_samples * globals.aa_samples;
    let q = id.y * tile.side + id.x;
    var sum = vec3<f32>(0.0);
    for (var s = 0u; s < nn; s++) {
        sum += samples[q * nn + s].xyz;
    }
    output[q] = vec4<f32>(sum / f32(nn), 1.0);
}
