//! Tags and constants shared by both tracers. Defined once here; the GPU tracer gets them
//! as a generated WGSL prelude ([`wgsl_prelude`]), so no magic number is repeated in WGSL.

/// Instance kinds (`PackedInstance::kind`).
pub const KIND_SPHERE: u32 = 0;
pub const KIND_CUBE: u32 = 1;
pub const KIND_CYLINDER: u32 = 2;
pub const KIND_CONE: u32 = 3;
pub const KIND_TORUS: u32 = 4;
/// A CSG object (a grid item): `params` = (first entry, entry count) of its post-order
/// program in `csg_program`, as exact small f32 integers; its leaves are instances after
/// the grid items (see `tracer::geometry::csg`).
pub const KIND_CSG: u32 = 5;
/// A mesh instance (a grid item): `params[0]` is the index of its mesh in
/// `PackedScene::meshes` as an exact small f32 integer; the mesh's triangles, stored once
/// in the mesh's own space, are traversed through the mesh's own grid (see
/// `tracer::traversal::traverse_mesh`).
pub const KIND_MESH: u32 = 6;
/// Slots of the per-ray item mailbox (a direct-mapped cache of the scene-grid items a ray
/// has tested): an item listed in several scene cells (a mesh instance, a large sphere) is
/// tested once per ray, since its nearest hit does not depend on the cell. A power of two,
/// so the slot is a mask of the item number.
pub const ITEM_MAILBOX_SIZE: u32 = 8;
/// Slots of the per-ray triangle mailbox (a direct-mapped cache of the triangles tested in
/// one mesh): a triangle listed in several cells of its mesh's grid (3.7 on average in
/// cow.obj's) is tested once along a ray, unless another took its slot in between. A
/// power of two, so the slot is a mask of the triangle number.
pub const TRIANGLE_MAILBOX_SIZE: u32 = 32;
/// Bits of each axis's steps-left counter in a DDA's packed `steps_left` word (x in the
/// lowest bits): a grid has at most `accel::grid::MAX_AXIS_CELLS` = 2¹⁰ cells an axis, so
/// at most 2¹⁰ − 1 steps are left along one, and three counters share one u32 — one
/// register where three were held live across every cell of both levels' walks
/// (docs/journal/2026-12-02-traversal-registers.md).
pub const DDA_STEPS_BITS: u32 = 10;
/// The mask of one axis's counter in the packed `steps_left` word.
pub const DDA_STEPS_MASK: u32 = (1 << DDA_STEPS_BITS) - 1;
/// The smallest normal f32 (a floor for divisors that must not be zero).
pub const F32_MIN_POSITIVE: f32 = f32::MIN_POSITIVE;

/// CSG program entries (`PackedScene::csg_program`, post-order): the opcode in the bits
/// from [`CSG_OP_SHIFT`] up, a leaf's instance index in the bits below.
pub const CSG_OP_SHIFT: u32 = 28;
/// Low bits of a program entry or an interval end's tag: the leaf's instance index.
pub const CSG_INDEX_MASK: u32 = (1 << CSG_OP_SHIFT) - 1;
pub const CSG_LEAF: u32 = 0;
pub const CSG_UNION: u32 = 1;
pub const CSG_INTERSECTION: u32 = 2;
/// a minus b (a is the earlier operand in post-order).
pub const CSG_DIFFERENCE: u32 = 3;
/// Tag bit of an interval end (and of `Hit::part`): the leaf's surface is seen from its
/// inside (a subtracted operand), so its normal is negated.
pub const CSG_FLIP: u32 = 1 << 31;
/// Deepest nesting of CSG operations in one object (a CSG node of two primitives is 1).
pub const CSG_MAX_DEPTH: u32 = 16;
/// Interval ends (two per interval) held by one ray's CSG evaluation, in all live lists
/// together plus the list being built: a fixed array in both tracers (GPU private
/// memory, 1 KiB with the tags). Flattening rejects any CSG object whose worst case
/// exceeds it, so neither tracer ever truncates. 128 holds a chain of 16 nested operations
/// on convex primitives (68 ends at most) or of 15 on tori (128).
pub const CSG_EVENT_CAPACITY: u32 = 128;
/// Interval lists alive at once in a post-order evaluation: at most depth + 1.
pub const CSG_LIST_CAPACITY: u32 = CSG_MAX_DEPTH + 1;
/// Interval ends of the two operands of a CSG operation closer than this fraction of the
/// magnitude of the coordinates involved (the ray origin's largest coordinate plus |t|)
/// count as one place: both change state at once. So a − b with coplanar caps leaves no
/// zero-width sliver of a's cap (speckles), and touching operands of a union leave no
/// internal face. Scale-free, like `OFFSET_RELATIVE`: 2⁻¹⁶ ≈ 128 f32 ulps, twice that
/// offset. The two caps' rounding is a few ulps of that magnitude divided by the sine of
/// the ray's angle to the cap; `tests/oracle/csg.rs` measures no speckle down to 1° from the
/// plane (0.5% of rays at 0.5°; with no tolerance, a quarter of the rays at every angle).
/// Features thinner than it (along the ray) merge away.
pub const CSG_COINCIDENT_RELATIVE: f32 = 1.0 / 65536.0;
/// Interval ends are clamped to ±this (a half-line inside a leaf, or a slab test's
/// "safe" reciprocal, gives huge ends): far beyond any hit, yet differences of two ends
/// stay finite (no IEEE infinity, which WGSL does not guarantee).
pub const CSG_T_LIMIT: f32 = 1.0e30;

/// Light kinds (`PackedLight::kind`).
pub const LIGHT_POINT: u32 = 0;
pub const LIGHT_AREA: u32 = 1;

/// Largest n of an area light's n×n shadow samples (`gr.area_light`, `shadow_samples`).
pub const MAX_SHADOW_SAMPLES: u32 = 64;
/// Default n of an area light's n×n shadow samples.
pub const DEFAULT_SHADOW_SAMPLES: u32 = 4;
/// First random dimension of the shadow samples (0 and 1 jitter the camera sample).
pub const SHADOW_DIMENSION_BASE: u32 = 2;

/// Material flags (`PackedMaterial::flags`).
pub const MATERIAL_REFLECTIVE: u32 = 1;
pub const MATERIAL_REFRACTIVE: u32 = 2;

/// `PackedMaterial::*_texture` meaning "no texture".
pub const NO_TEXTURE: u32 = u32::MAX;

/// The texture table at the start of `PackedScene::texels`: header i is the words
/// The GPU keeps the packed scene's arrays in textures of 2^`TABLE_ROW_BITS` texels a
/// row, read with `textureLoad` (src/gpu/upload/tables.rs says why). 4 096 texels: every Vulkan, Metal and DX12 device
/// allows 2-D textures at least that wide.
pub const TABLE_ROW_BITS: u32 = 12;
/// 16-byte texels of one instance (`PackedInstance`, 112 bytes) in its table.
pub const INSTANCE_TABLE_TEXELS: u32 = 7;
/// 16-byte texels of one mesh header (`PackedMesh`, 64 bytes) in its table.
pub const MESH_TABLE_TEXELS: u32 = 4;
/// 16-byte texels of one triangle (`PackedTriangle`'s 36 bytes, padded) in its table.
pub const TRIANGLE_TABLE_TEXELS: u32 = 3;
/// 16-byte texels of one material (`PackedMaterial`, 64 bytes) in its table.
pub const MATERIAL_TABLE_TEXELS: u32 = 4;
/// 16-byte texels of one light (`PackedLight`, 80 bytes) in its table.
pub const LIGHT_TABLE_TEXELS: u32 = 5;
/// 16-byte texels of one triangle's corner UVs (`PackedTriangleUv`'s 24 bytes, padded).
pub const TRIANGLE_UV_TABLE_TEXELS: u32 = 2;
/// 16-byte texels of one triangle's corner normals (`PackedTriangleNormals`'s 36 bytes,
/// padded) in its table.
pub const TRIANGLE_NORMAL_TABLE_TEXELS: u32 = 3;
/// `TEXTURE_HEADER_WORDS·i ..` = (offset of its first texel in `texels`, width, height,
/// header index of level 1 for a texture's level 0); headers 0 … n − 1 are the scene's
/// textures, the mip levels' headers follow; texels follow, row-major from the image's top
/// row, one RGBA8 word each (r in the low byte). See `pack::texture`.
pub const TEXTURE_HEADER_WORDS: u32 = 4;
/// Texture filtering: the smallest |cos| of the angle between a ray and the surface it
/// hits that widens the footprint (by 1/√cos, the geometric mean of the footprint
/// ellipse's axes). Below it the widening stays at 8×, so grazing surfaces keep some
/// detail rather than turning to the texture's mean colour.
pub const TEXTURE_FOOTPRINT_MIN_COSINE: f32 = 1.0 / 64.0;
/// Rec. 709 luminance weights: a bump map's height is the luminance of its texels.
pub const LUMINANCE_R: f32 = 0.2126;
pub const LUMINANCE_G: f32 = 0.7152;
pub const LUMINANCE_B: f32 = 0.0722;

/// Smallest sine of the angle between ∂p/∂u and ∂p/∂v for which bump mapping tilts the
/// normal (a scale-free test: below it the tangent frame is degenerate).
pub const BUMP_MIN_FRAME_SINE: f32 = 1.0e-4;

/// Smooth shading's terminator rule (`visible_normal`): the view direction reflected
/// about the shading normal must leave the surface's visible side with at least this
/// cosine to the geometric normal, else the shading normal is bent towards the geometric
/// one until it does (dimensionless, so scale-free). An interpolated normal that faces
/// away from the viewer, or reflects the view into the surface, would otherwise shade its
/// facet black or mirror the inside of the mesh.
pub const SMOOTH_MIN_REFLECTION_COSINE: f32 = 1.0e-2;

/// `triangle_frame`: a mesh triangle's UV triangle is degenerate (no ∂p/∂u, ∂p/∂v can be
/// solved from it) when its doubled signed area is at most this fraction of the product
/// of its two edge lengths, a scale-free test (the sine of the angle between the edges).
pub const TRIANGLE_FRAME_MIN_UV_SINE: f32 = 1.0e-6;
/// `triangle_frame`'s fallback frame crosses the normal with the x axis, or with the y
/// axis when the normal's |x| exceeds this (x then lies too close to the normal for a
/// well-conditioned cross product).
pub const TRIANGLE_FRAME_AXIS_SWITCH: f32 = 0.9;

/// Debug views (`PackedGlobals::debug_view`): the normal image, or colour = (u mod 1,
/// v mod 1, 0) of the first surface each primary ray hits.
pub const DEBUG_VIEW_NONE: u32 = 0;
pub const DEBUG_VIEW_UV: u32 = 1;

/// Anti-aliasing modes (`PackedGlobals::aa_mode`).
pub const AA_NONE: u32 = 0;
pub const AA_UNIFORM: u32 = 1;
pub const AA_ADAPTIVE: u32 = 2;

/// "No hit" distance: larger than any finite t a scene produces.
pub const T_MISS: f32 = f32::MAX;
/// Item index meaning "no item".
pub const NO_ITEM: u32 = u32::MAX;
/// What a scene walk's `scene_walk_take` answers, instead of an item to test, when the
/// next item is a mesh instance and two are pending already (`NO_ITEM`: the item was
/// passed over). No item has this number.
pub const WALK_FULL: u32 = u32::MAX - 1;

/// Capacity of the explicit secondary-ray stack (no recursion in either tracer).
pub const RAY_STACK_SIZE: u32 = 16;
/// Capacity of the GPU's ray stack when the scene has no dielectrics (only the primary
/// ray, or later one reflected ray, is ever on it; see src/tracer/path/trace.wgsl::trace_ray).
pub const PRIMARY_RAY_STACK_SIZE: u32 = 1;
/// Largest `max_depth` a scene may ask for.
pub const MAX_TRACE_DEPTH: u32 = 64;

/// Index of refraction of the medium outside every dielectric (air, taken as vacuum).
pub const AIR_IOR: f32 = 1.0;
/// Dielectrics nested deeper than this per ray (glass in water in …) are counted but not
/// recorded: a ray inside them sees the index of the deepest recorded level (see
/// `tracer::shading::dielectric::medium_push`). 4 covers a bubble in glass in water with one to spare.
/// `PackedGlobals::camera_media` holds exactly this many indices.
pub const MEDIUM_STACK_SIZE: u32 = 4;
/// A shadow ray passes through at most this many dielectric surfaces; one more counts as
/// blocked. Bounded because lavapipe counts every loop iteration of an invocation against
/// 65 535; 8 crosses a torus (4 surfaces) and two nested spheres.
pub const MAX_SHADOW_CROSSINGS: u32 = 8;

/// Secondary-ray origins move off the surface by this fraction of the magnitude of the
/// coordinates that produced the hit point (2⁻¹⁷ ≈ 64 f32 ulps): the hit point's own
/// rounding error scales with those magnitudes, so the offset is scale-free (a scene
/// scaled by 1e-3 or 1e3 offsets proportionally) — see `tracer::base::ray::offset_ray`.
pub const OFFSET_RELATIVE: f32 = 1.0 / 131072.0;

/// `enter_scene` stops short of the scene bounds by this fraction of the origin's largest
/// coordinate (2⁻²⁰ ≈ 8 f32 ulps), more than the rounding of o + t·d, so the moved origin
/// never lands past thin geometry at the bounds' edge.
pub const ENTER_MARGIN_RELATIVE: f32 = 1.0 / 1048576.0;

/// Reciprocal used for a zero direction component in slab tests: huge but finite, so no
/// IEEE infinity (which WGSL does not guarantee) is ever needed.
pub const SAFE_RCP_LIMIT: f32 = 1.0e30;

/// Torus root finder (`tracer::geometry::torus`): Newton-with-bisection iterations per root at most.
/// Every root is bracketed in an interval of at most ~2 units (the bounding sphere's
/// chord in units of rin + rout), so 24 halvings alone reach f32 precision; Newton
/// usually stops after 3–6. Small, since lavapipe counts every loop iteration of an
/// invocation against 65 535 (a torus test costs at most 4 roots × this).
pub const TORUS_NEWTON_ITERATIONS: u32 = 24;

/// Newton stops when a step is at most this fraction of the root (2⁻²², ≈ 2 ulps).
pub const TORUS_ROOT_TOLERANCE: f32 = 1.0 / 4194304.0;
/// The torus's bounding sphere and slab are grown by this, in units of rin + rout, so
/// that the rounding of the clipped ray origin (far origins: ~1e-7 × their distance)
/// never starts the root search past a hit.
pub const TORUS_BOUND_MARGIN: f32 = 1.0 / 64.0;
/// 2π (angles around an axis → u in [0, 1)).
pub const TWO_PI: f32 = std::f32::consts::TAU;

/// `[("NAME", NAME), …]`: constants as the WGSL prelude declares them, under their Rust
/// names, each name written once.
macro_rules! by_name {
    ($($name:ident),* $(,)?) => {
        &[$((stringify!($name), $name)),*]
    };
}

/// `f32::MAX` under the name the shaders use for it (apart from `T_MISS`, which is what
/// a miss's distance is).
const F32_MAX: f32 = f32::MAX;

/// The u32 constants the WGSL prelude declares, by name.
const WGSL_U32S: &[(&str, u32)] = by_name![
    KIND_SPHERE,
    KIND_CUBE,
    KIND_CYLINDER,
    KIND_CONE,
    KIND_TORUS,
    KIND_CSG,
    KIND_MESH,
    ITEM_MAILBOX_SIZE,
    TRIANGLE_MAILBOX_SIZE,
    DDA_STEPS_BITS,
    DDA_STEPS_MASK,
    CSG_OP_SHIFT,
    CSG_INDEX_MASK,
    CSG_LEAF,
    CSG_UNION,
    CSG_INTERSECTION,
    CSG_DIFFERENCE,
    CSG_FLIP,
    CSG_MAX_DEPTH,
    CSG_EVENT_CAPACITY,
    CSG_LIST_CAPACITY,
    LIGHT_POINT,
    LIGHT_AREA,
    MAX_SHADOW_SAMPLES,
    SHADOW_DIMENSION_BASE,
    MATERIAL_REFLECTIVE,
    MATERIAL_REFRACTIVE,
    NO_TEXTURE,
    TEXTURE_HEADER_WORDS,
    TABLE_ROW_BITS,
    INSTANCE_TABLE_TEXELS,
    MESH_TABLE_TEXELS,
    TRIANGLE_TABLE_TEXELS,
    MATERIAL_TABLE_TEXELS,
    LIGHT_TABLE_TEXELS,
    TRIANGLE_UV_TABLE_TEXELS,
    TRIANGLE_NORMAL_TABLE_TEXELS,
    DEBUG_VIEW_NONE,
    DEBUG_VIEW_UV,
    AA_NONE,
    AA_UNIFORM,
    AA_ADAPTIVE,
    NO_ITEM,
    WALK_FULL,
    RAY_STACK_SIZE,
    PRIMARY_RAY_STACK_SIZE,
    MAX_TRACE_DEPTH,
    MEDIUM_STACK_SIZE,
    MAX_SHADOW_CROSSINGS,
    MAX_AA_DEPTH,
    AA_FINE_DETAIL_DEPTH,
    AA_ITEM_EDGE_DEPTH,
    AA_ITEM_KEY_MASK,
    AA_SPLIT_POINTS,
    MAX_AA_SAMPLES,
    TILE_SIZE,
    GPU_INDIRECT_MAX_WORKGROUPS,
    PCG_MULTIPLIER,
    PROBE_CLOSEST_HIT,
    PROBE_ANY_HIT,
    PROBE_SHADOW_RAY,
    PROBE_SHADING_NORMAL,
    PCG_INCREMENT,
    PCG_WORD_MULTIPLIER,
    TORUS_NEWTON_ITERATIONS,
];

/// The f32 constants the WGSL prelude declares, by name.
const WGSL_F32S: &[(&str, f32)] = by_name![
    T_MISS,
    F32_MAX,
    OFFSET_RELATIVE,
    TEXTURE_FOOTPRINT_MIN_COSINE,
    ENTER_MARGIN_RELATIVE,
    F32_MIN_POSITIVE,
    SAFE_RCP_LIMIT,
    TWO_PI,
    AIR_IOR,
    BUMP_MIN_FRAME_SINE,
    SMOOTH_MIN_REFLECTION_COSINE,
    LUMINANCE_R,
    LUMINANCE_G,
    LUMINANCE_B,
    RANDOM_UNIT_SCALE,
    AA_LATTICE_JITTER,
    AA_TEXTURE_DETAIL_SHARE,
    AA_CENTRE_WEIGHT,
    TORUS_ROOT_TOLERANCE,
    TORUS_BOUND_MARGIN,
    CSG_COINCIDENT_RELATIVE,
    CSG_T_LIMIT,
    TRIANGLE_FRAME_MIN_UV_SINE,
    TRIANGLE_FRAME_AXIS_SWITCH,
];

/// WGSL `const` declarations for every constant above (the GPU tracer's prelude).
pub fn wgsl_prelude() -> String {
    let mut out = String::from("// Generated from src/constants.rs — do not edit.\n");
    out += &u32_declarations(WGSL_U32S);
    for (name, value) in WGSL_F32S {
        out += &format!("const {name}: f32 = {value:e};\n");
    }
    out
}

/// The wavefront kernels' vertex kinds (`tracer::wavefront::wavefront::VertexKind`): what the gather
/// pass does with a vertex — a miss's background, a lit point's ambient term and light
/// slots, the UV debug view's colour.
pub const VERTEX_MISS: u32 = 0;
pub const VERTEX_LIT: u32 = 1;
pub const VERTEX_UNLIT: u32 = 2;
/// The wavefront kernels' sample-record flag bits (`tracer::wavefront::wavefront::SampleRecords`'s
/// `camera_mirror`, `fine_detail` and the seed's `mirrors_corners`).
pub const SAMPLE_CAMERA_MIRROR: u32 = 1;
pub const SAMPLE_FINE_DETAIL: u32 = 2;
pub const SAMPLE_MIRRORS_CORNERS: u32 = 4;
/// GPU only: a tree's sample under adaptive AA with a child the queues had no room for
/// (wavefront_lattice_store sets the guard flags of the pixels around its lattice point).
pub const SAMPLE_NO_ROOM: u32 = 8;
/// Under adaptive AA, the first word of `work_counts` the wavefront's counters take, and
/// ×4 the first byte of `work_args` its indirect arguments take (256 bytes: after every
/// level's of adaptive AA, at MAX_AA_DEPTH at most 6 counters and 144 bytes of arguments,
/// and a storage-binding offset every adapter accepts): see src/tracer/wavefront/wavefront_lattice.wgsl.
pub const WAVEFRONT_WORK_BASE: u32 = 64;
/// `GpuTile::stratum` of a render's chunk: its samples are every stratum of each pixel
/// (glint view's frames give the one stratum instead).
pub const ALL_STRATA: u32 = u32::MAX;

/// The wavefront kernels' constants, emitted after the prelude only in modules that have
/// those kernels (`gpu::compile::shader::wavefront_kernels`), so the others stay as they were.
const WAVEFRONT_WGSL_U32S: &[(&str, u32)] = by_name![
    VERTEX_MISS,
    VERTEX_LIT,
    VERTEX_UNLIT,
    SAMPLE_CAMERA_MIRROR,
    SAMPLE_FINE_DETAIL,
    SAMPLE_MIRRORS_CORNERS,
    SAMPLE_NO_ROOM,
    WAVEFRONT_WORK_BASE,
    ALL_STRATA,
];

/// The WGSL constants of the wavefront kernels.
pub fn wavefront_wgsl_prelude() -> String {
    u32_declarations(WAVEFRONT_WGSL_U32S)
}

/// WGSL `const` declarations of u32 constants, one a line.
fn u32_declarations(constants: &[(&str, u32)]) -> String {
    constants
        .iter()
        .map(|(name, value)| format!("const {name}: u32 = {value}u;\n"))
        .collect()
}

/// Paths a generation of the wavefront kernels may hold with refraction, per sample of
/// the chunk (a tree's generation can be wider than the chunk: `src/tracer/wavefront/wavefront_tree.wgsl`;
/// a child that finds no room sends its pixel to the CPU tracer).
pub const TREE_PATHS_PER_SAMPLE: u32 = 4;
/// Vertices the wavefront kernels' vertex tree holds with refraction, per sample of the
/// chunk (shared: a sample may take more than its share).
pub const TREE_VERTICES_PER_SAMPLE: u32 = 64;

/// A vertex of the wavefront's vertex tree without a child in that place.
pub const NO_CHILD: u32 = u32::MAX;

/// The WGSL constants of the wavefront kernels for scenes with refraction, emitted after
/// [`wavefront_wgsl_prelude`] only in those modules.
pub fn wavefront_tree_wgsl_prelude() -> String {
    u32_declarations(by_name![
        TREE_PATHS_PER_SAMPLE,
        TREE_VERTICES_PER_SAMPLE,
        NO_CHILD
    ])
}

/// Deepest adaptive anti-aliasing split accepted (`aa_depth`).
pub const MAX_AA_DEPTH: u32 = 6;
/// Adaptive anti-aliasing splits a square with a sample (corner or centre) that saw fine
/// detail its colour may not show, down to this level at most (and `aa_depth`): a
/// penumbra (an area light partly occluded among its shadow samples) or texture detail at
/// the pixel's scale ([`AA_TEXTURE_DETAIL_SHARE`]). Level 1, whose four squares each have
/// a centre of their own, samples such a pixel at 13 points a quarter pixel apart, where
/// shadow noise (n² shadow rays per sample) or a texture's detail rather than edges sets
/// the error; level 2 measured no more accurate per ray once squares had centres
/// (docs/journal/2026-11-30-centre-in-every-square.md).
pub const AA_FINE_DETAIL_DEPTH: u32 = 1;
/// A camera ray's first hit on a diffuse texture counts as fine detail for adaptive
/// anti-aliasing when the texture, filtered over the pixel's footprint, differs from the
/// same texture filtered over twice that footprint by more than this share of
/// `aa_threshold` (in some channel): detail at the pixel's own scale, such as printed
/// letters or the seams of a wood grain, that a pixel's five samples alias (measured in
/// docs/journal/2026-11-30-texture-detail-and-mirrored-edges.md). A tenth, not the half
/// it was: once every square had a centre, a level-1 split samples a wood grain's
/// streaks a quarter pixel apart, and splitting down to detail of a tenth of the
/// threshold bought scrabble more accuracy per ray than any threshold did ("Texture
/// detail at a tenth of the threshold").
pub const AA_TEXTURE_DETAIL_SHARE: f32 = 0.1;
/// Adaptive anti-aliasing splits a square whose samples' camera rays hit different items
/// (scene items: a primitive, a CSG object, a mesh instance; or none) down to this level
/// at most (and `aa_depth`), whatever their colours' contrast: the boundary between two
/// objects of about the same colour, where a seam, gap or bevel thinner than the samples'
/// spacing hides (measured in docs/journal/2026-11-30-item-edges-split.md).
pub const AA_ITEM_EDGE_DEPTH: u32 = 2;
/// The bits of an item number that adaptive anti-aliasing's samples keep for
/// [`AA_ITEM_EDGE_DEPTH`]'s test (the GPU keeps them in the sample's fourth component, a
/// float, exact up to 2^24): items 2^24 apart look the same to it, so at worst an edge
/// between two such items does not split by itself (its contrast still can).
pub const AA_ITEM_KEY_MASK: u32 = 0x00ff_ffff;
/// Width of the square a lattice point of adaptive anti-aliasing is jittered in, in steps
/// of the finest lattice (2^aa_depth per pixel): 1 spreads each point over the whole cell
/// of the finest lattice around it, so the lattice samples the film stratified instead of
/// on a regular grid (a regular lattice puts every sample of a long straight edge at the
/// same offset from it, and a pixel-aligned edge exactly on its points: a visible line of
/// the same error along the edge). A power of two, so a jittered position is exact.
pub const AA_LATTICE_JITTER: f32 = 1.0;
/// Weight of a square's centre sample in the colour of an unsplit square (a pixel or a
/// smaller one) under adaptive anti-aliasing (a quincunx: the four corners share the
/// rest). The corners alone are a tent filter twice the square's width, which blurs
/// texture and fine detail that never splits the square; the centre is the square's own.
/// 1/2 measured best of 0.2–0.67 on the sweep's scenes, for pixels
/// (docs/journal/2026-11-30-sample-at-pixel-centre.md).
pub const AA_CENTRE_WEIGHT: f32 = 0.5;
/// Points an adaptive anti-aliasing split traces (one midpoint-pass invocation each): the
/// square's four edge midpoints and its four children's centres (the centres only where
/// the children are above `aa_depth`; a midpoint shared with a split neighbour is traced
/// by one of the two).
pub const AA_SPLIT_POINTS: u32 = 8;
/// Largest n of uniform n×n anti-aliasing.
pub const MAX_AA_SAMPLES: u32 = 64;
/// Square tile side, in pixels, for both tracers' work split.
pub const TILE_SIZE: u32 = 16;
/// Capacity of the CPU's per-pixel adaptive walk's square stack (src/tracer/sampling/render.rs): each
/// split pops one square and pushes four, so depth d needs at most 3·d + 1 entries. (The
/// lattice passes' integrate walk needs none: src/tracer/sampling/adaptive.rs::next_square.)
pub const AA_STACK_SIZE: u32 = 3 * MAX_AA_DEPTH + 1;

/// Largest side of the square GPU workgroup (`@workgroup_size(WORKGROUP_SIZE,
/// WORKGROUP_SIZE)`): the GPU context chooses the largest power of two up to it that its
/// adapter allows (`gpu::compile::kernel::KernelConfig`) and emits it after the prelude.
pub const WORKGROUP_SIZE: u32 = 8;
/// Invocations per workgroup of the one-dimensional GPU kernels (one sample each) at the
/// default side: WORKGROUP_SIZE².
pub const LINEAR_WORKGROUP_SIZE: u32 = WORKGROUP_SIZE * WORKGROUP_SIZE;
/// Workgroups per dimension an indirect dispatch asks for at most (WebGPU's guaranteed
/// minimum of `max_compute_workgroups_per_dimension`; more go in y).
pub const GPU_INDIRECT_MAX_WORKGROUPS: u32 = 65_535;
/// Submits of one GPU frame (fewer only when the frame has fewer chunks or rows): each
/// is a contiguous group of chunks, queued back to back; the host waits on each in turn
/// only to advance the progress bar, so the count does not grow with the image
/// (see `gpu::plan`).
pub const GPU_FRAME_PARTS: u32 = 4;

/// Adaptive anti-aliasing keeps a tile's samples on a lattice of (side·2^d + 1)² points
/// (d = aa_depth), so a tile's side shrinks as d grows: side·2^d ≤ this. The CPU's bound
/// (per rayon task; 257² × 13 B (colour, penumbra flag) ≈ 0.9 MB); the GPU's comes from
/// the adapter's binding limit (`gpu::plan::lattice_side`).
pub const CPU_ADAPTIVE_LATTICE_SIDE: u32 = 256;

/// Side of an adaptive tile (in pixels) for depth `depth` when its lattice may be at most
/// `lattice_side` + 1 points wide and the tile at most `max_side` pixels.
pub const fn adaptive_tile_side(max_side: u32, lattice_side: u32, depth: u32) -> u32 {
    let side = lattice_side >> depth;
    let side = if side == 0 { 1 } else { side };
    if side < max_side {
        side
    } else {
        max_side
    }
}

/// PCG hash constants (Jarzynski & Olano 2020), see `tracer::base::rng::pcg_hash`.
pub const PCG_MULTIPLIER: u32 = 747796405;
pub const PCG_INCREMENT: u32 = 2891336453;
pub const PCG_WORD_MULTIPLIER: u32 = 277803737;
/// 2⁻²⁴: maps the top 24 bits of a hash onto [0, 1) exactly.
pub const RANDOM_UNIT_SCALE: f32 = 1.0 / 16777216.0;

/// Kernel-probe modes (`testing::probe::ProbeRay::mode`, a test hook).
pub const PROBE_CLOSEST_HIT: u32 = 0;
pub const PROBE_ANY_HIT: u32 = 1;
/// A shadow ray (`shadow_blocked`): `origin` is the ray's origin, `dir` holds the light's
/// position and `t_max` the shaded surface's magnitude; the result's `t` is the ray's
/// reach (`shadow_reach`).
pub const PROBE_SHADOW_RAY: u32 = 2;
/// As `PROBE_CLOSEST_HIT`, reporting the smooth shading normal (`smooth_normal`) rather
/// than the geometric one in scenes with the SMOOTH feature.
pub const PROBE_SHADING_NORMAL: u32 = 3;

#[cfg(test)]
mod tests {
    /// Two merges once listed a constant twice; WGSL rejects a redeclared `const`.
    #[test]
    fn prelude_declares_each_constant_once() {
        let prelude = super::wgsl_prelude();
        let mut names: Vec<&str> = prelude
            .lines()
            .filter_map(|l| l.strip_prefix("const "))
            .filter_map(|l| l.split(':').next())
            .collect();
        let count = names.len();
        names.sort();
        names.dedup();
        assert_eq!(
            names.len(),
            count,
            "a constant is declared twice:\n{prelude}"
        );
    }
}
