//! The `gpu` test binary: the GPU tracer against the CPU reference at the four tiers (layout and
//! naga validation, kernel probes, frames, images) and the twins.
//! One binary per tier (docs/testing.md) links glint once instead of once per file.

#[path = "../common/mod.rs"]
mod common;
#[path = "../texture_support/mod.rs"]
mod texture_support;
#[path = "../twin_support/mod.rs"]
mod twin_support;

mod gpu_bench_torus;
mod gpu_corpus;
mod gpu_csg;
mod gpu_cylinder_cone;
mod gpu_depth_of_field;
mod gpu_disk_cache;
mod gpu_environment;
mod gpu_farm_tiles;
mod gpu_frame;
mod gpu_images;
mod gpu_layout;
mod gpu_lists;
mod gpu_mailboxes;
mod gpu_probes;
mod gpu_procedural;
mod gpu_refraction;
mod gpu_scrabble;
mod gpu_textures;
mod gpu_trace_forms;
mod gpu_wavefront;
mod gpu_wavefront_tree;
mod kernel_budget_combinations;
mod kernel_instrument;
mod queue_twins;
mod twins;
mod twins_broken;
mod view;
mod view_window;
