//! Finding hits in a scene: the two-level grids walked by 3D-DDA, a mesh instance's own
//! grid, and what a traversal returns; built on `geometry` and `base`.

pub mod dda;
pub mod hit;
pub mod traverse;
pub mod traverse_mesh;
