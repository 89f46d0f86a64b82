//! The `images` test binary: whole images on the CPU tracer: the exact goldens, the final
//! scene, textures and their assets.
//! One binary per tier (docs/testing.md) links glint once instead of once per file.

// texture_gen and texture_support both include tools/examples/texture_gen/patterns.rs (the
// gpu binary has texture_support alone); two copies of a few pure functions, no state.
#![allow(clippy::duplicate_mod)]

#[path = "../common/mod.rs"]
mod common;
#[path = "../../tools/examples/texture_gen/mod.rs"]
mod texture_gen;
#[path = "../texture_support/mod.rs"]
mod texture_support;

mod depth_of_field;
mod environment;
mod farm_tiles;
mod golden;
mod procedural;
mod procedural_aa;
mod scrabble;
mod texture_assets;
mod textures;
mod wavefront;
