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
// alignment WebGPU allows an adapter), where the plan binds them.
// Mirror of src/gpu/plan/adaptive.rs::lattice_queue_base — change both.
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

// The lattice point invocation idx of lattice pass `lattice_pass` traces (xy), and whether it
// traces one (z).
// Mirror of src/tracer/wavefront/wavefront_lattice.rs::lattice_pass_point — change both.
fn lattice_pass_point(lattice_pass: u32, idx: u32) -> vec3<u32> {
    if lattice_pass == 0u {
        return vec3<u32>(corner_to_trace(idx), 1u);
    }
    return midpoint_to_trace(lattice_pass - 1u, idx);
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
    let at = atomicAdd(&work_counts[WAVEFRONT_WORK_BASE + path_counter(0u)], 1u);
    start_sample(idx, at, jittered.fx, jittered.fy, jittered.seed);
}

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
        // Every counter of the layout (generated from the queue specification,
        // src/tracer/wavefront/queues.rs's COUNTERS): a chain's path and shadow counters; a
        // tree's also its leg counters, vertex bases and the light points word (which the
        // next lattice pass's camera pass notes again).
        for (var c = 0u; c < counter_words(); c++) {
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
