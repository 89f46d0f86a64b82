//! Whitted tracing without recursion: an explicit, fixed-size stack of secondary rays,
//! each with the weight of its contribution to the pixel, its depth, its cone (the
//! pixel's footprint, for texture filtering: see `texture`) and the media it travels in
//! (see `dielectric`).

use crate::constants::{
    AA_ADAPTIVE, AA_TEXTURE_DETAIL_SHARE, DEBUG_VIEW_UV, MATERIAL_REFLECTIVE, MATERIAL_REFRACTIVE,
    RAY_STACK_SIZE, T_MISS,
};
use crate::pack::layout::load_material;
use crate::pack::{PackedGlobals, PackedScene, SceneFeatures};
use crate::tracer::base::ray::{offset_ray, Ray};
use crate::tracer::base::rng::SampleSeed;
use crate::tracer::shading::dielectric::{dielectric_interface, MediumStack};
use crate::tracer::shading::shade::{background, shade_phong};
use crate::tracer::shading::smooth::{smooth_interface, smooth_normal, visible_normal};
use crate::tracer::shading::surface::{surface_at, Surface};
use crate::tracer::shading::texture::{
    camera_cone, cone_at, shading_normal, texture_detail, with_footprint,
};
use crate::tracer::traversal::hit::Hit;
use crate::tracer::traversal::traverse::{closest_hit, TraversalCounters};
use glam::{Vec2, Vec3};

// Mirror of src/tracer/path/trace.wgsl::StackEntry — change both.
#[derive(Clone, Copy, Debug)]
pub(crate) struct StackEntry {
    pub(crate) ray: Ray,
    pub(crate) weight: Vec3,
    pub(crate) depth: u32,
    /// The ray's cone for texture filtering: width at its origin, spread per unit length
    /// (`texture::camera_cone`; the WGSL twin has the field only with textures or bump
    /// maps).
    pub(crate) cone: Vec2,
    /// The media the ray travels in (only scenes with refraction change it; the WGSL
    /// twin has the field only then).
    pub(crate) media: MediumStack,
}

/// The stack entry of camera ray `primary`: weight 1, depth 0, the camera's cone and the
/// media around the camera. Every form starts its camera samples with it: `trace_ray`
/// here, the GPU's wavefront camera passes too.
// Mirror of src/tracer/path/trace.wgsl::camera_entry — change both.
pub(crate) fn camera_entry(g: &PackedGlobals, primary: &Ray) -> StackEntry {
    StackEntry {
        ray: *primary,
        weight: Vec3::ONE,
        depth: 0,
        cone: camera_cone(g, primary),
        media: camera_medium_stack(g),
    }
}

/// Colour seen along a primary ray, mirrors and dielectrics included (down to
/// `max_depth` bounces or `min_weight` contribution). A dielectric pushes its transmitted
/// ray, (1 − F) of the weight, then the reflected ray, whose weight is the mirror colour
/// plus F (one ray: both go the same way); Phong shading is added as for any material.
/// `seed` names the camera sample (its `depth` is ignored: each shading point gets its
/// own ray's depth). The camera ray's hit is traced and shaded before the loop over
/// secondary rays, which only rays it spawns enter: the GPU twin has that shape without
/// dielectrics in its software variant (on llvmpipe a loop around the first hit costs
/// 20–25% of the render even when it runs once, docs/journal/2026-11-30-one-hit-no-loop.md).
/// With dielectrics, and with mirrors in its hardware variant (`CAMERA_RAY_IN_LOOP`: one
/// inlined traversal instead of two, docs/journal/2026-12-02-one-traversal-in-mirror-scenes.md),
/// the camera ray is the twin's loop's first entry, whose first turn takes these steps in
/// this order (its depth-0 checks standing for the hints set here, and 0 + 1 × colour
/// being colour); so there is one CPU form, and both tracers take the same steps in the
/// same order (the twins test compares the CPU with both GPU forms).
// Mirror of src/tracer/path/trace.wgsl::trace_ray — change both.
pub fn trace_ray(
    scene: &PackedScene,
    primary: Ray,
    seed: SampleSeed,
    counters: &mut impl TraversalCounters,
) -> Vec3 {
    let g = &scene.globals;
    let first = camera_entry(g, &primary);
    let first_hit = closest_hit(scene, &primary, T_MISS, counters);
    counters.camera_hit(first_hit.item);
    if !first_hit.is_hit() {
        return background(scene, primary.dir);
    }
    let first_shaded = shade_hit(scene, &first, &first_hit, seed, counters);
    note_texture_detail(scene, &first_shaded.s, counters);
    let camera_mirror = is_mirror(scene, first_shaded.s.material);
    // The GPU's hardware variant keeps the dielectric stack's entries in a storage slot
    // per ray (src/gpu/compile/lists.rs; store_pending, load_pending): the same entries in the
    // same order, so the same steps.
    let mut stack = [first; RAY_STACK_SIZE as usize];
    let mut size = 0;
    let mut colour = first_shaded.colour;
    if !first_shaded.ends {
        push_secondary_rays(
            scene,
            &mut stack,
            &mut size,
            &first,
            &first_shaded,
            &first_hit,
        );
    }
    while size > 0 {
        size -= 1;
        let entry = stack[size];
        let hit = closest_hit(scene, &entry.ray, T_MISS, counters);
        if camera_mirror && entry.depth == 1 {
            // The one ray a mirror spawns: what the camera sees in it.
            counters.mirror_hit(hit.item);
        }
        if !hit.is_hit() {
            colour += entry.weight * background(scene, entry.ray.dir);
            continue;
        }
        let shaded = shade_hit(scene, &entry, &hit, seed, counters);
        colour += entry.weight * shaded.colour;
        if !shaded.ends {
            push_secondary_rays(scene, &mut stack, &mut size, &entry, &shaded, &hit);
        }
    }
    colour
}

/// Whether material `material` is a mirror to adaptive AA's item keys
/// (`pixel_sample::sample_item_key`): reflective and not a dielectric, so its camera hit
/// spawns one ray. (Keying a dielectric's rays too split nearly every sample behind glass,
/// whose paths part ways everywhere: docs/journal/2026-11-30-item-edges-split.md.)
// Mirror of src/tracer/path/trace.wgsl::is_mirror — change both.
pub(crate) fn is_mirror(scene: &PackedScene, material: u32) -> bool {
    let flags = load_material(scene, material).flags;
    flags & MATERIAL_REFLECTIVE != 0 && flags & MATERIAL_REFRACTIVE == 0
}

/// Tells `counters` (adaptive AA's hints) that the camera ray's first hit `s` shows
/// texture detail at the pixel's scale: [`texture_detail`] above AA_TEXTURE_DETAIL_SHARE
/// of `aa_threshold`. Only adaptive AA reads the hint, so only it pays the lookups.
// Mirror of src/tracer/path/trace.wgsl::note_texture_detail — change both.
pub(crate) fn note_texture_detail(
    scene: &PackedScene,
    s: &Surface,
    counters: &mut impl TraversalCounters,
) {
    let g = &scene.globals;
    if g.aa_mode != AA_ADAPTIVE || !scene.features.contains(SceneFeatures::TEXTURE) {
        return;
    }
    if texture_detail(scene, s) > AA_TEXTURE_DETAIL_SHARE * g.aa_threshold {
        counters.texture_detail();
    }
}

/// Pushes the rays that the shaded hit of `entry`'s ray spawns onto `stack` (which holds
/// `size` entries): with refraction the transmitted ray, then the reflected ray, each
/// while the depth, its weight and the stack allow.
// Mirror of src/tracer/path/trace.wgsl::push_secondary_rays — change both.
pub(crate) fn push_secondary_rays(
    scene: &PackedScene,
    stack: &mut [StackEntry; RAY_STACK_SIZE as usize],
    size: &mut usize,
    entry: &StackEntry,
    shaded: &ShadedHit,
    hit: &Hit,
) {
    let g = &scene.globals;
    let ray = entry.ray;
    let ShadedHit { s, facing, n, .. } = *shaded;
    let cone = cone_at(entry.cone, hit.t);
    let m = load_material(scene, s.material);
    let mut reflectance = if m.flags & MATERIAL_REFLECTIVE != 0 {
        Vec3::from(m.reflection)
    } else {
        Vec3::ZERO
    };
    if scene.features.contains(SceneFeatures::REFRACTION)
        && m.flags & MATERIAL_REFRACTIVE != 0
        && entry.depth < g.max_depth
    {
        let crossing = if scene.features.contains(SceneFeatures::SMOOTH) {
            let shading = smooth_normal(scene, hit, &s);
            smooth_interface(ray.dir, s.normal, shading, m.ior, &entry.media)
        } else {
            dielectric_interface(ray.dir, s.normal, m.ior, &entry.media)
        };
        reflectance += Vec3::splat(crossing.reflectance);
        let weight = entry.weight * (1.0 - crossing.reflectance);
        if weight.max_element() >= g.min_weight && *size < RAY_STACK_SIZE as usize {
            // The transmitted ray starts on the far side of the surface.
            stack[*size] = StackEntry {
                ray: Ray {
                    origin: offset_ray(s.p, -facing, s.magnitude),
                    dir: crossing.dir,
                },
                weight,
                depth: entry.depth + 1,
                cone,
                media: crossing.media,
            };
            *size += 1;
        }
    }
    if reflectance.max_element() > 0.0 && entry.depth < g.max_depth {
        let weight = entry.weight * reflectance;
        if weight.max_element() >= g.min_weight && *size < RAY_STACK_SIZE as usize {
            let dir = ray.dir - n * (2.0 * ray.dir.dot(n));
            // A reflected ray stays in the medium it came from.
            stack[*size] = StackEntry {
                ray: Ray {
                    origin: offset_ray(s.p, facing, s.magnitude),
                    dir: dir.normalize(),
                },
                weight,
                depth: entry.depth + 1,
                cone,
                ..*entry
            };
            *size += 1;
        }
    }
}

/// A ray's hit as `trace_ray` uses it: the shading point (with its texture
/// footprint), the normal facing the ray and the shading normal (interpolated on smooth
/// meshes, bumped, kept visible: `smooth`), and the colour
/// the point gives by itself — Phong shading, or the UV debug view, which `ends` the ray.
// Mirror of src/tracer/path/trace.wgsl::ShadedHit — change both.
pub(crate) struct ShadedHit {
    pub(crate) s: Surface,
    pub(crate) facing: Vec3,
    pub(crate) n: Vec3,
    pub(crate) colour: Vec3,
    pub(crate) ends: bool,
}

/// The hit of the ray of `entry`, shaded (see [`ShadedHit`]).
// Mirror of src/tracer/path/trace.wgsl::shade_hit — change both.
fn shade_hit(
    scene: &PackedScene,
    entry: &StackEntry,
    hit: &Hit,
    seed: SampleSeed,
    counters: &mut impl TraversalCounters,
) -> ShadedHit {
    let point = shading_point(scene, entry, hit);
    if let Some(colour) = point.uv_colour {
        let ShadingPoint { s, facing, n, .. } = point;
        return ShadedHit {
            s,
            facing,
            n,
            colour,
            ends: true,
        };
    }
    let ShadingPoint { s, facing, n, .. } = point;
    let shade_seed = SampleSeed {
        depth: entry.depth,
        ..seed
    };
    let colour = shade_phong(
        scene,
        &s,
        n,
        -entry.ray.dir,
        &entry.media,
        shade_seed,
        counters,
    );
    ShadedHit {
        s,
        facing,
        n,
        colour,
        ends: false,
    }
}

/// A hit as shading sees it before any light: the surface (with its texture footprint),
/// the normal facing the ray, the shading normal, and in the UV debug view the colour
/// that ends the ray. [`shade_hit`] and the wavefront's shading pass (`tracer::wavefront::wavefront_shade`)
/// both start here.
// Mirror of src/tracer/path/trace.wgsl::ShadingPoint — change both.
pub(crate) struct ShadingPoint {
    pub(crate) s: Surface,
    pub(crate) facing: Vec3,
    pub(crate) n: Vec3,
    /// The UV debug view's colour (u mod 1, v mod 1, 0); None when shading lights it.
    pub(crate) uv_colour: Option<Vec3>,
}

/// The [`ShadingPoint`] of the hit of `entry`'s ray.
// Mirror of src/tracer/path/trace.wgsl::shading_point — change both.
pub(crate) fn shading_point(scene: &PackedScene, entry: &StackEntry, hit: &Hit) -> ShadingPoint {
    let ray = entry.ray;
    let s = surface_at(scene, &ray, hit);
    let s = with_footprint(scene, s, ray.dir, entry.cone, hit.t);
    // The UV debug view (pack turns on TEXTURE for it): (u mod 1, v mod 1, 0).
    if scene.globals.debug_view == DEBUG_VIEW_UV {
        let uv = s.uv - s.uv.floor();
        let colour = Vec3::new(uv.x, uv.y, 0.0);
        return ShadingPoint {
            s,
            facing: s.normal,
            n: s.normal,
            uv_colour: Some(colour),
        };
    }
    let facing = facing_normal(s.normal, ray.dir);
    let mut n = facing;
    // The surface as shading sees it: with smooth meshes, its normal interpolated.
    let mut shading = s;
    let smooth = scene.features.contains(SceneFeatures::SMOOTH);
    if smooth {
        shading.normal = smooth_normal(scene, hit, &s);
        n = if facing.dot(s.normal) < 0.0 {
            -shading.normal
        } else {
            shading.normal
        };
    }
    if scene.features.contains(SceneFeatures::BUMP) {
        n = shading_normal(scene, &shading, n);
    }
    if smooth && shading.normal != s.normal {
        n = visible_normal(n, facing, -ray.dir);
    }
    ShadingPoint {
        s,
        facing,
        n,
        uv_colour: None,
    }
}

/// Two-sided shading: `normal`, negated where it faces away from a ray along `dir`.
/// Secondary rays leave along this geometric side (a bumped normal may lean across the
/// surface).
// Mirror of src/tracer/path/trace.wgsl::facing_normal — change both.
fn facing_normal(normal: Vec3, dir: Vec3) -> Vec3 {
    if normal.dot(dir) > 0.0 {
        -normal
    } else {
        normal
    }
}

/// The media primary rays start in, as packing found them (`dielectric::camera_media`).
// Mirror of src/tracer/path/trace.wgsl::camera_medium_stack — change both.
pub(crate) fn camera_medium_stack(g: &PackedGlobals) -> MediumStack {
    MediumStack {
        iors: g.camera_media,
        count: g.camera_media_count,
    }
}
