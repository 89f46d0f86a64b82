//! What a hit looks like: surface reconstruction, Phong shading with shadow rays,
//! smooth normals, dielectrics, textures and the environment map; built on the layers below.

pub mod dielectric;
pub mod environment;
pub mod procedural;
pub mod shade;
pub mod smooth;
pub mod surface;
pub mod texture;
