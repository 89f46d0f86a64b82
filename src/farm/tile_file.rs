//! Tile images: a PNG of the tile's pixels (8-bit RGB, the bytes the full render would
//! hold there) whose tEXt chunks record where it belongs — the full image's size, the
//! tile's pixel bounds, the render's digest ([`super::digest`]) and glint's version.
//! Written atomically through [`crate::image_io::write_via_temp`]; the chunks come before
//! the pixels, so [`read_tile_meta`] reads them without decoding the image.

use crate::film::Film;
use crate::image_io::write_via_temp;
use crate::tiling::PixelRect;
use std::fs::File;
use std::io::{BufReader, BufWriter};
use std::path::{Path, PathBuf};

/// tEXt keywords of a tile's record.
const KEY_FULL_SIZE: &str = "glint:full-size";
const KEY_BOUNDS: &str = "glint:bounds";
const KEY_DIGEST: &str = "glint:digest";
const KEY_VERSION: &str = "glint:version";
const KEY_TILE: &str = "glint:tile";

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

/// Why a tile file cannot be written or read; each names the file.
#[derive(Debug, thiserror::Error)]
pub enum TileFileError {
    #[error("{path}: tiles are written as PNG; give a .png output")]
    NotPng { path: PathBuf },
    #[error("cannot write {path}: {source}")]
    Write {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot read tile {path}: {message}")]
    Read { path: PathBuf, message: String },
    #[error("{path} is not a glint tile: {message}")]
    NotATile { path: PathBuf, message: String },
}

fn is_png(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("png"))
}

/// Checks that `path` can take a tile (a .png in an existing folder), before rendering.
pub fn check_tile_path(path: &Path) -> Result<(), String> {
    if !is_png(path) {
        return Err(TileFileError::NotPng {
            path: path.to_path_buf(),
        }
        .to_string());
    }
    crate::image_io::check_output_path(path).map_err(|e| e.to_string())
}

/// Writes `film` (the tile's pixels) to `path` with `meta`, atomically.
pub fn write_tile(film: &Film, meta: &TileMeta, path: &Path) -> Result<(), TileFileError> {
    if !is_png(path) {
        return Err(TileFileError::NotPng {
            path: path.to_path_buf(),
        });
    }
    let rgb = film.to_rgb8();
    let io = |e: std::io::Error| TileFileError::Write {
        path: path.to_path_buf(),
        source: e,
    };
    let encode = |e: png::EncodingError| std::io::Error::other(e.to_string());
    write_via_temp(path, |temp| -> Result<(), std::io::Error> {
        let file = File::create(temp)?;
        let mut encoder = png::Encoder::new(BufWriter::new(file), film.width, film.height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let (w, h) = meta.full_size;
        for (key, text) in [
            (KEY_FULL_SIZE, format!("{w}x{h}")),
            (KEY_BOUNDS, meta.bounds.to_string()),
            (KEY_DIGEST, meta.digest.clone()),
            (KEY_VERSION, meta.version.clone()),
        ]
        .into_iter()
        .chain(meta.tile.map(|(i, n)| (KEY_TILE, format!("{i}/{n}"))))
        {
            encoder.add_text_chunk(key.into(), text).map_err(encode)?;
        }
        let mut writer = encoder.write_header().map_err(encode)?;
        writer.write_image_data(&rgb).map_err(encode)?;
        writer.finish().map_err(encode)?;
        // finish() flushed the BufWriter; sync by reopening, as File is inside it.
        File::open(temp)?.sync_all()
    })
    .map_err(io)
}

fn open(path: &Path) -> Result<png::Reader<BufReader<File>>, TileFileError> {
    let read_err = |message: String| TileFileError::Read {
        path: path.to_path_buf(),
        message,
    };
    let file = File::open(path).map_err(|e| read_err(e.to_string()))?;
    png::Decoder::new(BufReader::new(file))
        .read_info()
        .map_err(|e| read_err(e.to_string()))
}

/// The record of the tile at `path`.
pub fn read_tile_meta(path: &Path) -> Result<TileMeta, TileFileError> {
    meta_of(path, &open(path)?)
}

fn meta_of(path: &Path, reader: &png::Reader<BufReader<File>>) -> Result<TileMeta, TileFileError> {
    let not_tile = |message: String| TileFileError::NotATile {
        path: path.to_path_buf(),
        message,
    };
    let info = reader.info();
    let text = |key: &str| {
        info.uncompressed_latin1_text
            .iter()
            .find(|c| c.keyword == key)
            .map(|c| c.text.clone())
            .ok_or_else(|| not_tile(format!("it has no {key} text chunk")))
    };
    let size = text(KEY_FULL_SIZE)?;
    let full_size = size
        .split_once('x')
        .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        .ok_or_else(|| not_tile(format!("{KEY_FULL_SIZE} '{size}' is not WxH")))?;
    let bounds_text = text(KEY_BOUNDS)?;
    let bounds = super::spec::parse_crop(&bounds_text)
        .map_err(|e| not_tile(format!("{KEY_BOUNDS}: {e}")))?;
    let (w, h) = full_size;
    if !bounds.fits(w, h) || (bounds.width(), bounds.height()) != (info.width, info.height) {
        return Err(not_tile(format!(
            "its bounds {bounds_text} do not match its {}×{} pixels inside a {w}×{h} image",
            info.width, info.height
        )));
    }
    if (info.color_type, info.bit_depth) != (png::ColorType::Rgb, png::BitDepth::Eight) {
        return Err(not_tile("its pixels are not 8-bit RGB".into()));
    }
    let tile = match text(KEY_TILE) {
        Ok(t) => Some(
            t.split_once('/')
                .and_then(|(i, n)| Some((i.parse().ok()?, n.parse().ok()?)))
                .ok_or_else(|| not_tile(format!("{KEY_TILE} '{t}' is not I/N")))?,
        ),
        Err(_) => None,
    };
    Ok(TileMeta {
        full_size,
        bounds,
        digest: text(KEY_DIGEST)?,
        version: text(KEY_VERSION)?,
        tile,
    })
}

/// The record and the 8-bit RGB pixels (row-major) of the tile at `path`.
pub fn read_tile(path: &Path) -> Result<(TileMeta, Vec<u8>), TileFileError> {
    let mut reader = open(path)?;
    let meta = meta_of(path, &reader)?;
    let read_err = |message: String| TileFileError::Read {
        path: path.to_path_buf(),
        message,
    };
    let len = reader
        .output_buffer_size()
        .ok_or_else(|| read_err("the image is too large".into()))?;
    let mut pixels = vec![0; len];
    let frame = reader
        .next_frame(&mut pixels)
        .map_err(|e| read_err(e.to_string()))?;
    pixels.truncate(frame.buffer_size());
    Ok((meta, pixels))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tile_round_trips_its_pixels_and_record() {
        let dir = crate::testing::scratch::temp_dir("farm-tile-file");
        let path = dir.join("t.png");
        let mut film = Film::new(3, 2);
        film.set(2, 1, [1.0, 0.5, 0.25]);
        let meta = TileMeta {
            full_size: (10, 7),
            bounds: PixelRect {
                x0: 4,
                x1: 7,
                y0: 5,
                y1: 7,
            },
            digest: "ab".repeat(32),
            version: "0.1.0".into(),
            tile: Some((3, 4)),
        };
        write_tile(&film, &meta, &path).unwrap();
        assert_eq!(read_tile_meta(&path).unwrap(), meta);
        let (read_meta, rgb) = read_tile(&path).unwrap();
        assert_eq!(read_meta, meta);
        assert_eq!(rgb, film.to_rgb8());
    }

    #[test]
    fn a_plain_png_is_not_a_tile_and_exr_is_refused() {
        let dir = crate::testing::scratch::temp_dir("farm-tile-plain");
        let path = dir.join("plain.png");
        crate::image_io::write_image(&Film::new(2, 2), &path).unwrap();
        let e = read_tile_meta(&path).unwrap_err().to_string();
        assert!(e.contains("plain.png is not a glint tile"), "{e}");
        let exr = dir.join("t.exr");
        assert!(matches!(
            write_tile(&Film::new(1, 1), &read_meta_stub(), &exr),
            Err(TileFileError::NotPng { .. })
        ));
        assert!(!exr.exists());
    }

    fn read_meta_stub() -> TileMeta {
        TileMeta {
            full_size: (1, 1),
            bounds: PixelRect::full(1, 1),
            digest: String::new(),
            version: String::new(),
            tile: None,
        }
    }
}
