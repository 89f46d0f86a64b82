//! `glint bench`: the benchmarks, kept apart from the tracers. Each speed figure is
//! printed with the error it was measured at; `cmd::run_bench` dispatches on the
//! arguments (`common::BenchArgs`). Their GPU kernel is `shaders/bench/torus.wgsl`.

pub mod cmd;
pub mod common;
pub mod ferrari;
pub mod gpu;
pub mod plot_svg;
pub mod splitmix;
pub mod sweep;
pub mod sweep_analysis;
pub mod timing;
pub mod torus;
pub mod torus_gpu;
pub mod torus_rays;
pub mod trace;
pub mod trace_dump;
pub mod trace_rays;
