//! glint: a Whitted-style ray tracer for CS488 Lua scenes.
//!
//! Data flow (see `docs/architecture.md`): `scene::lua` runs a script into a
//! [`scene::SceneGraph`]; `scene::flatten` bakes it to world space; `pack` lays it out as
//! Pod arrays with a uniform grid from `accel`; `cpu` (the reference) renders those arrays
//! into a [`film::Film`]; `image_io` writes it.

pub mod aa_map;
pub mod accel;
pub mod cli;
pub mod constants;
pub mod cpu;
pub mod diff;
pub mod film;
pub mod gpu;
pub mod image_io;
pub mod pack;
pub mod parity;
pub mod pipeline;
pub mod scene;
#[doc(hidden)]
pub mod testing;
pub mod tiling;
