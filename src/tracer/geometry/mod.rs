//! Ray–primitive intersection and each primitive's surface parameterisation (UVs,
//! tangent frames), CSG's interval lists included; built on `base` only.

pub mod csg;
pub mod cylinder_cone;
pub mod intersect;
pub mod torus;
pub mod triangle4;
pub mod uv;
