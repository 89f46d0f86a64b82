//! HDR environment maps against Mitsuba 3 (references checked in with their script,
//! tools/oracle/environment.py; CI does not install Mitsuba): a mirror sphere and a glass
//! sphere in a procedural HDR sky turned 30° about +y, 48×48, box filter, rendered by
//! Mitsuba's `path` integrator with an `envmap` emitter (only specular surfaces: Whitted's
//! light transport) and by glint with uniform 8×8 AA. The mirror (a `conductor` of
//! material 'none') must agree to rmse 0.01 linear: an error in the map's orientation,
//! rotation, texel centres or filtering is far above it. The glass differs by Schlick's
//! Fresnel (glint) against the exact dielectric one (Mitsuba) and is held to 0.03.

use crate::common;

use common::{packed_from_file, render_cpu, root, temp_dir};
use glint::film::Film;
use glint::scene::OptionOverrides;

/// The folder of the references and the sky they were rendered in.
const REFS: &str = "tests/oracle/refs/environment";

/// glint's render of the reference scene with the sphere's material `material`.
fn render(material: &str) -> Film {
    let dir = temp_dir("oracle-environment");
    std::fs::copy(root().join(REFS).join("sky.exr"), dir.join("sky.exr")).unwrap();
    let source = format!(
        "m = gr.material({{0,0,0}}, {{0,0,0}}, 1) {material}
         root = gr.node('root')
         s = gr.sphere('s') s:set_material(m) root:add_child(s)
         gr.render(root, 'o.exr', 48, 48, {{0, 0.6, 4}}, {{0, -0.6, -4}}, {{0, 1, 0}}, 40,
                   {{0, 0, 0}}, {{}}, {{aa = 'uniform', samples = 8, max_depth = 16,
                   min_weight = 0, environment = 'sky.exr', environment_rotation = 30}})"
    );
    let path = dir.join("sphere.lua");
    std::fs::write(&path, source).unwrap();
    render_cpu(&packed_from_file(&path, &OptionOverrides::default()).remove(0))
}

/// Root mean square of the difference over every channel of every pixel (linear).
fn rmse(a: &Film, b: &Film) -> f64 {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let sum: f64 = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .flat_map(|(p, q)| p.iter().zip(q).map(|(x, y)| f64::from(x - y).powi(2)))
        .sum();
    (sum / (3 * a.pixels.len()) as f64).sqrt()
}

fn reference(name: &str) -> Film {
    glint::image_io::read_image(&root().join(REFS).join(format!("{name}.exr"))).unwrap()
}

#[test]
fn mirror_sphere_in_an_environment_matches_mitsuba() {
    let error = rmse(&render("m:set_reflection(1)"), &reference("mirror"));
    eprintln!("mirror sphere: rmse {error:.5} against Mitsuba 3");
    assert!(error <= 0.01, "rmse {error}");
}

#[test]
fn glass_sphere_in_an_environment_matches_mitsuba_to_schlicks_error() {
    let error = rmse(&render("m:set_refraction(1.5)"), &reference("glass"));
    eprintln!("glass sphere: rmse {error:.5} against Mitsuba 3 (Schlick against exact Fresnel)");
    assert!(error <= 0.03, "rmse {error}");
}
