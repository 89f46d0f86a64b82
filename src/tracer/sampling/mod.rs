//! Pixels, tiles and anti-aliasing (none, uniform, adaptive, progressive for
//! `glint view`): which camera samples a pixel takes and how they are summed; built on
//! `path` and below.

pub mod adaptive;
pub mod pixel_sample;
pub mod progressive;
pub mod render;
pub mod sample_source;
