// wavefront.wgsl — the wavefront form of trace_ray for scenes without refraction (every
// path a chain), in the hardware kernel variant (WAVEFRONT: src/gpu/compile/shader.rs): a chunk's
// samples go through kernels joined by queues instead of one megakernel. Its samples:
// AA none's pixel centres, uniform AA's n² jittered strata a pixel (wavefront_resolve
// averages them after the last generation), or one stratum a pixel, tile.stratum (glint
// view's frame; progressive.wgsl's wavefront_view_store adds it to the sums). Per chunk,
// wavefront_camera fills generation 0's path queue; per generation g (tile.level)
// wavefront_closest traces each path to its hit, wavefront_shade (wavefront_shade.wgsl)
// shades each hit without tracing (its own term, one shadow request per light point
// facing it with the point's unshadowed term in the vertex's slot, the reflected ray
// appended to generation g + 1's queue), wavefront_args turns the counters into the
// indirect workgroup counts of the shadow pass and of the next generation,
// wavefront_shadow (wavefront_shadow.wgsl) traces each request (any hit) and zeroes the
// slot of a blocked one, and wavefront_gather (wavefront_gather.wgsl) sums each vertex's
// colour in shade_phong's order into its sample's colour (and, AA none, the chunk's output).
// Queues are filled by atomicAdd in any order: every entry carries its sample, and every
// sum runs in one invocation in the CPU's order, so the image is trace_ray's bit for bit.
// The queues, their accessors and their counters: batch.wgsl. Counters in work_counts
// (adaptive.wgsl's binding): generation g's paths at path_counter(g), its shadow requests
// at shadow_counter(g) (wavefront_args clears the ones the next generation appends to);
// indirect arguments in work_args, 6 words a generation (with CSG 3 + 3L: the shadow
// pass's slices, see wavefront_shadow).
// Mirror of src/tracer/wavefront/wavefront.rs — change both.

// #if WAVEFRONT
// #if REFRACTION
// With refraction (this module) paths are trees: the regions, the vertex tree, the glass
// shadow rounds and the fold are wavefront_tree.wgsl's; the blocks under `#if REFRACTION`
// below hand over to it. (The header above stays as chain modules compile it.)
// #endif
// The camera pass, sample k = idx of the chunk: in a render (tile.stratum = ALL_STRATA)
// stratum k mod n² of chunk pixel k div n², in glint view's frame stratum tile.stratum of
// chunk pixel k (pixels row-major over size, at stride size.x), n = globals.aa_samples
// under uniform AA (jittered), 1 under AA none (the pixel's centre): its record, and its
// camera ray as generation 0's path k.
// Mirror of the Strata and Stratum sources of src/tracer/wavefront/wavefront.rs::wavefront_camera — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn wavefront_camera(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = linear_index(id, groups);
    if k == 0u {
        atomicStore(&work_counts[path_counter(0u)], tile.items);
// #if REFRACTION
        note_tree_points(0u);
// #endif
    }
    if k >= tile.items {
        return;
    }
    let uniform = globals.aa_mode == AA_UNIFORM;
    let n = select(1u, globals.aa_samples, uniform);
    var p = k;
    var s = tile.stratum;
    if s == ALL_STRATA {
        p = k / (n * n);
        s = k % (n * n);
    }
    let stratum = stratum_position(tile.origin.x + p % tile.size.x, tile.origin.y + p / tile.size.x, s, n, uniform);
    // Path k (a tree's vertex k).
    start_sample(k, k, stratum.fx, stratum.fy, stratum.seed);
}

// Sample k's record (its seed; no colour or items yet) and its camera ray at (fx, fy),
// which starts in the media around the camera (camera_entry), as generation 0's path
// `at` — in a tree also the sample's camera vertex — with nothing under it on
// trace_ray's stack. Both camera passes (wavefront_camera, wavefront_lattice_camera)
// start their samples with it.
// Mirror of src/tracer/wavefront/wavefront.rs::start_sample — change both.
fn start_sample(k: u32, at: u32, fx: f32, fy: f32, seed: SampleSeed) {
    var flags = 0u;
    if seed.mirrors_corners {
        flags = SAMPLE_MIRRORS_CORNERS;
    }
    write_sample(k, vec3<f32>(0.0), NO_ITEM, NO_ITEM, flags, seed.pixel, seed.sample);
// #if DEPTH_OF_FIELD
    let entry = camera_entry(thin_lens_ray(camera_ray(fx, fy), lens_position(seed)));
// #else
    let entry = camera_entry(camera_ray(fx, fy));
// #endif
// #if REFRACTION
    write_camera_vertex(k, at);
// #endif
    store_path(0u, at, entry, 0u, k);
}

// The closest pass's invocation for path idx of generation tile.level: its hit, and the
// items a sample's hint keeps. Only the ray is live across closest_hit: the path's depth
// and sample are read after the hit record is stored (a store the compiler cannot tell
// apart from them, so it reloads them rather than keeping the first load's registers),
// which keeps textures.lua's kernel within the traversal budget of 96 VGPRs on NAVI21
// (112 in wave32, 104 in wave64 with the depth held through the traversal;
// docs/journal/2026-12-02-textures-closest-kernel.md).
// Mirror of src/tracer/wavefront/wavefront.rs::wavefront_closest — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn wavefront_closest(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    let g = tile.level;
    if i >= atomicLoad(&work_counts[path_counter(g)]) {
        return;
    }
    begin_lane(i);
    let parity = g % 2u;
    let hit = closest_hit(load_path(parity, i).ray, T_MISS);
    write_hit(i, hit.t, hit.item, hit.b1, hit.b2, hit.part);
    let depth = path_depth(parity, i);
    let k = path_sample(parity, i);
    if depth == 0u {
        set_sample_camera_item(k, hit.item);
    }
    if (sample_flags(k) & SAMPLE_CAMERA_MIRROR) != 0u && depth == 1u {
        // The one ray a mirror spawns: what the camera sees in it.
        set_sample_mirrored_item(k, hit.item);
    }
}

// After generation tile.level's shade pass (one invocation): the indirect workgroups of
// the next generation's passes (work_args[6g ..]) and of this generation's shadow pass
// (work_args[6g + 3 ..]; with CSG a generation's words are 3 + 3L, its slices' from
// 3 on, see wavefront_shadow), and the
// counters of generation g − 1 cleared for generation g + 1.
// Mirror of src/tracer/wavefront/wavefront.rs::wavefront_args — change both.
@compute @workgroup_size(1)
fn wavefront_args() {
// #if REFRACTION
    tree_generation_args_entry();
// #else
    let g = tile.level;
    let next = indirect_workgroups(atomicLoad(&work_counts[path_counter(g + 1u)]));
    let shadow_requests = atomicLoad(&work_counts[shadow_counter(g)]);
// #if CSG
    // One slice of at most N requests per light point (see wavefront_shadow): a
    // generation's 3 + 3L words, the next generation's passes', then slice s's at 3 + 3s.
    // The slices, L, from the host (tile.slice of this dispatch: plan.rs).
    let slices = tile.slice;
    let at = (3u + 3u * slices) * g;
    let first = indirect_workgroups(min(shadow_requests, tile.items));
    store_indirect_pair(at, next, first);
    for (var s = 1u; s < slices; s++) {
        let groups = indirect_workgroups(min(shadow_requests - min(shadow_requests, s * tile.items), tile.items));
        work_args[at + 3u + 3u * s] = groups.x;
        work_args[at + 4u + 3u * s] = groups.y;
        work_args[at + 5u + 3u * s] = groups.z;
    }
// #else
    store_indirect_pair(6u * g, next, indirect_workgroups(shadow_requests));
// #endif
    atomicStore(&work_counts[path_counter(g + 2u)], 0u);
    atomicStore(&work_counts[shadow_counter(g + 1u)], 0u);
// #endif
}

// Uniform AA, after the chunk's last generation: each chunk pixel's mean over its n²
// samples' colours (pixel p's samples are p·n² … p·n² + n² − 1), summed in sample order
// and divided by n² as render.wgsl's uniform_resolve does (the megakernel's image).
// Mirror of src/tracer/wavefront/wavefront.rs::wavefront_resolve — change both.
@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE)
fn wavefront_resolve(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= tile.size.x || id.y >= tile.size.y {
        return;
    }
    let nn = globals.aa_samples * globals.aa_samples;
    let first = (id.y * tile.size.x + id.x) * nn;
    var sum = vec3<f32>(0.0);
    for (var s = 0u; s < nn; s++) {
        sum += sample_colour(first + s);
    }
    output[id.y * tile.side + id.x] = vec4<f32>(sum / f32(nn), 1.0);
}
// #endif
