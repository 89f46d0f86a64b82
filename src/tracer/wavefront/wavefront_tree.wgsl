// wavefront_tree.wgsl — the wavefront kernels' pieces for scenes with refraction, where a
// dielectric's hit spawns two rays and a sample's paths form a tree (appended to the
// render module with wavefront.wgsl where src/gpu/compile/shader.rs::wavefront_kernels holds and
// the scene has REFRACTION):
// - path entries carry their medium stack and their pending count P (the entries under
//   them on trace_ray's stack when they would be popped): wavefront_shade pushes a hit's
//   children with push_secondary_rays onto a stack whose size starts at P, so a child's P
//   is the index it was pushed at and the rays trace_ray drops are dropped;
// - the vertex tree: generation g's path i is vertex base_g + i (base_g: a counter the
//   args kernel keeps); each vertex keeps its value (wavefront_gather: weight × its colour,
//   the camera vertex's colour as it is) and its two children in push order (transmitted,
//   then reflected), kept to the end of the chunk;
// - the fold (wavefront_fold, after the last generation): per sample, trace_ray's own
//   loop over a stack of vertex indices, so colour += value runs in its pop order;
// - glass shadow rounds: each shadow request's first leg (wavefront_shadow), then at most
//   MAX_SHADOW_CROSSINGS + 1 rounds of wavefront_leg_closest (traversal) and
//   wavefront_crossing (the opaque test, the normal-incidence transmission, the medium
//   stack, the next leg appended; a request that ends multiplies its slot), with
//   wavefront_leg_args between rounds.
// Queues in `samples` (vec4 entries; N = tile.items samples, C = path_capacity() =
// TREE_PATHS_PER_SAMPLE · N paths a generation, V = TREE_VERTICES_PER_SAMPLE · N
// vertices, L = light points): per sample its record, then per path two path queues
// (with media and pending count), a hit and a vertex, the vertex tree (V), each sample's
// camera vertex (NO_CHILD: none), then per path L light slots, L shadow requests, two
// leg queues of L legs and L leg hits. The records and the regions are specified once in
// src/tracer/wavefront/queues.rs; their accessors (path_pending, write_leg, node_children, …) are
// generated from it into the module (src/tracer/wavefront/queues/wgsl.rs).
// Counters in work_counts (generated from src/tracer/wavefront/queues.rs's COUNTERS): as
// for chains (path_counter, shadow_counter), round r's legs (leg_counter), generation g's
// vertex base (vertex_base_counter; its path i is vertex base + i), the scene's light
// points (tree_points_word: written by the camera pass, for the shadow pass and the
// rounds' kernels, whose regions lie after L-sized ones). Indirect arguments in work_args: round r's
// legs at leg_args(r) = 3r (r < 10), generation g's pair (next paths, requests) at
// tree_generation_args(g) = 30 + 6g (generated with the counters from
// src/tracer/wavefront/queues/counters.rs, whose Rust functions of those names the host's plan reads).
// Overflow: a generation holds at most C paths and the tree TREE_VERTICES_PER_SAMPLE · N
// vertices. A child that finds no room is not appended and its sample's guard flag is set:
// the host renders that pixel with the CPU tracer (src/gpu/render.rs::scatter), so no ray
// trace_ray traces is lost from the image.
// Mirror of src/tracer/wavefront/wavefront_tree.rs — change both.

// #if REFRACTION
// The scene's light points into their counter (tree_points), by invocation 0 of a camera
// pass (wavefront_camera, wavefront_lattice_camera), none of whose invocations reads it.
// Not in the shadow pass, whose every invocation reads it (store_leg): there its other
// workgroups — other threads on lavapipe — could read it before invocation 0 wrote it and
// put their legs at the wrong place (tests/gpu/gpu_wavefront_tree.rs, several chunks).
// `base`: where the wavefront's counters start in work_counts as the pass binds it (the
// lattice camera binds it whole: WAVEFRONT_WORK_BASE).
fn note_tree_points(base: u32) {
    atomicStore(&work_counts[base + tree_points_word()], light_points());
}

// The scene's light points, as the camera pass noted them (note_tree_points; the CPU's
// Batch::light_points, which its camera_pass notes).
fn tree_points() -> u32 {
    return atomicLoad(&work_counts[tree_points_word()]);
}

// The rays the hit of path i (vertex base_g + i, sample k) spawns, pushed as trace_ray
// pushes them onto its stack, which holds the path's pending entries then: so the same
// rays are dropped where the stack is full, and each child's pending count is its index
// in that stack. Each is appended to the next generation's queue and linked as the
// vertex's child, where the queue and the tree have room (else the sample's guard flag).
// Mirror of src/tracer/wavefront/wavefront_tree.rs::push_tree_children — change both.
fn push_tree_children(i: u32, entry: StackEntry, k: u32, shaded: ShadedHit, hit: Hit) {
    let g = tile.level;
    let parity = g % 2u;
    let pending = path_pending(parity, i);
    var stack: RayStack;
    var size = pending;
    push_secondary_rays(&stack, &size, entry, shaded, hit);
    let base = atomicLoad(&work_counts[vertex_base_counter(g)]);
    let next_base = base + atomicLoad(&work_counts[path_counter(g)]);
    let room = next_generation_room(next_base);
    for (var q = pending; q < size; q++) {
        let j = atomicAdd(&work_counts[path_counter(g + 1u)], 1u);
        if j >= room {
            // No room: the host renders this sample's pixel on the CPU.
            sample_without_room(k);
            continue;
        }
        store_path(1u - parity, j, load_pending(&stack, q), q, k);
        set_node_children_component(base + i, q - pending, next_base + j);
    }
}

// Sample k has a child without room: the guard flag of its chunk pixel — under uniform AA
// (a render) pixel k div n² (the camera pass's strata), else pixel k (AA none, glint
// view's frame) — or, adaptive AA's lattice sample, its record's SAMPLE_NO_ROOM (its
// store pass flags the pixels around its point).
fn sample_without_room(k: u32) {
    if tile.stratum == ALL_STRATA && globals.aa_mode == AA_ADAPTIVE {
        set_sample_flags(k, sample_flags(k) | SAMPLE_NO_ROOM);
        return;
    }
    var p = k;
    if tile.stratum == ALL_STRATA && globals.aa_mode == AA_UNIFORM {
        p = k / (globals.aa_samples * globals.aa_samples);
    }
    guard[(p / tile.size.x) * tile.side + p % tile.size.x] = 1u;
}

// Paths the next generation may hold when its vertices start at next_base: the queue's
// capacity, or what the tree has left.
fn next_generation_room(next_base: u32) -> u32 {
    return min(path_capacity(), TREE_VERTICES_PER_SAMPLE * tile.items - next_base);
}

// After generation tile.level's shade pass (one invocation, wavefront_args with
// refraction): the next generation's count cut to its room and its vertex base, the
// indirect workgroups of its passes and of this generation's shadow pass and first
// round (every request's first leg), the counters of generation g − 1 cleared for g + 1.
// Mirror of src/tracer/wavefront/wavefront.rs::wavefront_args (a tree's) — change both.
fn tree_generation_args_entry() {
    let g = tile.level;
    let next_base = atomicLoad(&work_counts[vertex_base_counter(g)]) + atomicLoad(&work_counts[path_counter(g)]);
    let next = min(atomicLoad(&work_counts[path_counter(g + 1u)]), next_generation_room(next_base));
    atomicStore(&work_counts[path_counter(g + 1u)], next);
    atomicStore(&work_counts[vertex_base_counter(g + 1u)], next_base);
    let requests = atomicLoad(&work_counts[shadow_counter(g)]);
    store_indirect_pair(tree_generation_args(g), indirect_workgroups(next), indirect_workgroups(requests));
    atomicStore(&work_counts[leg_counter(0u)], requests);
    atomicStore(&work_counts[leg_counter(1u)], 0u);
    store_leg_args(0u, requests);
    atomicStore(&work_counts[path_counter(g + 2u)], 0u);
    atomicStore(&work_counts[shadow_counter(g + 1u)], 0u);
}

// Round r's indirect workgroups over `legs` legs (with CSG at most C invocations, each
// with a list slot: see wavefront_leg_closest).
fn store_leg_args(r: u32, legs: u32) {
    var invocations = legs;
// #if CSG
    invocations = min(legs, path_capacity());
// #endif
    let groups = indirect_workgroups(invocations);
    let at = leg_args(r);
    work_args[at] = groups.x;
    work_args[at + 1u] = groups.y;
    work_args[at + 2u] = groups.z;
}

// Appends request r's `leg` to the next round's queue (round tile.level + 1).
// Mirror of src/tracer/wavefront/wavefront_tree.rs::LegQueue::append_leg — change both.
fn append_leg(r: u32, leg: ShadowLeg) {
    let l = atomicAdd(&work_counts[leg_counter(tile.level + 1u)], 1u);
    write_leg(tree_points(), 1u - tile.level % 2u, l, leg.start, leg.transmittance, leg.media, r);
}

// Leg l of round parity `parity`'s queue (the CPU's LegQueue::load_leg).
fn load_leg(parity: u32, l: u32) -> ShadowLeg {
    let points = tree_points();
    return ShadowLeg(leg_start(points, parity, l), leg_transmittance(points, parity, l), leg_media(points, parity, l));
}

// Shadow request r's first leg (wavefront_shadow with refraction; round 0's leg r): from
// its vertex's shadow origin, in the media of the vertex's path.
// Mirror of src/tracer/wavefront/wavefront_tree.rs::start_shadow_leg — change both.
fn start_shadow_leg(r: u32) {
    let points = tree_points();
    let i = request_slot(points, r) / points;
    write_leg(points, 0u, r, vertex_shadow_origin(i), 1.0, path_media(tile.level % 2u, i), r);
}

// Request r's light point and its vertex's magnitude.
// Mirror of src/tracer/wavefront/wavefront_tree.rs::request_target — change both.
fn request_target(r: u32) -> vec4<f32> {
    let points = tree_points();
    let i = request_slot(points, r) / points;
    return vec4<f32>(request_position(points, r), vertex_magnitude(i));
}

// Round tile.level's closest pass: each live leg's ray to the first surface short of
// its light point. With CSG, whose interval lists take a list slot per invocation (C of
// them), at most C invocations, each a grid-stride loop over legs idx, idx + C, …
// The loop's test reads the round's leg count again each turn (no kernel of the pass
// changes it) and holds no early return around the loop: RADV then keeps neither the
// count nor an exec mask live across closest_hit, which in wave64 spilled 2 SGPRs
// (csg.lua) and 10 (scrabble.lua) with the count and the return held
// (docs/journal/2026-12-02-leg-closest-registers.md).
// Mirror of src/tracer/wavefront/wavefront_tree.rs::wavefront_leg_closest — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn wavefront_leg_closest(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let idx = linear_index(id, groups);
// #if CSG
    begin_lane(idx);
    for (var l = idx; idx < path_capacity() && l < atomicLoad(&work_counts[leg_counter(tile.level)]); l += path_capacity()) {
        leg_closest_entry(l);
    }
// #else
    let count = atomicLoad(&work_counts[leg_counter(tile.level)]);
    if idx >= count {
        return;
    }
    leg_closest_entry(idx);
// #endif
}

// Leg l's closest hit, stored at its index.
// Mirror of src/tracer/wavefront/wavefront_tree.rs::leg_closest_entry — change both.
fn leg_closest_entry(l: u32) {
    let parity = tile.level % 2u;
    // Where the hit goes, found before the traversal: one index live across it rather
    // than the light points and l (with CSG this spared RADV's last 2 spilled SGPRs in
    // wave64; reading the light points again after it spilled 2 in scrabble.lua's).
    let at = leg_hit_entry(tree_points(), l);
    let light = request_target(leg_request(tree_points(), parity, l));
    let leg_ray = shadow_leg_ray(load_leg(parity, l), light.xyz, light.w);
    let hit = closest_hit(leg_ray.ray, leg_ray.reach);
    write_leg_hit_at(at, hit.t, hit.item, hit.b1, hit.b2, hit.part);
}

// Round tile.level's crossing step, one leg an invocation.
// Mirror of src/tracer/wavefront/wavefront_tree.rs::wavefront_crossing — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn wavefront_crossing(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let idx = linear_index(id, groups);
    let count = atomicLoad(&work_counts[leg_counter(tile.level)]);
// #if CSG
    // The closest pass's dispatch shape (at most C invocations).
    if idx >= path_capacity() {
        return;
    }
    for (var l = idx; l < count; l += path_capacity()) {
        crossing_entry(l, load_leg_hit(tree_points(), l), tile.level);
    }
// #else
    if idx >= count {
        return;
    }
    crossing_entry(idx, load_leg_hit(tree_points(), idx), tile.level);
// #endif
}

// Leg l's crossing `crossing`, whose closest hit is `hit`: a miss ends its request with
// the transmittance so far, an opaque surface (or the crossing after the last) with 0;
// glass appends the next leg.
// Mirror of src/tracer/wavefront/wavefront_tree.rs::crossing_entry — change both.
fn crossing_entry(l: u32, hit: Hit, crossing: u32) {
    let parity = crossing % 2u;
    let r = leg_request(tree_points(), parity, l);
    let leg = load_leg(parity, l);
    if !is_hit(hit) {
        end_request(r, leg.transmittance);
        return;
    }
    let light = request_target(r);
    let leg_ray = shadow_leg_ray(leg, light.xyz, light.w);
    let beyond = cross_shadow_surface(leg_ray.ray, hit, crossing, leg);
    if beyond.blocked {
        end_request(r, 0.0);
        return;
    }
    append_leg(r, beyond.leg);
}

// Request r's slot × its transmittance (shade.wgsl's shadowed_term: point_light's last
// product), once, when its last leg ends.
// Mirror of src/tracer/wavefront/wavefront_tree.rs::end_request — change both.
fn end_request(r: u32, transmittance: f32) {
    let slot = request_slot(tree_points(), r);
    write_slot(slot, shadowed_term(slot_term(slot), transmittance));
}

// After round tile.level's crossing step (one invocation): the next round's indirect
// workgroups, and the counter of the round after it cleared.
// Mirror of src/tracer/wavefront/wavefront_tree.rs::wavefront_leg_args — change both.
@compute @workgroup_size(1)
fn wavefront_leg_args() {
    let r = tile.level;
    store_leg_args(r + 1u, atomicLoad(&work_counts[leg_counter(r + 1u)]));
    atomicStore(&work_counts[leg_counter(r + 2u)], 0u);
}

// The fold pass (after the chunk's last generation), sample k = idx: its colour from its
// vertex tree, into its record (for uniform AA's resolve and glint view's store, as
// wavefront_gather leaves a chain's) and, a render under AA none, the chunk's output pixel.
// Mirror of src/tracer/wavefront/wavefront_tree.rs::wavefront_fold — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn wavefront_fold(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = linear_index(id, groups);
    if k >= tile.items {
        return;
    }
    let vertex = camera_vertex_index(k);
    if vertex == NO_CHILD {
        return;
    }
    let colour = fold_entry(vertex);
    set_sample_colour(k, colour);
    // A render under AA none: sample k is chunk pixel k (row-major over size, rows at
    // stride side).
    if globals.aa_mode == AA_NONE && tile.stratum == ALL_STRATA {
        output[(k / tile.size.x) * tile.side + k % tile.size.x] = vec4<f32>(colour, 1.0);
    }
}

// The colour of the sample whose camera vertex is vertex k: trace_ray's running sum over its
// stack — the camera vertex's value, then each vertex as it pops, its children pushed in
// push order (so the reflected subtree is summed before the transmitted one).
// Mirror of src/tracer/wavefront/wavefront_tree.rs::fold_entry — change both.
fn fold_entry(k: u32) -> vec3<f32> {
    var stack: array<u32, RAY_STACK_SIZE>;
    var size = 0u;
    var colour = node_value(k);
    push_children(k, &stack, &size);
    while size > 0u {
        size -= 1u;
        let vertex = stack[size];
        colour += node_value(vertex);
        push_children(vertex, &stack, &size);
    }
    return colour;
}

// Pushes vertex's children onto the fold's stack in the order shade appended them.
// Mirror of src/tracer/wavefront/wavefront_tree.rs::push_children — change both.
fn push_children(vertex: u32, stack: ptr<function, array<u32, RAY_STACK_SIZE>>, size: ptr<function, u32>) {
    let children = node_children(vertex);
    for (var c = 0u; c < 2u; c++) {
        let child = children[c];
        if child != NO_CHILD {
            (*stack)[*size] = child;
            *size += 1u;
        }
    }
}
// #endif
