//! Subcommand bodies for the `glint` binary; argument parsing lives in `main.rs`.

pub mod bench_cmd;
pub mod diff_cmd;
pub mod stats;
