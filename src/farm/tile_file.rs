//! Tile images: a PNG (8-bit RGB, the bytes the full render's PNG holds there) or an EXR
//! (linear f32 RGB, the full render's floats; [`super::tile_exr`]) of the tile's pixels,
//! whose text chunks (PNG tEXt, EXR text attributes) record where it belongs — the full
//! image's size, the tile's pixel bounds, the render's digest ([`super::digest`]) and
//! glint's version — and the digest of that record and the pixels
//! ([`super::digest::tile_digest`]). Written atomically through
//! [`crate::image_io::write_via_temp`]; read back, as untrusted input, by
//! `tile_read`.

use super::digest::{tile_digest, TilePixels};
use crate::film::Film;
use crate::image_io::write_via_temp;
use crate::tiling::PixelRect;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

/// Text keys of a tile's record.
pub(super) const KEY_FULL_SIZE: &str = "glint:full-size";
pub(super) const KEY_BOUNDS: &str = "glint:bounds";
pub(super) const KEY_DIGEST: &str = "glint:digest";
pub(super) const KEY_VERSION: &str = "glint:version";
pub(super) const KEY_TILE: &str = "glint:tile";
/// The digest of the rest of the record and the pixels; written last.
pub(super) const KEY_PIXELS: &str = "glint:pixels";

/// Where a tile belongs and what rendered it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TileMeta {
    /// The full image's width and height.
    pub full_size: (u32, u32),
    /// The tile's pixels in the full image (half-open).
    pub bounds: PixelRect,
    /// The render's digest (64 hex digits).
    pub digest: String,
    /// The glint version that wrote it.
    pub version: String,
    /// `--tile I/N`'s (I, N), when the tile was one of a split (`--crop` has none).
    pub tile: Option<(u32, u32)>,
}

/// A tile file's format, from its extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TileFormat {
    Png,
    Exr,
}

impl TileFormat {
    pub fn of(path: &Path) -> Option<TileFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "png" => Some(TileFormat::Png),
            "exr" => Some(TileFormat::Exr),
            _ => None,
        }
    }
}

/// Why a tile file cannot be written or read; each names the file.
#[derive(Debug, thiserror::Error)]
pub enum TileFileError {
    #[error(
        "{}: tiles are written as PNG or EXR; give a .png or .exr output",
        crate::display_path::shown(path)
    )]
    NotTileFormat { path: PathBuf },
    #[error("cannot write {}: {source}", crate::display_path::shown(path))]
    Write {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot read tile {}: {message}", crate::display_path::shown(path))]
    Read { path: PathBuf, message: String },
    #[error("{} is not a glint tile: {message}", crate::display_path::shown(path))]
    NotATile { path: PathBuf, message: String },
    #[error("{}: its pixels do not match the digest in its record ({KEY_PIXELS}): the tile was changed or damaged after it was written, or its record is another tile's; render it again", crate::display_path::shown(path))]
    Changed { path: PathBuf },
}

pub(super) fn format_of(path: &Path) -> Result<TileFormat, TileFileError> {
    TileFormat::of(path).ok_or_else(|| TileFileError::NotTileFormat {
        path: path.to_path_buf(),
    })
}

/// Checks that `path` can take a tile (a .png or .exr in an existing folder), before
/// rendering.
pub fn check_tile_path(path: &Path) -> Result<(), String> {
    format_of(path).map_err(|e| e.to_string())?;
    crate::image_io::check_output_path(path).map_err(|e| e.to_string())
}

/// The record as text pairs, in the order written, without its pixel digest (which
/// covers them).
pub(super) fn record(meta: &TileMeta) -> Vec<(&'static str, String)> {
    let (w, h) = meta.full_size;
    let mut pairs = vec![
        (KEY_FULL_SIZE, format!("{w}x{h}")),
        (KEY_BOUNDS, meta.bounds.to_string()),
        (KEY_DIGEST, meta.digest.clone()),
        (KEY_VERSION, meta.version.clone()),
    ];
    if let Some((i, n)) = meta.tile {
        pairs.push((KEY_TILE, format!("{i}/{n}")));
    }
    pairs
}

/// Writes `film` (the tile's pixels) to `path` with `meta`, atomically.
pub fn write_tile(film: &Film, meta: &TileMeta, path: &Path) -> Result<(), TileFileError> {
    let format = format_of(path)?;
    let mut pairs = record(meta);
    let pixel_digest = match format {
        TileFormat::Png => tile_digest(&pairs, TilePixels::Rgb8(&film.to_rgb8())),
        TileFormat::Exr => tile_digest(&pairs, TilePixels::Float(&film.pixels)),
    };
    pairs.push((KEY_PIXELS, pixel_digest));
    let result = write_via_temp(path, |file| -> Result<(), std::io::Error> {
        match format {
            TileFormat::Png => write_png(film, &pairs, file),
            TileFormat::Exr => {
                super::tile_exr::write_exr(film, &pairs, file).map_err(std::io::Error::other)
            }
        }
    });
    result.map_err(|source| TileFileError::Write {
        path: path.to_path_buf(),
        source,
    })
}

fn write_png(film: &Film, pairs: &[(&str, String)], file: &mut File) -> Result<(), std::io::Error> {
    let encode = |e: png::EncodingError| std::io::Error::other(e.to_string());
    let rgb = film.to_rgb8();
    let mut encoder = png::Encoder::new(BufWriter::new(file), film.width, film.height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    for (key, text) in pairs {
        encoder
            .add_text_chunk(key.to_string(), text.clone())
            .map_err(encode)?;
    }
    let mut writer = encoder.write_header().map_err(encode)?;
    writer.write_image_data(&rgb).map_err(encode)?;
    // finish() flushes the BufWriter; write_via_temp syncs the file.
    writer.finish().map_err(encode)
}
