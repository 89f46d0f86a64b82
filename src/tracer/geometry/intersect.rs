//! Ray–primitive intersection in f32: sphere (stable quadratic), box (slabs), triangle
//! (watertight). Analytic primitives are intersected in object space with an
//! unnormalised direction, so t is the world-space t.

use super::cylinder_cone::{intersect_cone, intersect_cylinder};
use super::torus::intersect_torus;
use crate::constants::{KIND_CONE, KIND_CUBE, KIND_CYLINDER, KIND_SPHERE, KIND_TORUS, T_MISS};
use crate::pack::{PackedInstance, PackedTriangle};
use crate::tracer::base::math::{safe_rcp3, Axis};
use glam::{Vec2, Vec3};

/// The t-interval [t0, t1] where `o + t·d` is inside the unit sphere at the origin, as
/// (t0, t1); empty (t0 > t1) when the line misses it. Haines et al., Ray Tracing Gems
/// ch. 7: the discriminant from the distance of the centre to the line (no catastrophic
/// b² − ac), and the root pair from q = −b − sign(b)·√Δ, t = c/q and q/a (no cancellation
/// in either root).
// Mirror of src/tracer/geometry/intersect.wgsl::sphere_interval — change both.
pub fn sphere_interval(o: Vec3, d: Vec3) -> Vec2 {
    // Compute the quadratic a·t² + 2b·t + c with f = o (centre at the origin).
    let a = d.dot(d);
    let b = o.dot(d);
    let c = o.dot(o) - 1.0;
    // Compute the discriminant as a·(r² − |f − (b/a)·d|²).
    let l = o - d * (b / a);
    let discriminant = a * (1.0 - l.dot(l));
    if discriminant < 0.0 {
        return Vec2::new(T_MISS, -T_MISS);
    }
    // Compute both roots without cancellation.
    let q = -b - discriminant.sqrt().copysign(b);
    if q == 0.0 {
        return Vec2::ZERO;
    }
    let r0 = c / q;
    let r1 = q / a;
    Vec2::new(r0.min(r1), r0.max(r1))
}

/// Nearest t in (0, t_max) where `o + t·d` meets the unit sphere at the origin, else
/// [`T_MISS`] (the nearer end of [`sphere_interval`] in range; from inside, the exit).
// Mirror of src/tracer/geometry/intersect.wgsl::intersect_sphere — change both.
pub fn intersect_sphere(o: Vec3, d: Vec3, t_max: f32) -> f32 {
    let interval = sphere_interval(o, d);
    if interval.x > interval.y {
        return T_MISS;
    }
    let (t0, t1) = (interval.x, interval.y);
    if t0 > 0.0 && t0 < t_max {
        t0
    } else if t1 > 0.0 && t1 < t_max {
        t1
    } else {
        T_MISS
    }
}

/// The slab interval [t_near, t_far] of `o + t·d` through the box [0,1]³ (empty:
/// t_near > t_far).
// Mirror of src/tracer/geometry/intersect.wgsl::box_interval — change both.
pub fn box_interval(o: Vec3, d: Vec3) -> Vec2 {
    let inv = safe_rcp3(d);
    let t0 = (Vec3::ZERO - o) * inv;
    let t1 = (Vec3::ONE - o) * inv;
    Vec2::new(t0.min(t1).max_element(), t0.max(t1).min_element())
}

/// Nearest t in (0, t_max) where `o + t·d` meets the box [0,1]³, else [`T_MISS`]
/// (slab test; from inside, the exit point).
// Mirror of src/tracer/geometry/intersect.wgsl::intersect_box — change both.
pub fn intersect_box(o: Vec3, d: Vec3, t_max: f32) -> f32 {
    let interval = box_interval(o, d);
    let (t_near, t_far) = (interval.x, interval.y);
    if t_near > t_far {
        return T_MISS;
    }
    let t = if t_near > 0.0 { t_near } else { t_far };
    if t > 0.0 && t < t_max {
        t
    } else {
        T_MISS
    }
}

/// Per-ray set-up of the watertight triangle test (Woop, Benthin & Wald, JCGT 2013):
/// the dominant axis of the direction becomes z, and a shear maps the direction to +z.
/// Computed once per ray (per mesh, in its space), so the per-triangle test only reads
/// the permutation (`kx`, `ky`, `kz`) and the shear (Sx, Sy, Sz).
// Mirror of src/tracer/geometry/intersect.wgsl::TriangleRay — change both.
#[derive(Clone, Copy, Debug)]
pub struct TriangleRay {
    pub origin: Vec3,
    pub kx: Axis,
    pub ky: Axis,
    pub kz: Axis,
    pub shear: Vec3,
}

// Mirror of src/tracer/geometry/intersect.wgsl::triangle_ray_setup — change both.
pub fn triangle_ray_setup(origin: Vec3, d: Vec3) -> TriangleRay {
    // Calculate the dimension where the ray direction is maximal.
    let ad = d.abs();
    let kz = if ad.x >= ad.y && ad.x >= ad.z {
        Axis::X
    } else if ad.y >= ad.z {
        Axis::Y
    } else {
        Axis::Z
    };
    let mut kx = kz.next();
    let mut ky = kx.next();
    let d = d.to_array();
    // Swap kx and ky to preserve the winding direction of triangles.
    if d[kz as usize] < 0.0 {
        std::mem::swap(&mut kx, &mut ky);
    }
    // Calculate the shear constants.
    let (dx, dy, dz) = (d[kx as usize], d[ky as usize], d[kz as usize]);
    let shear = Vec3::new(dx / dz, dy / dz, 1.0 / dz);
    TriangleRay {
        origin,
        kx,
        ky,
        kz,
        shear,
    }
}

/// p.x·q.y − p.y·q.x for the directed edge (p, q) in the sheared plane, always evaluated
/// with the endpoints in one canonical order and negated when they come swapped, so the
/// two triangles sharing an edge compute exactly opposite values (watertightness). In
/// IEEE arithmetic a·d − b·c = −(c·b − d·a) anyway, so this changes no CPU result; but a
/// GPU compiler may fuse one of the products into an FMA, and without the fixed order the
/// two sides of an edge would round differently and let rays slip between them. Written
/// as selects rather than two branches (the same products, so the same values): which
/// endpoint comes first is a coin toss per edge, which a branch predictor cannot learn.
// Mirror of src/tracer/geometry/intersect.wgsl::edge_function — change both.
pub fn edge_function(px: f32, py: f32, qx: f32, qy: f32) -> f32 {
    let canonical = px < qx || (px == qx && py < qy);
    let (sx, sy, ex, ey) = if canonical {
        (px, py, qx, qy)
    } else {
        (qx, qy, px, py)
    };
    let e = sx * ey - sy * ex;
    if canonical {
        e
    } else {
        -e
    }
}

/// The triangle vertex `p` relative to the ray origin, sheared: (x, y) in the plane
/// where the ray is the +z axis, and the unscaled z (`a[kz]`).
// Mirror of src/tracer/geometry/intersect.wgsl::shear_vertex — change both.
fn shear_vertex(r: &TriangleRay, p: Vec3) -> (f32, f32, f32) {
    let a = (p - r.origin).to_array();
    let az = a[r.kz as usize];
    (
        a[r.kx as usize] - r.shear.x * az,
        a[r.ky as usize] - r.shear.y * az,
        az,
    )
}

/// (t, b1, b2) of the hit with the triangle (p0, p1, p2) in (0, t_max), b1 and b2 the
/// barycentric weights of p1 and p2; t = [`T_MISS`] on a miss. Two-sided. Edges shared
/// by two triangles are never missed by both: the edge functions are computed
/// identically from the shared vertices, and a zero counts as inside.
// Mirror of src/tracer/geometry/intersect.wgsl::intersect_triangle — change both.
#[inline]
pub fn intersect_triangle(r: &TriangleRay, p0: Vec3, p1: Vec3, p2: Vec3, t_max: f32) -> Vec3 {
    let miss = Vec3::new(T_MISS, 0.0, 0.0);
    // Calculate the vertices relative to the ray origin, and perform the shear and scale
    // of the vertices.
    let (ax, ay, a_kz) = shear_vertex(r, p0);
    let (bx, by, b_kz) = shear_vertex(r, p1);
    let (cx, cy, c_kz) = shear_vertex(r, p2);
    // Calculate the scaled barycentric coordinates.
    let u = edge_function(cx, cy, bx, by);
    let v = edge_function(ax, ay, cx, cy);
    let w = edge_function(bx, by, ax, ay);
    // Perform the edge tests (bitwise | and &: six compares and no branch, where the
    // short-circuit form branches on signs a predictor cannot learn).
    let negative = (u < 0.0) | (v < 0.0) | (w < 0.0);
    let positive = (u > 0.0) | (v > 0.0) | (w > 0.0);
    if negative & positive {
        return miss;
    }
    // Calculate the determinant.
    let det = u + v + w;
    if det == 0.0 {
        return miss;
    }
    // Calculate the scaled z-coordinates of the vertices and the scaled hit distance.
    let az = r.shear.z * a_kz;
    let bz = r.shear.z * b_kz;
    let cz = r.shear.z * c_kz;
    let t_scaled = u * az + v * bz + w * cz;
    let t = t_scaled / det;
    if !(t > 0.0 && t < t_max) {
        return miss;
    }
    Vec3::new(t, v / det, w / det)
}

/// Object-space ray of an instance: origin and (unnormalised) direction through the
/// world→object rows.
// Mirror of src/tracer/geometry/intersect.wgsl::to_object_space — change both.
pub fn to_object_space(inst: &PackedInstance, o: Vec3, d: Vec3) -> (Vec3, Vec3) {
    let rows = &inst.world_to_object;
    let row = |i: usize| Vec3::new(rows[i][0], rows[i][1], rows[i][2]);
    let oo = Vec3::new(
        row(0).dot(o) + rows[0][3],
        row(1).dot(o) + rows[1][3],
        row(2).dot(o) + rows[2][3],
    );
    let od = Vec3::new(row(0).dot(d), row(1).dot(d), row(2).dot(d));
    (oo, od)
}

/// t of the nearest hit in (0, t_max) with an analytic instance, else [`T_MISS`]
/// (`KIND_CSG` instances need the scene: see `traverse::intersect_item`).
// Mirror of src/tracer/geometry/intersect.wgsl::intersect_instance — change both.
pub fn intersect_instance(inst: &PackedInstance, o: Vec3, d: Vec3, t_max: f32) -> f32 {
    let (oo, od) = to_object_space(inst, o, d);
    match inst.kind {
        KIND_SPHERE => intersect_sphere(oo, od, t_max),
        KIND_CUBE => intersect_box(oo, od, t_max),
        KIND_CYLINDER => intersect_cylinder(oo, od, t_max),
        KIND_CONE => intersect_cone(oo, od, inst.params[0], inst.params[1], t_max),
        KIND_TORUS => intersect_torus(oo, od, inst.params[0], inst.params[1], t_max),
        _ => T_MISS,
    }
}

/// The triangle's vertices as vectors.
// Mirror of src/tracer/geometry/intersect.wgsl::triangle_vertices — change both.
pub fn triangle_vertices(tri: &PackedTriangle) -> [Vec3; 3] {
    [Vec3::from(tri.p0), Vec3::from(tri.p1), Vec3::from(tri.p2)]
}
