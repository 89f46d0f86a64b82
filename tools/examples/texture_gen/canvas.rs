//! A colour canvas and a height field in f32, painted with rectangles and with coverage
//! (text), then quantised once to 8 bits: painting in floats keeps blends exact until the
//! end, so overlapping strokes do not accumulate rounding.

use image::{GrayImage, Luma, Rgb, RgbImage};

/// An sRGB-free colour in 0–255 per channel (texels are used as stored: no gamma).
pub type Colour = [f32; 3];

/// An RGB canvas.
pub struct Canvas {
    pub width: u32,
    pub height: u32,
    pixels: Vec<Colour>,
}

impl Canvas {
    pub fn new(width: u32, height: u32, background: Colour) -> Canvas {
        Canvas {
            width,
            height,
            pixels: vec![background; (width * height) as usize],
        }
    }

    /// Fills the pixels x0 ≤ x < x1, y0 ≤ y < y1 (clipped to the canvas).
    pub fn fill_rect(&mut self, x0: u32, y0: u32, x1: u32, y1: u32, colour: Colour) {
        for y in y0..y1.min(self.height) {
            for x in x0..x1.min(self.width) {
                self.pixels[(y * self.width + x) as usize] = colour;
            }
        }
    }

    /// Blends `colour` over pixel (x, y) with opacity `alpha` ∈ [0, 1]; outside: nothing.
    pub fn blend(&mut self, x: i32, y: i32, colour: Colour, alpha: f32) {
        if x < 0 || y < 0 || x >= self.width as i32 || y >= self.height as i32 {
            return;
        }
        let pixel = &mut self.pixels[(y as u32 * self.width + x as u32) as usize];
        let a = alpha.clamp(0.0, 1.0);
        for (p, c) in pixel.iter_mut().zip(colour) {
            *p += (c - *p) * a;
        }
    }

    /// Sets pixel (x, y) with a function of its position.
    pub fn paint(&mut self, mut colour_at: impl FnMut(u32, u32) -> Colour) {
        for y in 0..self.height {
            for x in 0..self.width {
                self.pixels[(y * self.width + x) as usize] = colour_at(x, y);
            }
        }
    }

    pub fn to_rgb8(&self) -> RgbImage {
        RgbImage::from_fn(self.width, self.height, |x, y| {
            let p = self.pixels[(y * self.width + x) as usize];
            Rgb(p.map(quantise))
        })
    }
}

/// A height field, 0 (low) to 1 (high).
pub struct HeightField {
    pub width: u32,
    pub height: u32,
    heights: Vec<f32>,
}

impl HeightField {
    pub fn new(width: u32, height: u32, level: f32) -> HeightField {
        HeightField {
            width,
            height,
            heights: vec![level; (width * height) as usize],
        }
    }

    /// Lowers pixel (x, y) towards `depth` by `amount` ∈ [0, 1] (never raises it).
    pub fn engrave(&mut self, x: i32, y: i32, depth: f32, amount: f32) {
        if x < 0 || y < 0 || x >= self.width as i32 || y >= self.height as i32 {
            return;
        }
        let h = &mut self.heights[(y as u32 * self.width + x as u32) as usize];
        let target = *h + (depth - *h) * amount.clamp(0.0, 1.0);
        *h = h.min(target);
    }

    /// Sets every height with a function of its position.
    pub fn paint(&mut self, mut height_at: impl FnMut(u32, u32) -> f32) {
        for y in 0..self.height {
            for x in 0..self.width {
                self.heights[(y * self.width + x) as usize] = height_at(x, y);
            }
        }
    }

    pub fn to_luma8(&self) -> GrayImage {
        GrayImage::from_fn(self.width, self.height, |x, y| {
            Luma([quantise(
                255.0 * self.heights[(y * self.width + x) as usize],
            )])
        })
    }
}

/// 0–255 float to a byte, rounding to nearest.
fn quantise(v: f32) -> u8 {
    v.clamp(0.0, 255.0).round() as u8
}

/// 0 below `edge0`, 1 above `edge1`, a cubic ramp between.
pub fn smoothstep(edge0: f32, edge1: f32, x: f32) -> f32 {
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Linear blend of two colours.
pub fn mix(a: Colour, b: Colour, t: f32) -> Colour {
    [0, 1, 2].map(|i| a[i] + (b[i] - a[i]) * t)
}
