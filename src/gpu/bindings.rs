//! The binding numbers of the scene's arrays, shared by the buffers that fill them
//! (`buffers`) and the bind group layout that declares them (`pipeline`).

/// The bindings of the scene's arrays, in `SceneBuffers::arrays` order (arrays added
/// later take numbers after every other entry's bindings, so those keep theirs).
pub const SCENE_ARRAY_BINDINGS: [u32; 10] = [1, 2, 3, 4, 5, 6, 14, 15, 16, 23];
