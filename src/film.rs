//! The film both tracers write into: linear f32 RGB, row-major, top row first.

/// A linear-RGB image of `width × height` pixels, top row first.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    pub width: u32,
    pub height: u32,
    /// `width * height` pixels, each linear RGB.
    pub pixels: Vec<[f32; 3]>,
}

impl Film {
    /// A black film.
    pub fn new(width: u32, height: u32) -> Film {
        Film {
            width,
            height,
            pixels: vec![[0.0; 3]; width as usize * height as usize],
        }
    }

    pub fn get(&self, x: u32, y: u32) -> [f32; 3] {
        self.pixels[(y * self.width + x) as usize]
    }

    pub fn set(&mut self, x: u32, y: u32, rgb: [f32; 3]) {
        let w = self.width;
        self.pixels[(y * w + x) as usize] = rgb;
    }

    /// 8-bit RGB as written to PNG: clamped to [0,1], no gamma (A4's convention),
    /// rounded to nearest.
    pub fn to_rgb8(&self) -> Vec<u8> {
        self.pixels
            .iter()
            .flat_map(|p| p.map(quantize_channel))
            .collect()
    }
}

/// One linear channel to 8 bits: clamp, scale, round to nearest. NaN maps to 0.
pub fn quantize_channel(c: f32) -> u8 {
    if c.is_nan() {
        return 0;
    }
    (c.clamp(0.0, 1.0) * 255.0 + 0.5) as u8
}
