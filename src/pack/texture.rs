//! The layout of `PackedScene::texels`, defined here once (both tracers read it through
//! `tracer::shading::texture` and `src/tracer/shading/texture.wgsl`):
//!
//! ```text
//! word 4i + 0   offset (in words, from the start of texels) of level i's first texel
//! word 4i + 1   width of level i
//! word 4i + 2   height of level i
//! word 4i + 3   for a texture's level 0: the header index of its level 1 (levels 1, 2, …
//!               have consecutive headers); 0 on the other levels
//! then          the texels of every level, row-major from the image's top row,
//!               one RGBA8 word each: r | g << 8 | b << 16 | a << 24
//! ```
//! (`TEXTURE_HEADER_WORDS` = 4 words per header.) Headers 0 … n − 1 are the scene's n
//! textures' level 0 (a material's texture index is its header index); the headers of the
//! coarser levels follow. Level k + 1 of a w×h level is max(1, ⌊w/2⌋)×max(1, ⌊h/2⌋), each
//! texel the rounded mean of the level-k texels whose indices map onto it (2×2, or 3 along
//! an odd side), down to 1×1: 1 + ⌊log2 max(w, h)⌋ levels (`texture_levels`), a third more
//! texels in all. Texels keep their stored 8-bit values: both tracers divide by 255 and
//! apply no gamma, and the means are taken of those values as stored.

use crate::constants::TEXTURE_HEADER_WORDS;
use crate::scene::Texture;

/// One level of a mip chain: its size and texels (level 0 borrows the texture's own).
struct Level<'a> {
    width: u32,
    height: u32,
    rgba: std::borrow::Cow<'a, [[u8; 4]]>,
}

/// Number of levels of a `width`×`height` texture's chain: 1 + ⌊log2 max(w, h)⌋.
// Mirror of src/tracer/shading/texture.wgsl::texture_levels — change both.
pub fn texture_levels(width: u32, height: u32) -> u32 {
    32 - width.max(height).max(1).leading_zeros()
}

/// The source indices (along one side of `size` texels) that texel `i` of the next level,
/// `next` texels long, averages: ⌊i·size/next⌋ ..< ⌊(i + 1)·size/next⌋.
fn source_span(i: u32, size: u32, next: u32) -> std::ops::Range<u32> {
    let at = |k: u32| (u64::from(k) * u64::from(size) / u64::from(next)) as u32;
    at(i)..at(i + 1)
}

/// The level below `level`: half the size (at least 1), each texel the rounded mean of
/// the texels it covers.
fn next_level(level: &Level) -> Level<'static> {
    let width = (level.width / 2).max(1);
    let height = (level.height / 2).max(1);
    let mut rgba = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        let rows = source_span(y, level.height, height);
        for x in 0..width {
            let columns = source_span(x, level.width, width);
            let mut sum = [0u32; 4];
            let mut count = 0u32;
            for sy in rows.clone() {
                for sx in columns.clone() {
                    let texel = level.rgba[(sy * level.width + sx) as usize];
                    for (s, c) in sum.iter_mut().zip(texel) {
                        *s += u32::from(c);
                    }
                    count += 1;
                }
            }
            rgba.push(sum.map(|s| ((s + count / 2) / count) as u8));
        }
    }
    Level {
        width,
        height,
        rgba: rgba.into(),
    }
}

/// Every level of `t`'s chain, level 0 (the texture itself, borrowed) first.
fn mip_chain(t: &Texture) -> Vec<Level<'_>> {
    let mut levels = vec![Level {
        width: t.width,
        height: t.height,
        rgba: t.rgba.as_slice().into(),
    }];
    for _ in 1..texture_levels(t.width, t.height) {
        let next = next_level(levels.last().expect("level 0 is there"));
        levels.push(next);
    }
    levels
}

/// The texture table followed by every level's texels.
pub fn pack_texels(textures: &[impl AsRef<Texture>]) -> Vec<u32> {
    let chains: Vec<Vec<Level>> = textures.iter().map(|t| mip_chain(t.as_ref())).collect();
    let headers: usize = chains.iter().map(Vec::len).sum();
    let texel_words: usize = chains.iter().flatten().map(|l| l.rgba.len()).sum();
    let mut texels = Vec::with_capacity(headers * TEXTURE_HEADER_WORDS as usize + texel_words);
    // Header order: every level 0, then each texture's levels 1, 2, … together.
    let mut order: Vec<&Level> = chains.iter().map(|c| &c[0]).collect();
    let mut first_coarse = Vec::with_capacity(chains.len());
    for chain in &chains {
        first_coarse.push(order.len() as u32);
        order.extend(&chain[1..]);
    }
    let mut offset = (headers * TEXTURE_HEADER_WORDS as usize) as u32;
    for (index, level) in order.iter().enumerate() {
        let coarse = if index < chains.len() && chains[index].len() > 1 {
            first_coarse[index]
        } else {
            0
        };
        texels.extend([offset, level.width, level.height, coarse]);
        offset += level.rgba.len() as u32;
    }
    for level in order {
        texels.extend(level.rgba.iter().map(|&p| u32::from_le_bytes(p)));
    }
    texels
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn texture(w: u32, h: u32, texel: impl Fn(u32) -> [u8; 4]) -> Texture {
        Texture {
            path: PathBuf::from("t.png"),
            width: w,
            height: h,
            rgba: (0..w * h).map(texel).collect(),
        }
    }

    #[test]
    fn level_counts() {
        assert_eq!(texture_levels(1, 1), 1);
        assert_eq!(texture_levels(2, 1), 2);
        assert_eq!(texture_levels(1024, 1024), 11);
        assert_eq!(texture_levels(5, 3), 3);
        assert_eq!(texture_levels(1024, 7), 11);
    }

    #[test]
    fn headers_then_texels_in_order() {
        let a = texture(2, 1, |i| [10 + 2 * i as u8, 1, 2, 3]);
        let b = texture(1, 3, |i| [20 + i as u8, 0, 0, 0]);
        let packed = pack_texels(&[Box::new(a), Box::new(b)]);
        // Headers: a0, b0, a1, b1 (b is 1×3: levels 1×3 and 1×1).
        let h = 4 * 4;
        assert_eq!(
            &packed[..h],
            &[
                h as u32,
                2,
                1,
                2,
                h as u32 + 2,
                1,
                3,
                3,
                h as u32 + 5,
                1,
                1,
                0,
                h as u32 + 6,
                1,
                1,
                0
            ]
        );
        assert_eq!(packed.len(), h + 2 + 3 + 1 + 1);
        assert_eq!(packed[h], 10 | 1 << 8 | 2 << 16 | 3 << 24);
        assert_eq!(packed[h + 2] & 0xff, 20);
        // a's 1×1 level: the mean of 10 and 12; b's: rows 0..3 averaged (20, 21, 22 → 21).
        assert_eq!(packed[h + 5] & 0xff, 11);
        assert_eq!(packed[h + 6] & 0xff, 21);
    }

    #[test]
    fn every_texel_counts_once_and_means_round() {
        // 5×3: level 1 is 2×1 (columns 0–1 and 2–4, all three rows), level 2 is 1×1.
        let t = texture(5, 3, |i| [(i * 10) as u8, 255, (i % 2) as u8, 7]);
        let chain = mip_chain(&t);
        assert_eq!(chain.len(), 3);
        assert_eq!((chain[1].width, chain[1].height), (2, 1));
        let mean = |xs: &[u32]| (xs.iter().sum::<u32>() + xs.len() as u32 / 2) / xs.len() as u32;
        let left = mean(&[0, 10, 50, 60, 100, 110]);
        let right = mean(&[20, 30, 40, 70, 80, 90, 120, 130, 140]);
        assert_eq!(chain[1].rgba[0][0] as u32, left);
        assert_eq!(chain[1].rgba[1][0] as u32, right);
        assert_eq!(chain[1].rgba[0][1], 255);
        assert_eq!(chain[2].rgba[0][0] as u32, mean(&[left, right]));
    }
}
