//! glint: a Whitted-style ray tracer for CS488 Lua scenes, as a library; the `glint`
//! command line (`src/bin/glint/`) is one program built on it.
//!
//! Data flow (see `docs/architecture.md`): `scene::lua` runs a script into a
//! [`scene::SceneGraph`]; `scene::flatten` bakes it to world space, with each mesh kept
//! once in its own space (`scene::instancing`); `pack` lays it out as Pod arrays with the
//! two-level grids from `accel`; `pipeline` hands those arrays to `cpu` (the reference
//! tracer) or `gpu` (its WGSL mirror on wgpu), each rendering into a [`film::Film`];
//! `image_io` writes it, and `parity` compares the two tracers' films.
//!
//! An embedding program calls [`pipeline::run_scene`] (a script to image files, its
//! progress through a [`pipeline::ProgressSink`] of its own), or the steps themselves;
//! `farm` splits renders into tiles and frames and assembles them, `diff` compares
//! images, `bench` holds the benchmarks' measuring core. The library uses none of the
//! binary's crates (clap, indicatif, winit, ash: the default `cli` feature), so
//! `glint = { default-features = false }` builds without them.

pub mod aa_map;
pub mod accel;
pub mod atomic_write;
pub mod bench;
pub mod constants;
pub mod diff;
pub mod display_path;
pub mod farm;
pub mod file_name;
pub mod film;
pub mod folder_walk;
pub mod gpu;
pub mod image_check;
pub mod image_io;
pub mod mailboxes;
pub mod pack;
pub mod parity;
pub mod pipeline;
pub mod scene;
pub mod script_driver;
#[doc(hidden)]
pub mod testing;
pub mod tiling;
pub mod tracer;
pub mod write_policy;
