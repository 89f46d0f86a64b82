// split.wgsl — measurement prototypes of a wavefront split of the tracing megakernel
// (docs/journal/2026-12-02-wavefront-split-measured.md). Not part of glint's render module:
// tools/benches/wavefront_split/measure.py appends this file to a scene's specialised render
// module (as `glint kernels --spirv-dir` writes it), resolves its `// #if` blocks with the
// scene's features, renames one of the entry points below to `main` and compiles it with
// `glint kernels --wgsl`. Each kernel reads its queue from `work_list` and writes its
// results to `split`, `samples` and (appending) through `work_counts`, so the compiler
// keeps all of its work; the queue layouts are the design's (the journal entry), not a
// tested interface. Nothing runs these kernels.

// A ray-queue entry: origin, dir, t_max, slot (8 words, 32 bytes).
const SPLIT_RAY_WORDS: u32 = 8u;
// A hit-queue entry: t, item, b1, b2, part (5 words, 20 bytes).
const SPLIT_HIT_WORDS: u32 = 5u;
// A shadow-queue entry: origin 3, position 3, magnitude, slot, unshadowed light 3 and,
// with refraction, the medium stack (MEDIUM_STACK_SIZE iors and a count): 16 words.
const SPLIT_SHADOW_WORDS: u32 = 16u;
// A path-queue entry (what shading reads): ray 6, weight 3, depth, slot, pixel, cone 2,
// media 5, hit 5, sample: 25 words, padded to 32.
const SPLIT_PATH_WORDS: u32 = 32u;

fn split_in_f(i: u32) -> f32 {
    return bitcast<f32>(work_list[i]);
}

fn split_in_v3(i: u32) -> vec3<f32> {
    return vec3<f32>(split_in_f(i), split_in_f(i + 1u), split_in_f(i + 2u));
}

fn split_out_f(i: u32, v: f32) {
    split[i] = bitcast<u32>(v);
}

fn split_out_v3(i: u32, v: vec3<f32>) {
    split_out_f(i, v.x);
    split_out_f(i + 1u, v.y);
    split_out_f(i + 2u, v.z);
}

// (a) Closest hit only: ray queue entry i → hit queue entry i.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn split_closest(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    if i >= tile.items {
        return;
    }
    begin_lane(i);
    let at = i * SPLIT_RAY_WORDS;
    let ray = Ray(split_in_v3(at), split_in_v3(at + 3u));
    let hit = closest_hit(ray, split_in_f(at + 6u));
    let o = i * SPLIT_HIT_WORDS;
    split_out_f(o, hit.t);
    split[o + 1u] = hit.item;
    split_out_f(o + 2u, hit.b1);
    split_out_f(o + 3u, hit.b2);
    split[o + 4u] = hit.part;
}

// (a') Closest hit and the surface at it (surface_at fused into the traversal kernel):
// ray queue entry i → the surface record (p, normal, magnitude, material, uv, dpdu, dpdv).
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn split_closest_surface(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    if i >= tile.items {
        return;
    }
    begin_lane(i);
    let at = i * SPLIT_RAY_WORDS;
    let ray = Ray(split_in_v3(at), split_in_v3(at + 3u));
    let hit = closest_hit(ray, split_in_f(at + 6u));
    let o = i * 20u;
    split[o + 19u] = hit.item;
    if !is_hit(hit) {
        return;
    }
    let s = surface_at(ray, hit);
    split_out_v3(o, s.p);
    split_out_v3(o + 3u, s.normal);
    split_out_f(o + 6u, s.magnitude);
    split[o + 7u] = s.material;
    split_out_f(o + 8u, s.uv.x);
    split_out_f(o + 9u, s.uv.y);
    split_out_v3(o + 10u, s.dpdu);
    split_out_v3(o + 13u, s.dpdv);
    split_out_f(o + 16u, hit.t);
    split_out_f(o + 17u, hit.b1);
    split_out_f(o + 18u, hit.b2);
}

// (b) Any hit only: shadow queue entry i → its light term, unshadowed × 0 or 1, in the
// sample's slot of `split` (3 words a slot).
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn split_any(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    if i >= tile.items {
        return;
    }
    begin_lane(i);
    let at = i * SPLIT_SHADOW_WORDS;
    let origin = split_in_v3(at);
    let position = split_in_v3(at + 3u);
    let blocked = shadow_blocked(origin, position, split_in_f(at + 6u));
    let slot = work_list[at + 7u];
    split_out_v3(slot * 3u, select(split_in_v3(at + 8u), vec3<f32>(0.0), blocked));
}

// #if REFRACTION
// (b, refraction) The shadow ray through glass: shadow_transmittance (closest hits and
// the surfaces crossed, up to MAX_SHADOW_CROSSINGS) with the shading point's media.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn split_transmittance(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    if i >= tile.items {
        return;
    }
    begin_lane(i);
    let at = i * SPLIT_SHADOW_WORDS;
    for (var m = 0u; m < MEDIUM_STACK_SIZE; m++) {
        shading_media.iors[m] = split_in_f(at + 11u + m);
    }
    shading_media.count = work_list[at + 11u + MEDIUM_STACK_SIZE];
    let transmittance = shadow_transmittance(split_in_v3(at), split_in_v3(at + 3u), split_in_f(at + 6u));
    let slot = work_list[at + 7u];
    split_out_v3(slot * 3u, split_in_v3(at + 8u) * transmittance);
}
// #endif

// (c, d) Shading without traversal: path queue entry i (its ray, state and hit) → the
// point's own colour (ambient, or the background on a miss) × weight into samples[i],
// one shadow-queue entry per light point that faces it (appended: work_counts[0]) and
// the secondary rays (appended to the path queue's next generation: work_counts[1]).
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn split_shade(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    if i >= tile.items {
        return;
    }
    begin_lane(i);
    let at = i * SPLIT_PATH_WORDS;
    var entry: StackEntry;
    entry.ray = Ray(split_in_v3(at), split_in_v3(at + 3u));
    entry.weight = split_in_v3(at + 6u);
    entry.depth = work_list[at + 9u];
    let slot = work_list[at + 10u];
// #if TEXTURE|BUMP
    entry.cone = vec2<f32>(split_in_f(at + 12u), split_in_f(at + 13u));
// #endif
// #if REFRACTION
    for (var m = 0u; m < MEDIUM_STACK_SIZE; m++) {
        entry.media.iors[m] = split_in_f(at + 14u + m);
    }
    entry.media.count = work_list[at + 14u + MEDIUM_STACK_SIZE];
// #endif
    let hit = Hit(split_in_f(at + 19u), work_list[at + 20u], split_in_f(at + 21u), split_in_f(at + 22u), work_list[at + 23u]);
    if !is_hit(hit) {
        samples[i] = vec4<f32>(entry.weight * background(entry.ray.dir), 0.0);
        return;
    }
    let seed = SampleSeed(work_list[at + 11u], work_list[at + 24u], entry.depth, false);
    let shaded = split_shade_hit(entry, hit, seed, slot);
// #if TEXTURE
    if entry.depth == 0u {
        note_texture_detail(shaded.s);
    }
// #endif
    samples[i] = vec4<f32>(entry.weight * shaded.colour, select(0.0, 1.0, fine_detail_seen));
// #if REFLECTION|REFRACTION
    if !shaded.ends {
        var stack: RayStack;
        var size = 0u;
        push_secondary_rays(&stack, &size, entry, shaded, hit);
        let base = arrayLength(&split) / 2u;
        for (var k = 0u; k < size; k++) {
            let next = load_pending(&stack, k);
            let q = base + atomicAdd(&work_counts[1], 1u) * SPLIT_PATH_WORDS;
            split_out_v3(q, next.ray.origin);
            split_out_v3(q + 3u, next.ray.dir);
            split_out_v3(q + 6u, next.weight);
            split[q + 9u] = next.depth;
            split[q + 10u] = slot * 2u + k;
// #if TEXTURE|BUMP
            split_out_f(q + 12u, next.cone.x);
            split_out_f(q + 13u, next.cone.y);
// #endif
// #if REFRACTION
            for (var m = 0u; m < MEDIUM_STACK_SIZE; m++) {
                split_out_f(q + 14u + m, next.media.iors[m]);
            }
            split[q + 14u + MEDIUM_STACK_SIZE] = next.media.count;
// #endif
        }
    }
// #endif
}

// trace.wgsl's shade_hit with split_shade_phong for shade_phong.
fn split_shade_hit(entry: StackEntry, hit: Hit, seed: SampleSeed, slot: u32) -> ShadedHit {
    let ray = entry.ray;
    var s = surface_at(ray, hit);
// #if TEXTURE|BUMP
    s = with_footprint(s, ray.dir, entry.cone, hit.t);
// #endif
// #if TEXTURE
    if globals.debug_view == DEBUG_VIEW_UV {
        let uv = s.uv - floor(s.uv);
        return ShadedHit(s, s.normal, s.normal, vec3<f32>(uv.x, uv.y, 0.0), true);
    }
// #endif
    let facing = facing_normal(s.normal, ray.dir);
    var n = facing;
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
// #if REFRACTION
    shading_media = entry.media;
// #endif
    var shade_seed = seed;
    shade_seed.depth = entry.depth;
    return ShadedHit(s, facing, n, split_shade_phong(s, n, -ray.dir, shade_seed, slot), false);
}

// shade.wgsl's shade_phong without shadow rays: the ambient term, returned, and one
// shadow request per light point (area lights: per stratum), in light and stratum order.
fn split_shade_phong(s: Surface, n: vec3<f32>, v: vec3<f32>, seed: SampleSeed, slot: u32) -> vec3<f32> {
    let m = load_material(s.material);
    var phong = Phong(m.kd, m.ks);
// #if TEXTURE
    phong = surface_colours(m, s);
// #endif
    let colour = phong.kd * globals.ambient;
    let origin = offset_ray(s.p, n, s.magnitude);
    for (var i = 0u; i < globals.num_lights; i++) {
        let light = load_light(i);
// #if AREA_LIGHT
        if light.kind == LIGHT_AREA {
            let k = light.samples;
            let scale = 1.0 / f32(k);
            let stream = shadow_stream(seed, i);
            for (var stratum = 0u; stratum < k * k; stratum++) {
                let a = (f32(stratum % k) + shadow_random(stream, stratum, 0u)) * scale - 0.5;
                let b = (f32(stratum / k) + shadow_random(stream, stratum, 1u)) * scale - 0.5;
                let position = light.position + light.edge_u * a + light.edge_v * b;
                split_request_shadow(s, phong, n, v, origin, position, light, slot);
            }
            continue;
        }
// #endif
        split_request_shadow(s, phong, n, v, origin, light.position, light, slot);
    }
    return colour;
}

// shade.wgsl's point_light up to the shadow ray, which it appends to the shadow queue
// with the light term it brings if nothing blocks it.
fn split_request_shadow(s: Surface, phong: Phong, n: vec3<f32>, v: vec3<f32>, origin: vec3<f32>, position: vec3<f32>, light: PackedLight, slot: u32) {
    let m = load_material(s.material);
    let to_light = position - s.p;
    let distance = length(to_light);
    let l = to_light / distance;
    let n_dot_l = dot(n, l);
    if !(n_dot_l > 0.0) {
        return;
    }
    let r = n * (2.0 * n_dot_l) - l;
    let specular = phong_power(dot(r, v), m.shininess);
    let c0 = light.falloff.x;
    let c1 = light.falloff.y;
    let c2 = light.falloff.z;
    let attenuation = 1.0 / (c0 + distance * (c1 + distance * c2));
    let term = (phong.kd * n_dot_l + phong.ks * specular) * light.colour * attenuation;
    let q = atomicAdd(&work_counts[0], 1u) * SPLIT_SHADOW_WORDS;
    split_out_v3(q, origin);
    split_out_v3(q + 3u, position);
    split_out_f(q + 6u, s.magnitude);
    split[q + 7u] = slot;
    split_out_v3(q + 8u, term);
// #if REFRACTION
    for (var k = 0u; k < MEDIUM_STACK_SIZE; k++) {
        split_out_f(q + 11u + k, shading_media.iors[k]);
    }
    split[q + 11u + MEDIUM_STACK_SIZE] = shading_media.count;
// #endif
}

// The camera kernel: sample i's camera ray, cone and media → path queue entry i.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn split_camera(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = linear_index(id, groups);
    if i >= tile.items {
        return;
    }
    let p = i % (tile.size.x * tile.size.y);
    let x = tile.origin.x + p % tile.size.x;
    let y = tile.origin.y + p / tile.size.x;
    let s = i / (tile.size.x * tile.size.y);
    let n = globals.aa_samples;
    let pixel = y * globals.width + x;
    let fx = f32(x) + (f32(s % n) + random_unit(pixel, s, 0u)) / f32(n);
    let fy = f32(y) + (f32(s / n) + random_unit(pixel, s, 1u)) / f32(n);
    let ray = camera_ray(fx, fy);
    let q = i * SPLIT_PATH_WORDS;
    split_out_v3(q, ray.origin);
    split_out_v3(q + 3u, ray.dir);
    split_out_v3(q + 6u, vec3<f32>(1.0));
    split[q + 9u] = 0u;
    split[q + 10u] = i;
    split[q + 11u] = pixel;
// #if TEXTURE|BUMP
    let cone = camera_cone(ray);
    split_out_f(q + 12u, cone.x);
    split_out_f(q + 13u, cone.y);
// #endif
// #if REFRACTION
    let media = camera_medium_stack();
    for (var m = 0u; m < MEDIUM_STACK_SIZE; m++) {
        split_out_f(q + 14u + m, media.iors[m]);
    }
    split[q + 14u + MEDIUM_STACK_SIZE] = media.count;
// #endif
    split[q + 24u] = s;
}
