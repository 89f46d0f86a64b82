//! The sample sources: where a camera sample lies on the film, and its seed. A pixel's
//! n×n strata ([`stratum_position`]: AA none's centre at n = 1, uniform AA's jittered
//! strata, `glint view`'s frame s taking stratum s) and adaptive AA's lattice points
//! ([`lattice_jitter`] of a point the lattice passes enumerate: `adaptive::corner_to_trace`,
//! `adaptive::midpoint_to_trace`, at `adaptive::lattice_position`). Each is written
//! once here and once in `sample_source.wgsl`, and every form of the integrator takes
//! it: the per-sample forms one sample at a time (`render::uniform_sample`,
//! `progressive::view_sample` through it, `pixel_sample::lattice_sample`), the batch forms
//! (the CPU wavefront) a [`SampleSource`] naming a batch of them.

use crate::constants::{
    AA_ADAPTIVE, AA_LATTICE_JITTER, AA_UNIFORM, LENS_DIMENSION, MAX_AA_DEPTH, PIXEL_DIMENSION,
};
use crate::pack::{PackedGlobals, PackedScene};
use crate::tracer::base::rng::{
    adaptive_seed, lattice_sequence_index, pcg_hash, random_unit, sequence_pair, shuffled_index,
    SampleSeed,
};
use glam::Vec2;

/// A camera sample: its film position (fx, fy) in pixels and its seed.
// Mirror of src/tracer/sampling/sample_source.wgsl::CameraSample — change both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSample {
    pub fx: f32,
    pub fy: f32,
    pub seed: SampleSeed,
}

/// Where a batch's camera samples come from; sample k of the batch is the k-th of the
/// source.
#[derive(Clone, Copy, Debug)]
pub enum SampleSource<'a> {
    /// n×n strata of each pixel (x, y) of `pixels`, sample k being stratum k mod n² of
    /// pixel k div n² (`render::uniform_sample`): AA none is n = 1 and not `uniform`
    /// (each pixel's centre), uniform AA n = `aa_samples`, jittered.
    Strata {
        pixels: &'a [[u32; 2]],
        n: u32,
        uniform: bool,
    },
    /// Stratum `s` of the n×n strata of each pixel of `pixels`, sample k being pixel k
    /// (jittered when `uniform`): `glint view`'s frame s (`progressive::view_sample`).
    Stratum {
        pixels: &'a [[u32; 2]],
        n: u32,
        uniform: bool,
        s: u32,
    },
    /// Adaptive AA's lattice points (film positions before their jitter:
    /// `pixel_sample::lattice_sample`).
    Lattice { points: &'a [[f32; 2]] },
}

impl SampleSource<'_> {
    /// The number of samples.
    pub fn len(&self) -> usize {
        match *self {
            SampleSource::Strata { pixels, n, .. } => pixels.len() * (n * n) as usize,
            SampleSource::Stratum { pixels, .. } => pixels.len(),
            SampleSource::Lattice { points } => points.len(),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Sample `k`'s film position and seed.
    pub fn camera_sample(&self, scene: &PackedScene, k: usize) -> CameraSample {
        let g = &scene.globals;
        match *self {
            SampleSource::Strata { pixels, n, uniform } => {
                let per_pixel = (n * n) as usize;
                let s = (k % per_pixel) as u32;
                stratum_position(g, pixels[k / per_pixel], s, n, uniform)
            }
            SampleSource::Stratum {
                pixels,
                n,
                uniform,
                s,
            } => stratum_position(g, pixels[k], s, n, uniform),
            SampleSource::Lattice { points } => {
                let [fx, fy] = points[k];
                lattice_jitter(g, fx, fy)
            }
        }
    }
}

/// Stratum `s` of pixel `xy`'s n×n strata, (s mod n, s div n): a point jittered within
/// it when `uniform`, else its centre (x + 0.5 exactly at n = 1); its seed names the
/// pixel and the stratum.
// Mirror of src/tracer/sampling/sample_source.wgsl::stratum_position — change both.
pub fn stratum_position(
    g: &PackedGlobals,
    xy: [u32; 2],
    s: u32,
    n: u32,
    uniform: bool,
) -> CameraSample {
    let [x, y] = xy;
    let pixel = y * g.width + x;
    let (i, j) = (s % n, s / n);
    let (jx, jy) = if uniform {
        (
            random_unit(pixel, s, PIXEL_DIMENSION),
            random_unit(pixel, s, PIXEL_DIMENSION + 1),
        )
    } else {
        (0.5, 0.5)
    };
    CameraSample {
        fx: x as f32 + (i as f32 + jx) / n as f32,
        fy: y as f32 + (j as f32 + jy) / n as f32,
        seed: SampleSeed {
            pixel,
            sample: s,
            depth: 0,
            mirrors_corners: false,
        },
    }
}

/// Adaptive AA's sample of lattice point (fx, fy), a dyadic film position (exact): the
/// point jittered, by hashes of its seed, within a square AA_LATTICE_JITTER steps of the
/// finest lattice (2^aa_depth per pixel) wide around it, with the point's own seed. The
/// jitter depends only on the point, so a point shared by neighbouring squares, pixels
/// or chunks is the same sample whichever pass traces it.
// Mirror of src/tracer/sampling/sample_source.wgsl::lattice_jitter — change both.
pub fn lattice_jitter(g: &PackedGlobals, fx: f32, fy: f32) -> CameraSample {
    let seed = adaptive_seed(fx, fy);
    // A power of two: the products below are exact, so a fused multiply-add on the GPU
    // rounds the sums as these do.
    let width = AA_LATTICE_JITTER / (1u32 << g.aa_depth) as f32;
    let jx = (random_unit(seed.pixel, seed.sample, PIXEL_DIMENSION) - 0.5) * width;
    let jy = (random_unit(seed.pixel, seed.sample, PIXEL_DIMENSION + 1) - 0.5) * width;
    CameraSample {
        fx: fx + jx,
        fy: fy + jy,
        seed,
    }
}

/// Where camera sample `seed` lies in its pixel's stratified sequence for the effect of
/// `dimension` (`constants::*_DIMENSION`): the pixel's key and the sample's index. A
/// pixel's n×n strata (uniform AA, the view's frames; AA none is n = 1) take the indices
/// 0..n² shuffled per pixel and dimension ([`shuffled_index`]), so that a sample's
/// stratum on the film and its strata of each effect are paired at random, not by one
/// fixed pattern; adaptive AA's lattice points take [`lattice_sequence_index`] of their
/// place in their pixel (the pixel whose top-left corner is at or above and left of
/// them), so each level a pixel splits to adds the sequence's next points.
// Mirror of src/tracer/sampling/sample_source.wgsl::sequence_index — change both.
pub fn sequence_index(g: &PackedGlobals, seed: SampleSeed, dimension: u32) -> (u32, u32) {
    if g.aa_mode == AA_ADAPTIVE {
        let within = (1u32 << MAX_AA_DEPTH) - 1;
        let (x, y) = (seed.pixel >> MAX_AA_DEPTH, seed.sample >> MAX_AA_DEPTH);
        let key = y.wrapping_mul(g.width).wrapping_add(x);
        return (
            key,
            lattice_sequence_index(seed.pixel & within, seed.sample & within),
        );
    }
    let n = if g.aa_mode == AA_UNIFORM {
        g.aa_samples
    } else {
        1
    };
    let shuffle = pcg_hash(seed.pixel ^ pcg_hash(!dimension));
    (seed.pixel, shuffled_index(seed.sample, n * n, shuffle))
}

/// Camera sample `seed`'s position on the lens, in [0, 1)² (the dimensions
/// LENS_DIMENSION and the next): its point of its pixel's sequence.
// Mirror of src/tracer/sampling/sample_source.wgsl::lens_position — change both.
pub fn lens_position(g: &PackedGlobals, seed: SampleSeed) -> Vec2 {
    let (key, index) = sequence_index(g, seed, LENS_DIMENSION);
    Vec2::from(sequence_pair(key, index, LENS_DIMENSION))
}
