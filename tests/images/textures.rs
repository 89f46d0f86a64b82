//! Textures, UVs and bump maps on the CPU reference tracer: texel layout and bilinear
//! filtering, a texture on a fully lit matte quad reproducing itself (PNG and JPEG), each
//! primitive's UV convention and tangent frame, the bump direction (a height ramp rising
//! along u tilts the normal towards −u), the UV debug view, and the scene errors for bad
//! texture arguments. (The committed assets are checked by tests/images/texture_assets.rs.)

use crate::common;
use crate::texture_support;

use common::{packed_from_source, render_cpu, temp_dir};
use glam::{Vec2, Vec3};
use glint::pack::texture::pack_texels;
use glint::pack::{PackedMaterial, PackedScene, SceneFeatures};
use glint::scene::texture::Texture;
use glint::scene::OptionOverrides;
use glint::tracer::base::ray::Ray;
use glint::tracer::shading::surface::{surface_at, Surface};
use glint::tracer::shading::texture::{bump_normal, sample_texture};
use glint::tracer::traversal::traverse::{closest_hit, NoCounters};
use std::path::{Path, PathBuf};

/// A texture packed from raw texels (for filtering tests).
fn texture(width: u32, height: u32, rgba: Vec<[u8; 4]>) -> Texture {
    Texture {
        path: PathBuf::from("test.png"),
        width,
        height,
        rgba,
    }
}

/// Bilinear with repeat, texel centres at half-integers, v = 0 at the bottom row.
#[test]
fn bilinear_filtering_with_repeat() {
    // 2×2: top row red, green; bottom row blue, white.
    let t = texture(
        2,
        2,
        vec![
            [255, 0, 0, 255],
            [0, 255, 0, 255],
            [0, 0, 255, 255],
            [255, 255, 255, 255],
        ],
    );
    let texels = pack_texels(&[Box::new(t)]);
    let at = |u: f32, v: f32| sample_texture(&texels, 0, Vec2::new(u, v));
    // Texel centres give the texels exactly.
    assert_eq!(at(0.25, 0.75), Vec3::new(1.0, 0.0, 0.0));
    assert_eq!(at(0.75, 0.75), Vec3::new(0.0, 1.0, 0.0));
    assert_eq!(at(0.25, 0.25), Vec3::new(0.0, 0.0, 1.0));
    assert_eq!(at(0.75, 0.25), Vec3::ONE);
    // Half way between the two top texels: their mean.
    assert!(
        (at(0.5, 0.75) - Vec3::new(0.5, 0.5, 0.0))
            .abs()
            .max_element()
            < 1e-6
    );
    // u = 0 is half way between the last column and the first (repeat), and so is u = 1.
    assert!(
        (at(0.0, 0.75) - Vec3::new(0.5, 0.5, 0.0))
            .abs()
            .max_element()
            < 1e-6
    );
    assert!((at(1.0, 0.75) - at(0.0, 0.75)).abs().max_element() < 1e-6);
    // Repeat in both directions, negative coordinates included.
    for (du, dv) in [(1.0, 0.0), (-3.0, 2.0), (7.0, -5.0)] {
        assert!((at(0.3 + du, 0.6 + dv) - at(0.3, 0.6)).abs().max_element() < 1e-4);
    }
    // Not a number: the wrap maps it to 0, no panic, no NaN.
    assert!(at(f32::NAN, f32::INFINITY).is_finite());
}

/// Renders `source` (a scene script run from `dir`).
fn packed_in(dir: &Path, source: &str, overrides: &OptionOverrides) -> PackedScene {
    let path = dir.join("scene.lua");
    std::fs::write(&path, source).unwrap();
    common::packed_from_file(&path, overrides).remove(0)
}

/// A quad exactly filling a square view of `w`×`h` pixels, lit by ambient 1 alone, with
/// the texture `file` (written from `image`) as its diffuse colour: its render on the CPU,
/// and the texture as decoded from the file.
fn textured_quad(
    file: &str,
    image: &image::RgbImage,
    w: u32,
    h: u32,
) -> (image::RgbImage, image::RgbImage) {
    let dir = temp_dir(&format!("textures-quad-{w}-{file}"));
    texture_support::save(image, &dir.join(file));
    let decoded = image::open(dir.join(file)).unwrap().to_rgb8();
    let source = format!(
        "m = gr.material('m') m:set_diffuse('{file}') \
         q = gr.mesh('q', {{{{0,0,0}},{{1,0,0}},{{1,1,0}},{{0,1,0}}}}, {{{{0,1,2,3}}}}, \
                          {{{{0,0}},{{1,0}},{{1,1}},{{0,1}}}}) \
         q:set_material(m) \
         gr.render(q, 'o.png', {w}, {h}, {{0.5,0.5,0.5}}, {{0,0,-1}}, {{0,1,0}}, 90, \
                   {{1,1,1}}, {{}}, {{aa='none'}})"
    );
    let scene = packed_in(&dir, &source, &OptionOverrides::default());
    assert!(scene.features.contains(SceneFeatures::TEXTURE));
    let rendered = image::RgbImage::from_raw(w, h, render_cpu(&scene).to_rgb8()).unwrap();
    (rendered, decoded)
}

/// The quad at one texel per pixel shows its texture texel for texel: pixel centres land
/// on texel centres, and the footprint is one texel (mip level 0).
fn quad_reproduces(file: &str, image: &image::RgbImage) {
    let (w, h) = image.dimensions();
    let (actual, expected) = textured_quad(file, image, w, h);
    let worst = actual
        .iter()
        .zip(expected.as_raw())
        .map(|(&a, &b)| (a as i32 - b as i32).abs())
        .max()
        .unwrap();
    assert!(worst <= 1, "{file}: largest texel difference {worst}/255");
}

#[test]
fn a_texture_on_a_fully_lit_matte_quad_reproduces_it() {
    quad_reproduces("noise.png", &texture_support::noise(16, 16, 7));
    // JPEG is lossy: the reference is the decoded file, which is what gets used.
    quad_reproduces("noise.jpg", &texture_support::noise(16, 16, 8));
}

/// Texture filtering: a 64×64 noise texture on the quad seen at 16×16 pixels (4×4 texels
/// per pixel) shows mip level 2, each pixel the mean of the 4×4 texels it covers (to the
/// rounding of the two box-filter levels and of the output). Unfiltered, pixels would show
/// single texels: noise, up to ~100/255 off.
#[test]
fn a_minified_texture_shows_the_mean_of_the_texels_each_pixel_covers() {
    let noise = texture_support::noise(64, 64, 11);
    let (actual, texture) = textured_quad("fine.png", &noise, 16, 16);
    let mut worst = 0.0f32;
    for (x, y, pixel) in actual.enumerate_pixels() {
        for c in 0..3 {
            let mut sum = 0.0;
            for dy in 0..4 {
                for dx in 0..4 {
                    sum += texture.get_pixel(4 * x + dx, 4 * y + dy).0[c] as f32;
                }
            }
            worst = worst.max((pixel.0[c] as f32 - sum / 16.0).abs());
        }
    }
    assert!(
        worst <= 1.5,
        "largest difference from the 4×4 means {worst}/255"
    );
}

/// The footprint: one pixel's width in uv, here exactly one texel of the 16-texel quad at
/// every pixel (the image plane is parallel to the quad, so the cone's cos^1.5 off-axis
/// shrink and the surface's 1/√cos stretch cancel), and 0 where the tangent frame is
/// degenerate.
#[test]
fn the_footprint_of_a_pixel_on_a_parallel_quad_is_one_texel_everywhere() {
    use glint::tracer::base::ray::camera_ray;
    use glint::tracer::shading::texture::{camera_cone, texture_footprint};
    let source = "q = gr.mesh('q', {{0,0,0},{1,0,0},{1,1,0},{0,1,0}}, {{0,1,2,3}}, \
                                   {{0,0},{1,0},{1,1},{0,1}}) \
                  m = gr.material('m') m:set_diffuse('bumps.png') q:set_material(m) \
                  gr.render(q, 'o.png', 16, 16, {0.5,0.5,0.5}, {0,0,-1}, {0,1,0}, 90, \
                            {0,0,0}, {}, {aa='none'})";
    let dir = temp_dir("textures-footprint");
    texture_support::save(&texture_support::bumps(), &dir.join("bumps.png"));
    let scene = packed_in(&dir, source, &OptionOverrides::default());
    for (fx, fy) in [(8.0, 8.0), (0.5, 0.5), (15.5, 3.5), (2.0, 14.0)] {
        let ray = camera_ray(&scene.globals, fx, fy);
        let hit = closest_hit(&scene, &ray, f32::INFINITY, &mut NoCounters);
        assert!(hit.is_hit());
        let s = surface_at(&scene, &ray, &hit);
        let footprint = texture_footprint(&s, ray.dir, camera_cone(&scene.globals, &ray), hit.t);
        assert!(
            (footprint * 16.0 - 1.0).abs() < 1e-4,
            "pixel ({fx}, {fy}): {} texels",
            footprint * 16.0
        );
        let flat = Surface {
            dpdu: Vec3::ZERO,
            ..s
        };
        assert_eq!(
            texture_footprint(&flat, ray.dir, Vec2::new(0.0, 1.0), hit.t),
            0.0
        );
    }
}

/// The surface a ray from `origin` towards `target` hits first.
fn surface_towards(scene: &PackedScene, origin: Vec3, target: Vec3) -> Surface {
    let ray = Ray {
        origin,
        dir: (target - origin).normalize(),
    };
    let hit = closest_hit(scene, &ray, f32::MAX, &mut NoCounters);
    assert!(hit.is_hit(), "no hit towards {target}");
    surface_at(scene, &ray, &hit)
}

/// One primitive (`make` a gr call) with the UV debug view (which packs the UV code), at
/// the identity transform.
fn single(make: &str) -> PackedScene {
    let source = format!(
        "n = {make} \
         gr.render(n, 'o.png', 8, 8, {{0,0,9}}, {{0,0,-1}}, {{0,1,0}}, 50, {{0,0,0}}, {{}}, \
                   {{debug='uv'}})"
    );
    packed_from_source(&source, &OptionOverrides::default()).remove(0)
}

fn assert_uv(s: &Surface, expected: [f32; 2], what: &str) {
    let d = (s.uv - Vec2::from(expected)).abs().max_element();
    assert!(d < 1e-4, "{what}: uv {} expected {expected:?}", s.uv);
    // The frame is right-handed around the outward normal: ∂p/∂u × ∂p/∂v along it.
    let g = s.dpdu.cross(s.dpdv);
    assert!(
        g.normalize().dot(s.normal) > 0.999,
        "{what}: dpdu {} × dpdv {} is not along the normal {}",
        s.dpdu,
        s.dpdv,
        s.normal
    );
}

/// A finite-difference check of ∂p/∂u and ∂p/∂v: moving along the surface by a small
/// step of p changes uv by (ε_u, ε_v) with step ≈ ε_u·dpdu + ε_v·dpdv.
fn assert_frame_matches_uv(scene: &PackedScene, a: &Surface, origin: Vec3, what: &str) {
    let tangent = a.dpdu.normalize() * 1e-3;
    let b = surface_towards(scene, origin, a.p + tangent);
    let du = b.uv - a.uv;
    let predicted = a.dpdu * du.x + a.dpdv * du.y;
    let moved = b.p - a.p;
    assert!(
        (predicted - moved).length() < 0.05 * moved.length(),
        "{what}: moved {moved}, the frame predicts {predicted} (duv {du})"
    );
}

/// Every analytic primitive's documented convention at known points, with the frame
/// agreeing with how the UV actually changes.
#[test]
fn uv_conventions_of_the_analytic_primitives() {
    let sphere = single("gr.sphere('s')");
    let far = 5.0;
    // Longitude from +x towards +y; latitude from the south pole.
    for (dir, uv) in [
        (Vec3::X, [0.0, 0.5]),
        (Vec3::Y, [0.25, 0.5]),
        (-Vec3::X, [0.5, 0.5]),
        (Vec3::new(0.0, -1.0, 1.0), [0.75, 0.75]),
        (Vec3::new(1.0, 0.0, -1.0), [0.0, 0.25]),
    ] {
        let d = dir.normalize();
        let s = surface_towards(&sphere, d * far, Vec3::ZERO);
        assert_uv(&s, uv, &format!("sphere towards {dir}"));
        if uv[0] > 0.1 {
            assert_frame_matches_uv(&sphere, &s, d * far, "sphere");
        }
    }
    // The north pole: v = 1, no NaN anywhere.
    let pole = surface_towards(&sphere, Vec3::new(0.0, 0.0, far), Vec3::ZERO);
    assert!((pole.uv.y - 1.0).abs() < 1e-6 && pole.dpdu.is_finite() && pole.dpdv.is_finite());

    // Box faces, seen from outside: (right, up) as documented.
    let cube = single("gr.cube('c')");
    for (origin, target, uv) in [
        (
            Vec3::new(0.2, 0.7, 5.0),
            Vec3::new(0.2, 0.7, 0.5),
            [0.2, 0.7],
        ),
        (
            Vec3::new(0.2, 0.7, -5.0),
            Vec3::new(0.2, 0.7, 0.5),
            [0.8, 0.7],
        ),
        (
            Vec3::new(5.0, 0.7, 0.2),
            Vec3::new(0.5, 0.7, 0.2),
            [0.8, 0.7],
        ),
        (
            Vec3::new(-5.0, 0.7, 0.2),
            Vec3::new(0.5, 0.7, 0.2),
            [0.2, 0.7],
        ),
        (
            Vec3::new(0.2, 5.0, 0.3),
            Vec3::new(0.2, 0.5, 0.3),
            [0.2, 0.7],
        ),
        (
            Vec3::new(0.2, -5.0, 0.3),
            Vec3::new(0.2, 0.5, 0.3),
            [0.2, 0.3],
        ),
    ] {
        let s = surface_towards(&cube, origin, target);
        assert_uv(&s, uv, &format!("box from {origin}"));
        assert_frame_matches_uv(&cube, &s, origin, "box");
    }

    // Cylinder: u around z from +x, v = z; caps planar (u to +x, v to +y).
    let cylinder = single("gr.cylinder('c')");
    let s = surface_towards(
        &cylinder,
        Vec3::new(0.0, 5.0, 0.3),
        Vec3::new(0.0, 0.0, 0.3),
    );
    assert_uv(&s, [0.25, 0.3], "cylinder side");
    assert_frame_matches_uv(&cylinder, &s, Vec3::new(0.0, 5.0, 0.3), "cylinder");
    let s = surface_towards(
        &cylinder,
        Vec3::new(0.5, 0.0, 5.0),
        Vec3::new(0.5, 0.0, 0.5),
    );
    assert_uv(&s, [0.75, 0.5], "cylinder top cap");

    // Cone: v = (z − zmin)/(zmax − zmin).
    let cone = single("gr.cone('c', 1, 3)");
    let s = surface_towards(&cone, Vec3::new(-9.0, 0.0, 2.0), Vec3::new(0.0, 0.0, 2.0));
    assert_uv(&s, [0.5, 0.5], "cone side");
    assert_frame_matches_uv(&cone, &s, Vec3::new(-9.0, 0.0, 2.0), "cone");

    // Torus: u around z, v around the tube from its outer equator towards +z.
    let torus = single("gr.torus('t', 2, 0.5)");
    let s = surface_towards(&torus, Vec3::new(0.0, 9.0, 0.0), Vec3::ZERO);
    assert_uv(&s, [0.25, 0.0], "torus outer equator");
    let s = surface_towards(&torus, Vec3::new(2.0, 0.0, 5.0), Vec3::new(2.0, 0.0, 0.0));
    assert_uv(&s, [0.0, 0.25], "torus top");
    assert_frame_matches_uv(&torus, &s, Vec3::new(2.0, 0.0, 5.0), "torus");
}

/// Meshes: the per-vertex UVs interpolated by the hit's barycentrics; without UVs, the
/// planar projection by the dominant normal axis (object space).
#[test]
fn mesh_uvs_interpolate_or_project() {
    let with = single(
        "gr.mesh('q', {{0,0,0},{2,0,0},{2,2,0},{0,2,0}}, {{0,1,2,3}}, \
                      {{0,0},{1,0},{1,1},{0,1}})",
    );
    let s = surface_towards(&with, Vec3::new(0.5, 1.5, 5.0), Vec3::new(0.5, 1.5, 0.0));
    assert_uv(&s, [0.25, 0.75], "mesh with UVs");
    // The frame maps a unit of u to the quad's 2 units of x.
    assert!(
        (s.dpdu - Vec3::new(2.0, 0.0, 0.0)).length() < 1e-5,
        "{}",
        s.dpdu
    );
    // A floor without UVs, translated: (u, v) = object (z, x).
    let without = single(
        "gr.mesh('f', {{0,0,0},{0,0,3},{3,0,3},{3,0,0}}, {{0,1,2,3}}) \
         n:translate(10, 1, 0)",
    );
    let s = surface_towards(
        &without,
        Vec3::new(11.5, 5.0, 0.25),
        Vec3::new(11.5, 0.0, 0.25),
    );
    assert_uv(&s, [0.25, 1.5], "mesh without UVs");
    // OBJ `vt`, through a file beside the scene.
    let dir = temp_dir("textures-obj");
    std::fs::write(
        dir.join("quad.obj"),
        "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
         f 1/1 2/2 3/3 4/4\n",
    )
    .unwrap();
    let source = "n = gr.mesh('q', 'quad.obj') \
                  gr.render(n, 'o.png', 8, 8, {0,0,9}, {0,0,-1}, {0,1,0}, 50, {0,0,0}, {}, \
                            {debug='uv'})";
    let obj = packed_in(&dir, source, &OptionOverrides::default());
    let s = surface_towards(&obj, Vec3::new(1.5, 0.5, 5.0), Vec3::new(1.5, 0.5, 0.0));
    assert_uv(&s, [0.75, 0.25], "OBJ vt");
}

/// A surface at the origin facing +z with the frame (dpdu, dpdv) and material `m`.
fn flat(dpdu: Vec3, dpdv: Vec3) -> Surface {
    Surface {
        p: Vec3::ZERO,
        normal: Vec3::Z,
        magnitude: 1.0,
        material: 0,
        uv: Vec2::new(0.5, 0.5),
        dpdu,
        dpdv,
        footprint: 0.0,
        p_object: Vec3::ZERO,
        instance: 0,
        world_footprint: 0.0,
    }
}

fn bump_material(strength: f32) -> PackedMaterial {
    PackedMaterial {
        bump_texture: 0,
        bump_strength: strength,
        ..PackedMaterial::zeroed()
    }
}

trait Zeroed {
    fn zeroed() -> Self;
}
impl Zeroed for PackedMaterial {
    fn zeroed() -> Self {
        bytemuck::Zeroable::zeroed()
    }
}

fn gray_texels(image: &image::GrayImage) -> Vec<u32> {
    let rgba = image
        .pixels()
        .map(|p| [p.0[0], p.0[0], p.0[0], 255])
        .collect();
    pack_texels(&[Box::new(texture(image.width(), image.height(), rgba))])
}

/// The proof of axes: a height ramp rising along u tilts the normal towards −u
/// (and one rising along v towards −v), by atan(strength × slope), whatever the scale
/// of the frame; a degenerate frame leaves the normal alone.
#[test]
fn a_height_ramp_rising_along_u_tilts_the_normal_towards_minus_u() {
    let strength = 0.1;
    // 64 columns from 0 to 1: slope 255·63/… ≈ 1 per unit of u (quantised to bytes).
    let ramp_u = gray_texels(&texture_support::ramp_u(64));
    let m = bump_material(strength);
    for scale in [1.0, 1e-3, 1e3] {
        let n = bump_normal(&ramp_u, &m, &flat(Vec3::X * scale, Vec3::Y * scale));
        assert!(n.x < -0.05 && n.y.abs() < 1e-6, "scale {scale}: {n}");
        let slope = -n.x / n.z;
        assert!(
            (slope - strength).abs() < 0.01 * strength + 0.002,
            "slope {slope}"
        );
    }
    // The frame turned by 90° (u along +y): the normal leans to −y.
    let n = bump_normal(&ramp_u, &m, &flat(Vec3::Y, -Vec3::X));
    assert!(n.y < -0.05 && n.x.abs() < 1e-6, "turned frame: {n}");
    // Along v.
    let ramp_v = gray_texels(&texture_support::ramp_v(64));
    let n = bump_normal(&ramp_v, &m, &flat(Vec3::X, Vec3::Y));
    assert!(n.y < -0.05 && n.x.abs() < 1e-6, "ramp along v: {n}");
    // A left-handed frame (dpdu × dpdv = −N) still tilts towards −u.
    let n = bump_normal(&ramp_u, &m, &flat(Vec3::X, -Vec3::Y));
    assert!(n.x < -0.05, "left-handed frame: {n}");
    // Degenerate frames: the normal unchanged, never NaN.
    for (dpdu, dpdv) in [
        (Vec3::ZERO, Vec3::Y),
        (Vec3::X, Vec3::X * 2.0),
        (Vec3::splat(f32::NAN), Vec3::Y),
    ] {
        assert_eq!(bump_normal(&ramp_u, &m, &flat(dpdu, dpdv)), Vec3::Z);
    }
}

/// Bump maps are filtered too: stripes two texels wide (heights 0, 0, 1, 1, …) tilt the
/// normal hard at their own scale, and not at all once the footprint spans four texels,
/// where mip level 2 has averaged them flat.
#[test]
fn a_minified_bump_map_averages_its_relief_away() {
    let stripes = image::GrayImage::from_fn(64, 64, |x, _| {
        image::Luma([if x / 2 % 2 == 0 { 0 } else { 255 }])
    });
    let texels = gray_texels(&stripes);
    let m = bump_material(0.01);
    // u at texel 1's centre: its neighbours one texel away are 0 (texel 0) and 1 (texel 2).
    let at = |footprint: f32| {
        let s = Surface {
            uv: Vec2::new(1.5 / 64.0, 0.5),
            footprint,
            ..flat(Vec3::X, Vec3::Y)
        };
        bump_normal(&texels, &m, &s)
    };
    let sharp = at(0.0);
    let smooth = at(4.0 / 64.0);
    assert!(sharp.x < -0.2, "level 0: {sharp}");
    assert!(
        smooth.x.abs() < 1e-3 && smooth.y.abs() < 1e-6,
        "level 2: {smooth}"
    );
}

/// The UV debug view shows (u mod 1, v mod 1, 0): on a quad with UVs from (0,0) to
/// (2,2) filling the view, every pixel's colour is its film position's UV, wrapped.
#[test]
fn the_uv_debug_view_shows_wrapped_uvs() {
    let source = "q = gr.mesh('q', {{0,0,0},{1,0,0},{1,1,0},{0,1,0}}, {{0,1,2,3}}, \
                                   {{0,0},{2,0},{2,2},{0,2}}) \
                  gr.render(q, 'o.png', 16, 16, {0.5,0.5,0.5}, {0,0,-1}, {0,1,0}, 90, \
                            {0,0,0}, {}, {aa='none', debug='uv'})";
    let scene = packed_from_source(source, &OptionOverrides::default()).remove(0);
    assert!(scene.features.contains(SceneFeatures::TEXTURE));
    let film = render_cpu(&scene);
    for y in 0..16 {
        for x in 0..16 {
            let u = ((x as f32 + 0.5) / 16.0 * 2.0).fract();
            let v = ((16.0 - y as f32 - 0.5) / 16.0 * 2.0).fract();
            let c = film.pixels[(y * 16 + x) as usize];
            assert!(
                (c[0] - u).abs() < 1e-4 && (c[1] - v).abs() < 1e-4 && c[2] == 0.0,
                "pixel ({x}, {y}): {c:?}, expected ({u}, {v}, 0)"
            );
        }
    }
}

/// Runs `source` from a directory holding `bumps.png`, returning the error message.
fn scene_error(source: &str) -> String {
    let dir = temp_dir("textures-errors");
    texture_support::save(&texture_support::bumps(), &dir.join("bumps.png"));
    std::fs::write(dir.join("junk.png"), b"not a png").unwrap();
    common::scene_error_in(&dir, source)
}

#[test]
fn bad_texture_arguments_are_errors_naming_file_line_and_argument() {
    let e = scene_error("m = gr.material('m')\nm:set_diffuse('missing.png')\n");
    assert!(
        e.contains("bad.lua:2: material:set_diffuse: argument 1 (file): cannot read texture")
            && e.contains("missing.png"),
        "{e}"
    );
    let e = scene_error("m = gr.material('m')\nm:set_specular('junk.png')\n");
    assert!(
        e.contains("bad.lua:2: material:set_specular: argument 1 (file): cannot decode texture")
            && e.contains("junk.png"),
        "{e}"
    );
    let e = scene_error("m = gr.material('m')\nm:set_bump('bumps.png', -1)\n");
    assert!(
        e.contains("bad.lua:2: material:set_bump: argument 2 (strength) must be a non-negative number, got -1"),
        "{e}"
    );
    let e = scene_error("m = gr.material('m')\nm:set_bump(5)\n");
    assert!(
        e.contains("bad.lua:2: material:set_bump: argument 1 (file) must be the file name"),
        "{e}"
    );
    let e = scene_error("m = gr.material('m')\nm:set_bump('bumps.png')\nm:set_diffuse({})\n");
    assert!(e.contains("bad.lua:3: material:set_diffuse"), "{e}");
}

/// Scenes without textures keep the plain arrays: no texels, no triangle UVs, no
/// texture features; a material with a texture that no geometry uses adds nothing.
#[test]
fn untextured_scenes_pack_no_texture_data() {
    let dir = temp_dir("textures-unused");
    texture_support::save(&texture_support::bumps(), &dir.join("bumps.png"));
    let source = "m = gr.material('m') m:set_diffuse('bumps.png') m:set_bump('bumps.png') \
                  q = gr.mesh('q', {{0,0,0},{1,0,0},{1,1,0}}, {{0,1,2}}) \
                  gr.render(q, 'o.png', 8, 8, {0,0,3}, {0,0,-1}, {0,1,0}, 50, {0,0,0}, {})";
    let scene = packed_in(&dir, source, &OptionOverrides::default());
    assert!(!scene.features.contains(SceneFeatures::TEXTURE));
    assert!(!scene.features.contains(SceneFeatures::BUMP));
    assert!(scene.texels.is_empty() && scene.triangle_uvs.is_empty());
    let used = source.replace("gr.render(q", "q:set_material(m) gr.render(q");
    let scene = packed_in(&dir, &used, &OptionOverrides::default());
    assert!(scene.features.contains(SceneFeatures::TEXTURE));
    assert!(scene.features.contains(SceneFeatures::BUMP));
    assert_eq!(scene.triangle_uvs.len(), 1);
    // 64×64: seven mip levels, 64² down to 1², each with its header.
    let chain: usize = (0..7).map(|k| (64usize >> k) * (64 >> k)).sum();
    assert_eq!(
        scene.texels.len(),
        7 * 4 + chain,
        "one texture's mip chain, stored once"
    );
}
