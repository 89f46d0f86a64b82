//! Writes every texture and height map of glint's scenes into `textures/` (or the folder
//! given as the first argument): `cargo run --example make_textures [-- DIR]`.
//!
//! The generator is deterministic: `tests/images/texture_assets.rs` checks that it reproduces the
//! committed PNGs byte for byte. What each image is, and how the Scrabble scene maps it
//! onto its geometry, is in `docs/scrabble.md`.

#[path = "texture_gen/mod.rs"]
mod texture_gen;

use std::path::PathBuf;

fn main() {
    let dir = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(texture_gen::textures_dir);
    if let Err(e) = texture_gen::write_all(&dir) {
        eprintln!("make_textures: {e}");
        std::process::exit(1);
    }
}
