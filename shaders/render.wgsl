// render.wgsl — pixels and tiles: anti-aliasing per pixel, and the `main` compute entry
// point, which renders one GPU_TILE_SIZE² tile (origin in `tile`) into `output`. Every
// sample depends only on (pixel, sample) hashes, as in the CPU tracer.

@group(0) @binding(7) var<uniform> tile: GpuTile;
// One RGBA pixel per tile pixel, row-major (GPU_TILE_SIZE wide); alpha is unused.
@group(0) @binding(8) var<storage, read_write> output: array<vec4<f32>>;

// Colour at film position (fx, fy) in pixels.
// Mirror of src/cpu/render.rs::sample — change both.
fn sample(fx: f32, fy: f32) -> vec3<f32> {
    return trace_ray(camera_ray(fx, fy));
}

// A square of the adaptive subdivision: top-left corner, side, depth, and the colours at
// its four corners (top-left, top-right, bottom-left, bottom-right).
// Mirror of src/cpu/render.rs::AdaptiveSquare — change both.
struct AdaptiveSquare {
    x: f32,
    y: f32,
    size: f32,
    depth: u32,
    corners: array<vec3<f32>, 4>,
}

// Largest per-channel spread of four colours.
// Mirror of src/cpu/render.rs::contrast — change both.
fn contrast(c: array<vec3<f32>, 4>) -> f32 {
    let lo = min(min(min(c[0], c[1]), c[2]), c[3]);
    let hi = max(max(max(c[0], c[1]), c[2]), c[3]);
    return max_element(hi - lo);
}

// Adaptive anti-aliasing of pixel (x, y) (Whitted 1980): sample the corners; where they
// differ by more than threshold, split into four and recurse — here with an explicit
// stack — down to max_depth. Sample positions lie on a dyadic lattice, so neighbouring
// pixels see the same colour at a shared corner.
// Mirror of src/cpu/render.rs::adaptive_pixel — change both.
fn adaptive_pixel(x: u32, y: u32, threshold: f32, max_depth: u32) -> vec3<f32> {
    let fx = f32(x);
    let fy = f32(y);
    // Corner k is (k & 1, k >> 1). (One `sample` call site per loop: the compiler inlines
    // every call, and the shader's size and compile time grow with the sites.)
    var corners: array<vec3<f32>, 4>;
    for (var k = 0u; k < 4u; k++) {
        corners[k] = sample(fx + f32(k & 1u), fy + f32(k >> 1u));
    }
    var stack: array<AdaptiveSquare, AA_STACK_SIZE>;
    stack[0] = AdaptiveSquare(fx, fy, 1.0, 0u, corners);
    var size = 1u;
    var sum = vec3<f32>(0.0);
    while size > 0u {
        size -= 1u;
        let sq = stack[size];
        // Weight of this square in the pixel: its area.
        let area = sq.size * sq.size;
        if sq.depth >= max_depth || contrast(sq.corners) <= threshold {
            sum += (sq.corners[0] + sq.corners[1] + sq.corners[2] + sq.corners[3]) * (0.25 * area);
            continue;
        }
        let h = sq.size * 0.5;
        let tl = sq.corners[0];
        let tr = sq.corners[1];
        let bl = sq.corners[2];
        let br = sq.corners[3];
        // Top, left, centre, right and bottom midpoints.
        let offsets = array<vec2<f32>, 5>(
            vec2<f32>(h, 0.0),
            vec2<f32>(0.0, h),
            vec2<f32>(h, h),
            vec2<f32>(sq.size, h),
            vec2<f32>(h, sq.size),
        );
        var mid: array<vec3<f32>, 5>;
        for (var k = 0u; k < 5u; k++) {
            mid[k] = sample(sq.x + offsets[k].x, sq.y + offsets[k].y);
        }
        let top = mid[0];
        let left = mid[1];
        let centre = mid[2];
        let right = mid[3];
        let bottom = mid[4];
        let depth = sq.depth + 1u;
        stack[size] = AdaptiveSquare(sq.x, sq.y, h, depth, array<vec3<f32>, 4>(tl, top, left, centre));
        stack[size + 1u] = AdaptiveSquare(sq.x + h, sq.y, h, depth, array<vec3<f32>, 4>(top, tr, centre, right));
        stack[size + 2u] = AdaptiveSquare(sq.x, sq.y + h, h, depth, array<vec3<f32>, 4>(left, centre, bl, bottom));
        stack[size + 3u] = AdaptiveSquare(sq.x + h, sq.y + h, h, depth, array<vec3<f32>, 4>(centre, right, bottom, br));
        size += 4u;
    }
    return sum;
}

// Colour of pixel (x, y) under the scene's anti-aliasing mode.
// Mirror of src/cpu/render.rs::render_pixel — change both.
fn render_pixel(x: u32, y: u32) -> vec3<f32> {
    let g = globals;
    if g.aa_mode == AA_ADAPTIVE {
        return adaptive_pixel(x, y, g.aa_threshold, g.aa_depth);
    }
    // Uniform: n×n strata, one jittered sample in each. None: one stratum, its centre
    // (x + 0.5 exactly). One loop for both keeps one `sample` call site (see above).
    let uniform = g.aa_mode == AA_UNIFORM;
    let n = select(1u, g.aa_samples, uniform);
    let pixel = y * g.width + x;
    var sum = vec3<f32>(0.0);
    for (var j = 0u; j < n; j++) {
        for (var i = 0u; i < n; i++) {
            let s = j * n + i;
            var jx = 0.5;
            var jy = 0.5;
            if uniform {
                jx = random_unit(pixel, s, 0u);
                jy = random_unit(pixel, s, 1u);
            }
            let fx = f32(x) + (f32(i) + jx) / f32(n);
            let fy = f32(y) + (f32(j) + jy) / f32(n);
            sum += sample(fx, fy);
        }
    }
    return sum / f32(n * n);
}

// Renders one pixel of the tile at tile.origin; invocations outside the image (edge
// tiles) do nothing.
// Mirror of the per-tile loop in src/cpu/render.rs::render_tiles — change both.
@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let x = tile.origin.x + id.x;
    let y = tile.origin.y + id.y;
    if id.x >= GPU_TILE_SIZE || id.y >= GPU_TILE_SIZE || x >= globals.width || y >= globals.height {
        return;
    }
    output[id.y * GPU_TILE_SIZE + id.x] = vec4<f32>(render_pixel(x, y), 1.0);
}
