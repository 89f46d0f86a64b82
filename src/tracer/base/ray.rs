//! Rays, camera rays and the self-intersection offset.

use crate::constants::OFFSET_RELATIVE;
use crate::pack::PackedGlobals;
use glam::Vec3;

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
