// glint view's presentation (src/bin/glint/view/present.rs): draws the progressive sums of
// src/tracer/sampling/progressive.wgsl (or the CPU tracer's, uploaded) into the window's surface, each sum
// divided by its count, clamped to [0, 1], no gamma (as glint's PNGs: A4's convention),
// each window pixel showing the film pixel under it (nearest; the film may be a
// reduced-resolution preview while the camera moves). Not part of the tracer: no twin.

struct Present {
    // The film's size in pixels.
    film: vec2<u32>,
    // The surface's size in pixels.
    surface: vec2<u32>,
}

@group(0) @binding(0) var<storage, read> sums: array<vec4<f32>>;
@group(0) @binding(1) var<uniform> present: Present;

// One triangle covering the surface.
@vertex
fn present_vertex(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let x = f32((i << 1u) & 2u) * 2.0 - 1.0;
    let y = f32(i & 2u) * 2.0 - 1.0;
    return vec4<f32>(x, y, 0.0, 1.0);
}

@fragment
fn present_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let film = present.film;
    let scale = vec2<f32>(film) / vec2<f32>(present.surface);
    let at = min(vec2<u32>(position.xy * scale), film - vec2<u32>(1u));
    let sum = sums[at.y * film.x + at.x];
    let mean = select(vec3<f32>(0.0), sum.xyz / sum.w, sum.w > 0.0);
    return vec4<f32>(clamp(mean, vec3<f32>(0.0), vec3<f32>(1.0)), 1.0);
}
