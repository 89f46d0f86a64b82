// adaptive.wgsl — adaptive anti-aliasing (Whitted 1980) per tile, in passes over a dyadic
// lattice of (tile.side·2^d + 1)² points in `samples` (d = aa_depth; lattice point (i, j)
// is film position (x0 + i/2^d, y0 + j/2^d), sampled within the lattice cell around it,
// jittered by a hash of its position: lattice_sample), one sample per invocation:
// adaptive_corners traces the pixel corners and, at d ≥ 1, the pixel centres (w of each
// sample: its hint, whether it saw fine detail and which item it hit); for each level
// k < d, adaptive_decide flags the level-k squares to split (square_splits, over each
// square's corners and centre) and appends them to level k's list, adaptive_work_args
// turns the list's length into the indirect dispatches of the passes over it, and
// adaptive_midpoints traces the listed squares' edge midpoints and their children's
// centres; then adaptive_integrate averages each pixel over its quadtree (an unsplit
// square above level d: quincunx_mean of its corners and centre, weighted by its area).
// Below level 0 the passes run over the compacted lists only (indirect dispatches), so
// idle invocations do not grow with depth.
// The decisions, samples and summation order are those of the per-pixel walk,
// src/tracer/sampling/render.rs::adaptive_pixel.
// Mirror of src/tracer/sampling/adaptive.rs — change both.

// Per level, the number of split squares on its list.
@group(0) @binding(17) var<storage, read_write> work_counts: array<atomic<u32>>;
// Per level, from split_offset(tile.side, level), the split squares (pack_square).
@group(0) @binding(18) var<storage, read_write> work_list: array<u32>;
// Indirect dispatch arguments, per level: the midpoint pass over its list, then the
// decide pass over its children (bound only to adaptive_work_args: a dispatch may not
// read its own arguments as storage).
@group(0) @binding(19) var<storage, read_write> work_args: array<u32>;

// Lattice steps per pixel: 2^d.
// Mirror of src/tiling.rs::AdaptiveTile::adaptive_scale — change both.
fn adaptive_scale() -> u32 {
    return 1u << globals.aa_depth;
}

// First split flag of level `level`: side²·(4^level − 1)/3 (level k has (side·2^k)²).
// Mirror of src/tiling.rs::split_offset — change both.
fn split_offset(side: u32, level: u32) -> u32 {
    return side * side * (((1u << (2u * level)) - 1u) / 3u);
}

// Index of level-`level` square (a, b)'s split flag.
// Mirror of src/tracer/sampling/adaptive.rs::split_index — change both.
fn split_index(level: u32, a: u32, b: u32) -> u32 {
    return split_offset(tile.side, level) + b * (tile.side << level) + a;
}

// Mirror of src/tracer/sampling/adaptive.rs::Lattice::is_split — change both.
fn is_split(level: u32, a: u32, b: u32) -> bool {
    return split[split_index(level, a, b)] != 0u;
}

// One list entry for level square (a, b) (a, b < 2^16: the lattice side is at most 2^15).
// Mirror of src/tracer/sampling/adaptive.rs::pack_square — change both.
fn pack_square(a: u32, b: u32) -> u32 {
    return a | (b << 16u);
}

// Mirror of src/tracer/sampling/adaptive.rs::unpack_square — change both.
fn unpack_square(entry: u32) -> vec2<u32> {
    return vec2<u32>(entry & 0xffffu, entry >> 16u);
}

// Entry k of level `level`'s list of split squares.
// Mirror of src/tracer/sampling/adaptive.rs::Lattice::split_square — change both.
fn split_square(level: u32, k: u32) -> vec2<u32> {
    return unpack_square(work_list[split_offset(tile.side, level) + k]);
}

// Index of lattice point (i, j).
// Mirror of src/tracer/sampling/adaptive.rs::lattice_index — change both.
fn lattice_index(i: u32, j: u32) -> u32 {
    return j * (tile.side * adaptive_scale() + 1u) + i;
}

// The sample at lattice point (i, j).
// Mirror of src/tracer/sampling/adaptive.rs::Lattice::lattice_point — change both.
fn lattice_point(i: u32, j: u32) -> vec3<f32> {
    return samples[lattice_index(i, j)].xyz;
}

// The samples at the corners of square (a, b) of `level`: top-left, top-right,
// bottom-left, bottom-right.
// Mirror of src/tracer/sampling/adaptive.rs::square_corners — change both.
fn square_corners(level: u32, a: u32, b: u32) -> array<vec3<f32>, 4> {
    let l = adaptive_scale() >> level;
    let i = a * l;
    let j = b * l;
    return array<vec3<f32>, 4>(
        lattice_point(i, j),
        lattice_point(i + l, j),
        lattice_point(i, j + l),
        lattice_point(i + l, j + l),
    );
}

// The hint of the sample at lattice point (i, j).
// Mirror of src/tracer/sampling/adaptive.rs::Lattice::point_hint — change both.
fn point_hint(i: u32, j: u32) -> SampleHint {
    return decode_hint(samples[lattice_index(i, j)].w);
}

// Lattice point of the centre of square (a, b) of `level` (when square_has_centre).
// Mirror of src/tracer/sampling/adaptive.rs::square_centre — change both.
fn square_centre(level: u32, a: u32, b: u32) -> vec2<u32> {
    let l = adaptive_scale() >> level;
    return vec2<u32>(a * l + l / 2u, b * l + l / 2u);
}

// Whether the squares of `level` have a traced centre of their own: every level above
// aa_depth (a square of the deepest level, one lattice step wide, has corners only). Its
// decision and, unsplit, its colour use it.
// Mirror of src/tracer/sampling/adaptive.rs::square_has_centre — change both.
fn square_has_centre(level: u32) -> bool {
    return level < globals.aa_depth;
}

// The hints of square (a, b) of `level` (< aa_depth: a square that decides has a
// centre): whether one of its corners or its centre saw fine detail, and whether their
// camera rays hit different items.
// Mirror of src/tracer/sampling/adaptive.rs::square_hints — change both.
fn square_hints(level: u32, a: u32, b: u32) -> SquareHints {
    let l = adaptive_scale() >> level;
    let i = a * l;
    let j = b * l;
    let first = point_hint(i, j);
    var hints = SquareHints(first.fine_detail, false);
    hints = add_sample_hint(hints, first, point_hint(i + l, j));
    hints = add_sample_hint(hints, first, point_hint(i, j + l));
    hints = add_sample_hint(hints, first, point_hint(i + l, j + l));
    let c = square_centre(level, a, b);
    return add_sample_hint(hints, first, point_hint(c.x, c.y));
}

// The contrast the split decision of square (a, b) of `level` (< aa_depth) weighs: of its
// corners and centre (square_contrast_of).
// Mirror of src/tracer/sampling/adaptive.rs::square_contrast — change both.
fn square_contrast(level: u32, a: u32, b: u32) -> f32 {
    let corners = square_corners(level, a, b);
    let c = square_centre(level, a, b);
    return square_contrast_of(corners, lattice_point(c.x, c.y));
}

// Whether a square of `level` whose samples' contrast is `spread` splits: the contrast
// times the square's side (2^−level pixels) exceeds `threshold` (NaN included), that is,
// the samples differ by more than 2^level · `threshold`; or, whatever the contrast, one of
// them saw fine detail and the level is above AA_FINE_DETAIL_DEPTH (soft-shadow noise and
// texture detail at the pixel's scale count as contrast, down to the density of uniform 4×4), or their camera rays hit different
// items and the level is above AA_ITEM_EDGE_DEPTH (an edge between objects of about the
// same colour). The per-pixel walk's test too.
// Mirror of src/tracer/sampling/adaptive.rs::square_splits — change both.
fn square_splits(spread: f32, hints: SquareHints, level: u32, threshold: f32) -> bool {
    // (A power of two: the product is exact, on both tracers.)
    let level_threshold = threshold * f32(1u << level);
    let differ = !(spread <= level_threshold);
    return differ || (hints.fine_detail && level < AA_FINE_DETAIL_DEPTH)
        || (hints.items_differ && level < AA_ITEM_EDGE_DEPTH);
}

// Film position of lattice point (i, j), exact (a dyadic fraction of few bits; ldexp
// rather than a division, which WGSL lets be inexact).
// Mirror of src/tracer/sampling/adaptive.rs::lattice_position — change both.
fn lattice_position(i: u32, j: u32) -> vec2<f32> {
    let s = adaptive_scale();
    let step = ldexp(1.0, -i32(globals.aa_depth));
    return vec2<f32>(
        f32(tile.origin.x + i / s) + f32(i % s) * step,
        f32(tile.origin.y + j / s) + f32(j % s) * step,
    );
}

// Traces lattice point (i, j) into the lattice: its colour and, in w, its hint.
// Mirror of src/tracer/sampling/adaptive.rs::trace_lattice_point — change both.
fn trace_lattice_point(i: u32, j: u32) {
    let pos = lattice_position(i, j);
    let k = lattice_index(i, j);
    let hinted = lattice_sample(pos.x, pos.y);
    samples[k] = vec4<f32>(hinted.colour, encode_hint(hinted.hint));
// #if ITERATION_GUARD
    if loop_limiter_tripped() {
        guard_lattice_point(i, j);
    }
// #endif
}

// #if ITERATION_GUARD|REFRACTION
// The guard flags of every pixel whose closed square holds lattice point (i, j), whose
// sample the GPU could not trace (lavapipe's loop limiter tripped in trace_lattice_point,
// or a tree of the hardware variant's queues had no room for a child: its lattice store pass): the
// host re-renders them on the CPU. Straight-line code: after the limiter trips, loops
// run one iteration.
fn guard_lattice_point(i: u32, j: u32) {
    let s = adaptive_scale();
    let x_hi = min(i / s, tile.size.x - 1u);
    let y_hi = min(j / s, tile.size.y - 1u);
    let x_lo = select(x_hi, (i - 1u) / s, i > 0u);
    let y_lo = select(y_hi, (j - 1u) / s, j > 0u);
    guard[y_lo * tile.side + x_lo] = 1u;
    guard[y_lo * tile.side + x_hi] = 1u;
    guard[y_hi * tile.side + x_lo] = 1u;
    guard[y_hi * tile.side + x_hi] = 1u;
}
// #endif

// #if !WAVEFRONT
// Corner pass (tile.items = src/tiling.rs::AdaptiveTile::first_pass_len invocations):
// invocation idx traces pixel corner (idx mod (w+1), idx div (w+1)) for idx < (w+1)(h+1),
// after those the centre of pixel number idx − (w+1)(h+1).
// Mirror of src/tracer/sampling/adaptive.rs::adaptive_corners — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn adaptive_corners(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let idx = linear_index(id, groups);
    if idx >= tile.items {
        return;
    }
    begin_lane(idx);
    let point = corner_to_trace(idx);
    trace_lattice_point(point.x, point.y);
}
// #endif

// The lattice point that invocation idx of the corner pass traces (see adaptive_corners):
// pixel corner (idx mod (w+1), idx div (w+1)) for idx < (w+1)(h+1), after those the
// centre of pixel number idx − (w+1)(h+1). Both forms' corner passes take it:
// adaptive_corners here and the hardware variant's lattice passes (lattice_pass_point).
// Mirror of src/tracer/sampling/adaptive.rs::corner_to_trace — change both.
fn corner_to_trace(idx: u32) -> vec2<u32> {
    let s = adaptive_scale();
    let corners = (tile.size.x + 1u) * (tile.size.y + 1u);
    if idx < corners {
        return vec2<u32>((idx % (tile.size.x + 1u)) * s, (idx / (tile.size.x + 1u)) * s);
    }
    let pixel = idx - corners;
    return square_centre(0u, pixel % tile.size.x, pixel / tile.size.x);
}

// Decide pass of tile.level: square (idx mod w, idx div w) at level 0, else child idx mod 4
// (top-left, top-right, bottom-left, bottom-right) of entry idx div 4 of level − 1's
// list. Flags it for splitting by square_splits and then appends it to the level's list.
// Mirror of src/tracer/sampling/adaptive.rs::adaptive_decide — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn adaptive_decide(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let idx = linear_index(id, groups);
    let level = tile.level;
    var square: vec2<u32>;
    if level == 0u {
        if idx >= tile.items {
            return;
        }
        square = vec2<u32>(idx % tile.size.x, idx / tile.size.x);
    } else {
        if idx >= 4u * atomicLoad(&work_counts[level - 1u]) {
            return;
        }
        let parent = split_square(level - 1u, idx / 4u);
        square = 2u * parent + vec2<u32>((idx % 4u) % 2u, (idx % 4u) / 2u);
    }
    let a = square.x;
    let b = square.y;
    var flag = 0u;
    if square_splits(square_contrast(level, a, b), square_hints(level, a, b), level, globals.aa_threshold) {
        flag = 1u;
    }
    split[split_index(level, a, b)] = flag;
    if flag != 0u {
        let slot = atomicAdd(&work_counts[level], 1u);
        work_list[split_offset(tile.side, level) + slot] = pack_square(a, b);
    }
}

// Workgroups (x, y, 1) of an indirect one-dimensional pass over `items` invocations.
fn indirect_workgroups(items: u32) -> vec3<u32> {
    let groups = (items + LINEAR_WORKGROUP_SIZE - 1u) / LINEAR_WORKGROUP_SIZE;
    let x = min(groups, GPU_INDIRECT_MAX_WORKGROUPS);
    return vec3<u32>(x, (groups + GPU_INDIRECT_MAX_WORKGROUPS - 1u) / GPU_INDIRECT_MAX_WORKGROUPS, 1u);
}

// Stores the workgroups of two indirect passes, first then second, as the six words at
// work_args[at ..] that two dispatches read (a level's in adaptive_work_args, a
// generation's in the split tracer's args kernel).
fn store_indirect_pair(at: u32, first: vec3<u32>, second: vec3<u32>) {
    work_args[at] = first.x;
    work_args[at + 1u] = first.y;
    work_args[at + 2u] = first.z;
    work_args[at + 3u] = second.x;
    work_args[at + 4u] = second.y;
    work_args[at + 5u] = second.z;
}

// After the decide pass of tile.level (one invocation): the indirect arguments of the
// midpoint pass over the level's list (AA_SPLIT_POINTS per square) and of the next
// level's decide pass (4 children per square), at work_args[6·level ..].
// Mirror of src/tracer/sampling/adaptive.rs::adaptive_work_args — change both.
@compute @workgroup_size(1)
fn adaptive_work_args() {
    let n = atomicLoad(&work_counts[tile.level]);
    let midpoints = indirect_workgroups(AA_SPLIT_POINTS * n);
    let children = indirect_workgroups(4u * n);
    store_indirect_pair(6u * tile.level, midpoints, children);
}

// #if !WAVEFRONT
// Midpoint pass of tile.level: point idx mod AA_SPLIT_POINTS of entry idx div
// AA_SPLIT_POINTS of the level's list (midpoint_to_trace), unless another invocation
// traces it or the child has no centre.
// Mirror of src/tracer/sampling/adaptive.rs::adaptive_midpoints — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn adaptive_midpoints(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let idx = linear_index(id, groups);
    let level = tile.level;
    if idx >= AA_SPLIT_POINTS * atomicLoad(&work_counts[level]) {
        return;
    }
    let point = midpoint_to_trace(level, idx);
    if point.z == 0u {
        return;
    }
    begin_lane(idx);
    trace_lattice_point(point.x, point.y);
}
// #endif

// The lattice point that invocation idx of level `level`'s midpoint pass traces, in xy,
// and in z whether it traces one: point idx mod AA_SPLIT_POINTS of entry idx div
// AA_SPLIT_POINTS of the level's list — its top, left, right and bottom edge midpoints,
// then the centres of its top-left, top-right, bottom-left and bottom-right children
// where those have centres (square_has_centre); its own centre was traced with its
// corners. A top (left) midpoint is the bottom (right) one of the square above (to the
// left); when that one is split, it traces it. Both forms' midpoint passes take it:
// adaptive_midpoints here and the hardware variant's lattice passes (lattice_pass_point).
// Mirror of src/tracer/sampling/adaptive.rs::midpoint_to_trace — change both.
fn midpoint_to_trace(level: u32, idx: u32) -> vec3<u32> {
    let m = idx % AA_SPLIT_POINTS;
    let square = split_square(level, idx / AA_SPLIT_POINTS);
    let a = square.x;
    let b = square.y;
    let top_traced = m == 0u && b > 0u && is_split(level, a, b - 1u);
    let left_traced = m == 1u && a > 0u && is_split(level, a - 1u, b);
    let no_centre = m >= 4u && !square_has_centre(level + 1u);
    if top_traced || left_traced || no_centre {
        return vec3<u32>(0u);
    }
    let l = adaptive_scale() >> level;
    let h = l / 2u;
    let q = l / 4u;
    // Edges (h, 0), (0, h), (l, h), (h, l); child k = m − 4's centre
    // (q + h·(k mod 2), q + h·(k div 2)).
    let k = m - 4u;
    let ox = select(select(select(h, l, m == 2u), 0u, m == 1u), q + h * (k & 1u), m >= 4u);
    let oy = select(select(select(h, l, m == 3u), 0u, m == 0u), q + h * (k >> 1u), m >= 4u);
    return vec3<u32>(a * l + ox, b * l + oy, 1u);
}

// Integrate pass: pixel (id.x, id.y)'s area-weighted mean over its quadtree, walked depth
// first without a stack: a split square's children in the order bottom-right,
// bottom-left, top-right, top-left (next_square), the sum in that walk's order (a leaf
// with a centre: the quincunx_mean of its corners and centre; one of the deepest level:
// the mean of its corners; each weighted by its area);
// alpha holds its number of leaves. (A private stack indexed at run time costs llvmpipe
// per-lane scatters and gathers: docs/gpu.md#the-kernel-variant-chosen-from-the-adapter.)
// Mirror of src/tracer/sampling/adaptive.rs::adaptive_integrate — change both.
@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE)
fn adaptive_integrate(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= tile.size.x || id.y >= tile.size.y {
        return;
    }
    let depth = globals.aa_depth;
    // (level, a, b)
    var sq = vec3<u32>(0u, id.x, id.y);
    var sum = vec3<f32>(0.0);
    var leaves = 0u;
    loop {
        let level = sq.x;
        let a = sq.y;
        let b = sq.z;
        if level < depth && is_split(level, a, b) {
            sq = vec3<u32>(level + 1u, 2u * a + 1u, 2u * b + 1u);
            continue;
        }
        let c = square_corners(level, a, b);
        leaves += 1u;
        let side = ldexp(1.0, -i32(level));
        let area = side * side;
        if square_has_centre(level) {
            let centre = square_centre(level, a, b);
            sum += quincunx_mean(c, lattice_point(centre.x, centre.y)) * area;
        } else {
            sum += (c[0] + c[1] + c[2] + c[3]) * (0.25 * area);
        }
        sq = next_square(level, a, b);
        if sq.x == 0u {
            break;
        }
    }
    output[id.y * tile.side + id.x] = vec4<f32>(sum, f32(leaves));
}

// The square the integrate walk visits after the subtree of square (level, a, b): its
// next sibling (bottom-right → bottom-left → top-right → top-left), or after a top-left
// child its parent's next; level 0 when the pixel's walk is over.
// Mirror of src/tracer/sampling/adaptive.rs::next_square — change both.
fn next_square(level: u32, a: u32, b: u32) -> vec3<u32> {
    var sq = vec3<u32>(level, a, b);
    while sq.x > 0u && (sq.y & 1u) == 0u && (sq.z & 1u) == 0u {
        sq = vec3<u32>(sq.x - 1u, sq.y / 2u, sq.z / 2u);
    }
    if sq.x == 0u {
        return sq;
    }
    if (sq.y & 1u) == 1u {
        return vec3<u32>(sq.x, sq.y - 1u, sq.z);
    }
    return vec3<u32>(sq.x, sq.y + 1u, sq.z - 1u);
}
