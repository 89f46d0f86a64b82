//! The table's wood: four planks with their grain along u (wavy growth lines from
//! fractal noise, each plank its own shade and grain offset, butt joints at staggered
//! places), and the matching height map (the grain's dark lines and the seams between
//! planks lie lower). Both tile seamlessly: every noise is periodic over the image.

use super::canvas::{mix, smoothstep, Canvas, Colour, HeightField};
use super::noise::fractal;

pub const SIDE: u32 = 512;
pub const PLANKS: u32 = 4;
const PLANK: u32 = SIDE / PLANKS;

const LIGHT: Colour = [200.0, 146.0, 92.0];
const DARK: Colour = [128.0, 78.0, 42.0];
const SEAM: Colour = [70.0, 42.0, 24.0];

/// Per plank: shade (0 light … 1 dark), grain offset, joint position (texels along u).
const PLANK_STYLE: [(f32, f32, u32); PLANKS as usize] = [
    (0.15, 0.0, 90),
    (0.35, 3.7, 330),
    (0.05, 7.1, 20),
    (0.25, 1.9, 250),
];

/// What a texel of wood is: its darkness (0 light … 1 dark) and whether it is a seam.
fn wood_at(x: u32, y: u32) -> (f32, f32) {
    let (u, v) = (
        (x as f32 + 0.5) / SIDE as f32,
        (y as f32 + 0.5) / SIDE as f32,
    );
    let plank = y / PLANK;
    let (shade, offset, joint) = PLANK_STYLE[plank as usize];
    // Growth lines: stripes across v, bent by low-frequency noise along u.
    let bend = fractal(u, v, 2, 8, 3, 11 + plank);
    let lines = (v * 96.0 + offset + 5.0 * bend).rem_euclid(1.0);
    let grain = smoothstep(0.55, 0.95, lines) * (1.0 - smoothstep(0.95, 1.0, lines));
    let streaks = fractal(u, v, 3, 48, 2, 31 + plank);
    let darkness = (0.25 * shade + 0.5 * grain + 0.35 * (streaks - 0.5) + 0.15).clamp(0.0, 1.0);
    // Seams: the plank's long edges and its butt joint, 2 texels wide.
    let across = (y % PLANK).min(PLANK - 1 - y % PLANK);
    let along = (x + SIDE - joint) % SIDE;
    let seam = if across < 1 || along < 2 { 1.0 } else { 0.0 };
    (darkness, seam)
}

/// The wood's colour texture and height map.
pub fn wood() -> (image::RgbImage, image::GrayImage) {
    let mut canvas = Canvas::new(SIDE, SIDE, LIGHT);
    canvas.paint(|x, y| {
        let (darkness, seam) = wood_at(x, y);
        mix(mix(LIGHT, DARK, darkness), SEAM, seam)
    });
    let mut height = HeightField::new(SIDE, SIDE, 1.0);
    height.paint(|x, y| {
        let (darkness, seam) = wood_at(x, y);
        (0.85 - 0.35 * darkness) * (1.0 - seam)
    });
    (canvas.to_rgb8(), height.to_luma8())
}
