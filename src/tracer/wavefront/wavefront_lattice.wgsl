// wavefront_lattice.wgsl — adaptive AA's tracing passes (the corner pass and each level's
// midpoint pass: adaptive.wgsl's adaptive_corners and adaptive_midpoints, whose points
// they enumerate alike) through the wavefront kernels, in the hardware kernel variant
// (WAVEFRONT). Lattice pass tile.level is 0 for the corner pass, 1 + k for level k's
// midpoint pass. Per lattice pass, wavefront_lattice_camera starts sample idx for the
// lattice point invocation idx traces (its record at idx, its camera ray at the point's
// jittered position with the point's seed, as lattice_sample takes them, appended to
// generation 0's path queue), the generations run as for AA none (wavefront.wgsl: closest,
// shade, args, shadow, gather), and wavefront_lattice_store writes each sample's colour
// and hint (encode_hint) into its lattice point, as trace_lattice_point would have.
// Layout: the tile's lattice from the start of `samples`, the wavefront's queues from
// lattice_queue_base(); its counters and indirect arguments from word
// WAVEFRONT_WORK_BASE of work_counts and byte 4·WAVEFRONT_WORK_BASE of work_args, after
// adaptive AA's levels'. The generations' dispatches bind `samples`, work_counts and
// work_args from those offsets (src/gpu/plan/adaptive.rs), so wavefront.wgsl indexes them from 0
// as for AA none; the camera pass binds `samples` from the queues and work_counts whole
// (it reads the level's count), the store pass both whole.
// Mirror of src/tracer/wavefront/wavefront_lattice.rs — change both.

// #if WAVEFRONT
// Where the wavefront's queues start in `samples` (vec4 entries): after the tile's
// lattice, at a multiple of 16 entries (256 bytes, the coarsest storage-binding offset
// alignment WebGPU allows an adapter). src/gpu/plan/adaptive.rs::lattice_queue_bytes is the same.
fn lattice_queue_base() -> u32 {
    let width = tile.side * adaptive_scale() + 1u;
    return (width * width + 15u) / 16u * 16u;
}

// The invocations of lattice pass `lattice_pass`: the corner pass's (corners, then centres at
// depth ≥ 1: src/tiling.rs::AdaptiveTile::first_pass_len), or AA_SPLIT_POINTS per square
// on level lattice_pass − 1's list.
// Mirror of src/tracer/wavefront/wavefront_lattice.rs::lattice_pass_len — change both.
fn lattice_pass_len(lattice_pass: u32) -> u32 {
    if lattice_pass == 0u {
        let corners = (tile.size.x + 1u) * (tile.size.y + 1u);
        return corners + select(0u, tile.size.x * tile.size.y, globals.aa_depth >= 1u);
    }
    return AA_SPLIT_POINTS * atomicLoad(&work_counts[lattice_pass - 1u]);
}

// The lattice point invocation idx of the corner pass traces: pixel corner
// (idx mod (w+1), idx div (w+1)) for idx < (w+1)(h+1), after those the centre of pixel
// number idx − (w+1)(h+1) (adaptive_corners' points).
// Mirror of src/tracer/wavefront/wavefront_lattice.rs::corner_pass_point — change both.
fn corner_pass_point(idx: u32) -> vec2<u32> {
    let s = adaptive_scale();
    let corners = (tile.size.x + 1u) * (tile.size.y + 1u);
    if idx < corners {
        return vec2<u32>((idx % (tile.size.x + 1u)) * s, (idx / (tile.size.x + 1u)) * s);
    }
    let pixel = idx - corners;
    return square_centre(0u, pixel % tile.size.x, pixel / tile.size.x);
}

// The lattice point invocation idx of level `level`'s midpoint pass traces, in xy, and in
// z whether it traces one (adaptive_midpoints' points): point idx mod AA_SPLIT_POINTS of
// entry idx div AA_SPLIT_POINTS of the level's list, its top, left, right and bottom edge
// midpoints, then its children's centres where those have centres; none for a top (left)
// midpoint that the split square above (to the left) traces.
// Mirror of src/tracer/wavefront/wavefront_lattice.rs::midpoint_pass_point — change both.
fn midpoint_pass_point(level: u32, idx: u32) -> vec3<u32> {
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

// The lattice point invocation idx of lattice pass `lattice_pass` traces (xy), and whether it
// traces one (z).
// Mirror of src/tracer/wavefront/wavefront_lattice.rs::lattice_pass_point — change both.
fn lattice_pass_point(lattice_pass: u32, idx: u32) -> vec3<u32> {
    if lattice_pass == 0u {
        return vec3<u32>(corner_pass_point(idx), 1u);
    }
    return midpoint_pass_point(lattice_pass - 1u, idx);
}

// The camera pass of lattice pass tile.level, sample idx: where its invocation traces a
// point, the sample's record (at idx) and its camera ray at the point's jittered
// position (lattice_jitter, lattice_sample's) appended to generation 0's queue, whose
// counter the previous store pass (or the tile's start) cleared. `samples` is bound from
// the queues.
// Mirror of src/tracer/wavefront/wavefront_lattice.rs::wavefront_lattice_camera, one invocation of its loop — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn wavefront_lattice_camera(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let idx = linear_index(id, groups);
    let lattice_pass = tile.level;
// #if REFRACTION
    if idx == 0u {
        note_tree_points(WAVEFRONT_WORK_BASE);
    }
    // The fold runs over this pass's invocations: none of a sample without a point.
    if idx < tile.items {
        write_camera_vertex(idx, NO_CHILD);
    }
// #endif
    if idx >= lattice_pass_len(lattice_pass) {
        return;
    }
    let point = lattice_pass_point(lattice_pass, idx);
    if point.z == 0u {
        return;
    }
    let position = lattice_position(point.x, point.y);
    let jittered = lattice_jitter(position.x, position.y);
    let seed = jittered.seed;
    var flags = 0u;
    if seed.mirrors_corners {
        flags = SAMPLE_MIRRORS_CORNERS;
    }
    write_sample(idx, vec3<f32>(0.0), NO_ITEM, NO_ITEM, flags, seed.pixel, seed.sample);
    let ray = camera_ray(jittered.position.x, jittered.position.y);
    var entry: StackEntry;
    entry.ray = ray;
    entry.weight = vec3<f32>(1.0);
    entry.depth = 0u;
// #if TEXTURE|BUMP
    entry.cone = camera_cone(ray);
// #endif
// #if REFRACTION
    // Camera rays start in the media around the camera (a tree's camera pass).
    entry.media = camera_medium_stack();
// #endif
    let at = atomicAdd(&work_counts[WAVEFRONT_WORK_BASE], 1u);
// #if REFRACTION
    write_camera_vertex(idx, at);
// #endif
    store_path(0u, at, entry, 0u, idx);
}

// #if REFRACTION
// The guard flags of every pixel whose closed square holds lattice point (i, j).
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

// The store pass of lattice pass tile.level, sample idx: the sample's colour and, in w,
// its hint (encode_hint of the camera item's key, mixed with the mirrored item's, and
// fine detail) into its lattice point. Invocation 0 clears the wavefront's counters for
// the next lattice pass. `samples` is bound whole (the records from lattice_queue_base()).
// Mirror of src/tracer/wavefront/wavefront_lattice.rs::wavefront_lattice_store, with the GPU's counters and guard flags — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn wavefront_lattice_store(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let idx = linear_index(id, groups);
    let lattice_pass = tile.level;
    if idx == 0u {
        // A chain's five counters; a tree's also its leg counters and vertex bases.
        var counters = 5u;
// #if REFRACTION
        counters = 10u;
// #endif
        for (var c = 0u; c < counters; c++) {
            atomicStore(&work_counts[WAVEFRONT_WORK_BASE + c], 0u);
        }
    }
    if idx >= lattice_pass_len(lattice_pass) {
        return;
    }
    let point = lattice_pass_point(lattice_pass, idx);
    if point.z == 0u {
        return;
    }
    // `samples` bound whole: the queues, sample records first, start at
    // lattice_queue_base(), a multiple of SAMPLE_STRIDE (the records' vec4s).
    let k = lattice_queue_base() / SAMPLE_STRIDE + idx;
    let flags = sample_flags(k);
    let fine_detail = (flags & SAMPLE_FINE_DETAIL) != 0u;
// #if REFRACTION
    // A tree without room for a child: every pixel whose closed square holds the point
    // goes to the CPU tracer (as trace_lattice_point's loop-limiter guard).
    if (flags & SAMPLE_NO_ROOM) != 0u {
        guard_lattice_point(point.x, point.y);
    }
// #endif
    let key = sample_item_key(sample_camera_item(k), sample_mirrored_item(k));
    samples[lattice_index(point.x, point.y)] = vec4<f32>(sample_colour(k), encode_hint(SampleHint(fine_detail, key)));
}
// #endif
