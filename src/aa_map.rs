//! `glint render --debug aa-samples`: adaptive anti-aliasing's work per pixel as an image.
//!
//! The value mapped is the pixel's count of *leaf squares* (the squares its quadtree
//! ended in; [`crate::tracer::sampling::render::adaptive_leaf_counts`], identical on the GPU): 1 where
//! the pixel was not split, and each split adds 3, up to 4^aa_depth. A pixel with L
//! leaves averaged 4·L corner colours, but adjacent leaves share corners, so it traced
//! fewer distinct samples; leaves are what the split decisions produce, so they are what
//! the map shows.
//!
//! Colour: the magma ramp (perceptually uniform, the one FLIP's heat maps use) at
//! t = log₄(leaves) / aa_depth, i.e. by how many levels' worth the pixel was split:
//! black = 1 leaf (no split), pale yellow = 4^aa_depth leaves (every square split down to
//! aa_depth). Log scale, because each level multiplies the leaves by up to 4.

use crate::film::Film;

/// Why a map cannot be made.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum AaMapError {
    /// The render does not use adaptive anti-aliasing: nothing is split, so a map would
    /// only restate the mode.
    #[error("--debug aa-samples maps adaptive anti-aliasing, but this render's aa is '{mode}' (from the script or --aa); add --aa adaptive")]
    NotAdaptive { mode: &'static str },
}

/// The magma ramp: 256 RGB entries, dark to bright.
pub fn magma_ramp() -> Vec<[u8; 3]> {
    nv_flip::magma_lut()
        .to_vec()
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect()
}

/// Position on the ramp (0..=1) of a pixel with `leaves` leaf squares at depth `depth`.
pub fn ramp_position(leaves: u32, depth: u32) -> f64 {
    if depth == 0 {
        return 0.0;
    }
    let levels = f64::from(leaves.max(1)).ln() / 4f64.ln();
    (levels / f64::from(depth)).clamp(0.0, 1.0)
}

/// Colour of a pixel with `leaves` leaf squares at depth `depth`.
pub fn aa_samples_colour(ramp: &[[u8; 3]], leaves: u32, depth: u32) -> [u8; 3] {
    let last = ramp.len() - 1;
    ramp[(ramp_position(leaves, depth) * last as f64).round() as usize]
}

/// The map of `leaves` (row-major, `width`×`height`) as a film whose 8-bit image holds the
/// ramp's bytes exactly.
pub fn aa_samples_film(leaves: &[u32], width: u32, height: u32, depth: u32) -> Film {
    let ramp = magma_ramp();
    let pixels = leaves
        .iter()
        .map(|&l| aa_samples_colour(&ramp, l, depth).map(|v| f32::from(v) / 255.0))
        .collect();
    Film {
        width,
        height,
        pixels,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramp_ends_are_no_split_and_full_split() {
        assert_eq!(ramp_position(1, 3), 0.0);
        assert_eq!(ramp_position(64, 3), 1.0);
        assert_eq!(ramp_position(4, 2), 0.5);
        assert_eq!(ramp_position(1, 0), 0.0);
    }

    #[test]
    fn distinct_leaf_counts_get_distinct_colours() {
        let ramp = magma_ramp();
        let colours: Vec<_> = [1, 4, 7, 10, 16, 64]
            .iter()
            .map(|&l| aa_samples_colour(&ramp, l, 3))
            .collect();
        for (i, a) in colours.iter().enumerate() {
            for b in &colours[i + 1..] {
                assert_ne!(a, b);
            }
        }
    }
}
