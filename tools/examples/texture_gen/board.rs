//! The Scrabble board: 15×15 squares with the standard premium squares in their real
//! places, coloured and labelled (TW, DW, TL, DL, the centre star), on a frame; and its
//! height map, with a groove between neighbouring squares (the slots that keep the tiles
//! in place, drawn by the bump map).
//!
//! Layout: 1024×1024 texels, a 32-texel frame around 15 squares of 64 texels; row 0 is
//! the image's top. The scene maps it onto a 16×16 board, so one square is one unit.

use super::canvas::{smoothstep, Canvas, Colour, HeightField};
use super::font::Font;

pub const SIDE: u32 = 1024;
pub const FRAME: u32 = 32;
pub const SQUARE: u32 = 64;
pub const SQUARES: u32 = 15;

/// The kind of a board square.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Premium {
    Plain,
    DoubleLetter,
    TripleLetter,
    DoubleWord,
    TripleWord,
    Centre,
}

/// The premium of square (row, column), 0-based: the standard board, which is symmetric
/// about both middle lines and both diagonals, so one eighth of it defines it.
pub fn premium(row: u32, column: u32) -> Premium {
    let (r, c) = (row.min(14 - row), column.min(14 - column));
    let (r, c) = (r.min(c), r.max(c));
    match (r, c) {
        (7, 7) => Premium::Centre,
        (0, 0) | (0, 7) => Premium::TripleWord,
        (1, 1) | (2, 2) | (3, 3) | (4, 4) => Premium::DoubleWord,
        (1, 5) | (5, 5) => Premium::TripleLetter,
        (0, 3) | (2, 6) | (3, 7) | (6, 6) => Premium::DoubleLetter,
        _ => Premium::Plain,
    }
}

const FRAME_COLOUR: Colour = [118.0, 24.0, 32.0];
const LINE_COLOUR: Colour = [236.0, 230.0, 212.0];
const INK_DARK: Colour = [40.0, 28.0, 24.0];
const INK_LIGHT: Colour = [250.0, 246.0, 236.0];

/// Fill colour, label and label colour of a premium.
fn style(p: Premium) -> (Colour, &'static str, Colour) {
    match p {
        Premium::Plain => ([212.0, 202.0, 168.0], "", INK_DARK),
        Premium::DoubleLetter => ([160.0, 204.0, 228.0], "DL", [20.0, 60.0, 110.0]),
        Premium::TripleLetter => ([36.0, 104.0, 186.0], "TL", INK_LIGHT),
        Premium::DoubleWord => ([238.0, 166.0, 162.0], "DW", [120.0, 20.0, 28.0]),
        Premium::TripleWord => ([204.0, 44.0, 38.0], "TW", INK_LIGHT),
        Premium::Centre => ([238.0, 166.0, 162.0], "\u{2605}", INK_DARK),
    }
}

/// Half the width of the light line between squares, in texels.
const LINE_HALF: u32 = 2;

/// The board's colour texture and height map.
pub fn board(font: &Font) -> (image::RgbImage, image::GrayImage) {
    let mut canvas = Canvas::new(SIDE, SIDE, FRAME_COLOUR);
    let grid_end = FRAME + SQUARES * SQUARE;
    canvas.fill_rect(FRAME, FRAME, grid_end, grid_end, LINE_COLOUR);
    for row in 0..SQUARES {
        for column in 0..SQUARES {
            let (x0, y0) = (FRAME + column * SQUARE, FRAME + row * SQUARE);
            let (fill, label, ink) = style(premium(row, column));
            canvas.fill_rect(
                x0 + LINE_HALF,
                y0 + LINE_HALF,
                x0 + SQUARE - LINE_HALF,
                y0 + SQUARE - LINE_HALF,
                fill,
            );
            if !label.is_empty() {
                let px = if label.len() > 2 { 62.0 } else { 30.0 };
                let (cx, cy) = (
                    x0 as f32 + SQUARE as f32 / 2.0,
                    y0 as f32 + SQUARE as f32 / 2.0,
                );
                font.draw_centred(label, px, cx, cy, &mut |x, y, c| canvas.blend(x, y, ink, c));
            }
        }
    }
    (canvas.to_rgb8(), grooves().to_luma8())
}

/// Height 1 inside the squares and on the frame, falling smoothly to 0 along every
/// square edge (a groove 2 × 3 texels wide).
fn grooves() -> HeightField {
    let mut field = HeightField::new(SIDE, SIDE, 1.0);
    let grid_end = FRAME + SQUARES * SQUARE;
    field.paint(|x, y| {
        let inside = |t: u32| (FRAME..=grid_end).contains(&t);
        if !inside(x) || !inside(y) {
            return 1.0;
        }
        // Texel centres' distance to the nearest square edge, in texels.
        let edge_distance = |t: u32| {
            let offset = (t - FRAME) % SQUARE;
            (offset as f32 + 0.5).min(SQUARE as f32 - offset as f32 - 0.5)
        };
        let d = edge_distance(x).min(edge_distance(y));
        0.3 + 0.7 * smoothstep(0.5, 3.5, d)
    });
    field
}
