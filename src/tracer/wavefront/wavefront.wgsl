// wavefront.wgsl — the wavefront form of trace_ray for scenes without refraction (every
// path a chain), in the hardware kernel variant (WAVEFRONT: src/gpu/compile/shader.rs): a chunk's
// samples go through kernels joined by queues instead of one megakernel. Its samples:
// AA none's pixel centres, uniform AA's n² jittered strata a pixel (wavefront_resolve
// averages them after the last generation), or one stratum a pixel, tile.stratum (glint
// view's frame; progressive.wgsl's wavefront_view_store adds it to the sums). Per chunk,
// wavefront_camera fills generation 0's path queue; per generation g (tile.level)
// wavefront_closest traces each path to its hit, wavefront_shade shades each hit without
// tracing (its own term, one shadow request per light point facing it with the point's
// unshadowed term in the vertex's slot, the reflected ray appended to generation g + 1's
// queue), wavefront_args turns the counters into the indirect workgroup counts of the
// shadow pass and of the next generation, wavefront_shadow traces each request (any hit)
// and zeroes the slot of a blocked one, and wavefront_gather sums each vertex's colour in
// shade_phong's order into its sample's colour (and, AA none, the chunk's output).
// Queues are filled by atomicAdd in any order: every entry carries its sample, and every
// sum runs in one invocation in the CPU's order, so the image is trace_ray's bit for bit.
// The queues are structures of arrays in `samples` (render.wgsl; vec4 entries), their
// records and regions specified once in src/tracer/wavefront/queues.rs: the accessors this file reads
// and writes them through (path_depth, write_hit, set_sample_flags, …) are generated from
// it into the module (src/queues/wgsl.rs), as are their regions (src/queues/layout.rs).
// Counters in work_counts (adaptive.wgsl's binding): generation g's paths at g mod 3, its
// shadow requests at 3 + g mod 2 (wavefront_args clears the ones the next generation
// appends to); indirect arguments in work_args, 6 words a generation (with CSG 3 + 3L:
// the shadow pass's slices, see wavefront_shadow).
// Mirror of src/tracer/wavefront/wavefront.rs — change both.

// #if WAVEFRONT
// #if REFRACTION
// With refraction (this module) paths are trees: the regions, the vertex tree, the glass
// shadow rounds and the fold are wavefront_tree.wgsl's; the blocks under `#if REFRACTION`
// below hand over to it. (The header above stays as chain modules compile it.)
// #endif
// The light points of the scene: one per point light, n² per n×n area light.
// Mirror of src/tracer/wavefront/wavefront.rs::light_points — change both.
fn light_points() -> u32 {
    var points = 0u;
    for (var i = 0u; i < globals.num_lights; i++) {
// #if AREA_LIGHT
        let light = load_light(i);
        if light.kind == LIGHT_AREA {
            points += light.samples * light.samples;
            continue;
        }
// #endif
        points += 1u;
    }
    return points;
}

// Generation g's path counter.
fn path_counter(g: u32) -> u32 {
    return g % 3u;
}

// Generation g's shadow-request counter.
fn shadow_counter(g: u32) -> u32 {
    return 3u + g % 2u;
}

// Path i of parity `parity` as trace_ray's stack holds it.
fn load_path(parity: u32, i: u32) -> StackEntry {
    var entry: StackEntry;
    entry.ray = Ray(path_origin(parity, i), path_dir(parity, i));
    entry.weight = path_weight(parity, i);
    entry.depth = path_depth(parity, i);
// #if TEXTURE|BUMP
    entry.cone = path_cone(parity, i);
// #endif
// #if REFRACTION
    entry.media = path_media(parity, i);
// #endif
    return entry;
}

// Writes `entry` of sample `sample` with pending count `pending` (a tree's: the entries
// under it on trace_ray's stack) as path i.
fn store_path(parity: u32, i: u32, entry: StackEntry, pending: u32, sample: u32) {
    var cone = vec2<f32>(0.0);
// #if TEXTURE|BUMP
    cone = entry.cone;
// #endif
// #if REFRACTION
    write_path(parity, i, entry.ray.origin, sample, entry.ray.dir, entry.depth, entry.weight, cone, pending, entry.media);
// #else
    write_path(parity, i, entry.ray.origin, sample, entry.ray.dir, entry.depth, entry.weight, cone);
// #endif
}

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
    let seed = stratum.seed;
    var flags = 0u;
    if seed.mirrors_corners {
        flags = SAMPLE_MIRRORS_CORNERS;
    }
    write_sample(k, vec3<f32>(0.0), NO_ITEM, NO_ITEM, flags, seed.pixel, seed.sample);
    // Camera rays start in the media around the camera (camera_entry).
    let entry = camera_entry(camera_ray(stratum.fx, stratum.fy));
// #if REFRACTION
    // Path k is vertex k.
    write_camera_vertex(k, k);
// #endif
    // A camera ray: nothing under it on trace_ray's stack.
    store_path(0u, k, entry, 0u, k);
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

// point_light's A4 term before its shadow ray, (kd·N·L + ks·spec)·I·attenuation, in w 1;
// w 0 where the light point is behind the surface (no shadow ray; the slot stays zero).
// The CPU's point_light and shading pass share one function; the WGSL point_light keeps
// its own copy of these lines, so that the software kernel (which has no wavefront) is
// the same module it was.
fn wavefront_unshadowed_term(s: Surface, phong: Phong, n: vec3<f32>, v: vec3<f32>, position: vec3<f32>, light: PackedLight) -> vec4<f32> {
    let m = load_material(s.material);
    let to_light = position - s.p;
    let distance = length(to_light);
    let l = to_light / distance;
    let n_dot_l = dot(n, l);
    if !(n_dot_l > 0.0) {
        return vec4<f32>(0.0);
    }
    let r = n * (2.0 * n_dot_l) - l;
    let specular = phong_power(dot(r, v), m.shininess);
    let c0 = light.falloff.x;
    let c1 = light.falloff.y;
    let c2 = light.falloff.z;
    let attenuation = 1.0 / (c0 + distance * (c1 + distance * c2));
    return vec4<f32>((phong.kd * n_dot_l + phong.ks * specular) * light.colour * attenuation, 1.0);
}

// Light point `slot` of vertex i at `position`: its unshadowed term in the slot (zero
// where it faces away) and, where it faces the point, a shadow request.
fn ask_shadow(s: Surface, phong: Phong, n: vec3<f32>, v: vec3<f32>, position: vec3<f32>, light: PackedLight, slot: u32, points: u32) {
    let term = wavefront_unshadowed_term(s, phong, n, v, position, light);
    write_slot(slot, term.xyz);
    if term.w != 0.0 {
        let r = atomicAdd(&work_counts[shadow_counter(tile.level)], 1u);
        write_request(points, r, position, slot);
    }
}

// The shade pass's invocation for path idx: a miss's background; a hit's own term, its
// light slots and shadow requests, the reflected ray appended to the next generation's
// queue, and at depth 0 the sample's hints.
// Mirror of src/tracer/wavefront/wavefront.rs::wavefront_shade — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn wavefront_shade(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    let g = tile.level;
    if i >= atomicLoad(&work_counts[path_counter(g)]) {
        return;
    }
    let parity = g % 2u;
    let entry = load_path(parity, i);
    let k = path_sample(parity, i);
    let hit = load_hit(i);
// #if REFRACTION
    // The ray stack push_secondary_rays fills is in this invocation's list slot.
    begin_lane(i);
    set_node_children(atomicLoad(&work_counts[vertex_base_counter(g)]) + i, vec2<u32>(NO_CHILD));
// #endif
    if !is_hit(hit) {
        set_vertex_own_kind(i, background(entry.ray.dir), VERTEX_MISS);
        return;
    }
    // trace.wgsl's shade_hit up to shade_phong (the CPU's shading_point).
    let ray = entry.ray;
    var s = surface_at(ray, hit);
// #if TEXTURE|BUMP
    s = with_footprint(s, ray.dir, entry.cone, hit.t);
// #endif
    var unlit = false;
    var uv_colour = vec3<f32>(0.0);
    var facing = s.normal;
    var n = s.normal;
// #if TEXTURE
    // The UV debug view (pack turns on TEXTURE for it): (u mod 1, v mod 1, 0).
    if globals.debug_view == DEBUG_VIEW_UV {
        let uv = s.uv - floor(s.uv);
        uv_colour = vec3<f32>(uv.x, uv.y, 0.0);
        unlit = true;
    }
// #endif
    if !unlit {
        facing = facing_normal(s.normal, ray.dir);
        n = facing;
// #if SMOOTH
        var shading = s;
        shading.normal = smooth_normal(hit, s);
        if dot(facing, s.normal) < 0.0 {
            n = -shading.normal;
        } else {
            n = shading.normal;
        }
// #else
        let shading = s;
// #endif
// #if BUMP
        n = shading_normal(shading, n);
// #endif
// #if SMOOTH
        if any(shading.normal != s.normal) {
            n = visible_normal(n, facing, -ray.dir);
        }
// #endif
    }
    if entry.depth == 0u {
        note_sample_hints(k, s);
    }
    if unlit {
        set_vertex_own_kind(i, uv_colour, VERTEX_UNLIT);
        return;
    }
    let m = load_material(s.material);
    var phong = Phong(m.kd, m.ks);
// #if TEXTURE
    phong = surface_colours(m, s);
// #endif
    set_vertex_own_kind(i, phong.kd * globals.ambient, VERTEX_LIT);
    let origin = offset_ray(s.p, n, s.magnitude);
    set_vertex_shadow_origin_magnitude(i, origin, s.magnitude);
    let v = -ray.dir;
    let seed = SampleSeed(sample_seed_pixel(k), sample_seed_sample(k), entry.depth, (sample_flags(k) & SAMPLE_MIRRORS_CORNERS) != 0u);
    ask_light_shadows(i, s, phong, n, v, seed);
    push_next_paths(i, entry, k, ShadedHit(s, facing, n, vec3<f32>(0.0), false), hit);
}

// At a camera hit (depth 0) of sample k: its hints in its record's flags, the texture
// detail seen at `s` and whether the camera's surface is a mirror.
// Mirror of src/tracer/wavefront/wavefront.rs::note_sample_hints — change both.
fn note_sample_hints(k: u32, s: Surface) {
    var flags = sample_flags(k);
// #if TEXTURE
    fine_detail_seen = false;
    note_texture_detail(s);
    if fine_detail_seen {
        flags |= SAMPLE_FINE_DETAIL;
    }
// #endif
// #if REFLECTION
    if is_mirror(s.material) {
        flags |= SAMPLE_CAMERA_MIRROR;
    }
// #endif
    set_sample_flags(k, flags);
}

// Every light point of path i's hit at `s` (an area light's strata from `seed`'s shadow
// streams), in slot order: its unshadowed term and, where it faces the point, a shadow
// request (ask_shadow).
// Mirror of src/tracer/wavefront/wavefront.rs::ask_light_shadows — change both.
fn ask_light_shadows(i: u32, s: Surface, phong: Phong, n: vec3<f32>, v: vec3<f32>, seed: SampleSeed) {
    let points = light_points();
    var slot = i * points;
    for (var index = 0u; index < globals.num_lights; index++) {
        let light = load_light(index);
// #if AREA_LIGHT
        if light.kind == LIGHT_AREA {
            let kk = light.samples;
            let scale = 1.0 / f32(kk);
            let stream = shadow_stream(seed, index);
            for (var stratum = 0u; stratum < kk * kk; stratum++) {
                // shade.wgsl's area_light's point (the CPU's area_light_point).
                let a = (f32(stratum % kk) + shadow_random(stream, stratum, 0u)) * scale - 0.5;
                let b = (f32(stratum / kk) + shadow_random(stream, stratum, 1u)) * scale - 0.5;
                let position = light.position + light.edge_u * a + light.edge_v * b;
                ask_shadow(s, phong, n, v, position, light, slot, points);
                slot += 1u;
            }
            continue;
        }
// #endif
        ask_shadow(s, phong, n, v, light.position, light, slot, points);
        slot += 1u;
    }
}

// The rays path i's hit (sample k) spawns, appended to the next generation's queue: a
// tree's through push_tree_children; without refraction at most the reflected ray,
// pushed onto an empty stack as trace_ray's chain has it.
// Mirror of src/tracer/wavefront/wavefront.rs::push_next_paths — change both.
fn push_next_paths(i: u32, entry: StackEntry, k: u32, shaded: ShadedHit, hit: Hit) {
// #if REFRACTION
    push_tree_children(i, entry, k, shaded, hit);
// #else
// #if REFLECTION
    let g = tile.level;
    let parity = g % 2u;
    var stack: RayStack;
    var size = 0u;
    push_secondary_rays(&stack, &size, entry, shaded, hit);
    if size > 0u {
        let at = atomicAdd(&work_counts[path_counter(g + 1u)], 1u);
        store_path(1u - parity, at, load_pending(&stack, 0u), 0u, k);
    }
// #endif
// #endif
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

// The shadow pass: each shadow request of generation tile.level through shadow_request,
// one a invocation. With CSG, whose interval lists take a slot of ray_lists per
// invocation (one per sample of the chunk: N), the pass is L dispatches (slices, L the
// light points: requests ≤ L·N) of at most N invocations, slice s's invocation idx taking
// request s·N + idx and list slot idx. A grid-stride loop over requests idx, idx + N, …
// instead spilled 8–10 SGPRs in wave64 around any_hit's own loops, without CSG 13
// (docs/journal/2026-12-02-shadow-kernel-csg-registers.md).
// Mirror of the loop of src/tracer/wavefront/wavefront.rs::shadow_pass — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn wavefront_shadow(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let idx = linear_index(id, groups);
// #if REFRACTION
    // Through glass: each request's first leg, for the rounds (wavefront_tree.wgsl).
    if idx >= atomicLoad(&work_counts[shadow_counter(tile.level)]) {
        return;
    }
    start_shadow_leg(idx);
// #else
// #if CSG
    let r = tile.slice * tile.items + idx;
    if idx >= tile.items || r >= atomicLoad(&work_counts[shadow_counter(tile.level)]) {
        return;
    }
    begin_lane(idx);
    shadow_request(r);
// #else
    let count = atomicLoad(&work_counts[shadow_counter(tile.level)]);
    if idx >= count {
        return;
    }
    shadow_request(idx);
// #endif
// #endif
}

// Shadow request r: its slot's term × the transmittance (1, or 0 where blocked).
// Mirror of src/tracer/wavefront/wavefront.rs::shadow_request — change both.
fn shadow_request(r: u32) {
    let points = light_points();
    let slot = request_slot(points, r);
    let i = slot / points;
    var transmittance = 1.0;
    if shadow_blocked(vertex_shadow_origin(i), request_position(points, r), vertex_magnitude(i)) {
        transmittance = 0.0;
    }
    // shade.wgsl's point_light's last product (the CPU's shadowed_term).
    var term = vec3<f32>(0.0);
    if !(transmittance <= 0.0) {
        term = slot_term(slot) * transmittance;
    }
    write_slot(slot, term);
}

// The gather pass's invocation for path idx: its vertex's colour in shade_phong's order,
// then into its sample's colour (the camera vertex's is the colour; a deeper one adds
// weight × colour) and the chunk's output pixel.
// Mirror of src/tracer/wavefront/wavefront.rs::wavefront_gather — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn wavefront_gather(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    let g = tile.level;
    if i >= atomicLoad(&work_counts[path_counter(g)]) {
        return;
    }
    let parity = g % 2u;
    let entry = load_path(parity, i);
    let k = path_sample(parity, i);
    var colour = vertex_own(i);
    if vertex_kind(i) == VERTEX_LIT {
        let points = light_points();
        var slot = i * points;
        for (var index = 0u; index < globals.num_lights; index++) {
            let light = load_light(index);
// #if AREA_LIGHT
            if light.kind == LIGHT_AREA {
                let kk = light.samples;
                var sum = vec3<f32>(0.0);
                var lit = 0u;
                for (var stratum = 0u; stratum < kk * kk; stratum++) {
                    let c = slot_term(slot);
                    lit += select(0u, 1u, any(c != vec3<f32>(0.0)));
                    sum += c;
                    slot += 1u;
                }
                if entry.depth == 0u && lit > 0u && lit < kk * kk {
                    set_sample_flags(k, sample_flags(k) | SAMPLE_FINE_DETAIL);
                }
                let scale = 1.0 / f32(kk);
                colour += sum * (scale * scale);
                continue;
            }
// #endif
            colour += slot_term(slot);
            slot += 1u;
        }
    }
// #if REFRACTION
    // A tree's values are summed by the fold, in trace_ray's pop order.
    var value = colour;
    if entry.depth != 0u {
        value = entry.weight * colour;
    }
    set_node_value(atomicLoad(&work_counts[vertex_base_counter(g)]) + i, value);
// #else
    var total = colour;
    if entry.depth != 0u {
        total = sample_colour(k) + entry.weight * colour;
    }
    set_sample_colour(k, total);
    // A render under AA none: sample k is chunk pixel k (row-major over size, rows at
    // stride side); uniform AA's pixels are wavefront_resolve's, adaptive AA's lattice
    // points wavefront_lattice.wgsl's wavefront_lattice_store's, glint view's sums
    // progressive.wgsl's wavefront_view_store's.
    if globals.aa_mode == AA_NONE && tile.stratum == ALL_STRATA {
        output[(k / tile.size.x) * tile.side + k % tile.size.x] = vec4<f32>(total, 1.0);
    }
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
