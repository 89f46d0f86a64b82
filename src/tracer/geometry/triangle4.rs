//! The watertight triangle test of [`intersect_triangle`] on four triangles at once, one
//! per SIMD lane (glam's `Vec4`: SSE2 on x86-64, four scalars elsewhere). CPU only: the
//! GPU tracer tests a cell's triangles one by one (src/tracer/traversal/traverse_mesh.wgsl), and this
//! file changes no answer, only how many the CPU computes per instruction.
//!
//! Each lane performs the scalar test's operations on its triangle in the same order, so
//! its hit/miss decision and its t are the scalar test's bit for bit (IEEE arithmetic is
//! the same in a lane as in a scalar register, and Rust fuses no multiply-add). One step
//! is written differently: the edge function's canonical endpoint order
//! ([`edge_function`], there for GPU compilers that fuse an FMA) is left out, since
//! without fusion a·d − b·c = −(c·b − d·a) exactly; the two forms then differ only in
//! the sign of a zero, which no decision or t depends on, but the barycentrics can. So a
//! caller that keeps a hit recomputes its barycentrics with [`intersect_triangle`] itself
//! ([`TriangleBatch::keep_nearest`]), and the result stays the scalar one.
//! `tests/oracle/triangle4.rs` checks the lanes against the scalar test, grazing and edge-on
//! rays included. (Measured on cow.obj, `glint bench --trace`, one thread: with the
//! batches and their inlining, about −30% time per shadow ray and −25% per camera ray;
//! docs/journal/2026-12-01-four-triangles-at-a-time.md.)
//!
//! [`edge_function`]: super::intersect::edge_function

use super::intersect::{intersect_triangle, triangle_ray_setup, triangle_vertices, TriangleRay};
use crate::constants::NO_ITEM;
use crate::pack::PackedTriangle;
use crate::tracer::base::math::Axis;
use glam::{BVec4A, Vec3, Vec4};

/// Triangles per batch: the lanes of a `Vec4`.
pub const LANES: usize = 4;

/// A [`TriangleRay`] spread over four lanes: the origin's coordinates and the shear
/// already in the ray's axis order (x = `kx`, y = `ky`, z = `kz`), and that order as one of
/// the six [`AxisOrder`]s, so a lane reads its triangle's coordinates in that order with
/// indices known when compiled.
#[derive(Clone, Copy, Debug)]
pub struct TriangleRay4 {
    order: AxisOrder,
    origin: [Vec4; 3],
    shear: [Vec4; 3],
}

/// The ray's axis order (kx, ky, kz): kz the direction's largest axis, kx and ky the other
/// two in cyclic order, swapped when the direction along kz is negative
/// (`triangle_ray_setup`), so six orders in all.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum AxisOrder {
    Xyz,
    Yxz,
    Yzx,
    Zyx,
    Zxy,
    Xzy,
}

impl AxisOrder {
    fn of(kx: Axis, ky: Axis, kz: Axis) -> AxisOrder {
        match (kx, ky, kz) {
            (Axis::X, Axis::Y, _) => AxisOrder::Xyz,
            (Axis::Y, Axis::X, _) => AxisOrder::Yxz,
            (Axis::Y, Axis::Z, _) => AxisOrder::Yzx,
            (Axis::Z, Axis::Y, _) => AxisOrder::Zyx,
            (Axis::Z, Axis::X, _) => AxisOrder::Zxy,
            _ => AxisOrder::Xzy,
        }
    }
}

impl TriangleRay4 {
    /// The four-lane form of `r`.
    pub fn new(r: &TriangleRay) -> TriangleRay4 {
        let axes = [r.kx, r.ky, r.kz];
        let origin = r.origin.to_array();
        TriangleRay4 {
            order: AxisOrder::of(r.kx, r.ky, r.kz),
            origin: axes.map(|axis| Vec4::splat(origin[axis as usize])),
            shear: [r.shear.x, r.shear.y, r.shear.z].map(Vec4::splat),
        }
    }
}

/// The four triangles' nine coordinates, one `Vec4` each (lane k: triangle k):
/// `[vertex][axis]`.
type Coordinates4 = [[Vec4; 3]; 3];

/// Loads the four triangles' coordinates into lanes: each triangle as two four-float
/// loads and one float, then a 4×4 transpose of each group of four (shuffles: cheaper than
/// filling the 36 lanes one float at a time).
// Mirror of src/tracer/geometry/intersect.wgsl::triangle_vertices for four triangles, in lanes — change both.
#[inline(always)]
fn load_coordinates4(tris: &[&PackedTriangle; LANES]) -> Coordinates4 {
    let floats = tris.map(bytemuck::cast_ref::<_, [f32; 9]>);
    let [a0, a1, a2, a3] = transpose4(floats.map(|f| Vec4::from_slice(&f[0..4])));
    let [b0, b1, b2, b3] = transpose4(floats.map(|f| Vec4::from_slice(&f[4..8])));
    let c = Vec4::new(floats[0][8], floats[1][8], floats[2][8], floats[3][8]);
    [[a0, a1, a2], [a3, b0, b1], [b2, b3, c]]
}

/// The 4×4 transpose of four rows: column k of the rows as lane vector k.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn transpose4(rows: [Vec4; 4]) -> [Vec4; 4] {
    use std::arch::x86_64::{_mm_movehl_ps, _mm_movelh_ps, _mm_unpackhi_ps, _mm_unpacklo_ps};
    let [r0, r1, r2, r3] = rows.map(std::arch::x86_64::__m128::from);
    // SAFETY: SSE is part of every x86-64 CPU (the target's baseline), and these shuffles
    // read nothing but their register arguments.
    let columns = unsafe {
        let (lo01, lo23) = (_mm_unpacklo_ps(r0, r1), _mm_unpacklo_ps(r2, r3));
        let (hi01, hi23) = (_mm_unpackhi_ps(r0, r1), _mm_unpackhi_ps(r2, r3));
        [
            _mm_movelh_ps(lo01, lo23),
            _mm_movehl_ps(lo23, lo01),
            _mm_movelh_ps(hi01, hi23),
            _mm_movehl_ps(hi23, hi01),
        ]
    };
    columns.map(Vec4::from)
}

/// The 4×4 transpose of four rows (portable form).
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
fn transpose4(rows: [Vec4; 4]) -> [Vec4; 4] {
    let r = rows.map(Vec4::to_array);
    [0, 1, 2, 3].map(|k| Vec4::new(r[0][k], r[1][k], r[2][k], r[3][k]))
}

/// Vertex `vertex` of the four triangles relative to the ray origin and sheared, as the
/// scalar `shear_vertex`: (x, y) in the plane where the ray is the +z axis, and the
/// unscaled z. `KX`, `KY`, `KZ`: the ray's axis order.
#[inline(always)]
fn shear_vertex4<const KX: usize, const KY: usize, const KZ: usize>(
    r: &TriangleRay4,
    vertex: &[Vec4; 3],
) -> [Vec4; 3] {
    let a_kx = vertex[KX] - r.origin[0];
    let a_ky = vertex[KY] - r.origin[1];
    let a_kz = vertex[KZ] - r.origin[2];
    [a_kx - r.shear[0] * a_kz, a_ky - r.shear[1] * a_kz, a_kz]
}

/// The edge function p.x·q.y − p.y·q.x of each lane (see the file's header on the
/// canonical order the scalar form adds).
#[inline(always)]
fn edge4(px: Vec4, py: Vec4, qx: Vec4, qy: Vec4) -> Vec4 {
    px * qy - py * qx
}

/// Which of the four triangles the ray hits in (0, t_max), as bits (lane k: bit k), and
/// each lane's t (meaningful where its bit is set): exactly the hits and t of
/// `intersect_triangle` on each triangle.
#[inline]
pub fn intersect_triangles4(
    r: &TriangleRay4,
    tris: &[&PackedTriangle; LANES],
    t_max: f32,
) -> (u32, Vec4) {
    let p = load_coordinates4(tris);
    // (One branch, the same for the whole walk, to a test whose axis indices are
    // constants.)
    match r.order {
        AxisOrder::Xyz => intersect_ordered4::<0, 1, 2>(r, &p, t_max),
        AxisOrder::Yxz => intersect_ordered4::<1, 0, 2>(r, &p, t_max),
        AxisOrder::Yzx => intersect_ordered4::<1, 2, 0>(r, &p, t_max),
        AxisOrder::Zyx => intersect_ordered4::<2, 1, 0>(r, &p, t_max),
        AxisOrder::Zxy => intersect_ordered4::<2, 0, 1>(r, &p, t_max),
        AxisOrder::Xzy => intersect_ordered4::<0, 2, 1>(r, &p, t_max),
    }
}

/// `intersect_triangles4` for the axis order `KX`, `KY`, `KZ` (the ray's).
// Mirror of src/tracer/geometry/intersect.wgsl::intersect_triangle on four triangles, one per lane — change both.
#[inline(always)]
fn intersect_ordered4<const KX: usize, const KY: usize, const KZ: usize>(
    r: &TriangleRay4,
    p: &Coordinates4,
    t_max: f32,
) -> (u32, Vec4) {
    let zero = Vec4::ZERO;
    let [ax, ay, a_kz] = shear_vertex4::<KX, KY, KZ>(r, &p[0]);
    let [bx, by, b_kz] = shear_vertex4::<KX, KY, KZ>(r, &p[1]);
    let [cx, cy, c_kz] = shear_vertex4::<KX, KY, KZ>(r, &p[2]);
    let u = edge4(cx, cy, bx, by);
    let v = edge4(ax, ay, cx, cy);
    let w = edge4(bx, by, ax, ay);
    let negative = u.cmplt(zero) | v.cmplt(zero) | w.cmplt(zero);
    let positive = u.cmpgt(zero) | v.cmpgt(zero) | w.cmpgt(zero);
    let det = u + v + w;
    let sz = r.shear[2];
    let t_scaled = u * (sz * a_kz) + v * (sz * b_kz) + w * (sz * c_kz);
    let t = t_scaled / det;
    let inside: BVec4A = !(negative & positive) & det.cmpne(zero);
    let in_range = t.cmpgt(zero) & t.cmplt(Vec4::splat(t_max));
    ((inside & in_range).bitmask(), t)
}

/// The scalar test's per-ray set-up and its four-lane form, made once per mesh walk.
pub struct TriangleRays {
    pub scalar: TriangleRay,
    pub lanes: TriangleRay4,
}

impl TriangleRays {
    /// `triangle_ray_setup` of the ray, in both forms.
    #[inline(always)]
    pub fn new(origin: Vec3, dir: Vec3) -> TriangleRays {
        let scalar = triangle_ray_setup(origin, dir);
        TriangleRays {
            scalar,
            lanes: TriangleRay4::new(&scalar),
        }
    }
}

/// The nearest triangle hit so far in a mesh walk: t (the walk's t_max until a hit), the
/// triangle's mesh-local number (`NO_ITEM` until a hit) and its barycentrics.
#[derive(Clone, Copy, Debug)]
pub struct NearestTriangle {
    pub t: f32,
    pub local: u32,
    pub b1: f32,
    pub b2: f32,
}

impl NearestTriangle {
    /// No hit yet, in a walk up to `t_max`.
    pub fn none(t_max: f32) -> NearestTriangle {
        NearestTriangle {
            t: t_max,
            local: NO_ITEM,
            b1: 0.0,
            b2: 0.0,
        }
    }

    /// Whether the walk kept a triangle.
    // Mirror of src/tracer/traversal/hit.wgsl::is_hit for a mesh walk's nearest triangle — change both.
    pub fn is_hit(&self) -> bool {
        self.local != NO_ITEM
    }
}

/// Up to [`LANES`] mesh-local triangle numbers waiting for one four-lane test, in the
/// order the cell lists them.
pub struct TriangleBatch {
    locals: [u32; LANES],
    len: usize,
}

impl TriangleBatch {
    pub const EMPTY: TriangleBatch = TriangleBatch {
        locals: [0; LANES],
        len: 0,
    };

    /// Adds a triangle; true when the batch is now full (test it before the next push).
    #[inline(always)]
    pub fn push(&mut self, local: u32) -> bool {
        self.locals[self.len & (LANES - 1)] = local;
        self.len += 1;
        self.len == LANES
    }

    /// The batch's triangles, lanes past its length repeating the first (their answers
    /// are masked off).
    #[inline(always)]
    fn lanes<'a>(&self, triangles: &'a [PackedTriangle]) -> [&'a PackedTriangle; LANES] {
        let at = |k: usize| &triangles[self.locals[if k < self.len { k } else { 0 }] as usize];
        [at(0), at(1), at(2), at(3)]
    }

    /// The hit bits of the batch's own lanes, then empties it.
    #[inline(always)]
    fn test(
        &mut self,
        rays: &TriangleRays,
        triangles: &[PackedTriangle],
        t_max: f32,
    ) -> (u32, Vec4) {
        let (hits, t) = intersect_triangles4(&rays.lanes, &self.lanes(triangles), t_max);
        let own = (1u32 << self.len) - 1;
        self.len = 0;
        (hits & own, t)
    }

    /// Whether one of the batch's triangles is hit in (0, t_max); empties the batch. A
    /// single triangle takes the lanes too (its own in all four): since the loads are
    /// transposed rows, that costs less than the scalar test, which reads coordinates by a
    /// runtime axis and exits on the edge signs by a branch no predictor learns (10⁶
    /// random triangles, about one per cell: shadow rays −15%, one thread).
    #[inline(always)]
    pub fn any_hit(
        &mut self,
        rays: &TriangleRays,
        triangles: &[PackedTriangle],
        t_max: f32,
    ) -> bool {
        match self.len {
            0 => false,
            _ => self.test(rays, triangles, t_max).0 != 0,
        }
    }

    /// Keeps in `best` the nearest hit below `best.t` among the batch's triangles (the
    /// first in order on a tie, as the scalar loop's strict `<`); empties the batch. The
    /// kept triangle is tested again by the scalar test, whose barycentrics it keeps
    /// (see the file's header).
    #[inline(always)]
    pub fn keep_nearest(
        &mut self,
        rays: &TriangleRays,
        triangles: &[PackedTriangle],
        best: &mut NearestTriangle,
    ) {
        let nearest = match self.len {
            0 => return,
            len => {
                let (hits, t) = self.test(rays, triangles, best.t);
                if hits == 0 {
                    return;
                }
                let t = t.to_array();
                let mut nearest = 0;
                for k in 1..len {
                    if hits & (1 << k) != 0 && (hits & (1 << nearest) == 0 || t[k] < t[nearest]) {
                        nearest = k;
                    }
                }
                self.locals[nearest]
            }
        };
        self.len = 0;
        let [p0, p1, p2] = triangle_vertices(&triangles[nearest as usize]);
        let h = intersect_triangle(&rays.scalar, p0, p1, p2, best.t);
        if h.x < best.t {
            *best = NearestTriangle {
                t: h.x,
                local: nearest,
                b1: h.y,
                b2: h.z,
            };
        }
    }
}
