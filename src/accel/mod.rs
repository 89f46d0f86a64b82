//! Acceleration structures: uniform grids (Cleary & Wyvill 1988) over plain item bounds,
//! traversed by 3D-DDA (Amanatides & Woo 1987) in `tracer::traversal::traverse` and its WGSL twin.
//! `pack` uses them at two levels: one grid over the scene's items (analytic primitives,
//! CSG objects, mesh instances) and one per mesh over its triangles in the mesh's own
//! space. This module knows boxes, triangle corners and item ids only; `pack` depends on
//! it, not the reverse.

pub mod aabb;
pub mod grid;
pub mod overlap;
