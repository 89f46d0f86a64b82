//! Subcommand bodies for the `glint` binary: `diff` and the `bench` modes (with the
//! benchmark's own arguments, `bench_common::BenchArgs`); `render`'s arguments and the
//! top-level parsing live in `main.rs`.

pub mod bench_cmd;
pub mod bench_common;
pub mod bench_gpu;
pub mod bench_sweep;
pub mod bench_torus;
pub mod bench_torus_gpu;
pub mod bench_torus_rays;
pub mod bench_trace;
pub mod diff_cmd;
pub mod ferrari;
pub mod plot_svg;
pub mod splitmix;
pub mod stats;
pub mod sweep_analysis;
pub mod timing;
pub mod trace_dump;
pub mod trace_rays;
