// render.wgsl — pixels and chunks: the render kernels for AA none (`main`) and uniform AA,
// each invocation tracing one sample (Mesa's lavapipe caps the loop iterations of one
// invocation, see loop_limiter_tripped), and what src/tracer/sampling/adaptive.wgsl shares. Every
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

// Sample s of pixel (x, y) under n×n stratification: the colour at its stratum's
// stratum_position (jittered when `uniform`, else the stratum's centre).
// Mirror of src/tracer/sampling/render.rs::uniform_sample — change both.
fn uniform_sample(x: u32, y: u32, s: u32, n: u32, uniform: bool) -> vec3<f32> {
    let at = stratum_position(x, y, s, n, uniform);
    return sample(at.fx, at.fy, at.seed);
}

// Index of a one-dimensional kernel's invocation: a dispatch wider than the adapter's
// workgroups per dimension continues in y (src/gpu/plan/mod.rs::linear_workgroups).
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

// #if !WAVEFRONT
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
// src/tracer/sampling/adaptive.wgsl.)
// Mirror of the AA-none case of src/tracer/sampling/render.rs::render_pixel — change both.
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
// #endif

// #if WAVEFRONT
// Uniform AA: the wavefront kernels' strata (wavefront.wgsl's camera pass) and
// wavefront_resolve, in place of the two passes below.
// #else
// Uniform AA, pass 1: sample (idx mod n², idx div n² as a tile pixel, row-major over the
// tile's size) of the tile into samples[(pixel's row-major index at stride tile.side)·n²
// + s].
// Mirror of src/tracer/sampling/render.rs::uniform_samples — change both.
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
// Mirror of src/tracer/sampling/render.rs::uniform_resolve — change both.
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
// #endif
