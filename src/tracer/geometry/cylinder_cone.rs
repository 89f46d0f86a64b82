//! Capped cylinder and capped cone in f32: ray intersection in object space (unnormalised
//! direction, so t is the world-space t) and the surface at a hit (point snapped onto the
//! surface, outward normal, UV and tangent frame).
//!
//! Both solids are a quadric region intersected with the slab between their cap planes:
//! - cylinder: x² + y² ≤ 1 and 0 ≤ z ≤ 1;
//! - cone: x² + y² ≤ z² and zmin ≤ z ≤ zmax (zmin < zmax). With zmin ≥ 0 (the common case)
//!   or zmax ≤ 0 this is one nappe, convex; with zmin < 0 < zmax it is the **double cone**:
//!   both nappes, each capped, touching at the tip (the origin).
//!
//! So the ray's inside is the quadric's t-interval(s) clipped to the slab's t-interval,
//! and the hit is the nearest end of those in (0, t_max): entry from outside, exit from
//! inside. Deciding both parts at once keeps rims consistent (no ray slips between a side
//! and a cap that each reject it).
//!
//! UVs: u = angle around z / 2π in [0, 1); on the sides v = z mapped to [0, 1]
//! (cylinder: v = z; cone: v = (z − zmin)/(zmax − zmin)); caps are planar: the cap disc of
//! radius R maps to [0, 1]² by u = (x/R + 1)/2, v = (y/R + 1)/2 (seen from +z, u to +x and
//! v to +y, on both caps). `dpdu`, `dpdv` are the object-space derivatives of the point.

use super::uv::ObjectSurface;
use crate::constants::{TWO_PI, T_MISS};
use crate::tracer::base::math::safe_rcp;
use glam::{Vec2, Vec3, Vec4};

/// The nearer of `best` and the ends of [lo, hi] that lie in (0, t_max), each shifted by
/// `t_shift` (empty when lo > hi).
// Mirror of src/tracer/geometry/cylinder_cone.wgsl::nearest_interval_end — change both.
fn nearest_interval_end(lo: f32, hi: f32, t_shift: f32, t_max: f32, best: f32) -> f32 {
    if lo > hi {
        return best;
    }
    let t_lo = t_shift + lo;
    let t_hi = t_shift + hi;
    if t_lo > 0.0 && t_lo < t_max && t_lo < best {
        t_lo
    } else if t_hi > 0.0 && t_hi < t_max && t_hi < best {
        t_hi
    } else {
        best
    }
}

/// u = angle of (x, y) around the z axis / 2π, in [0, 1) (0 on the axis itself).
// Mirror of src/tracer/geometry/cylinder_cone.wgsl::cylinder_cone_angle_u — change both.
fn cylinder_cone_angle_u(x: f32, y: f32) -> f32 {
    if x == 0.0 && y == 0.0 {
        return 0.0;
    }
    let u = y.atan2(x) / TWO_PI;
    if u < 0.0 {
        u + 1.0
    } else {
        u
    }
}

/// The t-interval [lo, hi] where `o + t·d` is inside the solid cylinder x² + y² ≤ 1,
/// 0 ≤ z ≤ 1, as (lo, hi); empty (lo > hi) when the line misses it.
// Mirror of src/tracer/geometry/cylinder_cone.wgsl::cylinder_interval — change both.
pub fn cylinder_interval(o: Vec3, d: Vec3) -> Vec2 {
    let miss = Vec2::new(T_MISS, -T_MISS);
    // Compute the side quadratic a·t² + 2b·t + c of x² + y² − 1 (intersect_sphere's
    // stable form, in xy).
    let a = d.x * d.x + d.y * d.y;
    let b = o.x * d.x + o.y * d.y;
    let c = o.x * o.x + o.y * o.y - 1.0;
    let mut side_lo = -T_MISS;
    let mut side_hi = T_MISS;
    if a > 0.0 {
        // Compute the discriminant as a·(1 − |l|²), l the line's point nearest the axis.
        let lx = o.x - d.x * (b / a);
        let ly = o.y - d.y * (b / a);
        let discriminant = a * (1.0 - (lx * lx + ly * ly));
        if discriminant < 0.0 {
            return miss;
        }
        // Compute both roots without cancellation.
        let q = -b - discriminant.sqrt().copysign(b);
        if q == 0.0 {
            side_lo = 0.0;
            side_hi = 0.0;
        } else {
            let r0 = c / q;
            let r1 = q / a;
            side_lo = r0.min(r1);
            side_hi = r0.max(r1);
        }
    } else if c > 0.0 {
        // Parallel to the axis, outside the side.
        return miss;
    }
    // Clip to the slab between the caps.
    let inv_dz = safe_rcp(d.z);
    let tz0 = (0.0 - o.z) * inv_dz;
    let tz1 = (1.0 - o.z) * inv_dz;
    Vec2::new(side_lo.max(tz0.min(tz1)), side_hi.min(tz0.max(tz1)))
}

/// Nearest t in (0, t_max) where `o + t·d` meets the solid cylinder x² + y² ≤ 1,
/// 0 ≤ z ≤ 1, else [`T_MISS`] (from inside, the exit point).
// Mirror of src/tracer/geometry/cylinder_cone.wgsl::intersect_cylinder — change both.
pub fn intersect_cylinder(o: Vec3, d: Vec3, t_max: f32) -> f32 {
    let interval = cylinder_interval(o, d);
    nearest_interval_end(interval.x, interval.y, 0.0, t_max, T_MISS)
}

/// Where a line is inside a cone: t = `t_shift` + t′ over the t′-intervals
/// [`spans`.x, `spans`.y] and [`spans`.z, `spans`.w] (each empty when its lo > hi; the
/// second after the first).
#[derive(Clone, Copy, Debug, PartialEq)]
// Mirror of src/tracer/geometry/cylinder_cone.wgsl::ConeIntervals — change both.
pub struct ConeIntervals {
    pub t_shift: f32,
    pub spans: Vec4,
}

/// The intervals where `o + t·d` is inside the solid cone x² + y² ≤ z², zmin ≤ z ≤ zmax
/// (two only for a double cone, see the module docs).
// Mirror of src/tracer/geometry/cylinder_cone.wgsl::cone_intervals — change both.
pub fn cone_intervals(o: Vec3, d: Vec3, zmin: f32, zmax: f32) -> ConeIntervals {
    let empty = Vec4::new(T_MISS, -T_MISS, T_MISS, -T_MISS);
    // Move the origin to the line's point nearest the tip: the quadratic's coefficients
    // are then of the size of the hit's distance from the tip, not of the origin's (no
    // catastrophic b² − ac for far origins, and rays passing near the tip keep their
    // precision). t = t_shift + t', t' the parameter from the moved origin.
    let t_shift = -o.dot(d) / d.dot(d);
    let os = o + d * t_shift;
    // Compute the quadratic a·t'² + 2b·t' + c of x² + y² − z².
    let a = d.x * d.x + d.y * d.y - d.z * d.z;
    let b = os.x * d.x + os.y * d.y - os.z * d.z;
    let c = os.x * os.x + os.y * os.y - os.z * os.z;
    let discriminant = b * b - a * c;
    // The t'-intervals where x² + y² ≤ z²: [lo0, hi0] and [lo1, hi1] (empty: lo > hi).
    let mut lo0 = -T_MISS;
    let mut hi0 = T_MISS;
    let mut lo1 = 1.0;
    let mut hi1 = 0.0;
    if a == 0.0 {
        // Parallel to a generator: 2b·t' + c ≤ 0 on a half-line (or everywhere/nowhere).
        if b > 0.0 {
            hi0 = -c / (2.0 * b);
        } else if b < 0.0 {
            lo0 = -c / (2.0 * b);
        } else if c > 0.0 {
            return ConeIntervals {
                t_shift,
                spans: empty,
            };
        }
    } else if a < 0.0 && discriminant <= 0.0 {
        // Steeper than the cone: inside for every t' (through the tip when Δ = 0).
    } else {
        if discriminant < 0.0 {
            return ConeIntervals {
                t_shift,
                spans: empty,
            };
        }
        // Compute both roots without cancellation.
        let q = -b - discriminant.sqrt().copysign(b);
        let (r0, r1) = if q == 0.0 {
            (0.0, 0.0)
        } else {
            let r0 = c / q;
            let r1 = q / a;
            (r0.min(r1), r0.max(r1))
        };
        if a > 0.0 {
            // Flatter than the cone: inside between the roots.
            lo0 = r0;
            hi0 = r1;
        } else {
            // Steeper: inside before the first root (one nappe) and after the second.
            hi0 = r0;
            lo1 = r1;
            hi1 = T_MISS;
        }
    }
    // Clip to the slab between the caps.
    let inv_dz = safe_rcp(d.z);
    let tz0 = (zmin - os.z) * inv_dz;
    let tz1 = (zmax - os.z) * inv_dz;
    let slab_lo = tz0.min(tz1);
    let slab_hi = tz0.max(tz1);
    ConeIntervals {
        t_shift,
        spans: Vec4::new(
            lo0.max(slab_lo),
            hi0.min(slab_hi),
            lo1.max(slab_lo),
            hi1.min(slab_hi),
        ),
    }
}

/// Nearest t in (0, t_max) where `o + t·d` meets the solid cone x² + y² ≤ z²,
/// zmin ≤ z ≤ zmax, else [`T_MISS`] (from inside, the exit point). With zmin < 0 < zmax,
/// the double cone (see the module docs).
// Mirror of src/tracer/geometry/cylinder_cone.wgsl::intersect_cone — change both.
pub fn intersect_cone(o: Vec3, d: Vec3, zmin: f32, zmax: f32, t_max: f32) -> f32 {
    let c = cone_intervals(o, d, zmin, zmax);
    let s = c.spans;
    let best = nearest_interval_end(s.x, s.y, c.t_shift, t_max, T_MISS);
    nearest_interval_end(s.z, s.w, c.t_shift, t_max, best)
}

/// The cylinder's surface at the object-space point `p` (near the surface): the nearest of
/// side and caps, with `p` snapped onto it.
// Mirror of src/tracer/geometry/cylinder_cone.wgsl::cylinder_surface — change both.
pub fn cylinder_surface(p: Vec3) -> ObjectSurface {
    let r = (p.x * p.x + p.y * p.y).sqrt();
    let d_side = (r - 1.0).abs();
    let d_bottom = p.z.abs();
    let d_top = (p.z - 1.0).abs();
    if d_side <= d_bottom && d_side <= d_top {
        // Side: snap radially onto r = 1, z into [0, 1].
        let (cx, cy) = if r > 0.0 {
            (p.x / r, p.y / r)
        } else {
            (1.0, 0.0)
        };
        let z = p.z.clamp(0.0, 1.0);
        return ObjectSurface {
            p: Vec3::new(cx, cy, z),
            normal: Vec3::new(cx, cy, 0.0),
            uv: Vec2::new(cylinder_cone_angle_u(cx, cy), z),
            dpdu: Vec3::new(-cy, cx, 0.0) * TWO_PI,
            dpdv: Vec3::new(0.0, 0.0, 1.0),
        };
    }
    // Cap: snap onto its plane, into the unit disc.
    let top = d_top < d_bottom;
    let s = if r > 1.0 { 1.0 / r } else { 1.0 };
    let (x, y) = (p.x * s, p.y * s);
    ObjectSurface {
        p: Vec3::new(x, y, if top { 1.0 } else { 0.0 }),
        normal: Vec3::new(0.0, 0.0, if top { 1.0 } else { -1.0 }),
        uv: Vec2::new(0.5 * (x + 1.0), 0.5 * (y + 1.0)),
        dpdu: Vec3::new(2.0, 0.0, 0.0),
        dpdv: Vec3::new(0.0, 2.0, 0.0),
    }
}

/// The cone's surface at the object-space point `p` (near the surface): the nearest of
/// side and caps (a cap of radius 0, at a tip, is never chosen), with `p` snapped onto it.
// Mirror of src/tracer/geometry/cylinder_cone.wgsl::cone_surface — change both.
pub fn cone_surface(p: Vec3, zmin: f32, zmax: f32) -> ObjectSurface {
    let r = (p.x * p.x + p.y * p.y).sqrt();
    // Distances to the side (in the (r, z) half-plane, from the generator r = |z|) and to
    // the caps.
    let d_side = (r - p.z.abs()) / 2.0f32.sqrt();
    let d_side = d_side.abs();
    let d_bottom = if zmin != 0.0 {
        (p.z - zmin).abs()
    } else {
        T_MISS
    };
    let d_top = if zmax != 0.0 {
        (p.z - zmax).abs()
    } else {
        T_MISS
    };
    let (cx, cy) = if r > 0.0 {
        (p.x / r, p.y / r)
    } else {
        (1.0, 0.0)
    };
    if d_side <= d_bottom && d_side <= d_top {
        // Side: project (r, z) onto the nappe's generator r = s·z, z into [zmin, zmax].
        let s = if p.z >= 0.0 { 1.0 } else { -1.0 };
        let z = (s * 0.5 * (r + p.z.abs())).clamp(zmin, zmax);
        let rs = z.abs();
        let height = zmax - zmin;
        return ObjectSurface {
            p: Vec3::new(cx * rs, cy * rs, z),
            // ∇(x² + y² − z²) ∝ (cx, cy, −s) on the nappe.
            normal: Vec3::new(cx, cy, -s).normalize(),
            uv: Vec2::new(cylinder_cone_angle_u(cx, cy), (z - zmin) / height),
            dpdu: Vec3::new(-cy * rs, cx * rs, 0.0) * TWO_PI,
            dpdv: Vec3::new(s * cx, s * cy, 1.0) * height,
        };
    }
    // Cap: snap onto its plane, into its disc of radius |z_cap|.
    let top = d_top < d_bottom;
    let z = if top { zmax } else { zmin };
    let radius = z.abs();
    let k = if r > radius { radius / r } else { 1.0 };
    let (x, y) = (p.x * k, p.y * k);
    ObjectSurface {
        p: Vec3::new(x, y, z),
        normal: Vec3::new(0.0, 0.0, if top { 1.0 } else { -1.0 }),
        uv: Vec2::new(0.5 * (x / radius + 1.0), 0.5 * (y / radius + 1.0)),
        dpdu: Vec3::new(2.0 * radius, 0.0, 0.0),
        dpdv: Vec3::new(0.0, 2.0 * radius, 0.0),
    }
}
