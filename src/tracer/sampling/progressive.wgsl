// #if WAVEFRONT
// glint view's frame tile.stratum in the hardware variant, after the wavefront kernels'
// generations over the band (src/gpu/view/progressive.rs; the camera pass took stratum
// tile.stratum of each band pixel, sample k = band pixel k): the sample's colour added
// to the pixel's running sum in `output` (the image's, row-major at the globals' width)
// as view_sample adds it (add_view_sample), so the sums are view_sample's bit for bit.
// Mirror of src/tracer/sampling/progressive.rs::wavefront_view_store, one invocation of its loop — change both.
@compute @workgroup_size(LINEAR_WORKGROUP_SIZE)
fn wavefront_view_store(@builtin(global_invocation_id) id: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let k = linear_index(id, groups);
    if k >= tile.items {
        return;
    }
    let p = (tile.origin.y + k / tile.size.x) * globals.width + tile.origin.x + k % tile.size.x;
    output[p] = add_view_sample(output[p], tile.stratum, sample_colour(k));
}
// #else
// glint view's progressive refinement (src/gpu/view/progressive.rs dispatches it): frame k
// adds sample k (tile.level) of each pixel's n×n jittered pattern to the pixel's running
// sum in `output`, whose fourth component counts the samples; after n² frames the sum is
// the one uniform_resolve forms (same samples, same order) and the view shows
// `glint render --aa uniform --samples n`. AA none: one frame of pixel centres.
// The sums stay on the device between frames; the window presents them
// (shaders/view_present.wgsl) from the same buffer. The window is dispatched in
// full-width bands (the tile: origin, size, row stride), each pixel of a band with a
// per-ray list slot of its own (lists.wgsl); the sums and the loop-limiter flags are the
// image's, row-major at the globals' width.
// Mirror of src/tracer/sampling/progressive.rs::view_sample — change both.
@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE)
fn view_sample(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= tile.size.x || id.y >= tile.size.y {
        return;
    }
    let uniform = globals.aa_mode == AA_UNIFORM;
    let n = select(1u, globals.aa_samples, uniform);
    let s = tile.level;
    let x = tile.origin.x + id.x;
    let y = tile.origin.y + id.y;
    begin_lane(id.y * tile.side + id.x);
    let p = y * globals.width + x;
    let colour = uniform_sample(x, y, s, n, uniform);
// #if ITERATION_GUARD
    // A sample the limiter cut short is not added: the sum stays as it was, and the host
    // re-traces this sample on the CPU tracer into it (Progressive::trace_sample).
    if loop_limiter_tripped() {
        guard[p] = 1u;
        return;
    }
// #endif
    output[p] = add_view_sample(output[p], s, colour);
}
// #endif

// A pixel's running sum with its sample s of colour `colour` added: from zero at s = 0
// (whatever `sum` held), the count in the fourth component. Both view kernels
// (view_sample, and the hardware variant's store pass) add their samples with it.
// Mirror of src/tracer/sampling/progressive.rs::add_view_sample — change both.
fn add_view_sample(sum: vec4<f32>, s: u32, colour: vec3<f32>) -> vec4<f32> {
    var before = vec3<f32>(0.0);
    if s != 0u {
        before = sum.xyz;
    }
    return vec4<f32>(before + colour, f32(s + 1u));
}
