//! glint: a Whitted-style ray tracer for CS488 Lua scenes.
//!
//! Data flow (see `docs/architecture.md`): `scene::lua` runs a script into a
//! [`scene::SceneGraph`]; `scene::flatten` bakes it to world space, with each mesh kept
//! once in its own space (`scene::instancing`); `pack` lays it out as Pod arrays with the
//! two-level grids from `accel`; `pipeline` hands those arrays to `cpu` (the reference
//! tracer) or `gpu` (its WGSL mirror on wgpu), each rendering into a [`film::Film`];
//! `image_io` writes it, and `parity` compares the two tracers' films.

pub mod aa_map;
pub mod accel;
pub mod bench;
pub mod cli;
pub mod constants;
pub mod cpu;
pub mod diff;
pub mod farm;
pub mod film;
pub mod gpu;
pub mod image_check;
pub mod image_io;
pub mod kernels;
pub mod mailboxes;
pub mod pack;
pub mod parity;
pub mod pipeline;
pub mod queues;
pub mod scene;
pub mod script_driver;
#[doc(hidden)]
pub mod testing;
pub mod tiling;
pub mod view;
pub mod write_policy;
