//! Shading against closed forms: the A4 Phong formula at a known point, huge shininess
//! without NaN, mirrors bounded by max_depth and min_weight, and scale invariance of whole
//! images (everything, camera included, scaled by 1e-3 and 1e3); no speckle from a
//! light lying exactly on a surface, at those scales too; smooth meshes against
//! POV-Ray, their terminator rule, and their normals against an f64 oracle at 1e-3 and 1e3.

use crate::common;

use common::{failure_dir, load_scenes};
use glam::{DMat4, DVec3, Vec3};
use glint::diff::assert_images_match;
use glint::pack::{pack, SceneFeatures};
use glint::scene::flatten::{FlatScene, Object, ObjectKind};
use glint::scene::{
    Background, Camera, Light, Material, OptionOverrides, RenderOptions, TraceDepth,
};
use glint::tracer::base::ray::Ray;
use glint::tracer::base::rng::SampleSeed;
use glint::tracer::path::trace::trace_ray;
use glint::tracer::shading::shade::phong_power;
use glint::tracer::traversal::traverse::NoCounters;

fn sphere_scene(
    material: Material,
    light: Light,
    ambient: [f32; 3],
    options: RenderOptions,
) -> FlatScene {
    FlatScene {
        objects: vec![Object {
            name: "s".into(),
            kind: ObjectKind::Sphere,
            object_to_world: DMat4::from_scale(DVec3::splat(2.0)),
            material: 0,
        }],
        triangles: vec![],
        meshes: Vec::new(),
        mesh_instances: Vec::new(),
        csg: Vec::new(),
        materials: vec![material],
        textures: Vec::new(),
        lights: vec![light],
        camera: Camera {
            eye: DVec3::new(0.0, 0.0, 10.0),
            view: DVec3::new(0.0, 0.0, -1.0),
            up: DVec3::Y,
            fov_deg: 30.0,
        },
        ambient,
        width: 8,
        height: 8,
        options,
    }
}

#[test]
fn phong_at_a_known_point_matches_the_a4_formula() {
    let material = Material {
        kd: [0.6, 0.3, 0.2],
        ks: [0.5, 0.5, 0.5],
        shininess: 12.0,
        ..Material::default()
    };
    let light = Light {
        position: DVec3::new(3.0, 4.0, 6.0),
        colour: [0.9, 0.8, 0.7],
        falloff: [1.0, 0.1, 0.01],
        area: None,
    };
    let scene = sphere_scene(
        material.clone(),
        light.clone(),
        [0.2, 0.25, 0.3],
        RenderOptions::default(),
    );
    let packed = pack(&scene).unwrap();
    // A ray from (0.3, 0.2, 10) straight down -z hits the radius-2 sphere at z = √(4 − 0.13).
    let origin = DVec3::new(0.3, 0.2, 10.0);
    let ray = Ray {
        origin: origin.as_vec3(),
        dir: Vec3::NEG_Z,
    };
    let got = trace_ray(&packed, ray, SampleSeed::default(), &mut NoCounters);
    // The A4 formula in f64.
    let p = DVec3::new(0.3, 0.2, (4.0f64 - 0.13).sqrt());
    let n = p.normalize();
    let v = DVec3::Z;
    let to_light = light.position - p;
    let d = to_light.length();
    let l = to_light / d;
    let r = 2.0 * n.dot(l) * n - l;
    let attenuation = 1.0 / (1.0 + 0.1 * d + 0.01 * d * d);
    let expected: Vec<f64> = (0..3)
        .map(|i| {
            let kd = material.kd[i] as f64;
            let ks = material.ks[i] as f64;
            kd * [0.2, 0.25, 0.3][i]
                + (kd * n.dot(l).max(0.0) + ks * r.dot(v).max(0.0).powf(12.0))
                    * light.colour[i] as f64
                    * attenuation
        })
        .collect();
    for i in 0..3 {
        assert!(
            (got[i] as f64 - expected[i]).abs() < 1e-5,
            "channel {i}: got {got}, expected {expected:?}"
        );
    }
}

#[test]
fn huge_shininess_gives_no_nan() {
    for exponent in [0.0f32, 1.0, 20.0, 5e7, f32::MAX] {
        for base in [0.0f32, 1e-30, 0.5, 0.999_999, 1.0, -0.5] {
            let v = phong_power(base, exponent);
            assert!(
                v.is_finite() && (0.0..=1.0).contains(&v),
                "phong_power({base}, {exponent}) = {v}"
            );
        }
    }
    assert_eq!(phong_power(1.0, 5e7), 1.0);
    assert_eq!(phong_power(0.999, 5e7), 0.0);
    assert_eq!(
        phong_power(0.0, 0.0),
        0.0,
        "no highlight where R·V = 0, whatever the exponent"
    );
}

/// A mirror sphere seen head-on: the centre pixel reflects the ray straight back, so its
/// colour is the local shading plus reflection × background(+z), counted once per level.
#[test]
fn mirror_depth_and_weight_limits() {
    let mirror = Material {
        kd: [0.0; 3],
        ks: [0.0; 3],
        reflection: [0.5; 3],
        ..Material::default()
    };
    let light = Light {
        position: DVec3::new(0.0, 0.0, 50.0),
        colour: [0.0; 3],
        falloff: [1.0, 0.0, 0.0],
        area: None,
    };
    let background = [0.2, 0.4, 0.8];
    let colour_with = |max_depth: u32, min_weight: f32| {
        let options = RenderOptions {
            max_depth: TraceDepth::constant(max_depth),
            min_weight,
            background: Background::Solid(background),
            ..RenderOptions::default()
        };
        let packed = pack(&sphere_scene(
            mirror.clone(),
            light.clone(),
            [0.0; 3],
            options,
        ))
        .unwrap();
        let ray = Ray {
            origin: Vec3::new(0.0, 0.0, 10.0),
            dir: Vec3::NEG_Z,
        };
        trace_ray(&packed, ray, SampleSeed::default(), &mut NoCounters)
    };
    assert_eq!(
        colour_with(0, 0.0),
        Vec3::ZERO,
        "max_depth 0: no reflection"
    );
    let one = colour_with(1, 0.0);
    assert!(
        (one - Vec3::from(background) * 0.5).abs().max_element() < 1e-6,
        "{one}"
    );
    assert_eq!(
        colour_with(1, 0.6),
        Vec3::ZERO,
        "weight 0.5 is below min_weight 0.6"
    );
}

#[test]
fn images_are_scale_invariant() {
    let overrides = OptionOverrides {
        width: Some(96),
        height: Some(64),
        ..OptionOverrides::default()
    };
    for path in [
        common::root().join("scenes/demo.lua"),
        common::root().join("scenes/columns.lua"),
        common::root().join("scenes/tori.lua"),
        common::root().join("scenes/smooth.lua"),
        common::corpus().join("a4-2021plus/macho-cows.lua"),
    ] {
        let scene = &load_scenes(&path, &overrides)[0];
        let reference = common::render_cpu(&pack(scene).unwrap());
        for s in [1e-3, 1e3] {
            let film = common::render_cpu(&pack(&common::scaled_scene(scene, s)).unwrap());
            assert!(
                film.pixels.iter().flatten().all(|v| v.is_finite()),
                "NaN at scale {s}"
            );
            let name = format!("scale-{s}-{}", common::scene_name(&path));
            let report =
                assert_images_match(&name, &film, &reference, 0.005, 0.999, &failure_dir())
                    .unwrap_or_else(|e| panic!("{e}"));
            println!("{name}: {report}");
        }
    }
}

/// Most pixels a light exactly on a surface may leave more than 16/255 darker than the
/// same light moved 0.01 off it (the Cornell box: 6% of pixels, isolated
/// speckle, where rounding decides whether the surface through the light blocks it).
const MAX_LIGHT_ON_SURFACE_DARKER: f64 = 0.001;

/// A point light in a ceiling's face (also through glass), on a shelf's edge, inside a
/// panel thinner than rounding, and an area light in the ceiling's plane, at scales 1,
/// 1e-3 and 1e3: shadow rays stop short of the light (`tracer::base::ray::shadow_reach`), so the
/// surface through it does not decide pixel by pixel whether it blocks.
#[test]
fn light_on_a_surface_does_not_speckle() {
    use common::light_on_surface::{light_on_surface_scene, speckle, LightOnSurface};
    let mut failures = Vec::new();
    for case in LightOnSurface::ALL {
        let (on, off) = (
            light_on_surface_scene(case, 0.0),
            light_on_surface_scene(case, 0.01),
        );
        for s in [1.0, 1e-3, 1e3] {
            let render = |scene: &FlatScene| {
                let scaled = common::scaled_scene(scene, s);
                common::render_cpu(&glint::pipeline::pack_scene(&scaled).unwrap())
            };
            let (film, reference) = (render(&on), render(&off));
            let (darker, isolated) = speckle(&film, &reference);
            println!(
                "{case:?} at scale {s}: {:.3}% of pixels darker by 16/255, {:.3}% isolated",
                darker * 100.0,
                isolated * 100.0
            );
            if darker > MAX_LIGHT_ON_SURFACE_DARKER {
                failures.push(format!("{case:?} at scale {s}: {:.3}%", darker * 100.0));
                let dir = failure_dir().join("light-on-surface");
                std::fs::create_dir_all(&dir).unwrap();
                for (film, what) in [(&film, "on"), (&reference, "off")] {
                    let path = dir.join(format!("{case:?}-{s}-{what}.png"));
                    glint::image_io::write_image(film, &path).unwrap();
                }
            }
        }
    }
    assert!(failures.is_empty(), "speckle: {failures:?}");
}

/// POV-Ray is an exact oracle for A4 Phong, and its `smooth_triangle` (mesh2 with
/// `normal_vectors`) interpolates vertex normals as glint does: the smooth torus of
/// scenes/meshes/torus-povray.lua against POV-Ray's render of its twin
/// tools/benches/povray/torus.pov (checked in: tests/golden/povray-torus.png, made by
/// tools/benches/povray/torus-reference.sh), within the corpus bar of RMSE 0.03 (measured
/// 0.0081). The same mesh shaded flat, as glint drew every mesh before, is off by 0.032.
#[test]
fn smooth_torus_matches_povrays_smooth_triangles() {
    use glint::diff::diff_films;
    use glint::scene::Shading;
    let path = common::root().join("scenes/meshes/torus-povray.lua");
    let reference =
        glint::image_io::read_image(&common::root().join("tests/golden/povray-torus.png"))
            .unwrap_or_else(|e| panic!("{e}"));
    let rmse_with = |shading| {
        let overrides = OptionOverrides {
            shading: Some(shading),
            ..OptionOverrides::default()
        };
        let packed = common::load_packed(&path, &overrides);
        let film = common::render_cpu(&packed);
        (
            packed.features,
            diff_films(&film, &reference).unwrap().0.rmse,
        )
    };
    let (features, smooth) = rmse_with(Shading::Smooth);
    let (flat_features, flat) = rmse_with(Shading::Flat);
    eprintln!("torus against POV-Ray: RMSE smooth {smooth:.5}, flat {flat:.5}");
    assert!(features.contains(SceneFeatures::SMOOTH), "[{features}]");
    assert!(
        !flat_features.contains(SceneFeatures::SMOOTH),
        "[{flat_features}]"
    );
    assert!(
        smooth <= 0.03,
        "smooth torus: RMSE {smooth:.5} against POV-Ray"
    );
    assert!(flat > 2.0 * smooth, "flat {flat:.5} vs smooth {smooth:.5}");
}

/// The terminator rule (tracer::shading::smooth::visible_normal) on a coarse smooth sphere (8 × 4
/// quads, so the interpolated normals of its silhouette triangles lean far behind their
/// facets): lit from the eye, no pixel of it is black (an interpolated normal facing away
/// from the viewer would leave its facet unlit); as a mirror (reflectance 0.9, nothing
/// else), every pixel shows the background once reflected or not at all (a normal that
/// reflects the view into the surface shows the mesh's inside, darker by 0.9 per bounce).
/// At scales 10⁻³, 1 and 10³. Both checks fail without the rule.
#[test]
fn smooth_silhouettes_are_neither_black_nor_see_inside() {
    use glint::scene::AaMode;
    let overrides = OptionOverrides {
        aa: Some(AaMode::None),
        width: Some(96),
        height: Some(96),
        ..OptionOverrides::default()
    };
    for scale in [1e-3, 1.0, 1e3] {
        let eye = 4.0 * scale;
        let lit = format!(
            "m = gr.material({{1, 1, 0}}, {{0, 0, 0}}, 1)\nroot = gr.node('root')\n{}\
             gr.render(root, 'x.png', 96, 96, {{0, 0, {eye:e}}}, {{0, 0, -1}}, {{0, 1, 0}}, 40, {{0, 0, 0}}, \
             {{gr.light({{0, 0, {eye:e}}}, {{1, 1, 1}}, {{1, 0, 0}})}}, {{background = {{0, 0, 1}}}})\n",
            common::smooth_sphere_lua("ball", 8, 4, scale, DVec3::ZERO)
        );
        let scene = common::packed_from_source(&lit, &overrides).remove(0);
        assert!(scene.features.contains(SceneFeatures::SMOOTH));
        let film = common::render_cpu(&scene);
        let on_ball: Vec<_> = film.pixels.iter().filter(|p| p[2] < 0.5).collect();
        let black = on_ball.iter().filter(|p| p[0].max(p[1]) <= 0.0).count();
        assert!(
            on_ball.len() > 2000,
            "scale {scale}: {} ball pixels",
            on_ball.len()
        );
        assert_eq!(
            black,
            0,
            "scale {scale}: {black} black pixels of {}",
            on_ball.len()
        );

        let mirror = format!(
            "m = gr.material({{0, 0, 0}}, {{0, 0, 0}}, 1) m:set_reflection(0.9)\nroot = gr.node('root')\n{}\
             gr.render(root, 'x.png', 96, 96, {{0, 0, {eye:e}}}, {{0, 0, -1}}, {{0, 1, 0}}, 40, {{0, 0, 0}}, {{}}, \
             {{background = {{top = {{0, 0, 1}}, bottom = {{0, 1, 0}}}}}})\n",
            common::smooth_sphere_lua("ball", 8, 4, scale, DVec3::ZERO)
        );
        let film = common::render_cpu(&common::packed_from_source(&mirror, &overrides).remove(0));
        let sums: Vec<f32> = film.pixels.iter().map(|p| p[1] + p[2]).collect();
        let reflected = sums.iter().filter(|&&s| (s - 0.9).abs() < 1e-4).count();
        let inside = sums
            .iter()
            .filter(|&&s| (s - 0.9).abs() >= 1e-4 && (s - 1.0).abs() >= 1e-4)
            .count();
        assert!(reflected > 2000, "scale {scale}: {reflected} mirror pixels");
        assert_eq!(
            inside, 0,
            "scale {scale}: {inside} pixels see the mirror's inside"
        );
    }
}

/// `smooth_normal` against an f64 oracle: a triangle with tilted corner normals, placed by
/// a non-uniform scale, two rotations and a translation (once: baked into world space
/// when packed; twice: kept in its own space, the normal through world→object), at scales
/// 10⁻³, 1 and 10³: the corners' unit normals interpolated with the hit's barycentrics and
/// mapped by the inverse transpose, within 10⁻⁶ at 210 points (measured 1.2×10⁻⁷), none of them the flat
/// normal.
#[test]
fn smooth_normals_interpolate_and_transform_at_every_scale() {
    use glint::tracer::shading::smooth::smooth_normal;
    use glint::tracer::shading::surface::surface_at;
    use glint::tracer::traversal::traverse::closest_hit;
    let corners = [DVec3::ZERO, DVec3::X, DVec3::Y];
    let normals = [
        DVec3::new(1.0, -1.0, 1.0),
        DVec3::new(2.0, 0.0, 1.0),
        DVec3::new(0.0, 2.0, 1.0),
    ];
    for scale in [1e-3, 1.0, 1e3] {
        let m = DMat4::from_translation(DVec3::new(3.0, -1.0, 2.0) * scale)
            * DMat4::from_rotation_z(50f64.to_radians())
            * DMat4::from_rotation_x(30f64.to_radians())
            * DMat4::from_scale(DVec3::new(1.0, 2.0, 0.5) * scale);
        let normal_matrix = glam::DMat3::from_mat4(m).inverse().transpose();
        for placements in [1, 2] {
            let mut lua = String::from(
                "m = gr.material({0.5, 0.5, 0.5}, {0, 0, 0}, 1)\nroot = gr.node('root')\n\
                 t = gr.mesh('t', {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}, nil, \
                 {{1, -1, 1}, {2, 0, 1}, {0, 2, 1}})\nt:set_material(m)\n",
            );
            for k in 0..placements {
                let _ = std::fmt::Write::write_fmt(
                    &mut lua,
                    format_args!(
                        "n{k} = gr.node('n{k}') n{k}:scale({s:e}, {d:e}, {h:e}) n{k}:rotate('x', 30) \
                         n{k}:rotate('z', 50) n{k}:translate({x:e}, {y:e}, {z:e}) n{k}:add_child(t) root:add_child(n{k})\n",
                        s = scale,
                        d = 2.0 * scale,
                        h = 0.5 * scale,
                        x = (3.0 + 100.0 * k as f64) * scale,
                        y = -scale,
                        z = 2.0 * scale
                    ),
                );
            }
            lua += "gr.render(root, 'x.png', 8, 8, {0, 0, 10}, {0, 0, -1}, {0, 1, 0}, 40, {0, 0, 0}, {})\n";
            let scene = common::packed_from_source(&lua, &OptionOverrides::default()).remove(0);
            assert!(scene.features.contains(SceneFeatures::SMOOTH));
            let geometric = (normal_matrix * DVec3::Z).normalize();
            let mut worst = 0.0f64;
            for i in 0..20 {
                for j in 0..20 - i {
                    let (b1, b2) = ((i as f64 + 0.3) / 20.0, (j as f64 + 0.3) / 20.0);
                    let local = corners[0] * (1.0 - b1 - b2) + corners[1] * b1 + corners[2] * b2;
                    let p = m.transform_point3(local);
                    let origin = p + geometric * (5.0 * scale);
                    let ray = Ray {
                        origin: origin.as_vec3(),
                        dir: (p - origin).normalize().as_vec3(),
                    };
                    let hit = closest_hit(&scene, &ray, f32::MAX, &mut NoCounters);
                    assert!(
                        hit.is_hit(),
                        "scale {scale}, {placements}: ray {i},{j} missed"
                    );
                    let s = surface_at(&scene, &ray, &hit);
                    let got = smooth_normal(&scene, &hit, &s).as_dvec3();
                    let (h1, h2) = (hit.b1 as f64, hit.b2 as f64);
                    let n_obj = normals[0].normalize() * (1.0 - h1 - h2)
                        + normals[1].normalize() * h1
                        + normals[2].normalize() * h2;
                    let mut expected = (normal_matrix * n_obj).normalize();
                    if expected.dot(s.normal.as_dvec3()) < 0.0 {
                        expected = -expected;
                    }
                    assert!(
                        expected.dot(geometric).abs() < 0.99,
                        "the oracle's normal is the flat one"
                    );
                    worst = worst.max((got - expected).length());
                }
            }
            eprintln!("scale {scale}, {placements} placement(s): worst |Δn| {worst:.2e}");
            assert!(
                worst < 1e-6,
                "scale {scale}, {placements}: |Δn| {worst:.2e}"
            );
        }
    }
}
