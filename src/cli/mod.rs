//! Subcommand bodies of the `glint` binary besides rendering: `diff`, `kernels`, and `--stats`'
//! report of a render. `render`'s arguments and the top-level parsing live in `main.rs`;
//! the `bench` modes live in [`crate::bench`].

pub mod diff_cmd;
pub mod kernels_cmd;
pub mod stats;
