//! The tile atlas: one 128-texel cell per letter A–Z (the letter and its standard point
//! value, as on a real tile) and blank ivory cells, 6×6 cells; and its height map, in
//! which letters and values are engraved.
//!
//! Cell k (A = 0 … Z = 25; 26 and above blank) is column k mod 6, row k div 6 from the
//! image's top. The scene maps a tile's top face onto its letter's cell and the tile's
//! sides onto the blank cell.

use super::canvas::{Canvas, Colour, HeightField};
use super::font::Font;

pub const CELL: u32 = 128;
pub const CELLS_PER_SIDE: u32 = 6;
pub const SIDE: u32 = CELL * CELLS_PER_SIDE;
/// The cell of the blank ivory face (the tiles' sides).
pub const BLANK_CELL: u32 = 26;

const IVORY: Colour = [240.0, 226.0, 190.0];
const INK: Colour = [38.0, 30.0, 24.0];

/// The standard English point value of a letter.
pub fn value(letter: char) -> u32 {
    match letter {
        'A' | 'E' | 'I' | 'L' | 'N' | 'O' | 'R' | 'S' | 'T' | 'U' => 1,
        'D' | 'G' => 2,
        'B' | 'C' | 'M' | 'P' => 3,
        'F' | 'H' | 'V' | 'W' | 'Y' => 4,
        'K' => 5,
        'J' | 'X' => 8,
        'Q' | 'Z' => 10,
        _ => panic!("no tile for {letter:?}"),
    }
}

/// Letter size (pixels per em), and the widest a letter's ink may be (wider letters,
/// W and M, are drawn smaller so they clear the value).
const LETTER_PX: f32 = 96.0;
const LETTER_MAX_INK: f32 = 74.0;
const VALUE_PX: f32 = 34.0;

/// The atlas's colour texture and height map.
pub fn tile_atlas(font: &Font) -> (image::RgbImage, image::GrayImage) {
    let mut canvas = Canvas::new(SIDE, SIDE, IVORY);
    let mut height = HeightField::new(SIDE, SIDE, 1.0);
    for (k, letter) in ('A'..='Z').enumerate() {
        let (x0, y0) = cell_origin(k as u32);
        let mut plot = |x: i32, y: i32, c: f32| {
            canvas.blend(x, y, INK, c);
            height.engrave(x, y, 0.35, c);
        };
        let (ink_width, _) = font.ink_size(&letter.to_string(), LETTER_PX);
        let px = LETTER_PX * (LETTER_MAX_INK / ink_width).min(1.0);
        font.draw_centred(&letter.to_string(), px, x0 + 56.0, y0 + 58.0, &mut plot);
        let digits = value(letter).to_string();
        let value_x = if digits.len() > 1 { 104.0 } else { 110.0 };
        font.draw_centred(&digits, VALUE_PX, x0 + value_x, y0 + 108.0, &mut plot);
    }
    (canvas.to_rgb8(), height.to_luma8())
}

/// Top-left texel of cell k, as floats.
fn cell_origin(k: u32) -> (f32, f32) {
    (
        (k % CELLS_PER_SIDE * CELL) as f32,
        (k / CELLS_PER_SIDE * CELL) as f32,
    )
}
