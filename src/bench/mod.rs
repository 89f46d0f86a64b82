//! The benchmarks' measuring core, kept apart from the tracers and shared by `glint bench`
//! (the binary's `bench` module, which times and reports them) and the tests that hold
//! them to the tracers: Ferrari's torus solver ([`ferrari`]) and its GPU kernel
//! `shaders/bench/torus.wgsl` ([`torus_gpu`]), the torus rays ([`torus_rays`]), the
//! traversal benchmark's rays and counts ([`trace_rays`]), and their seeded generator
//! ([`splitmix`]).

pub mod ferrari;
pub mod splitmix;
pub mod torus_gpu;
pub mod torus_rays;
pub mod trace_rays;
