// wavefront_gather.wgsl — the gather pass of the wavefront kernels: each vertex's colour
// in shade_phong's order into its sample's colour (and, AA none, the chunk's output), or
// with refraction into its vertex's value for wavefront_tree.wgsl's fold.
// Mirror of src/tracer/wavefront/wavefront_gather.rs — change both.

// #if WAVEFRONT
// The gather pass's invocation for path idx: its vertex's colour in shade_phong's order,
// then into its sample's colour (the camera vertex's is the colour; a deeper one adds
// weight × colour) and the chunk's output pixel.
// Mirror of src/tracer/wavefront/wavefront_gather.rs::wavefront_gather — change both.
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
// #endif
