//! Subcommand bodies for the `glint` binary; argument parsing lives in `main.rs`.

pub mod diff_cmd;
