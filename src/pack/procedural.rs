//! Procedural textures packed into `PackedScene::texels`, after the image textures
//! (`pack::texture`), for scenes with the PROCEDURAL feature:
//!
//! ```text
//! word base + 0 … 511   Perlin's permutation table, twice (constants::PERLIN_PERMUTATION)
//! then                  one block of PROCEDURAL_BLOCK_WORDS words per procedural texture
//!                       slot of every material (diffuse, specular, bump, in material order):
//!   0      PROCEDURAL_CHECKER / _NOISE / _MARBLE / _WOOD
//!   1      the word offset of the permutation table (base)
//!   2–4    c1 (f32 bits)       5–7   c2 (f32 bits)
//!   8      the checker's size, the others' scale (f32 bits)
//!   9      octaves             10    turbulence (f32 bits)      11   0
//! ```
//! A material's texture index for a procedural slot is `PROCEDURAL_TEXTURE` | the word
//! offset of its block (`tracer::shading::procedural`).

use crate::constants::{
    PERLIN_PERMUTATION, PERLIN_TABLE_WORDS, PROCEDURAL_BLOCK_WORDS, PROCEDURAL_CHECKER,
    PROCEDURAL_MARBLE, PROCEDURAL_NOISE, PROCEDURAL_TEXTURE, PROCEDURAL_WOOD, TEXTURE_HEADER_WORDS,
};
use crate::scene::{Material, Procedural, ProceduralKind, Texture, TextureRef};

use super::texture::texture_levels;

/// Words `pack::texture::pack_texels` takes for `textures`: a header and the texels of
/// every mip level (where the procedural words start).
pub fn image_words(textures: &[impl AsRef<Texture>]) -> u32 {
    let mut words = 0u64;
    for t in textures.iter().map(AsRef::as_ref) {
        let (mut w, mut h) = (t.width, t.height);
        for _ in 0..texture_levels(t.width, t.height) {
            words += u64::from(TEXTURE_HEADER_WORDS) + u64::from(w) * u64::from(h);
            w = (w / 2).max(1);
            h = (h / 2).max(1);
        }
    }
    words as u32
}

/// The procedural textures of `materials`' slots in packing order (each material's
/// diffuse, specular and bump slot).
fn procedural_slots(materials: &[Material]) -> impl Iterator<Item = &Procedural> {
    materials
        .iter()
        .flat_map(|m| [&m.diffuse_map, &m.specular_map, &m.bump_map])
        .filter_map(|slot| match slot {
            Some(TextureRef::Procedural(p)) => Some(p),
            _ => None,
        })
}

/// The texture indices of every material's (diffuse, specular, bump) slot: an image's
/// index, `PROCEDURAL_TEXTURE` | its block's word offset (the blocks following the
/// table at `base`), or `none`.
pub fn slot_indices(materials: &[Material], base: u32, none: u32) -> Vec<[u32; 3]> {
    let mut next = base + PERLIN_TABLE_WORDS;
    let mut index = |slot: &Option<TextureRef>| match slot {
        None => none,
        Some(TextureRef::Image(t)) => *t as u32,
        Some(TextureRef::Procedural(_)) => {
            let at = next;
            next += PROCEDURAL_BLOCK_WORDS;
            PROCEDURAL_TEXTURE | at
        }
    };
    materials
        .iter()
        .map(|m| {
            [
                index(&m.diffuse_map),
                index(&m.specular_map),
                index(&m.bump_map),
            ]
        })
        .collect()
}

/// The words of the procedural part of `texels`, starting at word `base`.
pub fn pack_procedurals(materials: &[Material], base: u32) -> Vec<u32> {
    let mut words: Vec<u32> = PERLIN_PERMUTATION
        .iter()
        .chain(PERLIN_PERMUTATION.iter())
        .map(|&p| u32::from(p))
        .collect();
    for p in procedural_slots(materials) {
        let kind = match p.kind {
            ProceduralKind::Checker => PROCEDURAL_CHECKER,
            ProceduralKind::Noise => PROCEDURAL_NOISE,
            ProceduralKind::Marble => PROCEDURAL_MARBLE,
            ProceduralKind::Wood => PROCEDURAL_WOOD,
        };
        words.extend([kind, base]);
        words.extend(p.c1.iter().chain(&p.c2).map(|c| c.to_bits()));
        words.extend([p.scale.to_bits(), p.octaves, p.turbulence.to_bits(), 0]);
    }
    words
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pack::texture::pack_texels;
    use std::path::PathBuf;

    #[test]
    fn image_words_is_what_pack_texels_writes() {
        let textures: Vec<Texture> = [(1, 1), (5, 3), (64, 17)]
            .iter()
            .map(|&(width, height)| Texture {
                path: PathBuf::from("t.png"),
                width,
                height,
                rgba: vec![[1, 2, 3, 4]; (width * height) as usize],
            })
            .collect();
        let refs: Vec<std::sync::Arc<Texture>> =
            textures.into_iter().map(std::sync::Arc::new).collect();
        assert_eq!(image_words(&refs) as usize, pack_texels(&refs).len());
    }

    #[test]
    fn blocks_follow_the_table_in_slot_order() {
        let checker = Procedural {
            kind: ProceduralKind::Checker,
            c1: [1.0, 0.0, 0.0],
            c2: [0.0, 0.0, 1.0],
            scale: 0.5,
            octaves: 1,
            turbulence: 0.0,
        };
        let wood = Procedural {
            kind: ProceduralKind::Wood,
            octaves: 3,
            turbulence: 2.0,
            ..checker
        };
        let materials = vec![
            Material {
                diffuse_map: Some(TextureRef::Image(4)),
                bump_map: Some(TextureRef::Procedural(wood)),
                ..Material::default()
            },
            Material {
                specular_map: Some(TextureRef::Procedural(checker)),
                ..Material::default()
            },
        ];
        let base = 100;
        let first = base + PERLIN_TABLE_WORDS;
        assert_eq!(
            slot_indices(&materials, base, u32::MAX),
            vec![
                [4, u32::MAX, PROCEDURAL_TEXTURE | first],
                [
                    u32::MAX,
                    PROCEDURAL_TEXTURE | (first + PROCEDURAL_BLOCK_WORDS),
                    u32::MAX
                ],
            ]
        );
        let words = pack_procedurals(&materials, base);
        assert_eq!(
            words.len() as u32,
            PERLIN_TABLE_WORDS + 2 * PROCEDURAL_BLOCK_WORDS
        );
        assert_eq!(words[..3], [151, 160, 137]);
        assert_eq!(words[256..259], [151, 160, 137]);
        let wood_block = &words[PERLIN_TABLE_WORDS as usize..];
        assert_eq!(wood_block[0], PROCEDURAL_WOOD);
        assert_eq!(wood_block[1], base);
        assert_eq!(f32::from_bits(wood_block[8]), 0.5);
        assert_eq!(wood_block[9], 3);
        assert_eq!(f32::from_bits(wood_block[10]), 2.0);
        let checker_block = &wood_block[PROCEDURAL_BLOCK_WORDS as usize..];
        assert_eq!(checker_block[0], PROCEDURAL_CHECKER);
        assert_eq!(f32::from_bits(checker_block[7]), 1.0);
    }
}
