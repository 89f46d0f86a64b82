//! `glint bench`: the benchmarks, kept apart from the tracers. Each speed figure is
//! printed with the error it was measured at; `cmd::run_bench` dispatches on the
//! arguments (`common::BenchArgs`). What they measure with and the tests hold to the
//! tracers lives in the library (`glint::bench`: Ferrari's torus solver, its GPU kernel
//! `shaders/bench/torus.wgsl`, the torus and traversal rays); this module times it,
//! sweeps it and reports.

pub mod cmd;
pub mod common;
pub mod gpu;
pub mod plot_svg;
pub mod sweep;
pub mod sweep_analysis;
pub mod timing;
pub mod torus;
pub mod trace;
pub mod trace_dump;
