//! Tile images: a PNG (8-bit RGB, the bytes the full render's PNG holds there) or an EXR
//! (linear f32 RGB, the full render's floats; [`super::tile_exr`]) of the tile's pixels,
//! whose text chunks (PNG tEXt, EXR text attributes) record where it belongs — the full
//! image's size, the tile's pixel bounds, the render's digest ([`super::digest`]) and
//! glint's version. Written atomically through [`crate::image_io::write_via_temp`]; the
//! record comes before the pixels, so [`read_tile_meta`] reads it alone.

use crate::film::Film;
use crate::image_io::write_via_temp;
use crate::tiling::PixelRect;
use std::fs::File;
use std::io::{BufReader, BufWriter};
use std::path::{Path, PathBuf};

/// Text keys of a tile's record.
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
    #[error("{path}: tiles are written as PNG or EXR; give a .png or .exr output")]
    NotTileFormat { path: PathBuf },
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

fn format_of(path: &Path) -> Result<TileFormat, TileFileError> {
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

/// The record as text pairs, in the order written.
fn record(meta: &TileMeta) -> Vec<(&'static str, String)> {
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
    let pairs = record(meta);
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
    let read_err = |message: String| TileFileError::Read {
        path: path.to_path_buf(),
        message,
    };
    match format_of(path)? {
        TileFormat::Png => {
            let reader = open(path)?;
            let info = reader.info();
            if (info.color_type, info.bit_depth) != (png::ColorType::Rgb, png::BitDepth::Eight) {
                return Err(TileFileError::NotATile {
                    path: path.to_path_buf(),
                    message: "its pixels are not 8-bit RGB".into(),
                });
            }
            let text = |key: &str| {
                info.uncompressed_latin1_text
                    .iter()
                    .find(|c| c.keyword == key)
                    .map(|c| c.text.clone())
            };
            meta_from(path, text, (info.width, info.height))
        }
        TileFormat::Exr => {
            let (texts, size) = super::tile_exr::read_exr_record(path).map_err(read_err)?;
            meta_from(path, |key| texts.get(key).cloned(), size)
        }
    }
}

/// The record from its texts, checked against the image's `pixels` (width, height).
fn meta_from(
    path: &Path,
    text: impl Fn(&str) -> Option<String>,
    pixels: (u32, u32),
) -> Result<TileMeta, TileFileError> {
    let not_tile = |message: String| TileFileError::NotATile {
        path: path.to_path_buf(),
        message,
    };
    let need = |key: &str| text(key).ok_or_else(|| not_tile(format!("it has no {key} text")));
    let size = need(KEY_FULL_SIZE)?;
    let full_size = size
        .split_once('x')
        .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        .ok_or_else(|| not_tile(format!("{KEY_FULL_SIZE} '{size}' is not WxH")))?;
    let bounds_text = need(KEY_BOUNDS)?;
    let bounds = super::spec::parse_crop(&bounds_text)
        .map_err(|e| not_tile(format!("{KEY_BOUNDS}: {e}")))?;
    let (w, h) = full_size;
    if !bounds.fits(w, h) || (bounds.width(), bounds.height()) != pixels {
        return Err(not_tile(format!(
            "its bounds {bounds_text} do not match its {}×{} pixels inside a {w}×{h} image",
            pixels.0, pixels.1
        )));
    }
    let tile = match text(KEY_TILE) {
        Some(t) => Some(
            t.split_once('/')
                .and_then(|(i, n)| Some((i.parse().ok()?, n.parse().ok()?)))
                .ok_or_else(|| not_tile(format!("{KEY_TILE} '{t}' is not I/N")))?,
        ),
        None => None,
    };
    Ok(TileMeta {
        full_size,
        bounds,
        digest: need(KEY_DIGEST)?,
        version: need(KEY_VERSION)?,
        tile,
    })
}

/// The record and the pixels of the tile at `path`: a PNG's bytes c as c/255 (which
/// [`Film::to_rgb8`] quantises back to c), an EXR's floats as they are.
pub fn read_tile(path: &Path) -> Result<(TileMeta, Film), TileFileError> {
    let meta = read_tile_meta(path)?;
    let read_err = |message: String| TileFileError::Read {
        path: path.to_path_buf(),
        message,
    };
    let film = match format_of(path)? {
        TileFormat::Png => {
            let mut reader = open(path)?;
            let len = reader
                .output_buffer_size()
                .ok_or_else(|| read_err("the image is too large".into()))?;
            let mut rgb = vec![0; len];
            let frame = reader
                .next_frame(&mut rgb)
                .map_err(|e| read_err(e.to_string()))?;
            rgb.truncate(frame.buffer_size());
            Film {
                width: meta.bounds.width(),
                height: meta.bounds.height(),
                pixels: rgb
                    .chunks_exact(3)
                    .map(|p| [0, 1, 2].map(|c| f32::from(p[c]) / 255.0))
                    .collect(),
            }
        }
        TileFormat::Exr => super::tile_exr::read_exr_film(path).map_err(read_err)?,
    };
    Ok((meta, film))
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
        let (read_meta, read) = read_tile(&path).unwrap();
        assert_eq!(read_meta, meta);
        assert_eq!(read.to_rgb8(), film.to_rgb8());
        // EXR: the floats themselves.
        let exr = dir.join("t.exr");
        film.set(0, 0, [0.123_456_7, 2.5, -0.0]);
        write_tile(&film, &meta, &exr).unwrap();
        assert_eq!(read_tile_meta(&exr).unwrap(), meta);
        let (_, read) = read_tile(&exr).unwrap();
        let bits = |f: &Film| {
            f.pixels
                .iter()
                .flat_map(|p| p.map(f32::to_bits))
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(&read), bits(&film));
    }

    #[test]
    fn a_plain_image_is_not_a_tile_and_jpeg_is_refused() {
        let dir = crate::testing::scratch::temp_dir("farm-tile-plain");
        let path = dir.join("plain.png");
        crate::image_io::write_image(&Film::new(2, 2), &path).unwrap();
        let e = read_tile_meta(&path).unwrap_err().to_string();
        assert!(e.contains("plain.png is not a glint tile"), "{e}");
        let plain_exr = dir.join("plain.exr");
        crate::image_io::write_image(&Film::new(2, 2), &plain_exr).unwrap();
        let e = read_tile_meta(&plain_exr).unwrap_err().to_string();
        assert!(e.contains("plain.exr is not a glint tile"), "{e}");
        let jpg = dir.join("t.jpg");
        assert!(matches!(
            write_tile(&Film::new(1, 1), &read_meta_stub(), &jpg),
            Err(TileFileError::NotTileFormat { .. })
        ));
        assert!(!jpg.exists());
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
