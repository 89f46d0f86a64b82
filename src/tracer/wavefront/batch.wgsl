// batch.wgsl — a wavefront batch's queues as the kernels read and write them: the
// scene's light points (a vertex's light slots), path entries as trace_ray's stack holds
// them. The queues are structures of arrays in `samples` (render.wgsl; vec4 entries),
// their records and regions specified once in src/tracer/wavefront/queues.rs: the
// accessors (path_depth, write_hit, set_sample_flags, …) and the counters of their
// entries in work_counts (path_counter, shadow_counter, …) are generated from it into the
// module (src/tracer/wavefront/queues/wgsl.rs), as are their regions (src/tracer/wavefront/queues/layout.rs).
// Mirror of src/tracer/wavefront/batch.rs — change both.

// #if WAVEFRONT
// The light points of the scene: one per point light, n² per n×n area light.
// Mirror of src/tracer/wavefront/batch.rs::light_points — change both.
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
// #endif
