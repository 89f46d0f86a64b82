// wavefront_shade.wgsl — the shade pass of the wavefront kernels: each hit of generation
// tile.level shaded without tracing (a miss's background; a hit's own term, one shadow
// request per light point facing it with the point's unshadowed term in the vertex's
// slot, the rays it spawns appended to generation g + 1's queue — a tree's through
// wavefront_tree.wgsl's push_tree_children — and at a camera hit the sample's hints).
// Mirror of src/tracer/wavefront/wavefront_shade.rs — change both.

// #if WAVEFRONT
// Light point `slot` (of `points` a vertex) at `position`: its unshadowed term in the slot
// (zero where it faces away) and, where it faces the point, a shadow request.
// Mirror of src/tracer/wavefront/wavefront_shade.rs::ask_shadow — change both.
fn ask_shadow(lit: LitPoint, position: vec3<f32>, light: PackedLight, slot: u32, points: u32) {
    let term = unshadowed_term(lit, position, light);
    write_slot(slot, term.xyz);
    if term.w != 0.0 {
        let r = atomicAdd(&work_counts[shadow_counter(tile.level)], 1u);
        write_request(points, r, position, slot);
    }
}

// The shade pass's invocation for path idx: a miss's background; a hit's own term, its
// light slots and shadow requests, the reflected ray appended to the next generation's
// queue, and at depth 0 the sample's hints.
// Mirror of src/tracer/wavefront/wavefront_shade.rs::wavefront_shade — change both.
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
    let point = shading_point(entry, hit);
    let s = point.s;
    let n = point.n;
    if entry.depth == 0u {
        note_sample_hints(k, s);
    }
    if point.unlit {
        set_vertex_own_kind(i, point.uv_colour, VERTEX_UNLIT);
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
    let v = -entry.ray.dir;
    let seed = SampleSeed(sample_seed_pixel(k), sample_seed_sample(k), entry.depth, (sample_flags(k) & SAMPLE_MIRRORS_CORNERS) != 0u);
    ask_light_shadows(i, LitPoint(s, phong, n, v), seed);
    push_next_paths(i, entry, k, ShadedHit(s, point.facing, n, vec3<f32>(0.0), false), hit);
}

// At a camera hit (depth 0) of sample k: its hints in its record's flags, the texture
// detail seen at `s` and whether the camera's surface is a mirror.
// Mirror of src/tracer/wavefront/wavefront_shade.rs::note_sample_hints — change both.
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
// Mirror of src/tracer/wavefront/wavefront_shade.rs::ask_light_shadows — change both.
fn ask_light_shadows(i: u32, lit: LitPoint, seed: SampleSeed) {
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
                ask_shadow(lit, position, light, slot, points);
                slot += 1u;
            }
            continue;
        }
// #endif
        ask_shadow(lit, light.position, light, slot, points);
        slot += 1u;
    }
}

// The rays path i's hit (sample k) spawns, appended to the next generation's queue: a
// tree's through push_tree_children; without refraction at most the reflected ray,
// pushed onto an empty stack as trace_ray's chain has it.
// Mirror of src/tracer/wavefront/wavefront_shade.rs::push_next_paths — change both.
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
// #endif
