//! Procedural textures on the CPU tracer, whole images against the analytic pattern:
//! a checker on a plane and on a turned, scaled and moved sphere lit by ambient 1 alone
//! (so every pixel shows kd: c1, c2, or near a cell edge a blend of them), classified
//! pixel by pixel from the object-space point the test computes itself; the pattern's
//! independence of the object's scale (10⁻³ … 10³, camera scaled with it); and the
//! scene language's errors for bad arguments.

use crate::common;

use common::{packed_from_source, render_cpu};
use glam::{DMat4, DVec3, Vec3};
use glint::pack::layout::load_instance;
use glint::pack::PackedScene;
use glint::scene::OptionOverrides;
use glint::tracer::base::ray::camera_ray;
use glint::tracer::shading::procedural::object_frame;
use glint::tracer::shading::surface::surface_at;
use glint::tracer::shading::texture::{camera_cone, with_footprint};
use glint::tracer::traversal::traverse::{closest_hit, NoCounters};

const C1: [f32; 3] = [0.9, 0.8, 0.1];
const C2: [f32; 3] = [0.1, 0.3, 0.7];

/// What a pixel shows against the analytic checker.
#[derive(Debug, Default)]
struct Classes {
    c1: usize,
    c2: usize,
    /// Pixels within a footprint of a cell edge: a blend of c1 and c2.
    blended: usize,
    missed: usize,
}

/// Renders `scene` (ambient 1, no lights, AA off) and checks every pixel that hits
/// against the checker of cube side `size` at the object point `to_object` gives for the
/// hit's world point: where the footprint lies within one cell, exactly that cell's
/// colour; elsewhere a blend of the two (on the segment from c1 to c2).
fn classify(scene: &PackedScene, size: f64, to_object: DMat4) -> Classes {
    let film = render_cpu(scene);
    let g = &scene.globals;
    let mut classes = Classes::default();
    for y in 0..g.height {
        for x in 0..g.width {
            let ray = camera_ray(g, x as f32 + 0.5, y as f32 + 0.5);
            let hit = closest_hit(scene, &ray, f32::MAX, &mut NoCounters);
            let got = Vec3::from(film.get(x, y));
            if !hit.is_hit() {
                classes.missed += 1;
                continue;
            }
            let s = surface_at(scene, &ray, &hit);
            let s = with_footprint(scene, s, ray.dir, camera_cone(g, &ray), hit.t);
            let frame = object_frame(load_instance(scene, s.instance), s.normal);
            let footprint = f64::from(s.world_footprint * frame.scale);
            let mut p = to_object.transform_point3(s.p.as_dvec3()) / size;
            // Distance (in object units) to the nearest cell face the footprint could
            // straddle. Along the normal the footprint has no extent: a face lying on a
            // cell boundary (the floor's top, at object y = 1) takes its cell from the
            // tracer's own snapped object point there, whose rounding decides the side.
            let n = frame.normal.as_dvec3();
            let mut edge = f64::MAX;
            for axis in 0..3 {
                if n[axis].abs() < 0.999 {
                    let f = p[axis] - p[axis].floor();
                    edge = edge.min(f.min(1.0 - f) * size);
                } else {
                    p[axis] = f64::from(s.p_object[axis] / size as f32);
                }
            }
            let parity = (p.x.floor() + p.y.floor() + p.z.floor()).rem_euclid(2.0);
            let expected = Vec3::from(if parity == 0.0 { C1 } else { C2 });
            if edge > footprint + 1e-4 * size {
                assert!(
                    (got - expected).abs().max_element() < 1e-5,
                    "pixel ({x}, {y}): {got} where the checker is {expected} (object point {p})"
                );
                if parity == 0.0 {
                    classes.c1 += 1;
                } else {
                    classes.c2 += 1;
                }
            } else {
                // On the segment c1 → c2.
                let (a, b) = (Vec3::from(C1), Vec3::from(C2));
                let t = (got - a).dot(b - a) / (b - a).length_squared();
                let off = (a + (b - a) * t - got).length();
                assert!(
                    (-1e-4..=1.0001).contains(&t) && off < 1e-4,
                    "pixel ({x}, {y}): {got} is no blend of c1 and c2"
                );
                classes.blended += 1;
            }
        }
    }
    classes
}

/// A floor (the unit cube scaled to 40 × 1 × 40, its top face at y = 0) with a checker
/// of side 1/32 in its own space: cells 1.25 world units wide, to the horizon.
#[test]
fn a_checker_floor_is_the_analytic_pattern_pixel_by_pixel() {
    let size = 1.0 / 32.0;
    let source = format!(
        "m = gr.material('m') m:set_diffuse(gr.checker({{0.9, 0.8, 0.1}}, {{0.1, 0.3, 0.7}}, {size}))
         f = gr.cube('floor') f:set_material(m) f:translate(-0.5, -1, -0.5) f:scale(40, 1, 40)
         gr.transform_order('pre')
         gr.render(f, 'o.png', 96, 64, {{0.3, 2, 6}}, {{0, -0.45, -1}}, {{0, 1, 0}}, 50,
                   {{1, 1, 1}}, {{}}, {{aa='none'}})"
    );
    let scene = packed_from_source(&source, &OptionOverrides::default()).remove(0);
    // Pre order: translate, then scale, applied to the cube as written: M = S·T.
    let to_object = (DMat4::from_scale(DVec3::new(40.0, 1.0, 40.0))
        * DMat4::from_translation(DVec3::new(-0.5, -1.0, -0.5)))
    .inverse();
    let classes = classify(&scene, size, to_object);
    eprintln!("{classes:?}");
    assert!(classes.c1 > 500 && classes.c2 > 500, "{classes:?}");
    // Near the horizon the footprint covers several cells: blends there.
    assert!(classes.blended > 100, "{classes:?}");
}

/// A checker on a sphere that is scaled (unevenly), turned and moved: the cells stay in
/// the sphere's own space, pixel by pixel.
#[test]
fn a_checker_on_a_transformed_sphere_moves_turns_and_scales_with_it() {
    let size = 0.5;
    let source = format!(
        "m = gr.material('m') m:set_diffuse(gr.checker({{0.9, 0.8, 0.1}}, {{0.1, 0.3, 0.7}}, {size}))
         b = gr.sphere('ball') b:set_material(m)
         gr.transform_order('pre')
         b:scale(1.5, 1, 0.8) b:rotate('z', 30) b:rotate('y', 40) b:translate(0.4, -0.2, -1)
         gr.render(b, 'o.png', 120, 120, {{0, 0, 6}}, {{0, 0, -1}}, {{0, 1, 0}}, 40,
                   {{1, 1, 1}}, {{}}, {{aa='none'}})"
    );
    let scene = packed_from_source(&source, &OptionOverrides::default()).remove(0);
    let to_world = DMat4::from_translation(DVec3::new(0.4, -0.2, -1.0))
        * DMat4::from_rotation_y(40f64.to_radians())
        * DMat4::from_rotation_z(30f64.to_radians())
        * DMat4::from_scale(DVec3::new(1.5, 1.0, 0.8));
    let classes = classify(&scene, size, to_world.inverse());
    eprintln!("{classes:?}");
    assert!(classes.c1 > 500 && classes.c2 > 500, "{classes:?}");
}

/// The same checkered and noise-bumped scene with everything (objects, camera, light)
/// scaled by 10⁻³ and 10³: the pattern and its filtering live in object units, so the
/// image does not change (each pixel within 2/255 but a few in 1000 at silhouettes).
#[test]
fn procedural_textures_do_not_change_with_the_scene_scale() {
    let render = |k: f64| {
        let source = format!(
            "m = gr.material({{0.8, 0.8, 0.8}}, {{0.4, 0.4, 0.4}}, 20)
             m:set_diffuse(gr.checker({{0.9, 0.8, 0.1}}, {{0.1, 0.3, 0.7}}, 0.25))
             m:set_bump(gr.noise({{0, 0, 0}}, {{1, 1, 1}}, 3, 3), 0.1)
             gr.transform_order('pre')
             root = gr.node('root')
             f = gr.cube('floor') f:set_material(m) f:translate(-0.5, -1, -0.5) f:scale(20, 1, 20)
             f:scale({k}, {k}, {k}) root:add_child(f)
             b = gr.sphere('ball') b:set_material(m) b:translate(0, 1, 0) b:scale({k}, {k}, {k})
             root:add_child(b)
             l = gr.light({{{lx}, {ly}, {lz}}}, {{0.8, 0.8, 0.8}}, {{1, 0, 0}})
             gr.render(root, 'o.png', 64, 48, {{0, {ey}, {ez}}}, {{0, -0.3, -1}}, {{0, 1, 0}}, 50,
                       {{0.3, 0.3, 0.3}}, {{l}}, {{aa='none'}})",
            lx = 3.0 * k,
            ly = 6.0 * k,
            lz = 4.0 * k,
            ey = 2.5 * k,
            ez = 7.0 * k,
        );
        render_cpu(&packed_from_source(&source, &OptionOverrides::default()).remove(0)).to_rgb8()
    };
    let reference = render(1.0);
    for k in [1e-3, 1e3] {
        let scaled = render(k);
        let off = reference
            .chunks(3)
            .zip(scaled.chunks(3))
            .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| x.abs_diff(*y) > 2))
            .count();
        assert!(
            off * 1000 <= 4 * reference.len() / 3,
            "scale {k}: {off} pixels differ"
        );
    }
}

/// The error of running `source` as `bad.lua`.
fn scene_error(source: &str) -> String {
    common::scene_error_in(&common::temp_dir("procedural-errors"), source)
}

/// Bad arguments name the file, the line, the call and the argument, and show the value.
#[test]
fn bad_procedural_arguments_are_errors_naming_file_line_argument_and_value() {
    for (source, expected) in [
        (
            "x = 1\nt = gr.checker({1,0,0}, {0,0,1}, -0.5)\n",
            "bad.lua:2: gr.checker: argument 3 (size) must be a positive number, got -0.5",
        ),
        (
            "t = gr.checker({1,0,0}, 'blue', 1)\n",
            "bad.lua:1: gr.checker: argument 2 (c2) must be a table of 3 numbers {r, g, b}, got 'blue'",
        ),
        (
            "t = gr.noise({1,0,0}, {0,0,1}, 0)\n",
            "bad.lua:1: gr.noise: argument 3 (scale) must be a positive number, got 0",
        ),
        (
            "t = gr.noise({1,0,0}, {0,0,1}, 2, 9)\n",
            "bad.lua:1: gr.noise: argument 4 (octaves) must be a positive integer (at most 8), got 9",
        ),
        (
            "t = gr.noise({1,0,0}, {0,0,1}, 2, 2.5)\n",
            "bad.lua:1: gr.noise: argument 4 (octaves) must be a positive integer (at most 8), got 2.5",
        ),
        (
            "t = gr.marble({1,0,0}, {0,0,1}, 2, -1)\n",
            "bad.lua:1: gr.marble: argument 4 (turbulence) must be a non-negative number, got -1",
        ),
        (
            "t = gr.wood({1,0,0}, {0,0,1}, 1/0)\n",
            "bad.lua:1: gr.wood: argument 3 (scale) must be a positive number, got inf",
        ),
        (
            "m = gr.material('m')\nm:set_bump(gr.noise({0,0,0}, {1,1,1}, 1), -2)\n",
            "bad.lua:2: material:set_bump: argument 2 (strength) must be a non-negative number, got -2",
        ),
        (
            "m = gr.material('m')\nm:set_bump(m)\n",
            "bad.lua:2: material:set_bump: argument 1 (file) must be the file name of a height map (PNG or JPEG) or a procedural texture, got material 'm'",
        ),
    ] {
        let e = scene_error(source);
        assert!(e.contains(expected), "{e}\nexpected: {expected}");
    }
}
