//! The binding numbers of the scene's tables, shared by the buffers that fill them
//! (`buffers`) and the bind group layout that declares them (`pipeline`).

/// The bindings of the scene's arrays, tables (textures: tables.rs) in
/// `SceneBuffers::tables` order: instances, triangles, materials, lights, cell_start,
/// cell_items, csg_program, texels, triangle_uvs, meshes, triangle_normals (arrays added
/// later take numbers after every other entry's bindings, so those keep theirs).
pub const SCENE_TABLE_BINDINGS: [u32; 11] = [1, 2, 3, 4, 5, 6, 14, 15, 16, 23, 24];
