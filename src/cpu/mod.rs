//! The CPU reference tracer. Every function here that the GPU tracer also needs has a
//! WGSL twin of the same name in `shaders/` (see each function's doc comment); the two
//! follow the same steps with the same constants, in f32.

pub mod adaptive;
pub mod camera_media;
pub mod csg;
pub mod cylinder_cone;
pub mod dda;
pub mod dielectric;
pub mod hit;
pub mod intersect;
pub mod math;
pub mod pixel_sample;
pub mod progressive;
pub mod queues;
pub mod ray;
pub mod render;
pub mod rng;
pub mod shade;
pub mod smooth;
pub mod surface;
pub mod texture;
pub mod torus;
pub mod trace;
pub mod traverse;
pub mod traverse_mesh;
pub mod triangle4;
pub mod uv;
pub mod wavefront;
pub mod wavefront_lattice;
pub mod wavefront_tree;

pub use render::{render, RenderProgress};
