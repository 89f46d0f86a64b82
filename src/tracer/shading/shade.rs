//! A4 Phong shading with shadow rays, and the background (or the environment map).

use super::dielectric::{shadow_transmittance, MediumStack};
use super::environment::environment;
use super::surface::{Phong, Surface};
use super::texture::surface_colours;
use crate::constants::LIGHT_AREA;
use crate::pack::layout::{load_light, load_material};
use crate::pack::{PackedLight, PackedScene, SceneFeatures};
use crate::tracer::base::ray::{offset_ray, shadow_reach, Ray};
use crate::tracer::base::rng::{shadow_random, shadow_stream, SampleSeed, ShadowStream};
use crate::tracer::traversal::traverse::{any_hit, TraversalCounters};
use glam::Vec3;

/// `base^exponent` for base in [0, 1] without NaN or overflow for any exponent ≥ 0
/// (shininess can be 5e7): zero unless base > 0.
// Mirror of src/tracer/shading/shade.wgsl::phong_power — change both.
pub fn phong_power(base: f32, exponent: f32) -> f32 {
    if base > 0.0 {
        (exponent * base.min(1.0).log2()).exp2()
    } else {
        0.0
    }
}

/// A shaded point as its lights see it: the surface, its Phong colours, the normal facing
/// the viewer and the direction to the viewer (what each light point's term reads).
// Mirror of src/tracer/shading/shade.wgsl::LitPoint — change both.
#[derive(Clone, Copy, Debug)]
pub(crate) struct LitPoint {
    pub(crate) s: Surface,
    /// The Phong colours at `s` ([`phong_at`]).
    pub(crate) phong: Phong,
    /// The shading normal, facing the viewer.
    pub(crate) n: Vec3,
    /// The direction to the viewer.
    pub(crate) v: Vec3,
}

/// A4 lighting at a surface point: kd·ambient plus, for each light a shadow ray reaches,
/// (kd·max(0,N·L) + ks·max(0,R·V)^shininess)·I/(c0 + c1·d + c2·d²). `n` faces the viewer;
/// `v` points to the viewer. An area light is n×n such point lights, one jittered point
/// per stratum of its parallelogram (random numbers from `seed`), each with 1/n² of its
/// colour. `media` are the media around the point (shadow rays through glass start
/// there; the WGSL twin reads them from `shading_media`).
// Mirror of src/tracer/shading/shade.wgsl::shade_phong — change both.
#[allow(clippy::too_many_arguments)]
pub fn shade_phong(
    scene: &PackedScene,
    s: &Surface,
    n: Vec3,
    v: Vec3,
    media: &MediumStack,
    seed: SampleSeed,
    counters: &mut impl TraversalCounters,
) -> Vec3 {
    let phong = phong_at(scene, s);
    let lit = LitPoint { s: *s, phong, n, v };
    let mut colour = ambient_term(scene, phong);
    let origin = offset_ray(s.p, n, s.magnitude);
    for index in 0..scene.globals.num_lights as usize {
        let light = load_light(scene, index as u32);
        if light.kind == LIGHT_AREA {
            let index = index as u32;
            colour += area_light(scene, &lit, origin, media, light, index, seed, counters);
        } else {
            let position = Vec3::from(light.position);
            colour += point_light(scene, &lit, origin, media, position, light, counters);
        }
    }
    colour
}

/// The Phong colours at `s`: its material's, or (in scenes with textures) its textures'
/// at the UV. Shared by [`shade_phong`] and the wavefront's shading pass
/// (`tracer::wavefront::wavefront_shade`), so the two cannot drift apart.
pub(crate) fn phong_at(scene: &PackedScene, s: &Surface) -> Phong {
    let m = load_material(scene, s.material);
    let mut phong = Phong {
        kd: Vec3::from(m.kd),
        ks: Vec3::from(m.ks),
    };
    if scene.features.contains(SceneFeatures::TEXTURE) {
        phong = surface_colours(scene, m, s);
    }
    phong
}

/// The ambient term kd·ambient a shaded point starts from.
pub(crate) fn ambient_term(scene: &PackedScene, phong: Phong) -> Vec3 {
    phong.kd * Vec3::from(scene.globals.ambient)
}

/// Light from a point at `position` with `light`'s colour and falloff: the A4 term, or
/// zero when the point is behind the surface or a shadow ray from `origin` is blocked
/// (dimmed instead by the glass it crosses, in scenes with refraction) before
/// [`shadow_reach`], just short of the light.
// Mirror of src/tracer/shading/shade.wgsl::point_light — change both.
fn point_light(
    scene: &PackedScene,
    lit: &LitPoint,
    origin: Vec3,
    media: &MediumStack,
    position: Vec3,
    light: &PackedLight,
    counters: &mut impl TraversalCounters,
) -> Vec3 {
    // Lights behind the surface (as seen from the viewer's side) add nothing.
    let Some(term) = unshadowed_term(scene, lit, position, light) else {
        return Vec3::ZERO;
    };
    let s = &lit.s;
    // With dielectrics, light passes through glass, dimmed (see dielectric.rs).
    let transmittance = if scene.features.contains(SceneFeatures::REFRACTION) {
        shadow_transmittance(scene, origin, position, s.magnitude, media, counters)
    } else if shadow_blocked(scene, origin, position, s.magnitude, counters) {
        0.0
    } else {
        1.0
    };
    shadowed_term(term, transmittance)
}

/// [`point_light`]'s A4 term before its shadow ray, (kd·N·L + ks·spec)·I·attenuation,
/// or None where the light point is behind the surface (N·L ≤ 0 or NaN: no shadow ray
/// is asked for and the light adds zero). The wavefront's shading pass
/// (`tracer::wavefront::wavefront_shade`) computes the same term and leaves the shadow ray to its own pass;
/// the products are those of `point_light`'s one expression, left to right, so
/// [`shadowed_term`] finishes them with the same bits.
// Mirror of src/tracer/shading/shade.wgsl::unshadowed_term — change both.
pub(crate) fn unshadowed_term(
    scene: &PackedScene,
    lit: &LitPoint,
    position: Vec3,
    light: &PackedLight,
) -> Option<Vec3> {
    let &LitPoint { s, phong, n, v } = lit;
    let m = load_material(scene, s.material);
    let to_light = position - s.p;
    let distance = to_light.length();
    let l = to_light / distance;
    let n_dot_l = n.dot(l);
    if n_dot_l.is_nan() || n_dot_l <= 0.0 {
        return None;
    }
    let r = n * (2.0 * n_dot_l) - l;
    let specular = phong_power(r.dot(v), m.shininess);
    let [c0, c1, c2] = light.falloff;
    let attenuation = 1.0 / (c0 + distance * (c1 + distance * c2));
    Some((phong.kd * n_dot_l + phong.ks * specular) * Vec3::from(light.colour) * attenuation)
}

/// A light point's term once its shadow ray is traced: zero where nothing gets through
/// (`transmittance` ≤ 0: a blocked ray), else `term` × `transmittance` (1 without
/// glass: the same bits as `term`, −0.0 and NaN included, since x·1 = x in IEEE 754).
// Mirror of src/tracer/shading/shade.wgsl::shadowed_term — change both.
pub(crate) fn shadowed_term(term: Vec3, transmittance: f32) -> Vec3 {
    if transmittance <= 0.0 {
        return Vec3::ZERO;
    }
    term * transmittance
}

/// Whether anything blocks the shadow ray from `origin` to a light at `position` before
/// [`shadow_reach`] (`magnitude`: the shaded surface's), just short of the light, so that
/// a surface through the light does not speckle.
// Mirror of src/tracer/shading/shade.wgsl::shadow_blocked — change both.
pub fn shadow_blocked(
    scene: &PackedScene,
    origin: Vec3,
    position: Vec3,
    magnitude: f32,
    counters: &mut impl TraversalCounters,
) -> bool {
    let shadow_dir = position - origin;
    let shadow_distance = shadow_dir.length();
    let shadow_ray = Ray {
        origin,
        dir: shadow_dir / shadow_distance,
    };
    let reach = shadow_reach(origin, position, shadow_distance, magnitude);
    any_hit(scene, &shadow_ray, reach, counters)
}

/// Light from area light number `index`: the mean of [`point_light`] over one jittered
/// point in each of the n×n strata of its parallelogram, stratum k = (k mod n, k div n);
/// when some of those points light it and others do not (a penumbra) at the first hit of
/// a camera ray (`seed.depth` 0), it tells `counters`
/// ([`TraversalCounters::partial_light`]). Deeper hits do not count: seen in a mirror or
/// through glass, a penumbra's noise is dimmed by the reflectance, and counting them there
/// split the whole of scrabble's tumbler (2.5× its 1280×720 render time).
// Mirror of src/tracer/shading/shade.wgsl::area_light — change both.
#[allow(clippy::too_many_arguments)]
fn area_light(
    scene: &PackedScene,
    lit: &LitPoint,
    origin: Vec3,
    media: &MediumStack,
    light: &PackedLight,
    index: u32,
    seed: SampleSeed,
    counters: &mut impl TraversalCounters,
) -> Vec3 {
    let k = light.samples;
    let mut sum = Vec3::ZERO;
    let mut lit_strata = 0;
    let stream = shadow_stream(seed, index);
    for stratum in 0..k * k {
        let position = area_light_point(light, &stream, stratum);
        let c = point_light(scene, lit, origin, media, position, light, counters);
        add_stratum(&mut sum, &mut lit_strata, c);
    }
    if penumbra(seed.depth, lit_strata, k) {
        counters.partial_light();
    }
    area_light_mean(sum, k)
}

/// The jittered point of stratum `stratum` (= (stratum mod n, stratum div n)) of area
/// light `light`'s n×n strata, from `stream` ([`shadow_stream`]).
pub(crate) fn area_light_point(light: &PackedLight, stream: &ShadowStream, stratum: u32) -> Vec3 {
    let k = light.samples;
    let scale = 1.0 / k as f32;
    let (centre, u, w) = (
        Vec3::from(light.position),
        Vec3::from(light.edge_u),
        Vec3::from(light.edge_v),
    );
    let a = ((stratum % k) as f32 + shadow_random(stream, stratum, 0)) * scale - 0.5;
    let b = ((stratum / k) as f32 + shadow_random(stream, stratum, 1)) * scale - 0.5;
    centre + u * a + w * b
}

/// Adds stratum term `c` to an area light's running `sum`, counting it in `lit` where it
/// is not zero (NaN counts: NaN ≠ 0).
pub(crate) fn add_stratum(sum: &mut Vec3, lit: &mut u32, c: Vec3) {
    *lit += (c != Vec3::ZERO) as u32;
    *sum += c;
}

/// Whether `lit` of an n×n area light's strata (n = `k`) lighting a point at depth
/// `depth` is a penumbra adaptive AA splits around: some strata but not all, at a camera
/// ray's first hit only (see [`area_light`]).
pub(crate) fn penumbra(depth: u32, lit: u32, k: u32) -> bool {
    depth == 0 && lit > 0 && lit < k * k
}

/// An n×n area light's strata `sum` (n = `k`) as its mean: × (1/n)², 1/n rounded first.
pub(crate) fn area_light_mean(sum: Vec3, k: u32) -> Vec3 {
    let scale = 1.0 / k as f32;
    sum * (scale * scale)
}

/// Colour of a ray that hits nothing: the environment map where the scene has one
/// (`SceneFeatures::ENVIRONMENT`), else the vertical gradient by direction (solid when
/// top = bottom), "up" being the camera's up.
// Mirror of src/tracer/shading/shade.wgsl::background — change both.
pub fn background(scene: &PackedScene, dir: Vec3) -> Vec3 {
    let g = &scene.globals;
    if scene.features.contains(SceneFeatures::ENVIRONMENT) {
        return environment(&scene.texels, g, dir);
    }
    let t = 0.5 * (dir.dot(Vec3::from(g.up)) + 1.0);
    Vec3::from(g.background_bottom) * (1.0 - t) + Vec3::from(g.background_top) * t
}
