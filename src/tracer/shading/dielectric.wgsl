// dielectric.wgsl — dielectrics (set_refraction): Snell refraction, Schlick's reflectance
// with the indices on both sides, total internal reflection, the per-ray medium stack and
// shadow rays that pass through glass. The rules are in src/tracer/shading/dielectric.rs's header;
// the media containing the camera come from the host (globals.camera_media).

// #if REFRACTION
// The media a ray travels in, innermost last. Nesting deeper than MEDIUM_STACK_SIZE is
// counted in count but not recorded (see medium_push).
// Mirror of src/tracer/shading/dielectric.rs::MediumStack — change both.
struct MediumStack {
    iors: array<f32, MEDIUM_STACK_SIZE>,
    count: u32,
}

// Index of the medium a ray travels in: the deepest recorded level, or air.
// Mirror of src/tracer/shading/dielectric.rs::medium_ior — change both.
fn medium_ior(media: MediumStack) -> f32 {
    if media.count == 0u {
        return AIR_IOR;
    }
    var m = media;
    return m.iors[min(m.count, MEDIUM_STACK_SIZE) - 1u];
}

// The stack after entering a medium of index ior. Past MEDIUM_STACK_SIZE levels the push
// is only counted, so the matching pop still lands on the right level.
// Mirror of src/tracer/shading/dielectric.rs::medium_push — change both.
fn medium_push(media: MediumStack, ior: f32) -> MediumStack {
    var m = media;
    if m.count < MEDIUM_STACK_SIZE {
        m.iors[m.count] = ior;
    }
    m.count += 1u;
    return m;
}

// The stack after leaving the innermost medium (air stays air).
// Mirror of src/tracer/shading/dielectric.rs::medium_pop — change both.
fn medium_pop(media: MediumStack) -> MediumStack {
    var m = media;
    if m.count > 0u {
        m.count -= 1u;
    }
    return m;
}

// sin²θt for a ray meeting an interface at cos θi = cos_incident with index ratio eta =
// n1/n2; ≥ 1 means total internal reflection.
// Mirror of src/tracer/shading/dielectric.rs::transmitted_sin2 — change both.
fn transmitted_sin2(cos_incident: f32, eta: f32) -> f32 {
    return eta * eta * max(1.0 - cos_incident * cos_incident, 0.0);
}

// Schlick's approximation of the Fresnel reflectance from index n1 into n2 (cos θt when
// going into a lower index; 1 at total internal reflection; 0 for equal indices).
// Mirror of src/tracer/shading/dielectric.rs::schlick_reflectance — change both.
fn schlick_reflectance(cos_incident: f32, n1: f32, n2: f32) -> f32 {
    if n1 == n2 {
        return 0.0;
    }
    let r = (n1 - n2) / (n1 + n2);
    let r0 = r * r;
    var cos_used = clamp(cos_incident, 0.0, 1.0);
    if n1 > n2 {
        let sin2 = transmitted_sin2(cos_used, n1 / n2);
        if sin2 >= 1.0 {
            return 1.0;
        }
        cos_used = sqrt(1.0 - sin2);
    }
    let k = 1.0 - cos_used;
    let k2 = k * k;
    return r0 + (1.0 - r0) * (k2 * k2 * k);
}

// Normal-incidence transmission 1 − R0 of a surface between indices n1 and n2: the
// factor a shadow ray loses at each dielectric surface it crosses.
// Mirror of src/tracer/shading/dielectric.rs::normal_transmission — change both.
fn normal_transmission(n1: f32, n2: f32) -> f32 {
    return 1.0 - schlick_reflectance(1.0, n1, n2);
}

// What refract_direction returns: valid is false at total internal reflection.
// Mirror of src/tracer/shading/dielectric.rs::refract_direction's Option — change both.
struct Refracted {
    dir: vec3<f32>,
    valid: bool,
}

// Unit direction of dir refracted at a surface with unit normal n facing the incoming ray,
// index ratio eta = n1/n2 (not WGSL's refract(), so that both tracers round alike).
// Mirror of src/tracer/shading/dielectric.rs::refract_direction — change both.
fn refract_direction(dir: vec3<f32>, n: vec3<f32>, eta: f32) -> Refracted {
    let cos_incident = clamp(-dot(n, dir), 0.0, 1.0);
    let sin2 = transmitted_sin2(cos_incident, eta);
    if sin2 >= 1.0 {
        return Refracted(dir, false);
    }
    let cos_transmitted = sqrt(1.0 - sin2);
    return Refracted(normalize(dir * eta + n * (eta * cos_incident - cos_transmitted)), true);
}

// What happens to a ray at a dielectric surface.
// Mirror of src/tracer/shading/dielectric.rs::Interface — change both.
struct Interface {
    // Share of the weight that is reflected (1 at total internal reflection).
    reflectance: f32,
    // Unit direction of the transmitted ray (meaningless when reflectance is 1).
    dir: vec3<f32>,
    // The transmitted ray's medium stack.
    media: MediumStack,
}

// The indices on both sides of a surface of index ior with geometric (outward) normal,
// for a ray in media, and the media beyond it.
// Mirror of src/tracer/shading/dielectric.rs::Sides — change both.
struct Sides {
    // The normal turned to face the incoming ray.
    n: vec3<f32>,
    // Index on the ray's side.
    n1: f32,
    // Index on the far side.
    n2: f32,
    // The media beyond the surface.
    beyond: MediumStack,
}

// Sides of a surface: entering when the ray runs against the outward normal (push the
// material's index), else leaving (pop: the far side is the medium under it).
// Mirror of src/tracer/shading/dielectric.rs::surface_sides — change both.
fn surface_sides(dir: vec3<f32>, normal: vec3<f32>, ior: f32, media: MediumStack) -> Sides {
    if dot(normal, dir) < 0.0 {
        return Sides(normal, medium_ior(media), ior, medium_push(media, ior));
    }
    let popped = medium_pop(media);
    return Sides(-normal, ior, medium_ior(popped), popped);
}

// The interface a ray in media meets at a surface of index ior with geometric (outward)
// normal.
// Mirror of src/tracer/shading/dielectric.rs::dielectric_interface — change both.
fn dielectric_interface(dir: vec3<f32>, normal: vec3<f32>, ior: f32, media: MediumStack) -> Interface {
    let sides = surface_sides(dir, normal, ior, media);
    let cos_incident = clamp(-dot(sides.n, dir), 0.0, 1.0);
    let reflectance = schlick_reflectance(cos_incident, sides.n1, sides.n2);
    let transmitted = refract_direction(dir, sides.n, sides.n1 / sides.n2);
    // refract_direction and schlick_reflectance decide TIR from the same sin²θt.
    return Interface(select(1.0, reflectance, transmitted.valid), transmitted.dir, sides.beyond);
}

// The medium stack of the point being shaded: trace_ray sets it before shade_phong, so
// that shadow rays start in the right medium without a parameter that only scenes with
// refraction would have (the CPU passes it as shade_phong's `media`).
var<private> shading_media: MediumStack;

// How much of a light at position reaches origin, a point in shading_media: 1 when
// nothing is in between, the product of normal_transmission over the dielectric surfaces
// crossed (indices on both sides from the medium stack), 0 when an opaque surface (or more
// than MAX_SHADOW_CROSSINGS dielectric ones) is in between. Each leg stops at
// shadow_reach (magnitude: the shaded surface's), just short of the light.
// Mirror of src/tracer/shading/dielectric.rs::shadow_transmittance — change both.
fn shadow_transmittance(origin: vec3<f32>, position: vec3<f32>, magnitude: f32) -> f32 {
    var leg = ShadowLeg(origin, 1.0, shading_media);
    for (var crossing = 0u; crossing <= MAX_SHADOW_CROSSINGS; crossing++) {
        let leg_ray = shadow_leg_ray(leg, position, magnitude);
        let hit = closest_hit(leg_ray.ray, leg_ray.reach);
        if !is_hit(hit) {
            return leg.transmittance;
        }
        let beyond = cross_shadow_surface(leg_ray.ray, hit, crossing, leg);
        if beyond.blocked {
            return 0.0;
        }
        leg = beyond.leg;
    }
    return 0.0;
}

// A shadow ray's state between the dielectric surfaces it crosses on its way to a light:
// where its next leg starts, the transmittance so far, the media it travels in. Shared by
// shadow_transmittance and the hardware variant's glass shadow rounds, which keep one a
// request between rounds.
// Mirror of src/tracer/shading/dielectric.rs::ShadowLeg — change both.
struct ShadowLeg {
    start: vec3<f32>,
    transmittance: f32,
    media: MediumStack,
}

// A leg's ray toward its light point and how far it looks (shadow_reach): the CPU's
// (Ray, f32).
struct LegRay {
    ray: Ray,
    reach: f32,
}

// What cross_shadow_surface returns: the next leg, or blocked (the CPU's None).
struct Crossed {
    leg: ShadowLeg,
    blocked: bool,
}

// The ray of `leg` toward a light at `position` and how far it looks for a surface
// (shadow_reach; magnitude: the shaded surface's).
// Mirror of src/tracer/shading/dielectric.rs::shadow_leg_ray — change both.
fn shadow_leg_ray(leg: ShadowLeg, position: vec3<f32>, magnitude: f32) -> LegRay {
    let to_light = position - leg.start;
    let distance = length(to_light);
    let ray = Ray(leg.start, to_light / distance);
    return LegRay(ray, shadow_reach(leg.start, position, distance, magnitude));
}

// The shadow ray of `leg` (`ray`) meets a surface at `hit`, its crossing number
// `crossing` (0 for the first surface): the next leg, beyond the surface and dimmed by its
// normal_transmission; blocked where the surface is opaque or the crossing is
// MAX_SHADOW_CROSSINGS.
// Mirror of src/tracer/shading/dielectric.rs::cross_shadow_surface — change both.
fn cross_shadow_surface(ray: Ray, hit: Hit, crossing: u32, leg: ShadowLeg) -> Crossed {
    let s = surface_at(ray, hit);
    let m = load_material(s.material);
    if (m.flags & MATERIAL_REFRACTIVE) == 0u || crossing == MAX_SHADOW_CROSSINGS {
        return Crossed(leg, true);
    }
    let sides = surface_sides(ray.dir, s.normal, m.ior, leg.media);
    let transmittance = leg.transmittance * normal_transmission(sides.n1, sides.n2);
    // Go on from just beyond the surface.
    let start = offset_ray(s.p, -sides.n, s.magnitude);
    return Crossed(ShadowLeg(start, transmittance, sides.beyond), false);
}
// #endif
