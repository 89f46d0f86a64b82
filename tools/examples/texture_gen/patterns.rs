//! The test patterns of `scenes/textures.lua`: the UV grid (orientation and mirroring
//! read at a glance) and a field of round bumps. Also used by the texture tests.

use image::{GrayImage, RgbImage};

/// Cells per side of the UV grid.
pub const GRID_CELLS: u32 = 8;
/// Texels per side of the UV grid.
pub const GRID_SIDE: u32 = 128;

/// The UV-grid texture: 8×8 cells whose red rises with u (left to right) and green with
/// v (bottom to top), blue alternating like a checkerboard, with dark 1-texel lines on
/// the cells' left and bottom edges and a white dot in cell (0, 0) — the u = v = 0
/// corner — so orientation and mirroring read at a glance.
pub fn uv_grid() -> RgbImage {
    let cell = GRID_SIDE / GRID_CELLS;
    RgbImage::from_fn(GRID_SIDE, GRID_SIDE, |x, y| {
        // Rows count from the image's bottom, as v does.
        let row_from_bottom = GRID_SIDE - 1 - y;
        let (i, j) = (x / cell, row_from_bottom / cell);
        let (cx, cy) = (x % cell, row_from_bottom % cell);
        if cx == 0 || cy == 0 {
            return image::Rgb([20, 20, 20]);
        }
        if i == 0 && j == 0 && (4..=7).contains(&cx) && (4..=7).contains(&cy) {
            return image::Rgb([255, 255, 255]);
        }
        let level = |k: u32| (60 + 195 * k / (GRID_CELLS - 1)) as u8;
        let blue = if (i + j) % 2 == 0 { 200 } else { 40 };
        image::Rgb([level(i), level(j), blue])
    })
}

/// Texels per side of the bump height map.
pub const BUMPS_SIDE: u32 = 64;

/// A periodic height field of 8×8 round bumps: h = ½ + ½·cos(2π·8x)·cos(2π·8y) over the
/// unit square, as 8-bit grey.
pub fn bumps() -> GrayImage {
    GrayImage::from_fn(BUMPS_SIDE, BUMPS_SIDE, |x, y| {
        let tau = std::f64::consts::TAU;
        let u = (x as f64 + 0.5) / BUMPS_SIDE as f64;
        let v = (y as f64 + 0.5) / BUMPS_SIDE as f64;
        let h = 0.5 + 0.5 * (tau * 8.0 * u).cos() * (tau * 8.0 * v).cos();
        image::Luma([(h * 255.0).round() as u8])
    })
}
