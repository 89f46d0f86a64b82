//! `glint assemble TILE... -o OUT`: the tiles of one render back into its image. The
//! tiles are untrusted input ([`super::tile_read`]): each is read once and its record
//! checked, then the memory the whole job takes (the tiles' files, the image, decoding
//! the largest tile) is checked against the budget before the image is allocated; the
//! tiles must share one digest and full size and cover the image exactly once, and each
//! tile's pixels must match its record's digest. Each refusal names the tiles at fault.
//! PNG tiles make a PNG, EXR tiles an EXR; the image is written with
//! [`crate::image_io::write_image`] (atomic), so it is byte for byte the file the full
//! render writes.

use super::tile_file::{TileFileError, TileFormat};
use super::tile_read::{TileFile, MAX_TILE_FILE_BYTES};
use crate::film::Film;
use crate::image_io::{write_image, ImageIoError};
use crate::tiling::PixelRect;
use std::collections::HashSet;
use std::path::{Path, PathBuf};

/// Bytes per pixel of the full image that assembling holds: the film (12), which tile
/// owns each pixel (4), and the encoder's copies while it writes (at most 16).
pub const ASSEMBLE_BYTES_PER_PIXEL: u64 = 32;

/// Why tiles cannot be assembled.
#[derive(Debug, thiserror::Error)]
pub enum AssembleError {
    #[error("no tiles given")]
    NoTiles,
    #[error(
        "{}: the tiles are {tiles}; give an output of that format (.{ext})",
        crate::display_path::shown(output)
    )]
    FormatMismatch {
        output: PathBuf,
        tiles: &'static str,
        ext: &'static str,
    },
    #[error(
        "{} is {tile_format}, {} {first_format}: the tiles of one image share a format",
        crate::display_path::shown(tile),
        crate::display_path::shown(first)
    )]
    MixedFormats {
        tile: PathBuf,
        first: PathBuf,
        tile_format: &'static str,
        first_format: &'static str,
    },
    #[error("{0}")]
    Tile(#[from] TileFileError),
    #[error("{} is from another render than {}: digest {tile_digest:.12}… against {first_digest:.12}… (scene, options, tracer or glint version differ)", crate::display_path::shown(tile), crate::display_path::shown(first))]
    Foreign {
        tile: PathBuf,
        first: PathBuf,
        tile_digest: String,
        first_digest: String,
    },
    #[error(
        "{} is a tile of a {tile_w}×{tile_h} image, {} of a {first_w}×{first_h} one",
        crate::display_path::shown(tile),
        crate::display_path::shown(first)
    )]
    SizeMismatch {
        tile: PathBuf,
        first: PathBuf,
        tile_w: u32,
        tile_h: u32,
        first_w: u32,
        first_h: u32,
    },
    #[error(
        "{} and {} overlap: pixels {overlap} (x0,x1,y0,y1) are in both",
        crate::display_path::shown(a),
        crate::display_path::shown(b)
    )]
    Overlap {
        a: PathBuf,
        b: PathBuf,
        overlap: PixelRect,
    },
    #[error("the tiles leave a gap: {missing} pixels are in no tile, within {bounds} (x0,x1,y0,y1){named}")]
    Gap {
        missing: u64,
        bounds: PixelRect,
        /// The missing tiles of the split, when the tiles name one (`, missing: tile 3/8 …`).
        named: String,
    },
    #[error("{}: assembling its {w}×{h} image from {count} tiles may take {need_mib} MiB (the tiles' files, the image, decoding the largest tile), over the memory limit of {limit_mib} MiB; --memory-limit MIB raises it", crate::display_path::shown(first))]
    OverBudget {
        first: PathBuf,
        w: u32,
        h: u32,
        count: usize,
        need_mib: u64,
        limit_mib: u64,
    },
    #[error("{0}")]
    Output(#[from] ImageIoError),
}

impl AssembleError {
    /// Exit code: 4 when the output could not be written, else 2 (the tiles given).
    pub fn exit_code(&self) -> u8 {
        match self {
            AssembleError::Output(_) => 4,
            _ => 2,
        }
    }
}

/// Reads, checks and joins `tiles` (all PNG or all EXR) within `budget` bytes, writing the
/// image to `output` (of the tiles' format: PNG tiles hold 8-bit pixels, EXR tiles the
/// floats).
pub fn assemble(tiles: &[PathBuf], output: &Path, budget: u64) -> Result<(), AssembleError> {
    let Some(first) = tiles.first() else {
        return Err(AssembleError::NoTiles);
    };
    let name = |f: Option<TileFormat>| match f {
        Some(TileFormat::Png) => "PNG",
        Some(TileFormat::Exr) => "EXR",
        None => "neither PNG nor EXR",
    };
    let format = TileFormat::of(first);
    for t in tiles {
        if TileFormat::of(t) != format {
            return Err(AssembleError::MixedFormats {
                tile: t.clone(),
                first: first.clone(),
                tile_format: name(TileFormat::of(t)),
                first_format: name(format),
            });
        }
    }
    if format.is_some() && TileFormat::of(output) != format {
        return Err(AssembleError::FormatMismatch {
            output: output.to_path_buf(),
            tiles: name(format),
            ext: if format == Some(TileFormat::Png) {
                "png"
            } else {
                "exr"
            },
        });
    }
    crate::image_io::check_output_path(output)?;
    let read = read_tiles(tiles, budget)?;
    check_alike(&read)?;
    check_budget(&read, budget)?;
    let film = join(&read)?;
    write_image(&film, output)?;
    Ok(())
}

/// Reads each tile once, its file counted against `budget` before it is read.
fn read_tiles(paths: &[PathBuf], budget: u64) -> Result<Vec<TileFile>, AssembleError> {
    let mut held = 0u64;
    let mut tiles = Vec::with_capacity(paths.len());
    for (index, path) in paths.iter().enumerate() {
        let left = budget.saturating_sub(held);
        let tile = if left < MAX_TILE_FILE_BYTES {
            // The budget, not the tile file cap, is what this file would pass.
            let over = |len: u64| {
                format!(
                    "it is {len} bytes; with the {index} tiles read before it ({held} bytes) that passes the memory limit of {} MiB; --memory-limit MIB raises it",
                    budget >> 20
                )
            };
            TileFile::open_within(path, left, &over)?
        } else {
            TileFile::open(path, MAX_TILE_FILE_BYTES)?
        };
        held += tile.file_len();
        tiles.push(tile);
    }
    Ok(tiles)
}

/// The tiles share one render digest and one full size.
fn check_alike(tiles: &[TileFile]) -> Result<(), AssembleError> {
    let Some(first) = tiles.first() else {
        return Err(AssembleError::NoTiles);
    };
    for tile in tiles {
        let (meta, first_meta) = (&tile.meta, &first.meta);
        if meta.digest != first_meta.digest {
            return Err(AssembleError::Foreign {
                tile: tile.path.clone(),
                first: first.path.clone(),
                tile_digest: meta.digest.clone(),
                first_digest: first_meta.digest.clone(),
            });
        }
        if meta.full_size != first_meta.full_size {
            let ((tile_w, tile_h), (first_w, first_h)) = (meta.full_size, first_meta.full_size);
            return Err(AssembleError::SizeMismatch {
                tile: tile.path.clone(),
                first: first.path.clone(),
                tile_w,
                tile_h,
                first_w,
                first_h,
            });
        }
    }
    Ok(())
}

/// What assembling `tiles` may hold at most, against `budget`: their files, the full
/// image and the decoding of the largest tile (tiles are decoded one at a time).
fn check_budget(tiles: &[TileFile], budget: u64) -> Result<(), AssembleError> {
    let (w, h) = tiles[0].meta.full_size;
    let files: u64 = tiles.iter().map(TileFile::file_len).sum();
    let decode = tiles.iter().map(TileFile::decode_bytes).max().unwrap_or(0);
    let image = u64::from(w) * u64::from(h) * ASSEMBLE_BYTES_PER_PIXEL;
    let need = files + image + decode;
    if need > budget {
        return Err(AssembleError::OverBudget {
            first: tiles[0].path.clone(),
            w,
            h,
            count: tiles.len(),
            need_mib: need.div_ceil(1 << 20),
            limit_mib: budget >> 20,
        });
    }
    Ok(())
}

/// The join, on tiles whose records are checked and fit the budget: each tile's place is
/// claimed (overlaps refused) before its pixels are decoded and checked.
fn join(tiles: &[TileFile]) -> Result<Film, AssembleError> {
    let (w, h) = tiles[0].meta.full_size;
    let decode_budget = tiles.iter().map(TileFile::decode_bytes).max().unwrap_or(0);
    // Which tile holds each pixel (u32::MAX: none yet).
    let mut owner = vec![u32::MAX; w as usize * h as usize];
    let mut film = Film::new(w, h);
    for (k, tile) in tiles.iter().enumerate() {
        let b = tile.meta.bounds;
        for y in b.y0..b.y1 {
            for x in b.x0..b.x1 {
                let slot = &mut owner[(y * w + x) as usize];
                if *slot != u32::MAX {
                    let other = &tiles[*slot as usize];
                    return Err(AssembleError::Overlap {
                        a: other.path.clone(),
                        b: tile.path.clone(),
                        overlap: other
                            .meta
                            .bounds
                            .intersection(&b)
                            .expect("they share a pixel"),
                    });
                }
                *slot = k as u32;
            }
        }
        let pixels = tile.pixels(decode_budget)?;
        for y in b.y0..b.y1 {
            for x in b.x0..b.x1 {
                film.set(x, y, pixels.get(x - b.x0, y - b.y0));
            }
        }
    }
    check_no_gap(&owner, w, tiles)?;
    Ok(film)
}

fn check_no_gap(owner: &[u32], w: u32, tiles: &[TileFile]) -> Result<(), AssembleError> {
    let mut missing = 0u64;
    let mut bounds: Option<PixelRect> = None;
    for (p, &o) in owner.iter().enumerate() {
        if o != u32::MAX {
            continue;
        }
        missing += 1;
        let (x, y) = (p as u32 % w, p as u32 / w);
        let b = bounds.get_or_insert(PixelRect {
            x0: x,
            x1: x + 1,
            y0: y,
            y1: y + 1,
        });
        *b = PixelRect {
            x0: b.x0.min(x),
            x1: b.x1.max(x + 1),
            y0: b.y0.min(y),
            y1: b.y1.max(y + 1),
        };
    }
    let Some(bounds) = bounds else {
        return Ok(());
    };
    Err(AssembleError::Gap {
        missing,
        bounds,
        named: missing_tiles(tiles),
    })
}

/// `, missing: tile 1/4 (x0,x1,y0,y1), …` when every tile names the same split (their
/// labels checked against it already).
fn missing_tiles(tiles: &[TileFile]) -> String {
    let Some((_, n)) = tiles[0].meta.tile else {
        return String::new();
    };
    if tiles.iter().any(|t| t.meta.tile.map(|t| t.1) != Some(n)) {
        return String::new();
    }
    let (w, h) = tiles[0].meta.full_size;
    let present: HashSet<u32> = tiles
        .iter()
        .filter_map(|t| t.meta.tile)
        .map(|t| t.0)
        .collect();
    let names: Vec<String> = (0..n)
        .filter(|i| !present.contains(i))
        .take(8)
        .map(|i| match super::split::tile_rect(w, h, i, n) {
            Ok(r) => format!("tile {i}/{n} ({r})"),
            Err(_) => format!("tile {i}/{n}"),
        })
        .collect();
    if names.is_empty() {
        return String::new();
    }
    format!("; missing: {}", names.join(", "))
}
