// layout.wgsl — twins of the Pod structs in src/pack/layout.rs (same names, same field
// order; tests/gpu/gpu_layout.rs checks every offset and size against Rust) and the bindings
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

// The vertex normals of a triangle's corners in its mesh's space (same order as the
// triangles; packed only with SMOOTH, all zero on a flat triangle).
// Mirror of src/pack/layout.rs::PackedTriangleNormals — change both.
struct PackedTriangleNormals {
    n0: array<f32, 3>,
    n1: array<f32, 3>,
    n2: array<f32, 3>,
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
    // Thin-lens radius in scene units (render option `aperture`); 0 is the pinhole.
    lens_radius: f32,
    // Distance from the eye, along forward, of the plane in focus (render option `focus`).
    focus_distance: f32,
// #if ENVIRONMENT
    // The word of the texel table where the environment map starts (its width, its
    // height, then its texels as f32 bits; src/pack/environment.rs).
    environment: u32,
    // cos and sin of the map's turn about +y.
    environment_cos: f32,
    environment_sin: f32,
// #else
    _environment_pad0: u32,
    _environment_pad1: u32,
    _environment_pad2: u32,
// #endif
    _pad0: u32,
    _pad1: u32,
}

// Mirror of src/gpu/upload/buffers.rs::GpuTile — change both.
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
// #if WAVEFRONT
    // The wavefront camera pass's stratum of each chunk pixel (glint view's frame), or
    // ALL_STRATA: every stratum of each (a render's chunk).
    stratum: u32,
    // The shadow pass's slice with CSG: requests slice × items … (see wavefront_shadow);
    // the args kernel's: the slices of a shadow pass.
    slice: u32,
// #endif
}

// The packed scene: the globals, and every array as a table: a texture 2^TABLE_ROW_BITS
// texels wide read with textureLoad, since llvmpipe loads a storage buffer lane by lane
// and a texel for all lanes at once (src/gpu/upload/tables.rs; src/gpu/upload/buffers.rs binds them,
// an empty array as one zeroed row). Elements of 16-byte-texel tables take *_TABLE_TEXELS
// texels each; one-word tables hold a word a texel. On software adapters the tables are
// bound as read-only storage textures (STORAGE_TABLES: llvmpipe's image load skips the
// sampler's paths, and fetches are most of a frame there: docs/gpu.md#the-scene-in-tables-textures-not-storage-buffers), elsewhere as
// sampled textures; the texels are the same.
// #if STORAGE_TABLES
alias QuadTable = texture_storage_2d<rgba32uint, read>;
alias WordTable = texture_storage_2d<r32uint, read>;
// #else
alias QuadTable = texture_2d<u32>;
alias WordTable = texture_2d<u32>;
// #endif
@group(0) @binding(0) var<uniform> globals: PackedGlobals;
@group(0) @binding(1) var instance_table: QuadTable;
@group(0) @binding(2) var triangle_table: QuadTable;
@group(0) @binding(3) var material_table: QuadTable;
@group(0) @binding(4) var light_table: QuadTable;
// The cells of all grids, CSR-style: the scene grid's, then each mesh's.
@group(0) @binding(5) var cell_start_table: WordTable;
@group(0) @binding(6) var cell_items_table: WordTable;
// CSG programs (post-order, see intersect_csg) and the texture table + texels.
@group(0) @binding(14) var csg_program_table: WordTable;
@group(0) @binding(15) var texel_table: WordTable;
// Corner UVs of each triangle (same order as the triangles; used with TEXTURE or BUMP).
@group(0) @binding(16) var triangle_uv_table: QuadTable;
// Each mesh's triangle range and grid (KIND_MESH instances index it).
@group(0) @binding(23) var mesh_table: QuadTable;
// Corner normals of each triangle (same order as the triangles; used with SMOOTH).
@group(0) @binding(24) var triangle_normal_table: QuadTable;

// Where element i of a table lies (src/gpu/upload/tables.rs lays them out row by row).
fn table_texel(i: u32) -> vec2<u32> {
    return vec2<u32>(i & ((1u << TABLE_ROW_BITS) - 1u), i >> TABLE_ROW_BITS);
}

// Texel i of a 16-byte-texel table.
fn table_at(table: QuadTable, i: u32) -> vec4<u32> {
// #if STORAGE_TABLES
    return textureLoad(table, table_texel(i));
// #else
    return textureLoad(table, table_texel(i), 0);
// #endif
}

// Word i of a one-word table.
// Mirror of src/pack/layout.rs::word_at — change both.
fn word_at(table: WordTable, i: u32) -> u32 {
// #if STORAGE_TABLES
    return textureLoad(table, table_texel(i)).x;
// #else
    return textureLoad(table, table_texel(i), 0).x;
// #endif
}

// cell_start[i]: where cell i's items begin in cell_items (cell i + 1's start ends them).
// Mirror of src/pack/layout.rs::cell_start_at — change both.
fn cell_start_at(i: u32) -> u32 {
    return word_at(cell_start_table, i);
}

// cell_items[i].
// Mirror of src/pack/layout.rs::cell_item_at — change both.
fn cell_item_at(i: u32) -> u32 {
    return word_at(cell_items_table, i);
}

// #if CSG
// csg_program[i].
// Mirror of src/pack/layout.rs::csg_program_at — change both.
fn csg_program_at(i: u32) -> u32 {
    return word_at(csg_program_table, i);
}
// #endif

// #if TEXTURE|BUMP|PROCEDURAL|ENVIRONMENT
// texels[i]: a word of the texture table, of a texture's texels, of the procedural
// textures' part after them or of the environment map.
// Mirror of src/pack/layout.rs::texel_word — change both.
fn texel_word(i: u32) -> u32 {
    return word_at(texel_table, i);
}
// #endif

// materials[i].
// Mirror of src/pack/layout.rs::load_material — change both.
fn load_material(i: u32) -> PackedMaterial {
    let base = i * MATERIAL_TABLE_TEXELS;
    let t0 = table_at(material_table, base);
    let t1 = table_at(material_table, base + 1u);
    let t2 = table_at(material_table, base + 2u);
    let t3 = table_at(material_table, base + 3u);
    return PackedMaterial(
        bitcast<vec3<f32>>(t0.xyz),
        bitcast<f32>(t0.w),
        bitcast<vec3<f32>>(t1.xyz),
        t1.w,
        bitcast<vec3<f32>>(t2.xyz),
        bitcast<f32>(t2.w),
        t3.x,
        t3.y,
        t3.z,
        bitcast<f32>(t3.w),
    );
}

// lights[i].
// Mirror of src/pack/layout.rs::load_light — change both.
fn load_light(i: u32) -> PackedLight {
    let base = i * LIGHT_TABLE_TEXELS;
    let t0 = table_at(light_table, base);
    let t1 = table_at(light_table, base + 1u);
    let t2 = table_at(light_table, base + 2u);
    let t3 = table_at(light_table, base + 3u);
    let t4 = table_at(light_table, base + 4u);
    return PackedLight(
        bitcast<vec3<f32>>(t0.xyz),
        t0.w,
        bitcast<vec3<f32>>(t1.xyz),
        t1.w,
        bitcast<vec3<f32>>(t2.xyz),
        0u,
        bitcast<vec3<f32>>(t3.xyz),
        0u,
        bitcast<vec3<f32>>(t4.xyz),
        0u,
    );
}

// #if MESH
// #if TEXTURE|BUMP
// triangle_uvs[i].
// Mirror of src/pack/layout.rs::load_triangle_uv — change both.
fn load_triangle_uv(i: u32) -> PackedTriangleUv {
    let base = i * TRIANGLE_UV_TABLE_TEXELS;
    let a = bitcast<vec4<f32>>(table_at(triangle_uv_table, base));
    let b = bitcast<vec4<f32>>(table_at(triangle_uv_table, base + 1u));
    return PackedTriangleUv(a.xy, a.zw, b.xy);
}
// #endif
// #endif

// #if SMOOTH
// triangle_normals[i]: n0.xyz n1.x | n1.yz n2.xy | n2.z, as triangles are laid out.
// Mirror of src/pack/layout.rs::load_triangle_normals — change both.
fn load_triangle_normals(i: u32) -> PackedTriangleNormals {
    let base = i * TRIANGLE_NORMAL_TABLE_TEXELS;
    let a = bitcast<vec4<f32>>(table_at(triangle_normal_table, base));
    let b = bitcast<vec4<f32>>(table_at(triangle_normal_table, base + 1u));
    let c = bitcast<vec4<f32>>(table_at(triangle_normal_table, base + 2u));
    return PackedTriangleNormals(
        array<f32, 3>(a.x, a.y, a.z),
        array<f32, 3>(a.w, b.x, b.y),
        array<f32, 3>(b.z, b.w, c.x),
    );
}
// #endif

// instances[i].
// Mirror of src/pack/layout.rs::load_instance — change both.
fn load_instance(i: u32) -> PackedInstance {
    // Texels 0–5: the rows of the two affine maps, as floats; texel 6: the rest.
    let base = i * INSTANCE_TABLE_TEXELS;
    let last = table_at(instance_table, base + 6u);
    return PackedInstance(
        array<vec4<f32>, 3>(
            bitcast<vec4<f32>>(table_at(instance_table, base)),
            bitcast<vec4<f32>>(table_at(instance_table, base + 1u)),
            bitcast<vec4<f32>>(table_at(instance_table, base + 2u)),
        ),
        array<vec4<f32>, 3>(
            bitcast<vec4<f32>>(table_at(instance_table, base + 3u)),
            bitcast<vec4<f32>>(table_at(instance_table, base + 4u)),
            bitcast<vec4<f32>>(table_at(instance_table, base + 5u)),
        ),
        last.x,
        last.y,
        bitcast<vec2<f32>>(last.zw),
    );
}

// meshes[i].
// Mirror of src/pack/layout.rs::load_mesh — change both.
fn load_mesh(i: u32) -> PackedMesh {
    let base = i * MESH_TABLE_TEXELS;
    let t0 = table_at(mesh_table, base);
    let t1 = table_at(mesh_table, base + 1u);
    let t2 = table_at(mesh_table, base + 2u);
    let t3 = table_at(mesh_table, base + 3u);
    return PackedMesh(
        bitcast<vec3<f32>>(t0.xyz),
        t0.w,
        bitcast<vec3<f32>>(t1.xyz),
        t1.w,
        bitcast<vec3<f32>>(t2.xyz),
        t2.w,
        t3.xyz,
        0u,
    );
}
