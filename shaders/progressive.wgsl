// glint view's progressive refinement (src/gpu/progressive.rs dispatches it): frame k
// adds sample k (tile.level) of each pixel's n×n jittered pattern to the pixel's running
// sum in `output`, whose fourth component counts the samples; after n² frames the sum is
// the one uniform_resolve forms (same samples, same order) and the view shows
// `glint render --aa uniform --samples n`. AA none: one frame of pixel centres.
// The sums stay on the device between frames; the window presents them
// (shaders/view_present.wgsl) from the same buffer.
// Mirror of src/cpu/progressive.rs::view_sample — change both.
@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE)
fn view_sample(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= tile.size.x || id.y >= tile.size.y {
        return;
    }
    let uniform = globals.aa_mode == AA_UNIFORM;
    let n = select(1u, globals.aa_samples, uniform);
    let s = tile.level;
    let p = id.y * tile.side + id.x;
    begin_lane(p);
    var before = vec3<f32>(0.0);
    if s != 0u {
        before = output[p].xyz;
    }
    let total = before + uniform_sample(tile.origin.x + id.x, tile.origin.y + id.y, s, n, uniform);
    output[p] = vec4<f32>(total, f32(s + 1u));
// #if ITERATION_GUARD
    if loop_limiter_tripped() {
        guard[p] = 1u;
    }
// #endif
}
