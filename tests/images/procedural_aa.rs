//! Antialiasing of procedural textures: a checker floor to the horizon, lit by ambient 1
//! alone, against its 16×16-supersampled reference computed here from the analytic
//! pattern (the floor is the plane y = 0; a subsample's class is the parity of its
//! cell). The procedural checker (box-filtered over each pixel's footprint) and the same
//! checker as an image texture (64×64, mip-mapped trilinear), each at 1 and 2×2 samples
//! per pixel: the rmse over the pixels the floor fills, and the render times. The
//! procedural checker at one sample must not shimmer: its error is within 5% of the
//! image texture's at the same samples, and well under the unfiltered point-sampled
//! pattern's.

use crate::common;
use crate::texture_support;

use common::{packed_from_file, render_cpu, temp_dir};
use glam::{DVec3, Vec3};
use glint::film::Film;
use glint::pack::PackedScene;
use glint::scene::OptionOverrides;
use glint::tracer::base::ray::camera_ray;
use std::time::Instant;

const WIDTH: u32 = 160;
const HEIGHT: u32 = 90;
/// Cells of 1 world unit: white where ⌊x⌋ + ⌊z⌋ is even.
fn analytic(p: DVec3) -> f64 {
    if (p.x.floor() + p.z.floor()).rem_euclid(2.0) == 0.0 {
        1.0
    } else {
        0.0
    }
}

/// The scene with the floor's diffuse colour `diffuse` and `samples`×`samples` uniform AA
/// (1: none); the floor is a quad 2000 wide at y = 0 with UVs of one texture period
/// (two cells) per two units.
fn floor_scene(dir: &std::path::Path, diffuse: &str, samples: u32) -> PackedScene {
    let aa = if samples == 1 {
        "aa='none'".to_string()
    } else {
        format!("aa='uniform', samples={samples}")
    };
    let source = format!(
        "m = gr.material('m') m:set_diffuse({diffuse})
         f = gr.mesh('floor', {{{{-1000,0,-1000}},{{1000,0,-1000}},{{1000,0,1000}},{{-1000,0,1000}}}},
                     {{{{0,3,2,1}}}}, {{{{0,0}},{{1000,0}},{{1000,1000}},{{0,1000}}}})
         f:set_material(m)
         gr.render(f, 'o.png', {WIDTH}, {HEIGHT}, {{0.3, 1.5, 0}}, {{0, -0.35, -1}}, {{0, 1, 0}}, 50,
                   {{1, 1, 1}}, {{}}, {{{aa}}})"
    );
    let path = dir.join(format!("floor-{samples}.lua"));
    std::fs::write(&path, source).unwrap();
    packed_from_file(&path, &OptionOverrides::default()).remove(0)
}

/// Per pixel the mean of the analytic pattern over 16×16 subsamples, or None where a
/// subsample misses the floor.
fn reference(scene: &PackedScene) -> Vec<Option<f64>> {
    let g = &scene.globals;
    let mut out = Vec::new();
    for y in 0..g.height {
        for x in 0..g.width {
            let mut sum = 0.0;
            let mut all_hit = true;
            for i in 0..256 {
                let fx = x as f32 + ((i % 16) as f32 + 0.5) / 16.0;
                let fy = y as f32 + ((i / 16) as f32 + 0.5) / 16.0;
                let ray = camera_ray(g, fx, fy);
                let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
                let t = -o.y / d.y;
                let p = o + d * t;
                if !(t > 0.0 && p.x.abs() < 1000.0 && p.z.abs() < 1000.0) {
                    all_hit = false;
                    break;
                }
                sum += analytic(p);
            }
            out.push(all_hit.then_some(sum / 256.0));
        }
    }
    out
}

fn rmse(film: &Film, reference: &[Option<f64>]) -> f64 {
    let (mut sum, mut n) = (0.0, 0);
    for (i, r) in reference.iter().enumerate() {
        if let Some(r) = r {
            let got = Vec3::from(film.get(i as u32 % WIDTH, i as u32 / WIDTH));
            sum += (f64::from(got.x) - r).powi(2);
            n += 1;
        }
    }
    (sum / f64::from(n)).sqrt()
}

#[test]
fn a_procedural_checker_to_the_horizon_is_antialiased_by_its_footprint() {
    let dir = temp_dir("procedural-aa");
    let checker = image::RgbImage::from_fn(64, 64, |x, y| {
        // Row 0 is the top (v = 1): the cell at u, v ∈ [0, ½) (x, z ∈ [−1000, −999)) is white.
        if (x / 32 + y / 32) % 2 == 1 {
            image::Rgb([255, 255, 255])
        } else {
            image::Rgb([0, 0, 0])
        }
    });
    texture_support::save(&checker, &dir.join("checker.png"));
    let reference = reference(&floor_scene(&dir, "gr.checker({1,1,1}, {0,0,0}, 1)", 1));
    let covered = reference.iter().flatten().count();
    assert!(covered > 5000, "{covered} pixels filled by the floor");
    let mut errors = Vec::new();
    for (name, diffuse) in [
        ("procedural", "gr.checker({1,1,1}, {0,0,0}, 1)"),
        ("image", "'checker.png'"),
    ] {
        for samples in [1, 2] {
            let scene = floor_scene(&dir, diffuse, samples);
            // The fastest of three renders (the first also faults the pages in).
            let mut seconds = f64::MAX;
            let mut film = render_cpu(&scene);
            for _ in 0..3 {
                let start = Instant::now();
                film = render_cpu(&scene);
                seconds = seconds.min(start.elapsed().as_secs_f64());
            }
            let error = rmse(&film, &reference);
            eprintln!(
                "{name} checker, {samples}×{samples} samples: rmse {error:.4}, {seconds:.3} s"
            );
            errors.push(error);
        }
    }
    // The pattern point-sampled at each pixel's centre, unfiltered.
    let g = &floor_scene(&dir, "gr.checker({1,1,1}, {0,0,0}, 1)", 1).globals;
    let (mut sum, mut n) = (0.0, 0);
    for (i, r) in reference.iter().enumerate() {
        if let Some(r) = r {
            let ray = camera_ray(
                g,
                (i as u32 % WIDTH) as f32 + 0.5,
                (i as u32 / WIDTH) as f32 + 0.5,
            );
            let (o, d) = (ray.origin.as_dvec3(), ray.dir.as_dvec3());
            sum += (analytic(o - d * (o.y / d.y)) - r).powi(2);
            n += 1;
        }
    }
    let point_sampled = (sum / f64::from(n)).sqrt();
    eprintln!("unfiltered point sampling, 1 sample: rmse {point_sampled:.4}");
    // Both filter isotropically over the footprint ellipse's geometric mean (w/√cos), so
    // at the same samples their errors are alike (measured: 0.108 and 0.104 at one
    // sample, 0.0620 and 0.0617 at 2×2); the box filter must not be worse by more.
    for (procedural, image) in [(errors[0], errors[2]), (errors[1], errors[3])] {
        assert!(
            procedural <= 1.05 * image,
            "procedural {procedural} vs image {image}"
        );
    }
    assert!(
        errors[0] < 0.6 * point_sampled,
        "{} vs unfiltered {point_sampled}",
        errors[0]
    );
}
