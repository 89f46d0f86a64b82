//! The `cli` test binary: the command line and the scene language end to end (renders,
//! errors, hostile scripts, fuzzing), the house rules and the docs' links.
//! One binary per tier (docs/testing.md) links glint once instead of once per file.

#[path = "../common/mod.rs"]
mod common;

mod cli;
mod doc_links;
mod farm;
mod first_gpu;
mod first_hour;
mod fuzz_front_end;
mod hostile;
mod house;
mod library_crate;
mod pipeline_cache;
mod scene_script;
mod view_cli;
