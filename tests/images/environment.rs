//! HDR environment maps on the CPU reference tracer: the orientation (a map with a colour
//! per axis direction, seen by cameras looking along ±x, ±y, ±z, turned and not), HDR
//! values reaching the film and an EXR unclamped, OpenEXR and Radiance HDR files alike, a
//! mirror sphere at scales 10⁻³ and 10³ seeing what it sees at scale 1, scenes without a
//! map packing nothing, and the scene errors for bad files and arguments.

use crate::common;

use common::{packed_from_file, render_cpu, temp_dir};
use glam::Vec3;
use glint::film::Film;
use glint::pack::{PackedScene, SceneFeatures};
use glint::scene::OptionOverrides;
use std::f32::consts::PI;
use std::path::Path;

/// The six axis directions and the colour [`axis_map`] gives each.
const AXES: [([f32; 3], [f32; 3]); 6] = [
    ([1.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
    ([-1.0, 0.0, 0.0], [0.0, 1.0, 1.0]),
    ([0.0, 1.0, 0.0], [0.0, 1.0, 0.0]),
    ([0.0, -1.0, 0.0], [1.0, 0.0, 1.0]),
    ([0.0, 0.0, 1.0], [0.0, 0.0, 1.0]),
    ([0.0, 0.0, -1.0], [1.0, 1.0, 0.0]),
];

/// The direction of the map's texel (i, j) of a w×h map, by Mitsuba's envmap convention:
/// column centres at u = (i + ½)/w, row j at v = j/(h − 1).
fn texel_direction(i: u32, j: u32, w: u32, h: u32) -> Vec3 {
    let phi = 2.0 * PI * (i as f32 + 0.5) / w as f32;
    let theta = PI * j as f32 / (h - 1) as f32;
    Vec3::new(
        phi.sin() * theta.sin(),
        theta.cos(),
        -phi.cos() * theta.sin(),
    )
}

/// A 64×33 map whose every texel has the colour of the axis nearest its direction.
fn axis_map() -> Film {
    let (w, h) = (64, 33);
    let mut film = Film::new(w, h);
    for j in 0..h {
        for i in 0..w {
            let d = texel_direction(i, j, w, h);
            let nearest = AXES
                .iter()
                .max_by(|a, b| d.dot(Vec3::from(a.0)).total_cmp(&d.dot(Vec3::from(b.0))))
                .unwrap();
            film.pixels[(j * w + i) as usize] = nearest.1;
        }
    }
    film
}

/// Packs `source` run from `dir` (where its files are).
fn packed_in(dir: &Path, source: &str) -> PackedScene {
    let path = dir.join("scene.lua");
    std::fs::write(&path, source).unwrap();
    packed_from_file(&path, &OptionOverrides::default()).remove(0)
}

/// A 5×5 render with nothing in the scene of the camera at the origin looking along
/// `view` (fov 10°) in the map `file` turned by `rotation` degrees: its centre pixel.
fn seen_along(dir: &Path, file: &str, view: [f32; 3], rotation: f32) -> [f32; 3] {
    let up = if view[1] == 0.0 {
        "{0,1,0}"
    } else {
        "{0,0,-1}"
    };
    let source = format!(
        "root = gr.node('root') \
         gr.render(root, 'o.png', 5, 5, {{0,0,0}}, {{{},{},{}}}, {up}, 10, {{0,0,0}}, {{}}, \
                   {{aa='none', environment='{file}', environment_rotation={rotation}}})",
        view[0], view[1], view[2]
    );
    let scene = packed_in(dir, &source);
    assert!(scene.features.contains(SceneFeatures::ENVIRONMENT));
    render_cpu(&scene).pixels[12]
}

/// A camera looking along each axis sees that axis's colour; with the map turned by 90°
/// about +y (+z towards +x) a camera looking along +x sees what was at +z, along +z what
/// was at −x; the poles stay.
#[test]
fn cameras_along_each_axis_see_its_colour() {
    let dir = temp_dir("environment-axes");
    glint::image_io::write_image(&axis_map(), &dir.join("axes.exr")).unwrap();
    for (view, colour) in AXES {
        assert_eq!(
            seen_along(&dir, "axes.exr", view, 0.0),
            colour,
            "along {view:?}"
        );
    }
    let colour_of = |d: [f32; 3]| AXES.iter().find(|a| a.0 == d).unwrap().1;
    for (view, was_at) in [
        ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        ([0.0, 0.0, 1.0], [-1.0, 0.0, 0.0]),
        ([-1.0, 0.0, 0.0], [0.0, 0.0, -1.0]),
        ([0.0, 0.0, -1.0], [1.0, 0.0, 0.0]),
        ([0.0, 1.0, 0.0], [0.0, 1.0, 0.0]),
        ([0.0, -1.0, 0.0], [0.0, -1.0, 0.0]),
    ] {
        assert_eq!(
            seen_along(&dir, "axes.exr", view, 90.0),
            colour_of(was_at),
            "turned 90°, along {view:?}"
        );
    }
    // A whole turn is no turn (to rounding).
    let turned = Vec3::from(seen_along(&dir, "axes.exr", [1.0, 0.0, 0.0], 360.0));
    assert!((turned - Vec3::X).abs().max_element() < 1e-5, "{turned}");
}

/// A constant map of HDR radiance 6.5 (an .hdr file: RGBE stores 6.5 exactly) fills the
/// film with 6.5, and an EXR written from the film keeps it.
#[test]
fn hdr_values_reach_the_film_and_exr_unclamped() {
    let dir = temp_dir("environment-hdr");
    let texels = vec![image::Rgb([6.5f32, 0.25, 3.0]); 8 * 4];
    let file = std::fs::File::create(dir.join("bright.hdr")).unwrap();
    image::codecs::hdr::HdrEncoder::new(file)
        .encode(&texels, 8, 4)
        .unwrap();
    let source = "root = gr.node('root') \
                  gr.render(root, 'o.exr', 4, 4, {0,0,0}, {0,0,-1}, {0,1,0}, 90, {0,0,0}, {}, \
                            {environment='bright.hdr'})";
    let film = render_cpu(&packed_in(&dir, source));
    assert!(
        film.pixels.iter().all(|p| *p == [6.5, 0.25, 3.0]),
        "{:?}",
        film.pixels[0]
    );
    let exr = dir.join("o.exr");
    glint::image_io::write_image(&film, &exr).unwrap();
    let back = glint::image_io::read_image(&exr).unwrap();
    assert_eq!(back.pixels, film.pixels);
}

/// A mirror sphere and a glass sphere in the axis map at scale 1; the scene source for
/// `scale`.
fn spheres_source(scale: f64) -> String {
    format!(
        "m = gr.material({{0,0,0}}, {{0,0,0}}, 1) m:set_reflection(1) \
         g = gr.material({{0,0,0}}, {{0,0,0}}, 1) g:set_refraction(1.5) \
         root = gr.node('root') root:scale({scale}, {scale}, {scale}) \
         a = gr.nh_sphere('a', {{-1.1,0,0}}, 1) a:set_material(m) root:add_child(a) \
         b = gr.nh_sphere('b', {{1.1,0,0}}, 1) b:set_material(g) root:add_child(b) \
         gr.render(root, 'o.png', 48, 24, {{0,{e1},{e2}}}, {{0,-{e1},-{e2}}}, {{0,1,0}}, 40, \
                   {{0,0,0}}, {{}}, {{aa='uniform', samples=2, environment='axes.exr'}})",
        e1 = 1.5 * scale,
        e2 = 6.0 * scale
    )
}

/// What the spheres show depends on directions only: at scales 10⁻³ and 10³ the image is
/// scale 1's.
#[test]
fn mirror_and_glass_see_the_same_map_at_every_scale() {
    let dir = temp_dir("environment-scales");
    glint::image_io::write_image(&axis_map(), &dir.join("axes.exr")).unwrap();
    let at_one = render_cpu(&packed_in(&dir, &spheres_source(1.0)));
    for scale in [1e-3, 1e3] {
        let film = render_cpu(&packed_in(&dir, &spheres_source(scale)));
        let out = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("environment");
        glint::diff::assert_images_match(
            &format!("scale {scale}"),
            &film,
            &at_one,
            0.001,
            0.999,
            &out,
        )
        .unwrap_or_else(|m| panic!("{m}"));
    }
}

/// Without the option nothing is packed: no feature, no words after the textures', the
/// globals' environment words zero (the padding they were).
#[test]
fn scenes_without_a_map_pack_nothing_for_it() {
    let dir = temp_dir("environment-none");
    let source = "root = gr.node('root') s = gr.sphere('s') root:add_child(s) \
                  gr.render(root, 'o.png', 4, 4, {0,0,3}, {0,0,-1}, {0,1,0}, 50, {0,0,0}, {})";
    let scene = packed_in(&dir, source);
    assert!(!scene.features.contains(SceneFeatures::ENVIRONMENT));
    assert!(scene.texels.is_empty());
    let g = scene.globals;
    assert_eq!(
        (g.environment, g.environment_cos, g.environment_sin),
        (0, 0.0, 0.0)
    );
}

/// Runs `options` (a `gr.render` options table) from a directory holding the files of
/// [`bad_files`], returning the error.
fn scene_error(options: &str) -> String {
    let dir = temp_dir("environment-errors");
    bad_files(&dir);
    let path = dir.join("bad.lua");
    let source = format!(
        "root = gr.node('root')\n\
         gr.render(root, 'o.png', 4, 4, {{0,0,0}}, {{0,0,-1}}, {{0,1,0}}, 50, {{0,0,0}}, {{}}, {options})\n"
    );
    std::fs::write(&path, source).unwrap();
    glint::scene::lua::run_scene_file(
        &path,
        &glint::scene::lua::ScriptConfig::default(),
        &mut |_, _| Ok(()),
    )
    .expect_err("the scene must fail")
    .to_string()
}

/// A good map under a wrong name, a PNG, a truncated EXR, text, and a Radiance header
/// claiming 100 000 × 100 000 pixels in a few bytes.
fn bad_files(dir: &Path) {
    let mut map = Film::new(4, 2);
    map.pixels.fill([1.0, 2.0, 3.0]);
    glint::image_io::write_image(&map, &dir.join("good.exr")).unwrap();
    let exr = std::fs::read(dir.join("good.exr")).unwrap();
    std::fs::write(dir.join("sky.png"), &exr).unwrap();
    std::fs::write(dir.join("cut.exr"), &exr[..exr.len() / 2]).unwrap();
    std::fs::write(dir.join("text.hdr"), b"not an image").unwrap();
    std::fs::write(
        dir.join("huge.hdr"),
        b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 100000 +X 100000\n\x02\x02",
    )
    .unwrap();
    glint::image_io::write_image(&Film::new(8, 8), &dir.join("real.png")).unwrap();
    std::fs::copy(dir.join("real.png"), dir.join("png.exr")).unwrap();
}

#[test]
fn bad_maps_and_arguments_are_errors_naming_file_line_and_argument() {
    let at = "bad.lua:2: gr.render: argument 11 (options): environment: ";
    for (options, says) in [
        ("{environment='missing.exr'}", "missing.exr"),
        (
            "{environment='sky.png'}",
            "must be an OpenEXR (.exr) or Radiance HDR (.hdr) file",
        ),
        (
            "{environment='png.exr'}",
            "its content is not the OpenEXR image its name says",
        ),
        (
            "{environment='text.hdr'}",
            "its content is not the Radiance HDR image its name says",
        ),
        ("{environment='cut.exr'}", "cannot decode environment"),
        (
            "{environment='huge.hdr'}",
            "is 100000×100000; sides must be from 1 to 16384",
        ),
        (
            "{environment=5}",
            "must be the file name of an OpenEXR or Radiance HDR image, got 5",
        ),
    ] {
        let e = scene_error(options);
        assert!(e.contains(at) && e.contains(says), "{options}: {e}");
    }
    let e = scene_error("{environment='good.exr', environment_rotation='east'}");
    assert!(
        e.contains("bad.lua:2: gr.render: argument 11 (options): environment_rotation must be a number of degrees"),
        "{e}"
    );
}
