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
// Queues in `samples` (vec4 entries; N = tile.items samples, C = TREE_PATHS_PER_SAMPLE · N
// paths a generation, L = light_points()):
//   [0, 2N)                     sample records (as for chains)
//   2N + 5C·p                   path queue of parity p, 5 a path: (origin, sample),
//                               (dir, depth), (weight, cone.x), (cone.y, pending, media
//                               count, 0), (media indices)
//   2N + 10C                    hits, 2 a path;  2N + 12C: vertices, 2 a path
//   2N + 14C                    the vertex tree, 2 a vertex (V = TREE_VERTICES_PER_SAMPLE
//                               · N of them): (value, first child), (second child)
//   2N + 14C + 2V               each sample's camera vertex (x; NO_CHILD: none), 1 a sample
//   S = 3N + 14C + 2V           light slots, L a path;  S + LC: shadow requests
//   S + 2LC + 3LC·p             legs of round parity p, 3 a leg: (start, transmittance),
//                               (media indices), (media count, request)
//   S + 8LC                     the round's leg hits, 2 a leg
// Counters in work_counts: as for chains (paths g mod 3, requests 3 + g mod 2), round r's
// legs at 5 + r mod 3, generation g's vertex base at 8 + g mod 2, the scene's light
// points at 10 (written by the camera pass, for the shadow pass and the rounds' kernels:
// their regions lie after L-sized ones). Indirect arguments in work_args: round r's
// legs at 3r (r < 10), generation g's pair (next paths, requests) at 30 + 6g.
// Overflow: a generation holds at most C paths and the tree TREE_VERTICES_PER_SAMPLE · N
// vertices. A child that finds no room is not appended and its sample's guard flag is set:
// the host renders that pixel with the CPU tracer (src/gpu/render.rs::scatter), so no ray
// trace_ray traces is lost from the image.
// Mirror of src/tracer/wavefront/wavefront_tree.rs — change both.

// #if REFRACTION
// Paths one generation of the chunk may hold.
fn tree_capacity() -> u32 {
    return TREE_PATHS_PER_SAMPLE * tile.items;
}

fn tree_paths(parity: u32) -> u32 {
    return 2u * tile.items + 5u * tree_capacity() * parity;
}

fn tree_hits() -> u32 {
    return 2u * tile.items + 10u * tree_capacity();
}

fn tree_vertices() -> u32 {
    return 2u * tile.items + 12u * tree_capacity();
}

fn tree_nodes() -> u32 {
    return 2u * tile.items + 14u * tree_capacity();
}

fn tree_camera_vertices() -> u32 {
    return tree_nodes() + 2u * TREE_VERTICES_PER_SAMPLE * tile.items;
}

fn tree_slots() -> u32 {
    return tree_camera_vertices() + tile.items;
}

fn tree_shadows(points: u32) -> u32 {
    return tree_slots() + points * tree_capacity();
}

fn tree_legs(parity: u32, points: u32) -> u32 {
    return tree_slots() + (2u + 3u * parity) * points * tree_capacity();
}

fn tree_leg_hits(points: u32) -> u32 {
    return tree_slots() + 8u * points * tree_capacity();
}

// The scene's light points into their counter (tree_points), by invocation 0 of a camera
// pass (wavefront_camera, wavefront_lattice_camera), none of whose invocations reads it.
// Not in the shadow pass, whose every invocation reads it (store_leg): there its other
// workgroups — other threads on lavapipe — could read it before invocation 0 wrote it and
// put their legs at the wrong place (tests/gpu/gpu_wavefront_tree.rs, several chunks).
// `base`: where the wavefront's counters start in work_counts as the pass binds it (the
// lattice camera binds it whole: WAVEFRONT_WORK_BASE).
fn note_tree_points(base: u32) {
    atomicStore(&work_counts[base + 10u], light_points());
}

// Round r's leg counter.
fn leg_counter(r: u32) -> u32 {
    return 5u + r % 3u;
}

// The scene's light points, as the camera pass noted them (note_tree_points; the CPU's
// Batch::light_points, which its camera_pass notes).
fn tree_points() -> u32 {
    return atomicLoad(&work_counts[10u]);
}

// Generation g's vertex base (its path i is vertex base + i).
fn vertex_base_counter(g: u32) -> u32 {
    return 8u + g % 2u;
}

// Where generation g's indirect arguments lie in work_args (words).
fn tree_generation_args(g: u32) -> u32 {
    return 30u + 6u * g;
}

// Where round r's legs' indirect arguments lie in work_args (words).
fn leg_args(r: u32) -> u32 {
    return 3u * r;
}

fn path_pending(parity: u32, i: u32) -> u32 {
    return bitcast<u32>(samples[tree_paths(parity) + 5u * i + 3u].y);
}

fn path_media(parity: u32, i: u32) -> MediumStack {
    let at = tree_paths(parity) + 5u * i;
    let m = samples[at + 4u];
    return MediumStack(array<f32, MEDIUM_STACK_SIZE>(m.x, m.y, m.z, m.w), bitcast<u32>(samples[at + 3u].z));
}

// Path i of parity `parity` as trace_ray's stack holds it.
fn load_tree_path(parity: u32, i: u32) -> StackEntry {
    let at = tree_paths(parity) + 5u * i;
    let a = samples[at];
    let b = samples[at + 1u];
    let c = samples[at + 2u];
    var entry: StackEntry;
    entry.ray = Ray(a.xyz, b.xyz);
    entry.weight = c.xyz;
    entry.depth = bitcast<u32>(b.w);
// #if TEXTURE|BUMP
    entry.cone = vec2<f32>(c.w, samples[at + 3u].x);
// #endif
    entry.media = path_media(parity, i);
    return entry;
}

// Writes `entry` of sample `sample` with pending count `pending` as path i (the CPU's
// PathQueue::store_path).
fn store_tree_path(parity: u32, i: u32, entry: StackEntry, pending: u32, sample: u32) {
    let at = tree_paths(parity) + 5u * i;
    samples[at] = vec4<f32>(entry.ray.origin, bitcast<f32>(sample));
    samples[at + 1u] = vec4<f32>(entry.ray.dir, bitcast<f32>(entry.depth));
    var cone = vec2<f32>(0.0);
// #if TEXTURE|BUMP
    cone = entry.cone;
// #endif
    samples[at + 2u] = vec4<f32>(entry.weight, cone.x);
    samples[at + 3u] = vec4<f32>(cone.y, bitcast<f32>(pending), bitcast<f32>(entry.media.count), 0.0);
    var m = entry.media;
    samples[at + 4u] = vec4<f32>(m.iors[0], m.iors[1], m.iors[2], m.iors[3]);
}

// Vertex v's value, and its children in push order.
fn tree_value(v: u32) -> vec3<f32> {
    return samples[tree_nodes() + 2u * v].xyz;
}

fn tree_children(v: u32) -> vec2<u32> {
    let at = tree_nodes() + 2u * v;
    return vec2<u32>(bitcast<u32>(samples[at].w), bitcast<u32>(samples[at + 1u].x));
}

fn set_tree_value(v: u32, value: vec3<f32>) {
    let at = tree_nodes() + 2u * v;
    samples[at] = vec4<f32>(value, samples[at].w);
}

// Sample k's camera vertex (the camera pass's path of it in generation 0, whose vertex
// base is 0): k itself where the camera pass takes sample k as path k, the path its
// atomicAdd gave it in adaptive AA's lattice camera; NO_CHILD where the sample traces
// nothing (a lattice invocation without a point).
fn tree_camera_vertex(k: u32) -> u32 {
    return bitcast<u32>(samples[tree_camera_vertices() + k].x);
}

fn set_tree_camera_vertex(k: u32, vertex: u32) {
    samples[tree_camera_vertices() + k] = vec4<f32>(bitcast<f32>(vertex), 0.0, 0.0, 0.0);
}

// A vertex childless until its shade step appends children.
fn clear_tree_children(v: u32) {
    let at = tree_nodes() + 2u * v;
    samples[at].w = bitcast<f32>(NO_CHILD);
    samples[at + 1u] = vec4<f32>(bitcast<f32>(NO_CHILD), 0.0, 0.0, 0.0);
}

fn set_tree_child(v: u32, place: u32, child: u32) {
    let at = tree_nodes() + 2u * v;
    if place == 0u {
        samples[at].w = bitcast<f32>(child);
    } else {
        samples[at + 1u].x = bitcast<f32>(child);
    }
}

// The rays the hit of path i (vertex base_g + i, sample k) spawns, pushed as trace_ray
// pushes them onto its stack, which holds the path's pending entries then: so the same
// rays are dropped where the stack is full, and each child's pending count is its index
// in that stack. Each is appended to the next generation's queue and linked as the
// vertex's child, where the queue and the tree have room (else the sample's guard flag).
// Mirror of the tree's part of src/tracer/wavefront/wavefront.rs::push_next_paths — change both.
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
        store_tree_path(1u - parity, j, load_pending(&stack, q), q, k);
        set_tree_child(base + i, q - pending, next_base + j);
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
    return min(tree_capacity(), TREE_VERTICES_PER_SAMPLE * tile.items - next_base);
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
    invocations = min(legs, tree_capacity());
// #endif
    let groups = indirect_workgroups(invocations);
    let at = leg_args(r);
    work_args[at] = groups.x;
    work_args[at + 1u] = groups.y;
    work_args[at + 2u] = groups.z;
}

// A shadow ray's state between the dielectric surfaces it crosses (the CPU's
// dielectric::ShadowLeg).
struct ShadowLeg {
    start: vec3<f32>,
    transmittance: f32,
    media: MediumStack,
}

// A leg's ray toward its light point and how far it looks (shadow_reach).
struct LegRay {
    ray: Ray,
    reach: f32,
}

// What cross_shadow_surface returns: the next leg, or blocked.
struct Crossed {
    leg: ShadowLeg,
    blocked: bool,
}

// Writes request r's leg as leg l of round parity `parity`'s queue.
fn store_leg(parity: u32, l: u32, r: u32, leg: ShadowLeg) {
    let at = tree_legs(parity, tree_points()) + 3u * l;
    var m = leg.media;
    samples[at] = vec4<f32>(leg.start, leg.transmittance);
    samples[at + 1u] = vec4<f32>(m.iors[0], m.iors[1], m.iors[2], m.iors[3]);
    samples[at + 2u] = vec4<f32>(bitcast<f32>(m.count), bitcast<f32>(r), 0.0, 0.0);
}

// Appends request r's `leg` to the next round's queue (round tile.level + 1).
// Mirror of src/tracer/wavefront/wavefront_tree.rs::LegQueue::append_leg — change both.
fn append_leg(r: u32, leg: ShadowLeg) {
    let l = atomicAdd(&work_counts[leg_counter(tile.level + 1u)], 1u);
    store_leg(1u - tile.level % 2u, l, r, leg);
}

// Leg l of round parity `parity`'s queue (the CPU's LegQueue::load_leg).
fn load_leg(parity: u32, l: u32) -> ShadowLeg {
    let at = tree_legs(parity, tree_points()) + 3u * l;
    let a = samples[at];
    let m = samples[at + 1u];
    let media = MediumStack(array<f32, MEDIUM_STACK_SIZE>(m.x, m.y, m.z, m.w), bitcast<u32>(samples[at + 2u].x));
    return ShadowLeg(a.xyz, a.w, media);
}

fn leg_request(parity: u32, l: u32) -> u32 {
    return bitcast<u32>(samples[tree_legs(parity, tree_points()) + 3u * l + 2u].y);
}

// The ray of `leg` toward a light at `position` and its reach (magnitude: the shaded
// surface's): the CPU's dielectric::shadow_leg_ray, which its shadow_transmittance
// shares; dielectric.wgsl's keeps its own lines, so the software variant's module stays
// byte for byte what it was.
fn shadow_leg_ray(leg: ShadowLeg, position: vec3<f32>, magnitude: f32) -> LegRay {
    let to_light = position - leg.start;
    let distance = length(to_light);
    let ray = Ray(leg.start, to_light / distance);
    return LegRay(ray, shadow_reach(leg.start, position, distance, magnitude));
}

// The leg's ray meets a surface at `hit`, its crossing number `crossing`: the next leg,
// beyond the surface and dimmed by its normal_transmission; blocked where the surface is
// opaque or the crossing is MAX_SHADOW_CROSSINGS (the CPU's
// dielectric::cross_shadow_surface; see shadow_leg_ray).
fn cross_shadow_surface(ray: Ray, hit: Hit, crossing: u32, leg: ShadowLeg) -> Crossed {
    let s = surface_at(ray, hit);
    let m = load_material(s.material);
    if (m.flags & MATERIAL_REFRACTIVE) == 0u || crossing == MAX_SHADOW_CROSSINGS {
        return Crossed(leg, true);
    }
    let sides = surface_sides(ray.dir, s.normal, m.ior, leg.media);
    let transmittance = leg.transmittance * normal_transmission(sides.n1, sides.n2);
    // Go on from just beyond the surface.
    let start = offset_ray(s.p, -sides.n, s.magnitude);
    return Crossed(ShadowLeg(start, transmittance, sides.beyond), false);
}

// Shadow request r's first leg (wavefront_shadow with refraction; round 0's leg r): from
// its vertex's shadow origin, in the media of the vertex's path.
// Mirror of the first-leg loop of src/tracer/wavefront/wavefront_tree.rs::glass_shadow_rounds — change both.
fn start_shadow_leg(r: u32) {
    let points = tree_points();
    let i = bitcast<u32>(samples[tree_shadows(points) + r].w) / points;
    let origin = samples[tree_vertices() + 2u * i + 1u].xyz;
    store_leg(0u, r, r, ShadowLeg(origin, 1.0, path_media(tile.level % 2u, i)));
}

// Request r's light point and its vertex's magnitude.
fn request_target(r: u32) -> vec4<f32> {
    let points = tree_points();
    let request = samples[tree_shadows(points) + r];
    let i = bitcast<u32>(request.w) / points;
    return vec4<f32>(request.xyz, samples[tree_vertices() + 2u * i + 1u].w);
}

// Round tile.level's closest pass: each live leg's ray to the first surface short of
// its light point. With CSG, whose interval lists take a list slot per invocation (C of
// them), at most C invocations, each a grid-stride loop over legs idx, idx + C, …
// The loop's test reads the round's leg count again each turn (no kernel of the pass
// changes it) and holds no early return around the loop: RADV then keeps neither the
// count nor an exec mask live across closest_hit, which in wave64 spilled 2 SGPRs
// (csg.lua) and 10 (scrabble.lua) with the count and the return held
// (docs/journal/2026-12-02-leg-closest-registers.md).
// Mirror of the round loop's closest pass of src/tracer/wavefront/wavefront_tree.rs::glass_shadow_rounds — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn wavefront_leg_closest(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let idx = linear_index(id, groups);
// #if CSG
    begin_lane(idx);
    for (var l = idx; idx < tree_capacity() && l < atomicLoad(&work_counts[leg_counter(tile.level)]); l += tree_capacity()) {
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
    // wave64).
    let at = tree_leg_hits(tree_points()) + 2u * l;
    let light = request_target(leg_request(parity, l));
    let leg_ray = shadow_leg_ray(load_leg(parity, l), light.xyz, light.w);
    let hit = closest_hit(leg_ray.ray, leg_ray.reach);
    samples[at] = vec4<f32>(hit.t, bitcast<f32>(hit.item), hit.b1, hit.b2);
    samples[at + 1u] = vec4<f32>(bitcast<f32>(hit.part), 0.0, 0.0, 0.0);
}

// Round tile.level's crossing step, one leg an invocation.
// Mirror of the round loop's crossing step of src/tracer/wavefront/wavefront_tree.rs::glass_shadow_rounds — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn wavefront_crossing(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let idx = linear_index(id, groups);
    let count = atomicLoad(&work_counts[leg_counter(tile.level)]);
// #if CSG
    // The closest pass's dispatch shape (at most C invocations).
    if idx >= tree_capacity() {
        return;
    }
    for (var l = idx; l < count; l += tree_capacity()) {
        crossing_entry(l, leg_hit(l), tile.level);
    }
// #else
    if idx >= count {
        return;
    }
    crossing_entry(idx, leg_hit(idx), tile.level);
// #endif
}

// Leg l's closest hit, as wavefront_leg_closest stored it.
fn leg_hit(l: u32) -> Hit {
    let at = tree_leg_hits(tree_points()) + 2u * l;
    let h = samples[at];
    return Hit(h.x, bitcast<u32>(h.y), h.z, h.w, bitcast<u32>(samples[at + 1u].x));
}

// Leg l's crossing `crossing`, whose closest hit is `hit`: a miss ends its request with
// the transmittance so far, an opaque surface (or the crossing after the last) with 0;
// glass appends the next leg.
// Mirror of src/tracer/wavefront/wavefront_tree.rs::crossing_entry — change both.
fn crossing_entry(l: u32, hit: Hit, crossing: u32) {
    let parity = crossing % 2u;
    let r = leg_request(parity, l);
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

// Request r's slot × its transmittance (shade.wgsl's point_light's last product, the
// CPU's shadowed_term), once, when its last leg ends.
// Mirror of the slot product of src/tracer/wavefront/wavefront_tree.rs::glass_shadow_rounds — change both.
fn end_request(r: u32, transmittance: f32) {
    let slot = tree_slots() + bitcast<u32>(samples[tree_shadows(tree_points()) + r].w);
    var term = vec3<f32>(0.0);
    if !(transmittance <= 0.0) {
        term = samples[slot].xyz * transmittance;
    }
    samples[slot] = vec4<f32>(term, 0.0);
}

// After round tile.level's crossing step (one invocation): the next round's indirect
// workgroups, and the counter of the round after it cleared.
// Mirror of the round loop's hand-over of src/tracer/wavefront/wavefront_tree.rs::glass_shadow_rounds — change both.
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
    let vertex = tree_camera_vertex(k);
    if vertex == NO_CHILD {
        return;
    }
    let colour = fold_entry(vertex);
    samples[2u * k] = vec4<f32>(colour, samples[2u * k].w);
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
    var colour = tree_value(k);
    push_children(k, &stack, &size);
    while size > 0u {
        size -= 1u;
        let vertex = stack[size];
        colour += tree_value(vertex);
        push_children(vertex, &stack, &size);
    }
    return colour;
}

// Pushes vertex's children onto the fold's stack in the order shade appended them.
// Mirror of src/tracer/wavefront/wavefront_tree.rs::push_children — change both.
fn push_children(vertex: u32, stack: ptr<function, array<u32, RAY_STACK_SIZE>>, size: ptr<function, u32>) {
    let children = tree_children(vertex);
    for (var c = 0u; c < 2u; c++) {
        let child = children[c];
        if child != NO_CHILD {
            (*stack)[*size] = child;
            *size += 1u;
        }
    }
}
// #endif
