// trace.wgsl — Whitted tracing without recursion: an explicit, fixed-size stack of
// secondary rays, each with the weight of its contribution to the pixel and its depth.

// Mirror of src/cpu/trace.rs::StackEntry — change both.
struct StackEntry {
    ray: Ray,
    weight: vec3<f32>,
    depth: u32,
}

// Colour seen along a primary ray, mirrors included (down to max_depth bounces or
// min_weight contribution). seed names the camera sample (its depth is ignored: each
// shading point gets its own ray's depth).
// Mirror of src/cpu/trace.rs::trace_ray — change both.
fn trace_ray(primary: Ray, seed: SampleSeed) -> vec3<f32> {
    let g = globals;
    var stack: array<StackEntry, RAY_STACK_SIZE>;
    stack[0] = StackEntry(primary, vec3<f32>(1.0), 0u);
    var size = 1u;
    var colour = vec3<f32>(0.0);
    while size > 0u {
        size -= 1u;
        let entry = stack[size];
        let ray = entry.ray;
        let hit = closest_hit(ray, T_MISS);
        if !is_hit(hit) {
            colour += entry.weight * background(ray.dir);
            continue;
        }
        let s = surface_at(ray, hit);
// #if TEXTURE
        // The UV debug view (pack turns on TEXTURE for it): (u mod 1, v mod 1, 0).
        if g.debug_view == DEBUG_VIEW_UV {
            let uv = s.uv - floor(s.uv);
            colour += entry.weight * vec3<f32>(uv.x, uv.y, 0.0);
            continue;
        }
// #endif
        // Two-sided shading: the normal faces the incoming ray.
        var n = s.normal;
        if dot(s.normal, ray.dir) > 0.0 {
            n = -s.normal;
        }
// #if BUMP
        n = shading_normal(s, n);
// #endif
        let v = -ray.dir;
        colour += entry.weight * shade_phong(s, n, v, SampleSeed(seed.pixel, seed.sample, entry.depth));
// #if REFLECTION
        let m = materials[s.material];
        if (m.flags & MATERIAL_REFLECTIVE) != 0u && entry.depth < g.max_depth {
            let weight = entry.weight * m.reflection;
            if max_element(weight) >= g.min_weight && size < RAY_STACK_SIZE {
                let dir = ray.dir - n * (2.0 * dot(ray.dir, n));
                stack[size] = StackEntry(
                    Ray(offset_ray(s.p, n, s.magnitude), normalize(dir)),
                    weight,
                    entry.depth + 1u,
                );
                size += 1u;
            }
        }
// #endif
    }
    return colour;
}
