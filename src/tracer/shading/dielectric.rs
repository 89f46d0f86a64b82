//! Dielectrics (`set_refraction`): Snell refraction, Schlick's reflectance with the
//! indices on both sides, total internal reflection, the per-ray medium stack, shadow
//! rays that pass through glass, and the media that contain the camera.
//!
//! Rules (docs/scene-language.md, "Glass and water"):
//! - A surface is *entered* when the ray runs against its geometric (outward) normal and
//!   *left* otherwise. Entering pushes the material's index on the ray's medium stack;
//!   leaving pops it. The index beyond an entered surface is the material's; beyond a
//!   left one, the medium under the top of the stack (air, [`AIR_IOR`], when empty).
//! - At a dielectric surface, F (Schlick) of the incoming weight goes to the reflected
//!   ray and 1 − F to the transmitted one; total internal reflection makes F = 1. Equal
//!   indices on both sides are no interface at all: F = 0.
//! - Shadow rays go straight (no caustics): each dielectric surface between a point and
//!   a light multiplies the light by [`normal_transmission`], the normal-incidence
//!   transmission 1 − R0 with the indices on its two sides (tracked from the shaded
//!   point's medium stack as for any ray); an opaque surface blocks.

use super::surface::surface_at;
use crate::constants::{AIR_IOR, MATERIAL_REFRACTIVE, MAX_SHADOW_CROSSINGS, MEDIUM_STACK_SIZE};
use crate::pack::layout::load_material;
use crate::pack::PackedScene;
use crate::tracer::base::ray::{offset_ray, shadow_reach, Ray};
use crate::tracer::traversal::hit::Hit;
use crate::tracer::traversal::traverse::{closest_hit, TraversalCounters};
use glam::Vec3;

/// The media a ray travels in, innermost last. Nesting deeper than [`MEDIUM_STACK_SIZE`]
/// is counted in `count` but not recorded (see [`medium_push`]).
// Mirror of src/tracer/shading/dielectric.wgsl::MediumStack — change both.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MediumStack {
    pub iors: [f32; MEDIUM_STACK_SIZE as usize],
    pub count: u32,
}

/// Index of the medium a ray travels in: the deepest recorded level, or air.
// Mirror of src/tracer/shading/dielectric.wgsl::medium_ior — change both.
pub fn medium_ior(media: &MediumStack) -> f32 {
    if media.count == 0 {
        return AIR_IOR;
    }
    media.iors[(media.count.min(MEDIUM_STACK_SIZE) - 1) as usize]
}

/// The stack after entering a medium of index `ior`. Past [`MEDIUM_STACK_SIZE`] levels
/// the push is only counted, so the matching pop still lands on the right level; a ray
/// between the unrecorded levels sees the deepest recorded index.
// Mirror of src/tracer/shading/dielectric.wgsl::medium_push — change both.
pub fn medium_push(media: &MediumStack, ior: f32) -> MediumStack {
    let mut m = *media;
    if m.count < MEDIUM_STACK_SIZE {
        m.iors[m.count as usize] = ior;
    }
    m.count += 1;
    m
}

/// The stack after leaving the innermost medium (air stays air).
// Mirror of src/tracer/shading/dielectric.wgsl::medium_pop — change both.
pub fn medium_pop(media: &MediumStack) -> MediumStack {
    let mut m = *media;
    if m.count > 0 {
        m.count -= 1;
    }
    m
}

/// sin²θt for a ray meeting an interface at cos θi = `cos_incident` with index ratio
/// `eta` = n1/n2 (Snell: sin θt = eta·sin θi); ≥ 1 means total internal reflection.
// Mirror of src/tracer/shading/dielectric.wgsl::transmitted_sin2 — change both.
pub fn transmitted_sin2(cos_incident: f32, eta: f32) -> f32 {
    eta * eta * (1.0 - cos_incident * cos_incident).max(0.0)
}

/// Schlick's approximation of the Fresnel reflectance from index n1 into n2, with R0 =
/// ((n1 − n2)/(n1 + n2))². Going into a lower index it uses cos θt rather than cos θi,
/// which keeps it reciprocal and makes it 1 at total internal reflection. Equal indices
/// reflect nothing.
// Mirror of src/tracer/shading/dielectric.wgsl::schlick_reflectance — change both.
pub fn schlick_reflectance(cos_incident: f32, n1: f32, n2: f32) -> f32 {
    if n1 == n2 {
        return 0.0;
    }
    let r = (n1 - n2) / (n1 + n2);
    let r0 = r * r;
    let mut cos_used = cos_incident.clamp(0.0, 1.0);
    if n1 > n2 {
        let sin2 = transmitted_sin2(cos_used, n1 / n2);
        if sin2 >= 1.0 {
            return 1.0;
        }
        cos_used = (1.0 - sin2).sqrt();
    }
    let k = 1.0 - cos_used;
    let k2 = k * k;
    r0 + (1.0 - r0) * (k2 * k2 * k)
}

/// Normal-incidence transmission 1 − R0 of a surface between indices n1 and n2: the
/// factor a shadow ray loses at each dielectric surface it crosses.
// Mirror of src/tracer/shading/dielectric.wgsl::normal_transmission — change both.
pub fn normal_transmission(n1: f32, n2: f32) -> f32 {
    1.0 - schlick_reflectance(1.0, n1, n2)
}

/// Unit direction of `dir` refracted at a surface with unit normal `n` facing the incoming
/// ray (n·dir ≤ 0), index ratio `eta` = n1/n2; None at total internal reflection.
// Mirror of src/tracer/shading/dielectric.wgsl::refract_direction — change both.
pub fn refract_direction(dir: Vec3, n: Vec3, eta: f32) -> Option<Vec3> {
    let cos_incident = (-n.dot(dir)).clamp(0.0, 1.0);
    let sin2 = transmitted_sin2(cos_incident, eta);
    if sin2 >= 1.0 {
        return None;
    }
    let cos_transmitted = (1.0 - sin2).sqrt();
    Some((dir * eta + n * (eta * cos_incident - cos_transmitted)).normalize())
}

/// What happens to a ray at a dielectric surface.
// Mirror of src/tracer/shading/dielectric.wgsl::Interface — change both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interface {
    /// Share of the weight that is reflected (1 at total internal reflection).
    pub reflectance: f32,
    /// Unit direction of the transmitted ray (meaningless when `reflectance` is 1).
    pub dir: Vec3,
    /// The transmitted ray's medium stack.
    pub media: MediumStack,
}

/// The indices on both sides of a surface of index `ior` with geometric (outward)
/// normal `normal`, for a ray in `media`, and the media beyond it.
// Mirror of src/tracer/shading/dielectric.wgsl::Sides — change both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sides {
    /// The normal turned to face the incoming ray.
    pub n: Vec3,
    /// Index on the ray's side.
    pub n1: f32,
    /// Index on the far side.
    pub n2: f32,
    /// The media beyond the surface.
    pub beyond: MediumStack,
}

/// [`Sides`] of a surface: entering when the ray runs against the outward normal
/// (push the material's index), else leaving (pop: the far side is the medium under it).
// Mirror of src/tracer/shading/dielectric.wgsl::surface_sides — change both.
pub fn surface_sides(dir: Vec3, normal: Vec3, ior: f32, media: &MediumStack) -> Sides {
    if normal.dot(dir) < 0.0 {
        return Sides {
            n: normal,
            n1: medium_ior(media),
            n2: ior,
            beyond: medium_push(media, ior),
        };
    }
    let popped = medium_pop(media);
    Sides {
        n: -normal,
        n1: ior,
        n2: medium_ior(&popped),
        beyond: popped,
    }
}

/// The interface a ray in `media` meets at a surface of index `ior` with geometric
/// (outward) normal `normal`.
// Mirror of src/tracer/shading/dielectric.wgsl::dielectric_interface — change both.
pub fn dielectric_interface(dir: Vec3, normal: Vec3, ior: f32, media: &MediumStack) -> Interface {
    let sides = surface_sides(dir, normal, ior, media);
    let cos_incident = (-sides.n.dot(dir)).clamp(0.0, 1.0);
    let reflectance = schlick_reflectance(cos_incident, sides.n1, sides.n2);
    let transmitted = refract_direction(dir, sides.n, sides.n1 / sides.n2);
    Interface {
        // refract_direction and schlick_reflectance decide TIR from the same sin²θt.
        reflectance: if transmitted.is_some() {
            reflectance
        } else {
            1.0
        },
        dir: transmitted.unwrap_or(dir),
        media: sides.beyond,
    }
}

/// How much of a light at `position` reaches `origin`, a point in `media`: 1 when
/// nothing is in between, the product of [`normal_transmission`] over the dielectric
/// surfaces crossed (indices on both sides from the medium stack, as for camera rays),
/// 0 when an opaque surface (or more than [`MAX_SHADOW_CROSSINGS`] dielectric ones) is
/// in between. Each leg stops at [`shadow_reach`] (`magnitude`: the shaded surface's),
/// just short of the light, so a surface through the light does not speckle. Only scenes
/// with refraction use this; the others keep `any_hit`.
// Mirror of src/tracer/shading/dielectric.wgsl::shadow_transmittance — change both.
pub fn shadow_transmittance(
    scene: &PackedScene,
    origin: Vec3,
    position: Vec3,
    magnitude: f32,
    media: &MediumStack,
    counters: &mut impl TraversalCounters,
) -> f32 {
    let mut leg = ShadowLeg {
        start: origin,
        transmittance: 1.0,
        media: *media,
    };
    for crossing in 0..=MAX_SHADOW_CROSSINGS {
        let (ray, reach) = shadow_leg_ray(&leg, position, magnitude);
        let hit = closest_hit(scene, &ray, reach, counters);
        if !hit.is_hit() {
            return leg.transmittance;
        }
        match cross_shadow_surface(scene, &ray, &hit, crossing, &leg) {
            Some(next) => leg = next,
            None => return 0.0,
        }
    }
    0.0
}

/// A shadow ray's state between the dielectric surfaces it crosses on its way to a light:
/// where its next leg starts, the transmittance so far, the media it travels in. Shared
/// by [`shadow_transmittance`] and the wavefront's glass shadow rounds
/// (`tracer::wavefront::wavefront_tree`), which keep one a request between rounds.
// Mirror of src/tracer/shading/dielectric.wgsl::ShadowLeg — change both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ShadowLeg {
    pub(crate) start: Vec3,
    pub(crate) transmittance: f32,
    pub(crate) media: MediumStack,
}

/// The ray of `leg` toward a light at `position` and how far it looks for a surface
/// ([`shadow_reach`]; `magnitude`: the shaded surface's).
// Mirror of src/tracer/shading/dielectric.wgsl::shadow_leg_ray — change both.
pub(crate) fn shadow_leg_ray(leg: &ShadowLeg, position: Vec3, magnitude: f32) -> (Ray, f32) {
    let to_light = position - leg.start;
    let distance = to_light.length();
    let ray = Ray {
        origin: leg.start,
        dir: to_light / distance,
    };
    (ray, shadow_reach(leg.start, position, distance, magnitude))
}

/// The shadow ray of `leg` (`ray`) meets a surface at `hit`, its crossing number
/// `crossing` (0 for the first surface): the next leg, beyond the surface and dimmed by
/// its [`normal_transmission`]; None where the surface blocks (opaque, or one crossing
/// more than [`MAX_SHADOW_CROSSINGS`]).
// Mirror of src/tracer/shading/dielectric.wgsl::cross_shadow_surface — change both.
pub(crate) fn cross_shadow_surface(
    scene: &PackedScene,
    ray: &Ray,
    hit: &Hit,
    crossing: u32,
    leg: &ShadowLeg,
) -> Option<ShadowLeg> {
    let s = surface_at(scene, ray, hit);
    let m = load_material(scene, s.material);
    if m.flags & MATERIAL_REFRACTIVE == 0 || crossing == MAX_SHADOW_CROSSINGS {
        return None;
    }
    let sides = surface_sides(ray.dir, s.normal, m.ior, &leg.media);
    Some(ShadowLeg {
        transmittance: leg.transmittance * normal_transmission(sides.n1, sides.n2),
        media: sides.beyond,
        // Go on from just beyond the surface.
        start: offset_ray(s.p, -sides.n, s.magnitude),
    })
}
