//! The `oracle` test binary: geometry and the CPU tracer against f64 oracles and brute force;
//! no GPU, no images on disk.
//! One binary per tier (docs/testing.md) links glint once instead of once per file.

#[path = "../common/mod.rs"]
mod common;
#[path = "../oracle_support/mod.rs"]
mod oracle_support;

mod adaptive;
mod area_lights;
mod bench_trace;
mod csg;
mod cylinder_cone_oracle;
mod depth_of_field;
mod environment;
mod grid;
mod instancing;
mod intersect_oracle;
mod refraction;
mod shading;
mod torus_oracle;
mod triangle4;
