//! The `#[repr(C)]` Pod structs both tracers read. Each has a WGSL twin of the same name
//! and field order (std430 storage layout: vec3 aligned to 16 bytes, so each `[f32; 3]`
//! is followed by a 4-byte scalar). Sizes are asserted here; field offsets are checked
//! against naga's layout of the WGSL twins by the layout test. Below the structs, the
//! readers both tracers index the packed arrays through (`load_instance`, `cell_start_at`, …).

use super::PackedScene;
use crate::constants::MEDIUM_STACK_SIZE;
use bytemuck::{Pod, Zeroable};

/// An analytic primitive instance: affine transforms as three rows of a 3×4 matrix.
/// Normals go to world space through the transpose of `world_to_object`'s linear part.
// Mirror of src/pack/layout.wgsl::PackedInstance — change both.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct PackedInstance {
    /// Rows of world→object (xyz: linear part, w: translation).
    pub world_to_object: [[f32; 4]; 3],
    /// Rows of object→world.
    pub object_to_world: [[f32; 4]; 3],
    /// `KIND_*` from `constants`.
    pub kind: u32,
    pub material: u32,
    /// Kind-specific parameters: cone (zmin, zmax); torus (rin, rout); CSG (first step,
    /// number of steps) of its program in `csg_program`; mesh (index into `meshes`, 0);
    /// (0, 0) for the other kinds. Indices are exact as f32 below 2^24 (`pack` checks).
    pub params: [f32; 2],
}

/// A triangle of a mesh, in the mesh's space (flat shaded: the normal is the cross
/// product of its edges); the material is its instance's. Nine packed floats (36
/// bytes): the WGSL twin holds `array<f32, 3>` corners, which have no vec3 padding.
// Mirror of src/pack/layout.wgsl::PackedTriangle — change both.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct PackedTriangle {
    pub p0: [f32; 3],
    pub p1: [f32; 3],
    pub p2: [f32; 3],
}

/// A mesh: its triangles `first_triangle..first_triangle + num_triangles` and its own
/// uniform grid over them, in the mesh's space. The grid's cells are
/// `first_cell..first_cell + dims product` of `cell_start` (whose entries index
/// `cell_items` directly); its cell items are triangle numbers relative to
/// `first_triangle`.
// Mirror of src/pack/layout.wgsl::PackedMesh — change both.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct PackedMesh {
    /// Lower corner of the grid bounds.
    pub grid_min: [f32; 3],
    pub first_cell: u32,
    /// Upper corner of the grid bounds.
    pub grid_max: [f32; 3],
    pub first_triangle: u32,
    /// Size of one cell.
    pub grid_cell_size: [f32; 3],
    /// Stored mesh triangles (each stored once however many instances share it).
    pub num_triangles: u32,
    /// Cells along each axis.
    pub grid_dims: [u32; 3],
    pub _pad0: u32,
}

/// The UVs of a triangle's corners (p0, p1, p2), in a separate array parallel to the
/// triangles (filled only when the scene has textures or bump maps, so untextured scenes
/// keep the 48-byte triangles that traversal reads alone).
// Mirror of src/pack/layout.wgsl::PackedTriangleUv — change both.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct PackedTriangleUv {
    pub uv0: [f32; 2],
    pub uv1: [f32; 2],
    pub uv2: [f32; 2],
}

/// The vertex normals of a triangle's corners (p0, p1, p2) in its mesh's space (unit in
/// the mesh's own; a mesh baked into world space keeps them unnormalised, as
/// `scene::instancing` says), in an array parallel to the triangles, packed only in scenes with the SMOOTH feature
/// (others keep the traversal's triangles alone); all zero on a flat triangle. Nine
/// packed floats, like `PackedTriangle`.
// Mirror of src/pack/layout.wgsl::PackedTriangleNormals — change both.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct PackedTriangleNormals {
    pub n0: [f32; 3],
    pub n1: [f32; 3],
    pub n2: [f32; 3],
}

/// A4 Phong material plus the mirror colour, the dielectric's index and texture maps.
// Mirror of src/pack/layout.wgsl::PackedMaterial — change both.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct PackedMaterial {
    pub kd: [f32; 3],
    pub shininess: f32,
    pub ks: [f32; 3],
    /// `MATERIAL_*` bits.
    pub flags: u32,
    pub reflection: [f32; 3],
    /// Index of refraction (`MATERIAL_REFRACTIVE`); 1 otherwise.
    pub ior: f32,
    /// Texture (index into the texture table in `texels`) replacing kd, or `NO_TEXTURE`.
    pub diffuse_texture: u32,
    /// Texture replacing ks, or `NO_TEXTURE`.
    pub specular_texture: u32,
    /// Height field of the bump map, or `NO_TEXTURE`.
    pub bump_texture: u32,
    /// Bump strength (height units per texture-space unit).
    pub bump_strength: f32,
}

/// A light. Point lights use `position`; area lights (`LIGHT_AREA`) are the parallelogram
/// centred at `position` with edges `edge_u`, `edge_v`, sampled n×n (`samples`).
// Mirror of src/pack/layout.wgsl::PackedLight — change both.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct PackedLight {
    pub position: [f32; 3],
    /// `LIGHT_*` tag.
    pub kind: u32,
    pub colour: [f32; 3],
    /// n of the n×n shadow samples (area lights).
    pub samples: u32,
    /// Attenuation coefficients (c0, c1, c2).
    pub falloff: [f32; 3],
    pub _pad0: u32,
    pub edge_u: [f32; 3],
    pub _pad1: u32,
    pub edge_v: [f32; 3],
    pub _pad2: u32,
}

/// Per-render uniform: camera, image, options and grid header.
// Mirror of src/pack/layout.wgsl::PackedGlobals — change both.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable, PartialEq)]
pub struct PackedGlobals {
    pub eye: [f32; 3],
    /// tan(fov/2).
    pub tan_half_fov: f32,
    /// Unit view direction.
    pub forward: [f32; 3],
    /// width / height.
    pub aspect: f32,
    /// Unit camera right vector.
    pub right: [f32; 3],
    pub width: u32,
    /// Unit camera up vector (perpendicular to forward).
    pub up: [f32; 3],
    pub height: u32,
    pub ambient: [f32; 3],
    pub num_lights: u32,
    pub background_top: [f32; 3],
    pub max_depth: u32,
    pub background_bottom: [f32; 3],
    pub min_weight: f32,
    /// Lower corner of the grid bounds.
    pub grid_min: [f32; 3],
    /// Scene grid items: every instance below this (analytic, CSG, mesh instances).
    pub num_instances: u32,
    /// Size of one grid cell.
    pub grid_cell_size: [f32; 3],
    /// Stored mesh triangles (each stored once however many instances share it).
    pub num_triangles: u32,
    /// Cells along each axis.
    pub grid_dims: [u32; 3],
    /// 1 = traverse the grid, 0 = brute force over every item.
    pub grid_enabled: u32,
    /// Upper corner of the grid bounds.
    pub grid_max: [f32; 3],
    /// `AA_*` tag.
    pub aa_mode: u32,
    /// n of uniform n×n anti-aliasing.
    pub aa_samples: u32,
    /// Adaptive anti-aliasing: corner contrast that splits a pixel (a square of side
    /// 2^−k pixel: 2^k times it).
    pub aa_threshold: f32,
    /// Adaptive anti-aliasing: deepest split.
    pub aa_depth: u32,
    /// How many dielectrics contain the eye (may exceed `MEDIUM_STACK_SIZE`, see
    /// `tracer::shading::dielectric::medium_push`); 0 without refraction.
    pub camera_media_count: u32,
    /// Their indices, outermost first: the medium stack primary rays start with.
    pub camera_media: [f32; MEDIUM_STACK_SIZE as usize],
    /// `DEBUG_VIEW_*` tag (render option `debug`).
    pub debug_view: u32,
    /// Thin-lens radius in scene units (render option `aperture`); 0 is the pinhole.
    pub lens_radius: f32,
    /// Distance from the eye, along `forward`, of the plane in focus (render option
    /// `focus`); read only where `lens_radius` > 0.
    pub focus_distance: f32,
    /// With ENVIRONMENT: the word of `texels` where the environment map starts (its
    /// width, its height, then its texels as f32 bits; `pack::environment`).
    pub environment: u32,
    /// With ENVIRONMENT: cos and sin of the map's turn about +y.
    pub environment_cos: f32,
    pub environment_sin: f32,
    pub _pad0: u32,
    pub _pad1: u32,
}

// The readers of the packed arrays. The GPU reads each array from a table texture
// (src/gpu/upload/tables.rs) through the WGSL twin of the reader; the CPU indexes the
// slice (a one-word array through `word_at`, as the WGSL reads a one-word table). Both
// tracers go through the readers, so a step that reads the scene reads it in the same
// place on both sides (tests/gpu/twins.rs compares their calls).

/// A one-word table: the packed arrays of `u32` (`cell_start`, `cell_items`,
/// `csg_program`, `texels`), which the GPU holds a word a texel (the WGSL's `WordTable`).
pub type WordTable = [u32];

/// Word i of a one-word table.
// Mirror of src/pack/layout.wgsl::word_at — change both.
#[inline(always)]
pub fn word_at(table: &WordTable, i: u32) -> u32 {
    table[i as usize]
}

/// `cell_start[i]`: where cell i's items begin in `cell_items` (cell i + 1's start ends
/// them).
// Mirror of src/pack/layout.wgsl::cell_start_at — change both.
#[inline(always)]
pub fn cell_start_at(scene: &PackedScene, i: u32) -> u32 {
    word_at(&scene.cell_start, i)
}

/// `cell_items[i]`.
// Mirror of src/pack/layout.wgsl::cell_item_at — change both.
#[inline(always)]
pub fn cell_item_at(scene: &PackedScene, i: u32) -> u32 {
    word_at(&scene.cell_items, i)
}

/// `csg_program[i]`.
// Mirror of src/pack/layout.wgsl::csg_program_at — change both.
pub fn csg_program_at(scene: &PackedScene, i: u32) -> u32 {
    word_at(&scene.csg_program, i)
}

/// `texels[i]`: a word of the texture table or of a texture's texels (the texture lookups
/// take the scene's `texels`, or a texture's own, as a slice).
// Mirror of src/pack/layout.wgsl::texel_word — change both.
#[inline(always)]
pub fn texel_word(texels: &[u32], i: u32) -> u32 {
    word_at(texels, i)
}

/// `materials[i]`.
// Mirror of src/pack/layout.wgsl::load_material — change both.
#[inline(always)]
pub fn load_material(scene: &PackedScene, i: u32) -> &PackedMaterial {
    &scene.materials[i as usize]
}

/// `lights[i]`.
// Mirror of src/pack/layout.wgsl::load_light — change both.
#[inline(always)]
pub fn load_light(scene: &PackedScene, i: u32) -> &PackedLight {
    &scene.lights[i as usize]
}

/// `instances[i]`.
// Mirror of src/pack/layout.wgsl::load_instance — change both.
#[inline(always)]
pub fn load_instance(scene: &PackedScene, i: u32) -> &PackedInstance {
    &scene.instances[i as usize]
}

/// `meshes[i]`.
// Mirror of src/pack/layout.wgsl::load_mesh — change both.
#[inline(always)]
pub fn load_mesh(scene: &PackedScene, i: u32) -> &PackedMesh {
    &scene.meshes[i as usize]
}

/// `triangle_uvs[i]`.
// Mirror of src/pack/layout.wgsl::load_triangle_uv — change both.
pub fn load_triangle_uv(scene: &PackedScene, i: u32) -> &PackedTriangleUv {
    &scene.triangle_uvs[i as usize]
}

/// `triangle_normals[i]`.
// Mirror of src/pack/layout.wgsl::load_triangle_normals — change both.
pub fn load_triangle_normals(scene: &PackedScene, i: u32) -> &PackedTriangleNormals {
    &scene.triangle_normals[i as usize]
}

const _: () = assert!(std::mem::size_of::<PackedInstance>() == 112);
const _: () = assert!(std::mem::size_of::<PackedTriangle>() == 36);
const _: () = assert!(std::mem::size_of::<PackedTriangleUv>() == 24);
const _: () = assert!(std::mem::size_of::<PackedTriangleNormals>() == 36);
const _: () = assert!(std::mem::size_of::<PackedMesh>() == 64);
const _: () = assert!(std::mem::size_of::<PackedMaterial>() == 64);
const _: () = assert!(std::mem::size_of::<PackedLight>() == 80);
const _: () = assert!(std::mem::size_of::<PackedGlobals>() == 240);
// The WGSL twin holds camera_media as one vec4 (a uniform array would need a 16-byte stride).
const _: () = assert!(MEDIUM_STACK_SIZE == 4);
