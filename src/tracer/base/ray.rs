//! Rays, camera rays and the self-intersection offset.

use crate::constants::{OFFSET_RELATIVE, TWO_PI};
use crate::pack::PackedGlobals;
use glam::{Vec2, Vec3};

// Mirror of src/tracer/base/ray.wgsl::Ray — change both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: Vec3,
    /// Unit direction in world space (object-space twins are not normalised).
    pub dir: Vec3,
}

/// Primary ray through film position (`fx`, `fy`) in pixels (0,0 = top-left corner of
/// the image, pixel centres at +0.5).
// Mirror of src/tracer/base/ray.wgsl::camera_ray — change both.
pub fn camera_ray(g: &PackedGlobals, fx: f32, fy: f32) -> Ray {
    let ndc_x = 2.0 * fx / g.width as f32 - 1.0;
    let ndc_y = 1.0 - 2.0 * fy / g.height as f32;
    let dir = Vec3::from(g.forward)
        + Vec3::from(g.right) * (ndc_x * g.aspect * g.tan_half_fov)
        + Vec3::from(g.up) * (ndc_y * g.tan_half_fov);
    Ray {
        origin: Vec3::from(g.eye),
        dir: dir.normalize(),
    }
}

/// The point of the unit disk for `u` in [0, 1)²: Shirley & Chiu's concentric map, which
/// takes each square about the centre to a circle, so strata of the square stay compact
/// strata of the disk and keep their areas.
// Mirror of src/tracer/base/ray.wgsl::concentric_disk — change both.
pub fn concentric_disk(u: Vec2) -> Vec2 {
    let a = u * 2.0 - Vec2::ONE;
    if a.x == 0.0 && a.y == 0.0 {
        return Vec2::ZERO;
    }
    let eighth = TWO_PI / 8.0;
    let (radius, angle) = if a.x.abs() > a.y.abs() {
        (a.x, eighth * (a.y / a.x))
    } else {
        (a.y, 2.0 * eighth - eighth * (a.x / a.y))
    };
    Vec2::new(angle.cos(), angle.sin()) * radius
}

/// The thin-lens camera ray of the `pinhole` ray (`camera_ray`'s) and lens position
/// `lens` in [0, 1)²: from the point of the lens disk (radius `lens_radius`, in the
/// plane of `right` and `up` through the eye) that `lens` maps to, towards where the
/// pinhole ray meets the plane in focus (perpendicular to `forward`, `focus_distance`
/// from the eye), so that plane stays sharp and the rest blurs. Its direction is
/// computed from the eye, not from world positions, so it loses no precision far from
/// the origin.
// Mirror of src/tracer/base/ray.wgsl::thin_lens_ray — change both.
pub fn thin_lens_ray(g: &PackedGlobals, pinhole: &Ray, lens: Vec2) -> Ray {
    let to_focus = pinhole.dir * (g.focus_distance / pinhole.dir.dot(Vec3::from(g.forward)));
    let disk = concentric_disk(lens) * g.lens_radius;
    let offset = Vec3::from(g.right) * disk.x + Vec3::from(g.up) * disk.y;
    Ray {
        origin: pinhole.origin + offset,
        dir: (to_focus - offset).normalize(),
    }
}

/// Moves a hit point off its surface along the unit normal `n` (pointing to the side the
/// new ray leaves towards), by [`OFFSET_RELATIVE`] of `magnitude`, the largest coordinate
/// magnitude that went into computing `p` (Wächter & Binder, Ray Tracing Gems ch. 6, bound
/// the error the same way; expressing it per hit rather than per component keeps it
/// proportional near the origin too, with no scene-scale constant).
// Mirror of src/tracer/base/ray.wgsl::offset_ray — change both.
pub fn offset_ray(p: Vec3, n: Vec3, magnitude: f32) -> Vec3 {
    p + n * (magnitude.max(p.abs().max_element()) * OFFSET_RELATIVE)
}

/// How far a shadow ray from `origin` looks for blockers on its way to a light at
/// `position`, `distance` away: the distance less the bound [`offset_ray`] moves origins
/// by, taken at the largest coordinate magnitude of either end (and `magnitude`, the
/// shaded surface's). A surface through the light (a point light in a ceiling's face or
/// on a box's edge, an area light in a panel's plane) is then never hit at t ≈ distance,
/// where rounding alone would decide, pixel by pixel, whether it blocks (speckle); the
/// bound scales with the scene, like the origin's offset. A light closer than the bound
/// is reached by a zero-length ray, which nothing blocks.
// Mirror of src/tracer/base/ray.wgsl::shadow_reach — change both.
pub fn shadow_reach(origin: Vec3, position: Vec3, distance: f32, magnitude: f32) -> f32 {
    let ends = origin.abs().max_element().max(position.abs().max_element());
    (distance - magnitude.max(ends) * OFFSET_RELATIVE).max(0.0)
}
