// pixel_sample.wgsl — what the render kernels (render.wgsl) and adaptive AA's passes
// (adaptive.wgsl) both build on: one camera sample's colour, with the hint adaptive AA
// reads beside it, the contrast of a square's corners and centre, and an unsplit
// square's colour.

// Colour at film position (fx, fy) in pixels; seed names the camera sample (and, with
// depth of field, its lens position).
// Mirror of src/tracer/sampling/pixel_sample.rs::sample — change both.
fn sample(fx: f32, fy: f32, seed: SampleSeed) -> vec3<f32> {
// #if DEPTH_OF_FIELD
    return trace_ray(thin_lens_ray(camera_ray(fx, fy), lens_position(seed)), seed);
// #else
    return trace_ray(camera_ray(fx, fy), seed);
// #endif
}

// What adaptive AA's split decisions read from a lattice sample beside its colour: whether
// its first surface showed fine detail that the colours of a few samples may not show (an
// area light reaching it through some of its shadow samples but not all, or a texture's
// detail at the pixel's scale: fine_detail_seen), and the item its camera ray hit first,
// as sample_item_key (camera_item; mirrored_item where that is a mirror).
// Mirror of src/tracer/sampling/pixel_sample.rs::SampleHint — change both.
struct SampleHint {
    fine_detail: bool,
    item: u32,
}

// The part of item number `item` (NO_ITEM: none) that a SampleHint keeps: its low
// AA_ITEM_KEY_MASK bits, which encode_hint's float holds exactly.
// Mirror of src/tracer/sampling/pixel_sample.rs::item_key — change both.
fn item_key(item: u32) -> u32 {
    return item & AA_ITEM_KEY_MASK;
}

// A hint as a lattice sample's fourth component: ±(item + 1), negative for fine detail (an
// integer of at most 2^24, so the float is exact and decode_hint gives it back).
// Mirror of src/tracer/sampling/pixel_sample.rs::encode_hint — change both.
fn encode_hint(hint: SampleHint) -> f32 {
    return select(1.0, -1.0, hint.fine_detail) * f32(hint.item + 1u);
}

// The hint encode_hint stored in w.
// Mirror of src/tracer/sampling/pixel_sample.rs::decode_hint — change both.
fn decode_hint(w: f32) -> SampleHint {
    return SampleHint(w < 0.0, u32(abs(w)) - 1u);
}

// A sample's colour and its SampleHint.
struct HintedSample {
    colour: vec3<f32>,
    hint: SampleHint,
}

// What the split decision of a square reads beside its samples' contrast: whether one of
// its samples saw fine detail, and whether they hit different items.
// Mirror of src/tracer/sampling/pixel_sample.rs::SquareHints — change both.
struct SquareHints {
    fine_detail: bool,
    items_differ: bool,
}

// hints with sample hint h added (first: the square's first sample's hint).
// Mirror of src/tracer/sampling/pixel_sample.rs::add_sample_hint — change both.
fn add_sample_hint(hints: SquareHints, first: SampleHint, h: SampleHint) -> SquareHints {
    return SquareHints(hints.fine_detail || h.fine_detail, hints.items_differ || h.item != first.item);
}

// item_key of a sample whose camera ray hit item `camera` first and, where that is a
// mirror, whose reflected ray hit item `mirrored` first (NO_ITEM: not a mirror, or the
// reflected ray hit nothing): the camera item's key mixed with a hash of the mirrored one.
// Mirror of src/tracer/sampling/pixel_sample.rs::sample_item_key — change both.
fn sample_item_key(camera: u32, mirrored: u32) -> u32 {
    if mirrored == NO_ITEM {
        return item_key(camera);
    }
    return item_key(camera ^ ((mirrored + 1u) * 0x9e3779b1u));
}

// sample, and its SampleHint. Adaptive AA's lattice samples.
// Mirror of src/tracer/sampling/pixel_sample.rs::hinted_sample — change both.
fn hinted_sample(fx: f32, fy: f32, seed: SampleSeed) -> HintedSample {
    fine_detail_seen = false;
    camera_item = NO_ITEM;
    mirrored_item = NO_ITEM;
    let colour = sample(fx, fy, seed);
    let key = sample_item_key(camera_item, mirrored_item);
    return HintedSample(colour, SampleHint(fine_detail_seen, key));
}

// Adaptive AA's sample at lattice point (fx, fy), a dyadic film position (exact):
// hinted_sample at the point's lattice_jitter (the point jittered, with its own seed), so
// a point shared by neighbouring squares, pixels or chunks is the same sample whichever
// pass traces it.
// Mirror of src/tracer/sampling/pixel_sample.rs::lattice_sample — change both.
fn lattice_sample(fx: f32, fy: f32) -> HintedSample {
    let at = lattice_jitter(fx, fy);
    return hinted_sample(at.fx, at.fy, at.seed);
}

// Largest per-channel spread of a square's four corner samples and its centre sample:
// what the split decision of adaptive AA weighs.
// Mirror of src/tracer/sampling/pixel_sample.rs::square_contrast_of — change both.
fn square_contrast_of(c: array<vec3<f32>, 4>, centre: vec3<f32>) -> f32 {
    let lo = min(min(min(min(c[0], c[1]), c[2]), c[3]), centre);
    let hi = max(max(max(max(c[0], c[1]), c[2]), c[3]), centre);
    return max_element(hi - lo);
}

// Colour of a square that adaptive AA did not split, from its corner samples and its
// centre sample: the centre weighs AA_CENTRE_WEIGHT, the corners share the rest.
// Mirror of src/tracer/sampling/pixel_sample.rs::quincunx_mean — change both.
fn quincunx_mean(c: array<vec3<f32>, 4>, centre: vec3<f32>) -> vec3<f32> {
    let corner_weight = 0.25 * (1.0 - AA_CENTRE_WEIGHT);
    return (c[0] + c[1] + c[2] + c[3]) * corner_weight + centre * AA_CENTRE_WEIGHT;
}
