//! Tiles read as untrusted input: they come back from other machines, and a farm's node
//! can be broken or hostile. Each file is opened once, as the regular file it is
//! ([`crate::scene::files::read_regular`]: a FIFO or a device refused without blocking, its size checked
//! before it is read), and everything after works on the bytes read: the format told
//! by content, the record parsed and checked — a full size glint could render, bounds
//! inside it matching the pixels, an `I/N` label whose tile of the split has exactly
//! those bounds, an EXR of one part whose data window is checked before the decoder sizes
//! anything from it — and the pixels decoded within a budget and checked against the
//! record's pixel digest ([`super::digest::tile_digest`]).

use super::digest::{tile_digest, TilePixels};
use super::spec::MAX_TILES;
use super::split::tile_rect;
use super::tile_file::{
    format_of, record, TileFileError, TileFormat, TileMeta, KEY_BOUNDS, KEY_DIGEST, KEY_FULL_SIZE,
    KEY_PIXELS, KEY_TILE, KEY_VERSION,
};
use crate::film::Film;
use crate::scene::files::read_regular_within;
use crate::scene::flatten::MAX_PIXELS;
use crate::scene::lua::MAX_IMAGE_SIDE;
use std::io::Cursor;
use std::path::{Path, PathBuf};

/// Largest tile file read (the cap every image file has).
pub const MAX_TILE_FILE_BYTES: u64 = crate::image_check::MAX_IMAGE_FILE_BYTES;

/// Bytes per pixel decoding one tile may hold: its film (12), the decoder's buffers (a
/// PNG's rows, an EXR's chunks) and the digest's rows, with slack (as `glint diff`).
pub const DECODE_BYTES_PER_PIXEL: u64 = 32;

/// What the PNG decoder may allocate for a tile's text chunks and other ancillary data:
/// a record is a few hundred bytes.
const RECORD_BYTES: usize = 1 << 20;

/// A record's text pairs (key, text) as the file holds them.
type TextPairs = Vec<(String, String)>;

/// A tile file read once: its bytes and its checked record. The pixels are decoded from
/// the same bytes ([`TileFile::pixels`]), never from the file again.
pub struct TileFile {
    pub path: PathBuf,
    pub format: TileFormat,
    pub meta: TileMeta,
    /// The record's `glint:pixels`.
    pixel_digest: String,
    bytes: Vec<u8>,
}

impl TileFile {
    /// Reads the tile at `path` (a regular file of at most `max_bytes`) and checks its
    /// record.
    pub fn open(path: &Path, max_bytes: u64) -> Result<TileFile, TileFileError> {
        TileFile::open_within(path, max_bytes, &|len| {
            format!("it is {len} bytes, over the limit of {max_bytes} bytes")
        })
    }

    /// [`TileFile::open`] with a file over `max_bytes` said by `over` (given its size):
    /// `assemble`'s budget names what is left of `--memory-limit`.
    pub fn open_within(
        path: &Path,
        max_bytes: u64,
        over: &dyn Fn(u64) -> String,
    ) -> Result<TileFile, TileFileError> {
        let format = format_of(path)?;
        let read_err = |message: String| TileFileError::Read {
            path: path.to_path_buf(),
            message,
        };
        let bytes = read_regular_within(path, "tile", max_bytes, over).map_err(read_err)?;
        let by_content = crate::image_check::sniff(&bytes);
        let (expected, name) = match format {
            TileFormat::Png => (image::ImageFormat::Png, "a PNG"),
            TileFormat::Exr => (image::ImageFormat::OpenExr, "an OpenEXR image"),
        };
        if by_content != Some(expected) {
            return Err(not_tile(
                path,
                format!("its content is not {name}, as its name says"),
            ));
        }
        let (texts, size): (TextPairs, (u32, u32)) = match format {
            TileFormat::Png => png_record(&bytes).map_err(read_err)?,
            TileFormat::Exr => {
                let (texts, size) =
                    super::tile_exr::read_exr_record(&bytes, MAX_PIXELS).map_err(read_err)?;
                (texts.into_iter().collect(), size)
            }
        };
        let text = |key: &str| texts.iter().find(|(k, _)| k == key).map(|(_, v)| v.clone());
        let (meta, pixel_digest) = meta_from(path, text, size)?;
        Ok(TileFile {
            path: path.to_path_buf(),
            format,
            meta,
            pixel_digest,
            bytes,
        })
    }

    /// The bytes the file held (what the tile costs while it is kept).
    pub fn file_len(&self) -> u64 {
        self.bytes.len() as u64
    }

    /// The most bytes [`TileFile::pixels`] may take.
    pub fn decode_bytes(&self) -> u64 {
        let b = self.meta.bounds;
        u64::from(b.width()) * u64::from(b.height()) * DECODE_BYTES_PER_PIXEL
    }

    /// The tile's pixels, checked against the record's pixel digest: a PNG's bytes c as
    /// c/255 (which [`Film::to_rgb8`] quantises back to c), an EXR's floats as they are.
    /// Refused when decoding could take more than `budget` bytes.
    pub fn pixels(&self, budget: u64) -> Result<Film, TileFileError> {
        let read_err = |message: String| TileFileError::Read {
            path: self.path.clone(),
            message,
        };
        if self.decode_bytes() > budget {
            return Err(read_err(format!(
                "decoding its {}×{} pixels may take {} MiB, over the {} MiB left of the memory limit; --memory-limit MIB raises it",
                self.meta.bounds.width(),
                self.meta.bounds.height(),
                self.decode_bytes().div_ceil(1 << 20),
                budget >> 20
            )));
        }
        let (film, digest) = match self.format {
            TileFormat::Png => {
                let rgb = png_pixels(&self.bytes).map_err(read_err)?;
                let digest = tile_digest(&record(&self.meta), TilePixels::Rgb8(&rgb));
                let film = Film {
                    width: self.meta.bounds.width(),
                    height: self.meta.bounds.height(),
                    pixels: rgb
                        .chunks_exact(3)
                        .map(|p| [0, 1, 2].map(|c| f32::from(p[c]) / 255.0))
                        .collect(),
                };
                (film, digest)
            }
            TileFormat::Exr => {
                let film = super::tile_exr::read_exr_film(&self.bytes).map_err(read_err)?;
                let digest = tile_digest(&record(&self.meta), TilePixels::Float(&film.pixels));
                (film, digest)
            }
        };
        let b = self.meta.bounds;
        if (film.width, film.height) != (b.width(), b.height())
            || film.pixels.len() != b.width() as usize * b.height() as usize
        {
            return Err(read_err(format!(
                "its pixels are {}×{}, its record says {}×{}",
                film.width,
                film.height,
                b.width(),
                b.height()
            )));
        }
        if digest != self.pixel_digest {
            return Err(TileFileError::Changed {
                path: self.path.clone(),
            });
        }
        Ok(film)
    }
}

fn not_tile(path: &Path, message: String) -> TileFileError {
    TileFileError::NotATile {
        path: path.to_path_buf(),
        message,
    }
}

/// A PNG decoder over `bytes`, its ancillary chunks held to [`RECORD_BYTES`].
fn png_reader(bytes: &[u8]) -> Result<png::Reader<Cursor<&[u8]>>, String> {
    let limits = png::Limits {
        bytes: RECORD_BYTES,
    };
    png::Decoder::new_with_limits(Cursor::new(bytes), limits)
        .read_info()
        .map_err(|e| e.to_string())
}

/// A PNG tile's text chunks and size, refusing any pixel format but 8-bit RGB.
fn png_record(bytes: &[u8]) -> Result<(TextPairs, (u32, u32)), String> {
    let reader = png_reader(bytes)?;
    let info = reader.info();
    let rgb8 = (png::ColorType::Rgb, png::BitDepth::Eight);
    if (info.color_type, info.bit_depth) != rgb8 || reader.output_color_type() != rgb8 {
        return Err("its pixels are not 8-bit RGB, as a tile's are".into());
    }
    let texts = info
        .uncompressed_latin1_text
        .iter()
        .map(|c| (c.keyword.clone(), c.text.clone()))
        .collect();
    Ok((texts, (info.width, info.height)))
}

/// A PNG tile's RGB bytes (its size checked by [`png_record`] and the record already).
fn png_pixels(bytes: &[u8]) -> Result<Vec<u8>, String> {
    let mut reader = png_reader(bytes)?;
    let len = reader
        .output_buffer_size()
        .ok_or("the image is too large")?;
    let mut rgb = Vec::new();
    rgb.try_reserve_exact(len).map_err(|e| e.to_string())?;
    rgb.resize(len, 0);
    let frame = reader.next_frame(&mut rgb).map_err(|e| e.to_string())?;
    rgb.truncate(frame.buffer_size());
    Ok(rgb)
}

/// The record from its texts, checked against the image's `pixels` (width, height) and
/// the split, with its pixel digest.
fn meta_from(
    path: &Path,
    text: impl Fn(&str) -> Option<String>,
    pixels: (u32, u32),
) -> Result<(TileMeta, String), TileFileError> {
    let not_tile = |message: String| not_tile(path, message);
    let need = |key: &str| text(key).ok_or_else(|| not_tile(format!("it has no {key} text")));
    let size = need(KEY_FULL_SIZE)?;
    let full_size: (u32, u32) = size
        .split_once('x')
        .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        .ok_or_else(|| not_tile(format!("{KEY_FULL_SIZE} '{size}' is not WxH")))?;
    let (w, h) = full_size;
    if w == 0
        || h == 0
        || w > MAX_IMAGE_SIDE
        || h > MAX_IMAGE_SIDE
        || u64::from(w) * u64::from(h) > MAX_PIXELS
    {
        return Err(not_tile(format!(
            "it claims to be part of a {w}×{h} image, which glint never renders (at most {MAX_PIXELS} pixels, each side at most {MAX_IMAGE_SIDE})"
        )));
    }
    let bounds_text = need(KEY_BOUNDS)?;
    let bounds = super::spec::parse_crop(&bounds_text)
        .map_err(|e| not_tile(format!("{KEY_BOUNDS}: {e}")))?;
    if !bounds.fits(w, h) || (bounds.width(), bounds.height()) != pixels {
        return Err(not_tile(format!(
            "its bounds {bounds_text} do not match its {}×{} pixels inside a {w}×{h} image",
            pixels.0, pixels.1
        )));
    }
    let tile = match text(KEY_TILE) {
        Some(t) => {
            let label = t
                .split_once('/')
                .and_then(|(i, n)| Some((i.parse().ok()?, n.parse().ok()?)))
                .ok_or_else(|| not_tile(format!("{KEY_TILE} '{t}' is not I/N")))?;
            check_label(label, full_size, bounds).map_err(not_tile)?;
            Some(label)
        }
        None => None,
    };
    let digest = need(KEY_DIGEST)?;
    if !is_hex_digest(&digest) {
        return Err(not_tile(format!("its {KEY_DIGEST} is not 64 hex digits")));
    }
    let Some(pixel_digest) = text(KEY_PIXELS) else {
        return Err(not_tile(format!(
            "it has no {KEY_PIXELS} digest of its pixels (written by a glint from before tiles had one, or not by glint): render it again"
        )));
    };
    if !is_hex_digest(&pixel_digest) {
        return Err(not_tile(format!("its {KEY_PIXELS} is not 64 hex digits")));
    }
    let meta = TileMeta {
        full_size,
        bounds,
        digest,
        version: need(KEY_VERSION)?,
        tile,
    };
    Ok((meta, pixel_digest))
}

/// Checks that tile `i` of `n` of a `full_size` image has exactly `bounds` under the
/// split every farm task computes ([`tile_rect`]).
fn check_label(
    (i, n): (u32, u32),
    (w, h): (u32, u32),
    bounds: crate::tiling::PixelRect,
) -> Result<(), String> {
    if n == 0 || n > MAX_TILES || i >= n {
        return Err(format!(
            "its label {i}/{n} is no tile of a split (--tile takes 1 to {MAX_TILES} tiles, numbered from 0)"
        ));
    }
    let expected = tile_rect(w, h, i, n).map_err(|e| format!("its label {i}/{n}: {e}"))?;
    if expected != bounds {
        return Err(format!(
            "it is labelled tile {i}/{n}, whose pixels in a {w}×{h} image are {expected} (x0,x1,y0,y1), but its bounds are {bounds}"
        ));
    }
    Ok(())
}

fn is_hex_digest(s: &str) -> bool {
    s.len() == 64 && s.bytes().all(|b| b.is_ascii_hexdigit())
}

/// The record of the tile at `path` (read as [`TileFile::open`] reads it).
pub fn read_tile_meta(path: &Path) -> Result<TileMeta, TileFileError> {
    Ok(TileFile::open(path, MAX_TILE_FILE_BYTES)?.meta)
}

/// The record and the pixels of the tile at `path`, checked against its pixel digest
/// (within `budget` bytes for decoding).
pub fn read_tile(path: &Path, budget: u64) -> Result<(TileMeta, Film), TileFileError> {
    let tile = TileFile::open(path, MAX_TILE_FILE_BYTES)?;
    let film = tile.pixels(budget)?;
    Ok((tile.meta, film))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::farm::tile_file::write_tile;
    use crate::tiling::PixelRect;

    #[test]
    fn a_tile_round_trips_its_pixels_and_record() {
        let (dir, path) = crate::testing::scratch::temp_file("farm-tile-file", "t.png");
        // Tile 3 of 4 of a 10×7 image (a 2×2 grid): columns 5..10, rows 3..7.
        let mut film = Film::new(5, 4);
        film.set(2, 1, [1.0, 0.5, 0.25]);
        let meta = TileMeta {
            full_size: (10, 7),
            bounds: PixelRect {
                x0: 5,
                x1: 10,
                y0: 3,
                y1: 7,
            },
            digest: "ab".repeat(32),
            version: "0.1.0".into(),
            tile: Some((3, 4)),
        };
        write_tile(&film, &meta, &path).unwrap();
        assert_eq!(read_tile_meta(&path).unwrap(), meta);
        let (read_meta, read) = read_tile(&path, 1 << 20).unwrap();
        assert_eq!(read_meta, meta);
        assert_eq!(read.to_rgb8(), film.to_rgb8());
        // EXR: the floats themselves.
        let exr = dir.join("t.exr");
        film.set(0, 0, [0.123_456_7, 2.5, -0.0]);
        write_tile(&film, &meta, &exr).unwrap();
        assert_eq!(read_tile_meta(&exr).unwrap(), meta);
        let (_, read) = read_tile(&exr, 1 << 20).unwrap();
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

    #[test]
    fn a_label_must_name_the_tile_of_the_split_with_its_bounds() {
        let first = tile_rect(16, 8, 0, 2).unwrap();
        assert_eq!(check_label((0, 2), (16, 8), first), Ok(()));
        let e = check_label((1, 2), (16, 8), first).unwrap_err();
        assert!(
            e.contains("labelled tile 1/2") && e.contains("8,16,0,8"),
            "{e}"
        );
        // Forged counts: over --tile's limit, or no grid of that many tiles (65537 is prime).
        for (label, needle) in [
            ((0, u32::MAX), "4294967295"),
            ((0, 65537), "65537"),
            ((3, 2), "3/2"),
        ] {
            let e = check_label(label, (16, 8), first).unwrap_err();
            assert!(e.contains(needle), "{e}");
        }
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
