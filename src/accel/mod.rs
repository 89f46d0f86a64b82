//! Acceleration structures. glint uses one: a uniform grid (Cleary & Wyvill 1988),
//! traversed by 3D-DDA (Amanatides & Woo 1987) in `cpu::traverse` and its WGSL twin.

pub mod grid;
