// trace.wgsl — Whitted tracing without recursion: an explicit, fixed-size stack of
// secondary rays, each with the weight of its contribution to the pixel, its depth, (with
// textures or bump maps) its cone for texture filtering (see texture.wgsl) and (with
// refraction) the media it travels in (see dielectric.wgsl).

// The item the camera ray of the last sample hit first (NO_ITEM: none; the CPU's
// TraversalCounters::camera_hit); pixel_sample.wgsl's hinted_sample reads it after a sample.
var<private> camera_item: u32;
// The item the ray reflected by the camera ray's first surface hit first, where that
// surface is a mirror (is_mirror), else NO_ITEM (the CPU's TraversalCounters::mirror_hit);
// pixel_sample.wgsl's hinted_sample reads it too.
var<private> mirrored_item: u32;

// Mirror of src/tracer/path/trace.rs::StackEntry — change both.
struct StackEntry {
    ray: Ray,
    weight: vec3<f32>,
    depth: u32,
// #if TEXTURE|BUMP
    // The ray's cone for texture filtering: width at its origin, spread per unit length.
    cone: vec2<f32>,
// #endif
// #if REFRACTION
    media: MediumStack,
// #endif
}

// #if REFLECTION|REFRACTION
// The stack of secondary rays. Without dielectrics it never holds more than one ray: at
// most one reflected ray per shading point, pushed after that point's own entry was
// popped (the CPU's has RAY_STACK_SIZE entries and uses the first). A private array sized
// for rays the scene cannot spawn costs a software adapter memory traffic on every access
// (llvmpipe keeps a dynamically indexed array in memory, per lane).
// With dielectrics the stack is RAY_STACK_SIZE entries of 68 bytes: in the hardware
// variant (LISTS_IN_STORAGE) they are in this invocation's slot of ray_lists
// (lists.wgsl), since as a private array they would be scratch memory, and the variable
// is a placeholder that keeps one shape for both variants (store_pending, load_pending).
// #if REFRACTION
// #if LISTS_IN_STORAGE
alias RayStack = u32;
// #else
alias RayStack = array<StackEntry, RAY_STACK_SIZE>;
// #endif
// #else
alias RayStack = array<StackEntry, PRIMARY_RAY_STACK_SIZE>;
// #endif

// Stores entry as the stack's entry k.
fn store_pending(stack: ptr<function, RayStack>, k: u32, entry: StackEntry) {
// #if REFRACTION
// #if LISTS_IN_STORAGE
    let at = k * STACK_ENTRY_WORDS;
    set_lane_vec3(at, entry.ray.origin);
    set_lane_vec3(at + 3u, entry.ray.dir);
    set_lane_vec3(at + 6u, entry.weight);
    ray_lists[lane_word(at + 9u)] = entry.depth;
// #if TEXTURE|BUMP
    set_lane_f32(at + 10u, entry.cone.x);
    set_lane_f32(at + 11u, entry.cone.y);
// #endif
    for (var m = 0u; m < MEDIUM_STACK_SIZE; m++) {
        set_lane_f32(at + 12u + m, entry.media.iors[m]);
    }
    ray_lists[lane_word(at + 12u + MEDIUM_STACK_SIZE)] = entry.media.count;
// #else
    (*stack)[k] = entry;
// #endif
// #else
    (*stack)[k] = entry;
// #endif
}

// The stack's entry k, as store_pending stored it.
fn load_pending(stack: ptr<function, RayStack>, k: u32) -> StackEntry {
// #if REFRACTION
// #if LISTS_IN_STORAGE
    let at = k * STACK_ENTRY_WORDS;
    var entry: StackEntry;
    entry.ray = Ray(lane_vec3(at), lane_vec3(at + 3u));
    entry.weight = lane_vec3(at + 6u);
    entry.depth = ray_lists[lane_word(at + 9u)];
// #if TEXTURE|BUMP
    entry.cone = vec2<f32>(lane_f32(at + 10u), lane_f32(at + 11u));
// #endif
    for (var m = 0u; m < MEDIUM_STACK_SIZE; m++) {
        entry.media.iors[m] = lane_f32(at + 12u + m);
    }
    entry.media.count = ray_lists[lane_word(at + 12u + MEDIUM_STACK_SIZE)];
    return entry;
// #else
    return (*stack)[k];
// #endif
// #else
    return (*stack)[k];
// #endif
}
// #endif

// The stack entry of camera ray `primary`: weight 1, depth 0, the camera's cone and the
// media around the camera. Every kernel that starts camera samples takes it: trace_ray
// here, the hardware variant's camera kernels too.
// Mirror of src/tracer/path/trace.rs::camera_entry — change both.
fn camera_entry(primary: Ray) -> StackEntry {
    var entry: StackEntry;
    entry.ray = primary;
    entry.weight = vec3<f32>(1.0);
    entry.depth = 0u;
// #if TEXTURE|BUMP
    entry.cone = camera_cone(primary);
// #endif
// #if REFRACTION
    entry.media = camera_medium_stack();
// #endif
    return entry;
}

// Colour seen along a primary ray, mirrors and dielectrics included (down to max_depth
// bounces or min_weight contribution). A dielectric pushes its transmitted ray, (1 − F) of
// the weight, then the reflected ray, whose weight is the mirror colour plus F (one ray:
// both go the same way); Phong shading is added as for any material. seed names the
// camera sample (its depth is ignored: each shading point gets its own ray's depth).
// Without dielectrics the camera ray's hit is traced and shaded before the loop over
// secondary rays, which only rays it spawns enter, and which scenes without mirrors do not
// have: on llvmpipe a loop around the first hit costs 20–25% of the render even when it
// runs once (docs/journal/2026-11-30-one-hit-no-loop.md). With dielectrics the camera ray is the loop's first entry
// (below); either way the steps are the CPU twin's, in its order.
// #if CAMERA_RAY_IN_LOOP
// #if !REFRACTION
// In the hardware variant scenes with mirrors take the loop form too (CAMERA_RAY_IN_LOOP,
// src/gpu/compile/shader.rs): a hit before the loop inlines closest_hit and shade_hit a second
// time, which RADV compiled to twice the code and more spilled SGPRs (demo's main, wave64:
// 39 KiB and 105, against 20 KiB and 50; docs/journal/2026-12-02-one-traversal-in-mirror-scenes.md). The loop's first turn takes
// the steps the hit before the loop would, in the same order: 0 + 1 × colour is colour.
// #endif
// #endif
// Mirror of src/tracer/path/trace.rs::trace_ray — change both.
fn trace_ray(primary: Ray, seed: SampleSeed) -> vec3<f32> {
    let first = camera_entry(primary);
// #if CAMERA_RAY_IN_LOOP
// #if REFRACTION
    // With dielectrics the kernel is large (and scenes with them tend to have many other
    // features): a second inlined copy of the first hit's traversal and shading costs
    // llvmpipe more than the loop around it saves (scrabble +15%, the every-feature
    // kernel 2.6×: docs/journal/2026-11-30-one-hit-no-loop.md), so the camera ray is the loop's first entry.
// #else
    // With mirrors in the hardware variant: one inlined copy of the traversal and
    // shading, not two (see above).
// #endif
    var stack: RayStack;
    store_pending(&stack, 0u, first);
    var size = 1u;
    var colour = vec3<f32>(0.0);
    var camera_mirror = false;
// #else
    let first_hit = closest_hit(primary, T_MISS);
    camera_item = first_hit.item;
    if !is_hit(first_hit) {
        return background(primary.dir);
    }
    let first_shaded = shade_hit(first, first_hit, seed);
// #if TEXTURE
    note_texture_detail(first_shaded.s);
// #endif
// #if REFLECTION
    let camera_mirror = is_mirror(first_shaded.s.material);
    var stack: RayStack;
    var size = 0u;
    var colour = first_shaded.colour;
    if !first_shaded.ends {
        push_secondary_rays(&stack, &size, first, first_shaded, first_hit);
    }
// #else
    return first_shaded.colour;
// #endif
// #endif
// #if REFLECTION|REFRACTION
    while size > 0u {
        size -= 1u;
        let entry = load_pending(&stack, size);
        let hit = closest_hit(entry.ray, T_MISS);
// #if CAMERA_RAY_IN_LOOP
        if entry.depth == 0u {
            camera_item = hit.item;
        }
// #endif
        if camera_mirror && entry.depth == 1u {
            // The one ray a mirror spawns: what the camera sees in it.
            mirrored_item = hit.item;
        }
        if !is_hit(hit) {
            colour += entry.weight * background(entry.ray.dir);
            continue;
        }
        let shaded = shade_hit(entry, hit, seed);
// #if CAMERA_RAY_IN_LOOP
        if entry.depth == 0u {
// #if TEXTURE
            note_texture_detail(shaded.s);
// #endif
            camera_mirror = is_mirror(shaded.s.material);
        }
// #endif
        colour += entry.weight * shaded.colour;
        if !shaded.ends {
            push_secondary_rays(&stack, &size, entry, shaded, hit);
        }
    }
    return colour;
// #endif
}

// #if REFLECTION|REFRACTION
// Whether material `material` is a mirror to adaptive AA's item keys (pixel_sample.wgsl's
// sample_item_key): reflective and not a dielectric, so its camera hit spawns one ray.
// Mirror of src/tracer/path/trace.rs::is_mirror — change both.
fn is_mirror(material: u32) -> bool {
    let flags = load_material(material).flags;
    return (flags & MATERIAL_REFLECTIVE) != 0u && (flags & MATERIAL_REFRACTIVE) == 0u;
}
// #endif

// #if TEXTURE
// Sets fine_detail_seen (adaptive AA's hint) when the camera ray's first hit s shows
// texture detail at the pixel's scale: texture_detail above AA_TEXTURE_DETAIL_SHARE of
// aa_threshold. Only adaptive AA reads the hint, so only it pays the lookups.
// Mirror of src/tracer/path/trace.rs::note_texture_detail — change both.
fn note_texture_detail(s: Surface) {
    if globals.aa_mode != AA_ADAPTIVE {
        return;
    }
    if texture_detail(s) > AA_TEXTURE_DETAIL_SHARE * globals.aa_threshold {
        fine_detail_seen = true;
    }
}
// #endif

// #if REFLECTION|REFRACTION
// Pushes the rays that the shaded hit of entry's ray spawns onto the stack (which holds
// size entries): with refraction the transmitted ray, then the reflected ray, each while
// the depth, its weight and the stack allow.
// Mirror of src/tracer/path/trace.rs::push_secondary_rays — change both.
fn push_secondary_rays(stack: ptr<function, RayStack>, size: ptr<function, u32>, entry: StackEntry, shaded: ShadedHit, hit: Hit) {
    let g = globals;
    let ray = entry.ray;
    let s = shaded.s;
    let facing = shaded.facing;
    let n = shaded.n;
// #if TEXTURE|BUMP
    let cone = cone_at(entry.cone, hit.t);
// #endif
    let m = load_material(s.material);
    var reflectance = vec3<f32>(0.0);
    if (m.flags & MATERIAL_REFLECTIVE) != 0u {
        reflectance = m.reflection;
    }
// #if REFRACTION
    if (m.flags & MATERIAL_REFRACTIVE) != 0u && entry.depth < g.max_depth {
// #if SMOOTH
        let crossing = smooth_interface(ray.dir, s.normal, smooth_normal(hit, s), m.ior, entry.media);
// #else
        let crossing = dielectric_interface(ray.dir, s.normal, m.ior, entry.media);
// #endif
        reflectance += vec3<f32>(crossing.reflectance);
        let weight = entry.weight * (1.0 - crossing.reflectance);
        if max_element(weight) >= g.min_weight && *size < RAY_STACK_SIZE {
            // The transmitted ray starts on the far side of the surface.
            var transmitted = entry;
            transmitted.ray = Ray(offset_ray(s.p, -facing, s.magnitude), crossing.dir);
            transmitted.weight = weight;
            transmitted.depth = entry.depth + 1u;
// #if TEXTURE|BUMP
            transmitted.cone = cone;
// #endif
            transmitted.media = crossing.media;
            store_pending(stack, *size, transmitted);
            *size += 1u;
        }
    }
// #endif
    if max_element(reflectance) > 0.0 && entry.depth < g.max_depth {
        let weight = entry.weight * reflectance;
        if max_element(weight) >= g.min_weight && *size < RAY_STACK_SIZE {
            let dir = ray.dir - n * (2.0 * dot(ray.dir, n));
            // A reflected ray stays in the medium it came from.
            var next = entry;
            next.ray = Ray(offset_ray(s.p, facing, s.magnitude), normalize(dir));
            next.weight = weight;
            next.depth = entry.depth + 1u;
// #if TEXTURE|BUMP
            next.cone = cone;
// #endif
            store_pending(stack, *size, next);
            *size += 1u;
        }
    }
}
// #endif

// A ray's hit as trace_ray uses it: the shading point (with its texture footprint),
// the normal facing the ray and the shading normal (interpolated on smooth meshes,
// bumped, kept visible: smooth.wgsl), and the colour the point
// gives by itself — Phong shading, or the UV debug view, which `ends` the ray.
// Mirror of src/tracer/path/trace.rs::ShadedHit — change both.
struct ShadedHit {
    s: Surface,
    facing: vec3<f32>,
    n: vec3<f32>,
    colour: vec3<f32>,
    ends: bool,
}

// The hit of the ray of `entry`, shaded (see ShadedHit).
// Mirror of src/tracer/path/trace.rs::shade_hit — change both.
fn shade_hit(entry: StackEntry, hit: Hit, seed: SampleSeed) -> ShadedHit {
    let point = shading_point(entry, hit);
    if point.unlit {
        return ShadedHit(point.s, point.facing, point.n, point.uv_colour, true);
    }
// #if REFRACTION
    shading_media = entry.media;
// #endif
    var shade_seed = seed;
    shade_seed.depth = entry.depth;
    return ShadedHit(point.s, point.facing, point.n, shade_phong(point.s, point.n, -entry.ray.dir, shade_seed), false);
}

// A hit as shading sees it before any light: the surface (with its texture footprint),
// the normal facing the ray, the shading normal, and in the UV debug view (`unlit`) the
// colour that ends the ray. shade_hit and the hardware variant's shade pass both start
// here.
// Mirror of src/tracer/path/trace.rs::ShadingPoint — change both.
struct ShadingPoint {
    s: Surface,
    facing: vec3<f32>,
    n: vec3<f32>,
    uv_colour: vec3<f32>,
    unlit: bool,
}

// The ShadingPoint of the hit of `entry`'s ray.
// Mirror of src/tracer/path/trace.rs::shading_point — change both.
fn shading_point(entry: StackEntry, hit: Hit) -> ShadingPoint {
    let ray = entry.ray;
    var s = surface_at(ray, hit);
// #if TEXTURE|BUMP
    s = with_footprint(s, ray.dir, entry.cone, hit.t);
// #endif
// #if TEXTURE
    // The UV debug view (pack turns on TEXTURE for it): (u mod 1, v mod 1, 0).
    if globals.debug_view == DEBUG_VIEW_UV {
        let uv = s.uv - floor(s.uv);
        return ShadingPoint(s, s.normal, s.normal, vec3<f32>(uv.x, uv.y, 0.0), true);
    }
// #endif
    let facing = facing_normal(s.normal, ray.dir);
    var n = facing;
// #if SMOOTH
    // The surface as shading sees it: with smooth meshes, its normal interpolated.
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
    return ShadingPoint(s, facing, n, vec3<f32>(0.0), false);
}

// Two-sided shading: normal, negated where it faces away from a ray along dir. Secondary
// rays leave along this geometric side (a bumped normal may lean across the surface).
// Mirror of src/tracer/path/trace.rs::facing_normal — change both.
fn facing_normal(normal: vec3<f32>, dir: vec3<f32>) -> vec3<f32> {
    if dot(normal, dir) > 0.0 {
        return -normal;
    }
    return normal;
}

// #if REFRACTION
// The medium stack primary rays start with (the host found the media around the eye).
// Mirror of src/tracer/path/trace.rs::camera_medium_stack — change both.
fn camera_medium_stack() -> MediumStack {
    let c = globals.camera_media;
    return MediumStack(array<f32, MEDIUM_STACK_SIZE>(c.x, c.y, c.z, c.w), globals.camera_media_count);
}
// #endif
