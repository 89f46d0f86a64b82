// wavefront_shadow.wgsl — the shadow pass of the wavefront kernels: each shadow request
// of generation tile.level traced to any hit, the slot of a blocked one zeroed; with
// refraction each request's first leg for wavefront_tree.wgsl's glass shadow rounds.
// Mirror of src/tracer/wavefront/wavefront_shadow.rs — change both.

// #if WAVEFRONT
// The shadow pass: each shadow request of generation tile.level through shadow_request
// (with refraction start_shadow_leg), one an invocation. With CSG, whose interval lists take a slot of ray_lists per
// invocation (one per sample of the chunk: N), the pass is L dispatches (slices, L the
// light points: requests ≤ L·N) of at most N invocations, slice s's invocation idx taking
// request s·N + idx and list slot idx. A grid-stride loop over requests idx, idx + N, …
// instead spilled 8–10 SGPRs in wave64 around any_hit's own loops, without CSG 13
// (docs/journal/2026-12-02-shadow-kernel-csg-registers.md).
// Mirror of src/tracer/wavefront/wavefront_shadow.rs::wavefront_shadow — change both.
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
// Mirror of src/tracer/wavefront/wavefront_shadow.rs::shadow_request — change both.
fn shadow_request(r: u32) {
    let points = light_points();
    let slot = request_slot(points, r);
    let i = slot / points;
    var transmittance = 1.0;
    if shadow_blocked(vertex_shadow_origin(i), request_position(points, r), vertex_magnitude(i)) {
        transmittance = 0.0;
    }
    write_slot(slot, shadowed_term(slot_term(slot), transmittance));
}
// #endif
