// probe.wgsl — test-only entry point (tier-3 kernel probes): traces seeded rays from
// `probe_rays` with closest_hit and reports (hit, t, item, part, normal) per ray from
// surface_at (or, in PROBE_ANY_HIT mode, any_hit's answer alone; in PROBE_SHADOW_RAY mode,
// shadow_blocked's answer and shadow_reach's reach), for comparison with the CPU functions ray by ray.

// Mirror of src/testing/probe.rs::ProbeRay — change both.
struct ProbeRay {
    origin: vec3<f32>,
    t_max: f32,
    // Unit direction.
    dir: vec3<f32>,
    // PROBE_CLOSEST_HIT, PROBE_ANY_HIT, PROBE_SHADOW_RAY (then dir holds the light's
    // position and t_max the shaded surface's magnitude) or PROBE_SHADING_NORMAL.
    mode: u32,
}

// Mirror of src/testing/probe.rs::ProbeResult — change both.
struct ProbeResult {
    // 1 on a hit, 0 on a miss.
    hit: u32,
    t: f32,
    item: u32,
    // A CSG hit's surface (leaf instance | CSG_FLIP); NO_ITEM otherwise.
    part: u32,
    // surface_at's geometric normal, or in PROBE_SHADING_NORMAL mode in a scene with
    // smooth meshes smooth_normal's (zero on a miss).
    normal: vec3<f32>,
    _pad1: u32,
}

@group(0) @binding(9) var<storage, read> probe_rays: array<ProbeRay>;
@group(0) @binding(10) var<storage, read_write> probe_results: array<ProbeResult>;

// Mirror of src/testing/probe.rs::probe — change both.
@compute @workgroup_size(WORKGROUP_SIZE * WORKGROUP_SIZE)
fn probe(@builtin(global_invocation_id) id: vec3<u32>) {
    let index = id.x;
    if index >= arrayLength(&probe_rays) {
        return;
    }
    let pr = probe_rays[index];
    begin_lane(index);
    let ray = Ray(pr.origin, pr.dir);
    if pr.mode == PROBE_SHADOW_RAY {
        // dir holds the light's position, t_max the shaded surface's magnitude.
        let distance = length(pr.dir - pr.origin);
        let reach = shadow_reach(pr.origin, pr.dir, distance, pr.t_max);
        let blocked = shadow_blocked(pr.origin, pr.dir, pr.t_max);
        probe_results[index] = ProbeResult(u32(blocked), reach, NO_ITEM, NO_ITEM, vec3<f32>(0.0), 0u);
        return;
    }
    if pr.mode == PROBE_ANY_HIT {
        probe_results[index] = ProbeResult(u32(any_hit(ray, pr.t_max)), 0.0, NO_ITEM, NO_ITEM, vec3<f32>(0.0), 0u);
        return;
    }
    let hit = closest_hit(ray, pr.t_max);
    var result = ProbeResult(0u, hit.t, hit.item, hit.part, vec3<f32>(0.0), 0u);
    if is_hit(hit) {
        result.hit = 1u;
        let s = surface_at(ray, hit);
        result.normal = s.normal;
// #if SMOOTH
        if pr.mode == PROBE_SHADING_NORMAL {
            result.normal = smooth_normal(hit, s);
        }
// #endif
    }
    probe_results[index] = result;
}
