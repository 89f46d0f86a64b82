// layout.wgsl — twins of the Pod structs in src/pack/layout.rs (same names, same field
// order; tests/gpu_layout.rs checks every offset and size against Rust) and the bindings
// both entry points share. Change both.

// Mirror of src/pack/layout.rs::PackedInstance — change both.
struct PackedInstance {
    // Rows of world→object (xyz: linear part, w: translation).
    world_to_object: array<vec4<f32>, 3>,
    // Rows of object→world.
    object_to_world: array<vec4<f32>, 3>,
    // KIND_* tag.
    kind: u32,
    material: u32,
    // Kind-specific parameters: cone (zmin, zmax), torus (rin, rout); 0 otherwise.
    params: vec2<f32>,
}

// Mirror of src/pack/layout.rs::PackedTriangle — change both.
// (Corners as array<f32, 3>: 36 bytes a triangle, no vec3 padding.)
struct PackedTriangle {
    p0: array<f32, 3>,
    p1: array<f32, 3>,
    p2: array<f32, 3>,
}

// A mesh: its triangles and its own uniform grid over them, in the mesh's space (cells
// from first_cell in cell_start; cell items are triangle numbers from first_triangle).
// Mirror of src/pack/layout.rs::PackedMesh — change both.
struct PackedMesh {
    grid_min: vec3<f32>,
    first_cell: u32,
    grid_max: vec3<f32>,
    first_triangle: u32,
    grid_cell_size: vec3<f32>,
    num_triangles: u32,
    grid_dims: vec3<u32>,
    _pad0: u32,
}

// Mirror of src/pack/layout.rs::PackedTriangleUv — change both.
struct PackedTriangleUv {
    uv0: vec2<f32>,
    uv1: vec2<f32>,
    uv2: vec2<f32>,
}

// Mirror of src/pack/layout.rs::PackedMaterial — change both.
struct PackedMaterial {
    kd: vec3<f32>,
    shininess: f32,
    ks: vec3<f32>,
    // MATERIAL_* bits.
    flags: u32,
    reflection: vec3<f32>,
    // Index of refraction (MATERIAL_REFRACTIVE); 1 otherwise.
    ior: f32,
    // Texture (index into the texture table in `texels`) replacing kd, or NO_TEXTURE.
    diffuse_texture: u32,
    // Texture replacing ks, or NO_TEXTURE.
    specular_texture: u32,
    // Height field of the bump map, or NO_TEXTURE.
    bump_texture: u32,
    // Bump strength (height units per texture-space unit).
    bump_strength: f32,
}

// Mirror of src/pack/layout.rs::PackedLight — change both.
struct PackedLight {
    position: vec3<f32>,
    // LIGHT_* tag.
    kind: u32,
    colour: vec3<f32>,
    // n of the n×n shadow samples (area lights).
    samples: u32,
    // Attenuation coefficients (c0, c1, c2).
    falloff: vec3<f32>,
    _pad0: u32,
    edge_u: vec3<f32>,
    _pad1: u32,
    edge_v: vec3<f32>,
    _pad2: u32,
}

// Mirror of src/pack/layout.rs::PackedGlobals — change both.
struct PackedGlobals {
    eye: vec3<f32>,
    // tan(fov/2).
    tan_half_fov: f32,
    // Unit view direction.
    forward: vec3<f32>,
    // width / height.
    aspect: f32,
    // Unit camera right vector.
    right: vec3<f32>,
    width: u32,
    // Unit camera up vector (perpendicular to forward).
    up: vec3<f32>,
    height: u32,
    ambient: vec3<f32>,
    num_lights: u32,
    background_top: vec3<f32>,
    max_depth: u32,
    background_bottom: vec3<f32>,
    min_weight: f32,
    // Lower corner of the grid bounds.
    grid_min: vec3<f32>,
    num_instances: u32,
    // Size of one grid cell.
    grid_cell_size: vec3<f32>,
    num_triangles: u32,
    // Cells along each axis.
    grid_dims: vec3<u32>,
    // 1 = traverse the grid, 0 = brute force over every item.
    grid_enabled: u32,
    // Upper corner of the grid bounds.
    grid_max: vec3<f32>,
    // AA_* tag.
    aa_mode: u32,
    // n of uniform n×n anti-aliasing.
    aa_samples: u32,
    // Adaptive anti-aliasing: corner contrast that splits a square.
    aa_threshold: f32,
    // Adaptive anti-aliasing: deepest split.
    aa_depth: u32,
    // How many dielectrics contain the eye (may exceed MEDIUM_STACK_SIZE, see
    // dielectric.wgsl::medium_push); 0 without refraction.
    camera_media_count: u32,
    // Their indices, outermost first (MEDIUM_STACK_SIZE = 4 of them, asserted in Rust):
    // the medium stack primary rays start with.
    camera_media: vec4<f32>,
    // DEBUG_VIEW_* tag (render option `debug`).
    debug_view: u32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

// Mirror of src/gpu/buffers.rs::GpuTile — change both.
struct GpuTile {
    // Top-left pixel of the tile this dispatch renders.
    origin: vec2<u32>,
    // Pixels across and down (at most `side`).
    size: vec2<u32>,
    // The tile side the per-tile buffers are laid out for (row stride, in pixels).
    side: u32,
    // Adaptive passes: the level of the squares this pass decides or splits.
    level: u32,
    // One-dimensional kernels: the invocations that have work.
    items: u32,
    // Iterations of the loop-limiter check (always 2; see render.wgsl).
    sentinel: u32,
}

// The packed scene (src/gpu/buffers.rs binds every array; an empty one holds one unused
// element, since a binding may not be empty).
@group(0) @binding(0) var<uniform> globals: PackedGlobals;
@group(0) @binding(1) var<storage, read> instances: array<PackedInstance>;
@group(0) @binding(2) var<storage, read> triangles: array<PackedTriangle>;
@group(0) @binding(3) var<storage, read> materials: array<PackedMaterial>;
@group(0) @binding(4) var<storage, read> lights: array<PackedLight>;
@group(0) @binding(5) var<storage, read> cell_start: array<u32>;
@group(0) @binding(6) var<storage, read> cell_items: array<u32>;
// CSG programs (post-order, see intersect_csg) and the texture table + texels.
@group(0) @binding(14) var<storage, read> csg_program: array<u32>;
@group(0) @binding(15) var<storage, read> texels: array<u32>;
// Corner UVs of each triangle (same order as `triangles`; only with TEXTURE or BUMP).
@group(0) @binding(16) var<storage, read> triangle_uvs: array<PackedTriangleUv>;
// Each mesh's triangle range and grid (KIND_MESH instances index it).
@group(0) @binding(23) var<storage, read> meshes: array<PackedMesh>;
