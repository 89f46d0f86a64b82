//! The texture generator behind `tools/examples/make_textures.rs`: every image of `textures/`
//! as PNG bytes, made from code and a font in the repository (nothing else is read), so
//! the same build always makes the same bytes.

#![allow(dead_code)]

pub mod board;
pub mod canvas;
pub mod font;
pub mod noise;
pub mod patterns;
pub mod tiles;
pub mod wood;

use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ExtendedColorType, ImageEncoder};
use std::path::{Path, PathBuf};

/// The repository's `textures/` folder.
pub fn textures_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("textures")
}

/// One generated image: its file name under `textures/` and its PNG bytes.
pub struct Asset {
    pub name: &'static str,
    pub png: Vec<u8>,
}

/// Every generated asset, in a fixed order.
pub fn all_assets() -> Vec<Asset> {
    let font = font::Font::load();
    let (board_colour, board_height) = board::board(&font);
    let (tiles_colour, tiles_height) = tiles::tile_atlas(&font);
    let (wood_colour, wood_height) = wood::wood();
    vec![
        Asset {
            name: "uv-grid.png",
            png: encode_rgb(&patterns::uv_grid()),
        },
        Asset {
            name: "bumps.png",
            png: encode_grey(&patterns::bumps()),
        },
        Asset {
            name: "scrabble-board.png",
            png: encode_rgb(&board_colour),
        },
        Asset {
            name: "scrabble-board-height.png",
            png: encode_grey(&board_height),
        },
        Asset {
            name: "scrabble-tiles.png",
            png: encode_rgb(&tiles_colour),
        },
        Asset {
            name: "scrabble-tiles-height.png",
            png: encode_grey(&tiles_height),
        },
        Asset {
            name: "wood.png",
            png: encode_rgb(&wood_colour),
        },
        Asset {
            name: "wood-height.png",
            png: encode_grey(&wood_height),
        },
    ]
}

/// Writes every asset into `dir` (each to a temporary file, then renamed).
pub fn write_all(dir: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    for asset in all_assets() {
        let path = dir.join(asset.name);
        let temporary = dir.join(format!(".{}.tmp", asset.name));
        std::fs::write(&temporary, &asset.png)?;
        std::fs::rename(&temporary, &path)?;
        println!("{} ({} bytes)", path.display(), asset.png.len());
    }
    Ok(())
}

/// PNG bytes of an RGB image: best compression, adaptive filters (the smallest files).
pub fn encode_rgb(image: &image::RgbImage) -> Vec<u8> {
    encode(
        image.as_raw(),
        image.width(),
        image.height(),
        ExtendedColorType::Rgb8,
    )
}

/// PNG bytes of a grey image.
pub fn encode_grey(image: &image::GrayImage) -> Vec<u8> {
    encode(
        image.as_raw(),
        image.width(),
        image.height(),
        ExtendedColorType::L8,
    )
}

fn encode(raw: &[u8], width: u32, height: u32, colour: ExtendedColorType) -> Vec<u8> {
    let mut bytes = Vec::new();
    PngEncoder::new_with_quality(&mut bytes, CompressionType::Best, FilterType::Adaptive)
        .write_image(raw, width, height, colour)
        .expect("encoding a PNG in memory cannot fail");
    bytes
}
