//! Progressive uniform anti-aliasing for `glint view`: frame k adds sample k of every
//! pixel's n×n jittered pattern to a running sum, so after n² frames each pixel's sum
//! is the one [`super::render::render_pixel`] forms (same samples, same order, from zero)
//! and sum / n² is `glint render`'s pixel, bit for bit. AA none is one frame of pixel
//! centres. The sums' fourth component counts the samples in them.

use super::render::uniform_sample;
use crate::constants::AA_UNIFORM;
use crate::film::Film;
use crate::pack::PackedScene;
use crate::tracer::traversal::traverse::NoCounters;
use glam::{Vec3, Vec4};
use rayon::prelude::*;

/// Adds sample `s` of every pixel of `scene` (its globals' size, camera and AA) to
/// `sums` (row-major, the globals' width; `s` = 0 starts them afresh).
pub fn accumulate_sample(scene: &PackedScene, s: u32, sums: &mut [[f32; 4]]) {
    let width = scene.globals.width as usize;
    let pixels = width * scene.globals.height as usize;
    sums[..pixels]
        .par_chunks_mut(width)
        .enumerate()
        .for_each(|(y, row)| {
            for (x, sum) in row.iter_mut().enumerate() {
                *sum = view_sample(scene, x as u32, y as u32, s, *sum);
            }
        });
}

/// `sum` with sample `s` of pixel (x, y) added, as `render_pixel`'s loop adds it.
// Mirror of src/tracer/sampling/progressive.wgsl::view_sample — change both.
pub fn view_sample(scene: &PackedScene, x: u32, y: u32, s: u32, sum: [f32; 4]) -> [f32; 4] {
    let g = &scene.globals;
    let uniform = g.aa_mode == AA_UNIFORM;
    let n = if uniform { g.aa_samples } else { 1 };
    let colour = uniform_sample(scene, x, y, s, n, uniform, &mut NoCounters);
    add_view_sample(Vec4::from(sum), s, colour).to_array()
}

/// A pixel's running `sum` with its sample `s` of colour `colour` added: from zero at
/// s = 0 (whatever `sum` held), the count in the fourth component. Every form of a view
/// frame adds its samples with it.
// Mirror of src/tracer/sampling/progressive.wgsl::add_view_sample — change both.
pub fn add_view_sample(sum: Vec4, s: u32, colour: Vec3) -> Vec4 {
    let before = if s == 0 { Vec3::ZERO } else { sum.truncate() };
    (before + colour).extend((s + 1) as f32)
}

/// The store pass of a view frame through the wavefront form (`glint view`'s frame `s` in
/// the hardware variant): sample k of the frame's batch (`SampleSource::Stratum`,
/// stratum s of pixel k), of colour `colours[k]`, added to pixel k's sum in `sums`.
// Mirror of src/tracer/sampling/progressive.wgsl::wavefront_view_store, its invocations in one loop — change both.
pub fn wavefront_view_store(sums: &mut [[f32; 4]], s: u32, colours: &[Vec3]) {
    for (sum, &colour) in sums.iter_mut().zip(colours) {
        *sum = add_view_sample(Vec4::from(*sum), s, colour).to_array();
    }
}

/// The image of `sums` (width × height pixels): each sum divided by its count, as
/// `render_pixel` divides (a pixel with no samples is black).
pub fn film_of_sums(sums: &[[f32; 4]], width: u32, height: u32) -> Film {
    let mut film = Film::new(width, height);
    for y in 0..height {
        for x in 0..width {
            let s = sums[(y * width + x) as usize];
            let mean = if s[3] > 0.0 {
                Vec3::new(s[0], s[1], s[2]) / s[3]
            } else {
                Vec3::ZERO
            };
            film.set(x, y, mean.to_array());
        }
    }
    film
}
