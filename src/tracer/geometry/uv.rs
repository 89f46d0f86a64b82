//! UVs and tangent frames of the sphere, the box and mesh triangles (the cylinder, cone
//! and torus have theirs in `cylinder_cone` and `torus`). Conventions (docs/scene-language.md,
//! "UV conventions"; all in object space, pole and axis along z as for the other primitives):
//! - sphere: u = longitude/2π in [0, 1) (atan2(y, x), 0 on +x, increasing towards +y),
//!   v = latitude/π + 1/2 in [0, 1] (0 at the south pole z = −1, 1 at the north pole);
//! - box: each face maps to [0, 1]², seen from outside unmirrored: ∂p/∂u is the face's
//!   "right" and ∂p/∂v its "up" (+y on the four side faces; on the top face +y, up is −z;
//!   on the bottom face −y, up is +z), so ∂p/∂u × ∂p/∂v is the outward normal;
//! - triangles: the corners' UVs interpolated with the hit's barycentrics; the frame
//!   solves p1 − p0 = Δu₁·∂p/∂u + Δv₁·∂p/∂v (likewise for p2), falling back to an
//!   orthonormal frame around the normal when the UVs are degenerate.

use crate::constants::{TRIANGLE_FRAME_AXIS_SWITCH, TRIANGLE_FRAME_MIN_UV_SINE, TWO_PI};
use glam::{Vec2, Vec3};

/// An analytic surface at a point, in object space: the point snapped onto it, its unit
/// outward normal, UV and ∂p/∂u, ∂p/∂v (∂p/∂u × ∂p/∂v points along the normal). What
/// every primitive's `*_surface` returns (sphere and box here; cylinder, cone, torus in
/// their own files).
// Mirror of src/tracer/geometry/uv.wgsl::ObjectSurface — change both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObjectSurface {
    pub p: Vec3,
    pub normal: Vec3,
    pub uv: Vec2,
    pub dpdu: Vec3,
    pub dpdv: Vec3,
}

/// The unit sphere at `p` (reprojected onto the sphere). At the poles ∂p/∂u = 0 (bump
/// mapping then leaves the normal alone); nothing divides by the distance to the axis.
// Mirror of src/tracer/geometry/uv.wgsl::sphere_surface — change both.
pub fn sphere_surface(p: Vec3) -> ObjectSurface {
    // Reproject onto the unit sphere.
    let p = p.normalize();
    let r = (p.x * p.x + p.y * p.y).sqrt();
    let phi = p.y.atan2(p.x);
    let latitude = p.z.atan2(r);
    let mut u = phi / TWO_PI;
    if u < 0.0 {
        u += 1.0;
    }
    let v = latitude / (0.5 * TWO_PI) + 0.5;
    ObjectSurface {
        p,
        normal: p,
        uv: Vec2::new(u, v),
        dpdu: Vec3::new(-p.y, p.x, 0.0) * TWO_PI,
        dpdv: Vec3::new(-p.z * phi.cos(), -p.z * phi.sin(), r) * (0.5 * TWO_PI),
    }
}

/// The box [0,1]³ at `p`: the face nearest the point, the point snapped onto it.
// Mirror of src/tracer/geometry/uv.wgsl::cube_surface — change both.
pub fn cube_surface(p: Vec3) -> ObjectSurface {
    let mut p = p;
    // The face nearest the point: snap the point onto it.
    let dist = p.abs().min((p - Vec3::ONE).abs());
    let axis = if dist.x <= dist.y && dist.x <= dist.z {
        0
    } else if dist.y <= dist.z {
        1
    } else {
        2
    };
    let upper = p[axis] > 0.5;
    p[axis] = if upper { 1.0 } else { 0.0 };
    let sign = if upper { 1.0 } else { -1.0 };
    let mut normal = Vec3::ZERO;
    normal[axis] = sign;
    // The face's right (∂p/∂u) and up (∂p/∂v) as seen from outside.
    let (dpdu, dpdv) = if axis == 0 {
        (Vec3::new(0.0, 0.0, -sign), Vec3::Y)
    } else if axis == 1 {
        (Vec3::X, Vec3::new(0.0, 0.0, -sign))
    } else {
        (Vec3::new(sign, 0.0, 0.0), Vec3::Y)
    };
    let centred = p - Vec3::splat(0.5);
    ObjectSurface {
        p,
        normal,
        uv: Vec2::new(dpdu.dot(centred) + 0.5, dpdv.dot(centred) + 0.5),
        dpdu,
        dpdv,
    }
}

/// (∂p/∂u, ∂p/∂v) of the triangle (p0, p1, p2) with corner UVs (uv0, uv1, uv2) and unit
/// normal `normal`. When the UV triangle is degenerate (its doubled area at most
/// [`TRIANGLE_FRAME_MIN_UV_SINE`] of the product of its edges — a scale-free test), an
/// orthonormal frame around the normal.
// Mirror of src/tracer/geometry/uv.wgsl::triangle_frame — change both.
pub fn triangle_frame(p: [Vec3; 3], uv: [Vec2; 3], normal: Vec3) -> (Vec3, Vec3) {
    let e1 = p[1] - p[0];
    let e2 = p[2] - p[0];
    let d1 = uv[1] - uv[0];
    let d2 = uv[2] - uv[0];
    let det = d1.x * d2.y - d1.y * d2.x;
    let scale = d1.length() * d2.length();
    if det.abs() > TRIANGLE_FRAME_MIN_UV_SINE * scale {
        let inv = 1.0 / det;
        return ((e1 * d2.y - e2 * d1.y) * inv, (e2 * d1.x - e1 * d2.x) * inv);
    }
    // Any axis not along the normal gives a perpendicular; dpdu × dpdv = normal.
    let axis = if normal.x.abs() > TRIANGLE_FRAME_AXIS_SWITCH {
        Vec3::Y
    } else {
        Vec3::X
    };
    let dpdu = normal.cross(axis).normalize();
    (dpdu, normal.cross(dpdu))
}
