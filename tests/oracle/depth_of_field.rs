//! Depth of field against its oracles: Mitsuba 3's `thinlens` sensor (references checked
//! in under tests/oracle/refs/, rendered by tools/oracle/depth_of_field.py from the scene
//! of tools/oracle/depth_of_field.lua), the circle of confusion a thin lens predicts for
//! an edge off the plane in focus (and none on it), at scales 10⁻³ to 10³ with the eye
//! far from the origin, and the stratified lens positions' error against independent ones.

use crate::common::{load_packed, packed_from_source, render_cpu, root};
use crate::oracle_support::film_rmse as rmse;
use glam::Vec2;
use glam::Vec3;
use glint::constants::LENS_DIMENSION;
use glint::film::Film;
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::OptionOverrides;
use glint::tracer::base::ray::{camera_ray, thin_lens_ray};
use glint::tracer::base::rng::{random_unit, SampleSeed};
use glint::tracer::path::trace::trace_ray;
use glint::tracer::sampling::sample_source::{lens_position, stratum_position};
use glint::tracer::traversal::traverse::NoCounters;

/// The oracle scene's thin lens (tools/oracle/depth_of_field.py's APERTURE and FOCUS).
const APERTURE: f32 = 0.6;
const FOCUS: f32 = 6.2;

fn oracle_scene(aperture: f32) -> PackedScene {
    let overrides = OptionOverrides {
        aperture: Some(aperture),
        focus: Some(FOCUS),
        ..OptionOverrides::default()
    };
    load_packed(&root().join("tools/oracle/depth_of_field.lua"), &overrides)
}

fn reference(name: &str) -> Film {
    let path = root().join("tests/oracle/refs").join(name);
    glint::image_io::read_image(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Linear rmse against Mitsuba 3 (4 096 spp, box filter, `direct`): the pinhole first
/// (the same field of view and handedness: ≤ 0.001, the issue measured 0.0009 on its
/// scene), then the thin lens, ≤ 0.01.
#[test]
fn thin_lens_matches_mitsuba() {
    let pinhole = oracle_scene(0.0);
    assert!(!pinhole.features.contains(SceneFeatures::DEPTH_OF_FIELD));
    let pinhole_rmse = rmse(&render_cpu(&pinhole), &reference("pinhole.exr"));
    let lens = oracle_scene(APERTURE);
    assert!(lens.features.contains(SceneFeatures::DEPTH_OF_FIELD));
    let lens_rmse = rmse(&render_cpu(&lens), &reference("depth_of_field.exr"));
    eprintln!("rmse against Mitsuba 3: pinhole {pinhole_rmse:.5}, thin lens {lens_rmse:.5}");
    assert!(pinhole_rmse <= 0.001, "pinhole rmse {pinhole_rmse}");
    assert!(lens_rmse <= 0.01, "thin-lens rmse {lens_rmse}");
}

/// The share of a uniform disk of radius 1 left of the line x = t (t in [−1, 1]).
fn disk_share_below(t: f64) -> f64 {
    let t = t.clamp(-1.0, 1.0);
    (t * (1.0 - t * t).sqrt() + t.asin() + std::f64::consts::FRAC_PI_2) / std::f64::consts::PI
}

/// The image of a lit edge (a slab covering x < the eye's x, at depth `depth`), 96×16 at a
/// vertical field of view of 20°, seen through a lens of radius `aperture` focused at
/// `focus`, all scaled by `scale`, with the eye at `eye`·scale.
fn edge_image(depth: f64, aperture: f64, focus: f64, scale: f64, eye: [f64; 3]) -> Film {
    let [ex, ey, ez] = eye.map(|e| e * scale);
    let s = scale;
    let source = format!(
        "gr.transform_order('pre')
         m = gr.material({{1, 1, 1}}, {{0, 0, 0}}, 1)
         root = gr.node('root')
         slab = gr.cube('slab')
         slab:set_material(m)
         slab:scale({w}, {w}, {t})
         slab:translate({x}, {y}, {z})
         root:add_child(slab)
         gr.render(root, 'edge.png', 96, 16, {{{ex}, {ey}, {ez}}}, {{0, 0, -1}}, {{0, 1, 0}}, 20,
             {{1, 1, 1}}, {{}}, {{aa = 'uniform', samples = 16, background = {{0, 0, 0}},
             aperture = {a}, focus = {f}}})",
        w = 100.0 * s,
        t = 0.1 * s,
        x = ex - 100.0 * s,
        y = ey - 50.0 * s,
        z = ez - depth * s - 0.1 * s,
        a = aperture * s,
        f = focus * s,
    );
    render_cpu(&packed_from_source(&source, &OptionOverrides::default())[0])
}

/// Each column's mean over the rows (the edge is vertical: every row is the same).
fn column_profile(film: &Film) -> Vec<f64> {
    (0..film.width)
        .map(|x| {
            (0..film.height)
                .map(|y| film.get(x, y)[0] as f64)
                .sum::<f64>()
                / film.height as f64
        })
        .collect()
}

/// What a thin lens predicts for [`edge_image`]'s columns: a scene point at depth z
/// spreads over a disk of radius R = aperture·|focus/z − 1| on the plane in focus, which
/// is R / (2·focus·tan(fov/2)/height) pixels; the edge (at the image's centre column) is
/// so blurred by the disk, then averaged over each pixel (the box filter).
fn predicted_profile(depth: f64, aperture: f64, focus: f64) -> Vec<f64> {
    let pixel = 2.0 * focus * 10f64.to_radians().tan() / 16.0;
    let radius = aperture * (focus / depth - 1.0).abs() / pixel;
    (0..96)
        .map(|x| {
            let steps = 256;
            (0..steps)
                .map(|i| {
                    let d = x as f64 + (i as f64 + 0.5) / steps as f64 - 48.0;
                    if radius == 0.0 {
                        (d < 0.0) as u32 as f64
                    } else {
                        disk_share_below(-d / radius)
                    }
                })
                .sum::<f64>()
                / steps as f64
        })
        .collect()
}

fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p - q).abs())
        .fold(0.0, f64::max)
}

/// An edge on the plane in focus stays sharp (one pixel's step); one nearer or farther
/// blurs by the circle of confusion the thin lens predicts (within 0.02 of the predicted
/// profile, where a radius 15% off differs by 0.04), at scales 10⁻³, 1 and 10³ and with
/// the eye far from the origin. A lens position ignored (a pinhole's sharp edge) or a
/// plane in focus at another distance fails.
#[test]
fn focus_plane_is_sharp_and_blur_is_the_circle_of_confusion() {
    let (aperture, focus) = (1.0, 10.0);
    for scale in [1e-3, 1.0, 1e3] {
        for eye in [[0.0, 0.0, 0.0], [30.0, -20.0, 50.0]] {
            for depth in [focus, 5.0, 20.0] {
                let got = column_profile(&edge_image(depth, aperture, focus, scale, eye));
                let want = predicted_profile(depth, aperture, focus);
                let worst = largest_difference(&got, &want);
                assert!(
                    worst <= 0.02,
                    "scale {scale}, eye {eye:?}, depth {depth}: profile off by {worst}\n\
                     got  {got:.3?}\nwant {want:.3?}"
                );
                if depth != focus {
                    let wider = predicted_profile(depth, aperture * 1.15, focus);
                    assert!(largest_difference(&want, &wider) > 0.03, "depth {depth}");
                }
            }
        }
    }
}

/// The oracle scene at n×n uniform AA with the lens positions of `lens` (sample s of
/// pixel (x, y) given by its seed), on the CPU's per-sample path, as `render` takes them.
fn render_with_lens(scene: &PackedScene, n: u32, lens: impl Fn(SampleSeed) -> Vec2) -> Film {
    let g = &scene.globals;
    let mut film = Film::new(g.width, g.height);
    for y in 0..g.height {
        for x in 0..g.width {
            let mut sum = Vec3::ZERO;
            for s in 0..n * n {
                let at = stratum_position(g, [x, y], s, n, true);
                let pinhole = camera_ray(g, at.fx, at.fy);
                let ray = thin_lens_ray(g, &pinhole, lens(at.seed));
                sum += trace_ray(scene, ray, at.seed, &mut NoCounters);
            }
            film.set(x, y, (sum / (n * n) as f32).to_array());
        }
    }
    film
}

/// The lens positions of the sample dimensions (a pixel's shuffled, scrambled
/// (0,2)-sequence, the tracer's own render) against independent ones at equal sample
/// count: rmse against Mitsuba's converged image, at 4 and 16 samples a pixel.
/// Stratified must be the smaller. (The harness gives the tracer's image bit for bit when
/// handed the tracer's lens positions.)
#[test]
fn stratified_lens_positions_beat_independent_ones() {
    let reference = reference("depth_of_field.exr");
    for n in [2, 4] {
        let mut scene = oracle_scene(APERTURE);
        scene.globals.aa_samples = n;
        let g = scene.globals;
        let stratified = render_cpu(&scene);
        let harness = render_with_lens(&scene, n, |seed| lens_position(&g, seed));
        assert_eq!(harness.pixels, stratified.pixels, "n = {n}");
        let independent = render_with_lens(&scene, n, |seed| {
            Vec2::new(
                random_unit(seed.pixel, seed.sample, LENS_DIMENSION),
                random_unit(seed.pixel, seed.sample, LENS_DIMENSION + 1),
            )
        });
        let (e_s, e_i) = (
            rmse(&stratified, &reference),
            rmse(&independent, &reference),
        );
        eprintln!(
            "{} samples a pixel: rmse stratified {e_s:.5}, independent {e_i:.5} ({:.2}x)",
            n * n,
            e_i / e_s
        );
        assert!(e_s < e_i, "n = {n}: stratified {e_s}, independent {e_i}");
    }
}
