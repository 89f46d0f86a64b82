//! `glint assemble TILE... -o OUT`: the tiles of one render back into its image. The
//! tiles must share one digest and full size and cover the image exactly once; each
//! refusal names the tiles at fault. PNG tiles make a PNG, EXR tiles an EXR; the image is
//! written with
//! [`crate::image_io::write_image`] (atomic), so it is byte for byte the file the full
//! render writes.

use super::tile_file::{read_tile, TileFileError, TileFormat, TileMeta};
use crate::film::Film;
use crate::image_io::{write_image, ImageIoError};
use crate::tiling::PixelRect;
use std::path::{Path, PathBuf};

/// Why tiles cannot be assembled.
#[derive(Debug, thiserror::Error)]
pub enum AssembleError {
    #[error("no tiles given")]
    NoTiles,
    #[error("{output}: the tiles are {tiles}; give an output of that format (.{ext})")]
    FormatMismatch {
        output: PathBuf,
        tiles: &'static str,
        ext: &'static str,
    },
    #[error(
        "{tile} is {tile_format}, {first} {first_format}: the tiles of one image share a format"
    )]
    MixedFormats {
        tile: PathBuf,
        first: PathBuf,
        tile_format: &'static str,
        first_format: &'static str,
    },
    #[error("{0}")]
    Tile(#[from] TileFileError),
    #[error("{tile} is from another render than {first}: digest {tile_digest:.12}… against {first_digest:.12}… (scene, options, tracer or glint version differ)")]
    Foreign {
        tile: PathBuf,
        first: PathBuf,
        tile_digest: String,
        first_digest: String,
    },
    #[error("{tile} is a tile of a {tile_w}×{tile_h} image, {first} of a {first_w}×{first_h} one")]
    SizeMismatch {
        tile: PathBuf,
        first: PathBuf,
        tile_w: u32,
        tile_h: u32,
        first_w: u32,
        first_h: u32,
    },
    #[error("{a} and {b} overlap: pixels {overlap} (x0,x1,y0,y1) are in both")]
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

/// Reads, checks and joins `tiles` (all PNG or all EXR), writing the image to `output`
/// (of the tiles' format: PNG tiles hold 8-bit pixels, EXR tiles the floats).
pub fn assemble(tiles: &[PathBuf], output: &Path) -> Result<(), AssembleError> {
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
    let read: Vec<(TileMeta, Film)> = tiles
        .iter()
        .map(|t| read_tile(t))
        .collect::<Result<_, _>>()?;
    let film = join(tiles, &read)?;
    write_image(&film, output)?;
    Ok(())
}

/// The checks and the join, on tiles read already.
pub fn join(paths: &[PathBuf], tiles: &[(TileMeta, Film)]) -> Result<Film, AssembleError> {
    let Some((first, _)) = tiles.first() else {
        return Err(AssembleError::NoTiles);
    };
    for (k, (meta, _)) in tiles.iter().enumerate() {
        if meta.digest != first.digest {
            return Err(AssembleError::Foreign {
                tile: paths[k].clone(),
                first: paths[0].clone(),
                tile_digest: meta.digest.clone(),
                first_digest: first.digest.clone(),
            });
        }
        if meta.full_size != first.full_size {
            let ((tile_w, tile_h), (first_w, first_h)) = (meta.full_size, first.full_size);
            return Err(AssembleError::SizeMismatch {
                tile: paths[k].clone(),
                first: paths[0].clone(),
                tile_w,
                tile_h,
                first_w,
                first_h,
            });
        }
    }
    let (w, h) = first.full_size;
    // Which tile holds each pixel (u32::MAX: none yet).
    let mut owner = vec![u32::MAX; w as usize * h as usize];
    let mut film = Film::new(w, h);
    for (k, (meta, pixels)) in tiles.iter().enumerate() {
        let b = meta.bounds;
        for y in b.y0..b.y1 {
            for x in b.x0..b.x1 {
                let slot = &mut owner[(y * w + x) as usize];
                if *slot != u32::MAX {
                    let other = *slot as usize;
                    return Err(AssembleError::Overlap {
                        a: paths[other].clone(),
                        b: paths[k].clone(),
                        overlap: tiles[other]
                            .0
                            .bounds
                            .intersection(&b)
                            .expect("they share a pixel"),
                    });
                }
                *slot = k as u32;
                film.set(x, y, pixels.get(x - b.x0, y - b.y0));
            }
        }
    }
    check_no_gap(&owner, w, tiles)?;
    Ok(film)
}

fn check_no_gap(owner: &[u32], w: u32, tiles: &[(TileMeta, Film)]) -> Result<(), AssembleError> {
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

/// `, missing: tile 1/4 (x0,x1,y0,y1), …` when every tile names the same split.
fn missing_tiles(tiles: &[(TileMeta, Film)]) -> String {
    let Some((_, n)) = tiles[0].0.tile else {
        return String::new();
    };
    if tiles.iter().any(|(m, _)| m.tile.map(|t| t.1) != Some(n)) {
        return String::new();
    }
    let (w, h) = tiles[0].0.full_size;
    let names: Vec<String> = (0..n)
        .filter(|i| !tiles.iter().any(|(m, _)| m.tile.map(|t| t.0) == Some(*i)))
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
