//! The binding numbers of the scene's tables, shared by the buffers that fill them
//! (`buffers`) and the bind group layout that declares them (`pipeline`).

use super::tables::TableFormat;

/// The bindings of the scene's arrays, tables (textures: `super::tables`) in
/// `SceneBuffers::tables` order: instances, triangles, materials, lights, cell_start,
/// cell_items, csg_program, texels, triangle_uvs, meshes (arrays added later take numbers
/// after every other entry's bindings, so those keep theirs).
pub const SCENE_TABLE_BINDINGS: [u32; 10] = [1, 2, 3, 4, 5, 6, 14, 15, 16, 23];

/// The texel format of each table of [`SCENE_TABLE_BINDINGS`], in the same order: one
/// word a texel for cell_start, cell_items, csg_program and texels, four for the rest.
pub const SCENE_TABLE_FORMATS: [TableFormat; 10] = {
    use TableFormat::{Quads, Words};
    [
        Quads, Quads, Quads, Quads, Words, Words, Words, Words, Quads, Quads,
    ]
};
