//! Render farms and animations: the interface a farm scheduler drives (Slurm job arrays,
//! Kubernetes Indexed Jobs, any queue that runs one command per task). `glint render`
//! splits an image into tiles (`--tile I/N`, `--crop`) and a script into frames
//! (`--frames`), each written as a file of its own that records where it belongs and a
//! digest of what determined its pixels; `glint assemble` puts tiles back together, bit
//! for bit the full render. See docs/farm.md.
//!
//! Layout: [`spec`] parses the flags' values (the binary's `farm_args` declares the
//! flags), [`split`] cuts an image into tiles, [`digest`] fingerprints a render and a
//! tile's pixels, [`tile_file`] writes tile images (EXR ones with [`tile_exr`]),
//! [`tile_read`] reads them back as untrusted input, [`assemble`] checks and joins them,
//! [`run`] drives a script through frames and tiles.

pub mod assemble;
pub mod digest;
pub mod run;
pub mod spec;
pub mod split;
pub mod tile_exr;
pub mod tile_file;
pub mod tile_read;
