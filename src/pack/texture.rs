//! The layout of `PackedScene::texels`, defined here once (both tracers read it through
//! `cpu::texture` and `shaders/texture.wgsl`):
//!
//! ```text
//! word 3i + 0   offset (in words, from the start of texels) of texture i's first texel
//! word 3i + 1   width of texture i
//! word 3i + 2   height of texture i
//! then          the texels of each texture, row-major from the image's top row,
//!               one RGBA8 word each: r | g << 8 | b << 16 | a << 24
//! ```
//! (`TEXTURE_HEADER_WORDS` = 3 words per header.) Texels keep their stored 8-bit values:
//! both tracers divide by 255 and apply no gamma.

use crate::constants::TEXTURE_HEADER_WORDS;
use crate::scene::Texture;

/// The texture table followed by every texture's texels.
pub fn pack_texels(textures: &[impl AsRef<Texture>]) -> Vec<u32> {
    let header = textures.len() * TEXTURE_HEADER_WORDS as usize;
    let total = header
        + textures
            .iter()
            .map(|t| t.as_ref().rgba.len())
            .sum::<usize>();
    let mut texels = Vec::with_capacity(total);
    let mut offset = header as u32;
    for t in textures {
        let t = t.as_ref();
        texels.extend([offset, t.width, t.height]);
        offset += t.rgba.len() as u32;
    }
    for t in textures {
        texels.extend(t.as_ref().rgba.iter().map(|&p| u32::from_le_bytes(p)));
    }
    texels
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    #[test]
    fn headers_then_texels_in_order() {
        let t = |w: u32, h: u32, base: u8| Texture {
            path: PathBuf::from("t.png"),
            width: w,
            height: h,
            rgba: (0..w * h).map(|i| [base + i as u8, 1, 2, 3]).collect(),
        };
        let packed = pack_texels(&[Box::new(t(2, 1, 10)), Box::new(t(1, 3, 20))]);
        assert_eq!(&packed[..6], &[6, 2, 1, 8, 1, 3]);
        assert_eq!(packed.len(), 6 + 2 + 3);
        assert_eq!(packed[6], 10 | 1 << 8 | 2 << 16 | 3 << 24);
        assert_eq!(packed[8] & 0xff, 20);
    }
}
