//! The deterministic split of a `width × height` image into N tiles: a grid of
//! cols × rows = N cells, the factorisation whose cells are closest to square, cut at
//! `k·width/cols` and `k·height/rows`. Every farm task computes the same grid from
//! (width, height, N) alone, so tile I of N is the same pixels on every machine.

use crate::tiling::PixelRect;

/// Why an image cannot be cut into N tiles.
#[derive(Debug, PartialEq, Eq, thiserror::Error)]
pub enum SplitError {
    #[error("--tile {index}/{count}: the index must be below the tile count (0 to {})", count - 1)]
    IndexOutOfRange { index: u32, count: u32 },
    #[error("--tile .../{count}: a {width}×{height} image has no grid of {count} tiles of at least one pixel each")]
    TooManyTiles { count: u32, width: u32, height: u32 },
}

/// Columns and rows of the N-tile grid of a `width × height` image: among cols × rows = N
/// with cols ≤ width and rows ≤ height, the one whose cells' aspect ratio is nearest 1
/// (ties: fewer columns, so strips of full rows).
pub fn tile_grid(width: u32, height: u32, count: u32) -> Result<(u32, u32), SplitError> {
    let mut best: Option<(f64, u32)> = None;
    for cols in 1..=count {
        if !count.is_multiple_of(cols) {
            continue;
        }
        let rows = count / cols;
        if cols > width || rows > height {
            continue;
        }
        let aspect = (f64::from(width) / f64::from(cols)) / (f64::from(height) / f64::from(rows));
        let badness = aspect.ln().abs();
        // Strictly better only: the first (fewest columns) wins a tie.
        if best.is_none_or(|(b, _)| badness < b - 1e-12) {
            best = Some((badness, cols));
        }
    }
    match best {
        Some((_, cols)) => Ok((cols, count / cols)),
        None => Err(SplitError::TooManyTiles {
            count,
            width,
            height,
        }),
    }
}

/// The pixels of tile `index` (0-based, row-major over the grid) of `count`.
pub fn tile_rect(width: u32, height: u32, index: u32, count: u32) -> Result<PixelRect, SplitError> {
    if index >= count {
        return Err(SplitError::IndexOutOfRange { index, count });
    }
    let (cols, rows) = tile_grid(width, height, count)?;
    let (col, row) = (index % cols, index / cols);
    // u64: width · cols may pass u32.
    let cut =
        |k: u32, side: u32, parts: u32| (u64::from(k) * u64::from(side) / u64::from(parts)) as u32;
    Ok(PixelRect {
        x0: cut(col, width, cols),
        x1: cut(col + 1, width, cols),
        y0: cut(row, height, rows),
        y1: cut(row + 1, height, rows),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every pixel in exactly one tile.
    fn assert_exact_cover(width: u32, height: u32, count: u32) {
        let mut hits = vec![0u8; (width * height) as usize];
        for i in 0..count {
            let r = tile_rect(width, height, i, count).unwrap();
            assert!(!r.is_empty() && r.fits(width, height), "{r:?}");
            for y in r.y0..r.y1 {
                for x in r.x0..r.x1 {
                    hits[(y * width + x) as usize] += 1;
                }
            }
        }
        assert!(hits.iter().all(|&h| h == 1), "{width}×{height} / {count}");
    }

    #[test]
    fn tilings_cover_each_pixel_once() {
        for (w, h) in [(1, 1), (7, 5), (1280, 720), (13, 1), (1, 9)] {
            for n in 1..=16 {
                if tile_grid(w, h, n).is_ok() {
                    assert_exact_cover(w, h, n);
                }
            }
        }
    }

    #[test]
    fn grids_are_near_square() {
        assert_eq!(tile_grid(1280, 720, 1), Ok((1, 1)));
        assert_eq!(tile_grid(1280, 720, 2), Ok((2, 1)));
        assert_eq!(tile_grid(1280, 720, 4), Ok((2, 2)));
        assert_eq!(tile_grid(1280, 720, 8), Ok((4, 2)));
        assert_eq!(tile_grid(1280, 720, 16), Ok((4, 4)));
        assert_eq!(tile_grid(100, 1000, 7), Ok((1, 7)));
    }

    #[test]
    fn impossible_splits_are_errors() {
        assert!(matches!(
            tile_grid(3, 1, 5),
            Err(SplitError::TooManyTiles { .. })
        ));
        assert_eq!(tile_grid(3, 1, 3), Ok((3, 1)));
        assert!(matches!(
            tile_rect(10, 10, 4, 4),
            Err(SplitError::IndexOutOfRange { index: 4, count: 4 })
        ));
    }
}
