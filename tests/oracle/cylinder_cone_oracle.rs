//! Numerical stress tests of the f32 cylinder and cone intersections against f64 oracles,
//! in the style of `intersect_oracle.rs` (pbrt-v4's `shapes_test.cpp`): seeded random
//! shapes at all scales (1e-3..1e4, log-uniform, anisotropic), random rotations and
//! placements, rays from up to 1e4 sizes away, axis-parallel rays, rays through the tip,
//! origins on the surface, and rays leaving the surface.
//!
//! Every assertion message carries the seed of its case; rerun one case by calling the
//! case function with that seed.

use crate::oracle_support;
use oracle_support::*;

use glam::{DMat4, DVec3, Vec3};
use glint::constants::T_MISS;
use glint::pack::{pack, PackedScene};
use glint::scene::flatten::{FlatScene, Object, ObjectKind};
use glint::scene::{Camera, GridMode, Material, RenderOptions};
use glint::tracer::base::ray::{offset_ray, Ray};
use glint::tracer::geometry::cylinder_cone::{
    cone_surface, cylinder_surface, intersect_cone, intersect_cylinder,
};
use glint::tracer::geometry::intersect::intersect_instance;
use glint::tracer::shading::surface::surface_at;
use glint::tracer::traversal::traverse::{hit_miss, Hit};

// ---------------------------------------------------------------------------------------
// Seeded randomness (splitmix64), as in intersect_oracle.rs.

// ---------------------------------------------------------------------------------------
// Scenes and rays.

fn pack_one(kind: ObjectKind, m: DMat4) -> PackedScene {
    let scene = FlatScene {
        objects: vec![Object {
            name: String::from("shape"),
            kind,
            object_to_world: m,
            material: 0,
        }],
        triangles: Vec::new(),
        meshes: Vec::new(),
        mesh_instances: Vec::new(),
        csg: Vec::new(),
        materials: vec![Material::default()],
        textures: Vec::new(),
        lights: Vec::new(),
        camera: Camera {
            eye: DVec3::new(0.0, 0.0, 10.0),
            view: DVec3::NEG_Z,
            up: DVec3::Y,
            fov_deg: 50.0,
        },
        ambient: [0.0; 3],
        width: 8,
        height: 8,
        options: RenderOptions {
            grid: GridMode::Auto,
            ..RenderOptions::default()
        },
    };
    pack(&scene).expect("pack")
}

/// translate · rotate · scale: base scale log-uniform in 1e-3..1e4, per-axis anisotropy
/// in [1/2, 2], centre up to 3 sizes from the origin. Returns the matrix and the scale.
fn random_transform(rng: &mut Rng) -> (DMat4, f64) {
    let s = rng.log_uniform(1e-3, 1e4);
    let scale = DVec3::new(
        s * rng.log_uniform(0.5, 2.0),
        s * rng.log_uniform(0.5, 2.0),
        s * rng.log_uniform(0.5, 2.0),
    );
    let centre = rng.unit_vector() * (s * rng.range(0.0, 3.0));
    (
        DMat4::from_scale_rotation_translation(scale, rng.rotation(), centre),
        s,
    )
}

/// A random cone: zmin ≥ 0 (half the cases, a quarter of those with the tip at zmin = 0),
/// zmax ≤ 0 (a sixth), or a double cone zmin < 0 < zmax (a third).
fn random_cone(rng: &mut Rng) -> ObjectKind {
    let (zmin, zmax) = match rng.below(6) {
        0..=2 => {
            let zmin = if rng.f64() < 0.25 {
                0.0
            } else {
                rng.range(0.0, 2.0)
            };
            (zmin, zmin + rng.log_uniform(0.05, 3.0))
        }
        3 => {
            let zmax = if rng.f64() < 0.25 {
                0.0
            } else {
                -rng.range(0.0, 2.0)
            };
            (zmax - rng.log_uniform(0.05, 3.0), zmax)
        }
        _ => (-rng.range(0.1, 2.0), rng.range(0.1, 2.0)),
    };
    ObjectKind::Cone {
        zmin: zmin as f32,
        zmax: zmax as f32,
    }
}

// ---------------------------------------------------------------------------------------
// f64 oracle. A shape is a union of convex pieces, each {quadric ≤ 0} ∩ {zlo ≤ z ≤ zhi};
// the nearest hit is the nearest end in (0, t_max) of the pieces' t-intervals. The shape
// grown and shrunk by the margin decide "grazing" (as the box oracle does): the answer
// changes between them (silhouettes, rims, the tip) or the origin lies between them.

#[derive(Clone, Copy)]
enum Quadric {
    /// x² + y² ≤ r².
    Cylinder(f64),
    /// x² + y² ≤ (z − apex)², on the nappe the slab selects.
    Cone(f64),
}

#[derive(Clone, Copy)]
struct Piece {
    quadric: Quadric,
    zlo: f64,
    zhi: f64,
}

/// The t-intervals where a·t² + 2b·t + c ≤ 0.
fn below_zero(a: f64, b: f64, c: f64) -> Vec<(f64, f64)> {
    let inf = f64::INFINITY;
    if a == 0.0 {
        return if b > 0.0 {
            vec![(-inf, -c / (2.0 * b))]
        } else if b < 0.0 {
            vec![(-c / (2.0 * b), inf)]
        } else if c <= 0.0 {
            vec![(-inf, inf)]
        } else {
            vec![]
        };
    }
    let disc = b * b - a * c;
    if disc < 0.0 {
        return if a > 0.0 { vec![] } else { vec![(-inf, inf)] };
    }
    let q = -b - disc.sqrt().copysign(b);
    let (r0, r1) = if q == 0.0 {
        (0.0, 0.0)
    } else {
        ((c / q).min(q / a), (c / q).max(q / a))
    };
    if a > 0.0 {
        vec![(r0, r1)]
    } else {
        vec![(-inf, r0), (r1, inf)]
    }
}

impl Piece {
    fn intervals(&self, o: DVec3, d: DVec3) -> Vec<(f64, f64)> {
        if self.zlo > self.zhi {
            return vec![];
        }
        // Shift the origin to the line's point nearest (0, 0, apex or 0), as the tracer
        // does, so even f64 keeps its precision for origins 1e4 sizes away.
        let centre = match self.quadric {
            Quadric::Cylinder(_) => DVec3::new(0.0, 0.0, 0.5 * (self.zlo + self.zhi)),
            Quadric::Cone(apex) => DVec3::new(0.0, 0.0, apex),
        };
        let shift = (centre - o).dot(d) / d.dot(d);
        let os = o + d * shift;
        let (a, b, c) = match self.quadric {
            Quadric::Cylinder(r) => (
                d.x * d.x + d.y * d.y,
                os.x * d.x + os.y * d.y,
                os.x * os.x + os.y * os.y - r * r,
            ),
            Quadric::Cone(apex) => {
                let z = os.z - apex;
                (
                    d.x * d.x + d.y * d.y - d.z * d.z,
                    os.x * d.x + os.y * d.y - z * d.z,
                    os.x * os.x + os.y * os.y - z * z,
                )
            }
        };
        let (slab_lo, slab_hi) = if d.z == 0.0 {
            if os.z < self.zlo || os.z > self.zhi {
                return vec![];
            }
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            let (t0, t1) = ((self.zlo - os.z) / d.z, (self.zhi - os.z) / d.z);
            (t0.min(t1), t0.max(t1))
        };
        below_zero(a, b, c)
            .into_iter()
            .map(|(lo, hi)| (lo.max(slab_lo) + shift, hi.min(slab_hi) + shift))
            .filter(|(lo, hi)| lo <= hi)
            .collect()
    }

    fn contains(&self, p: DVec3) -> bool {
        let f = match self.quadric {
            Quadric::Cylinder(r) => p.x * p.x + p.y * p.y - r * r,
            Quadric::Cone(apex) => p.x * p.x + p.y * p.y - (p.z - apex) * (p.z - apex),
        };
        f <= 0.0 && p.z >= self.zlo && p.z <= self.zhi
    }
}

/// The pieces of a shape offset by `m` (object units; negative shrinks).
fn pieces(kind: ObjectKind, m: f64) -> Vec<Piece> {
    match kind {
        ObjectKind::Cylinder => vec![Piece {
            quadric: Quadric::Cylinder(1.0 + m),
            zlo: -m,
            zhi: 1.0 + m,
        }],
        ObjectKind::Cone { zmin, zmax } => {
            let (zmin, zmax) = (zmin as f64, zmax as f64);
            // A nappe offset by m along its normal is the nappe with its apex moved by
            // m·√2 along the axis.
            let k = m * std::f64::consts::SQRT_2;
            let mut out = Vec::new();
            if zmax > 0.0 {
                out.push(Piece {
                    quadric: Quadric::Cone(-k),
                    zlo: (zmin - m).max(-k),
                    zhi: zmax + m,
                });
            }
            if zmin < 0.0 {
                out.push(Piece {
                    quadric: Quadric::Cone(k),
                    zlo: zmin - m,
                    zhi: (zmax + m).min(k),
                });
            }
            out
        }
        _ => unreachable!(),
    }
}

fn nearest_end(pieces: &[Piece], o: DVec3, d: DVec3, t_max: f64) -> Option<f64> {
    pieces
        .iter()
        .flat_map(|p| p.intervals(o, d))
        .flat_map(|(lo, hi)| [lo, hi])
        .filter(|&t| t > 0.0 && t < t_max)
        .min_by(|a, b| a.total_cmp(b))
}

fn oracle(kind: ObjectKind, o: DVec3, d: DVec3, t_max: f64, margin: f64, floor: f64) -> Oracle {
    let exact = pieces(kind, 0.0);
    let grown = pieces(kind, margin);
    let shrunk = pieces(kind, -margin);
    let t = nearest_end(&exact, o, d, t_max);
    let hits = |p: &[Piece]| nearest_end(p, o, d, f64::INFINITY).is_some();
    let inside = |p: &[Piece]| p.iter().any(|p| p.contains(o));
    let near_t_max = t.is_some_and(|t| (t - t_max).abs() <= MARGIN * t + floor);
    // The tip is a singular point (a "rim" of zero radius): a ray through it may count it
    // as a hit or not (the double cone's nappes touch there).
    let near_tip = matches!(kind, ObjectKind::Cone { .. }) && {
        let t_tip = (-o.dot(d) / d.dot(d)).max(0.0);
        (o + d * t_tip).length() < margin
    };
    Oracle {
        t,
        grazing: hits(&grown) != hits(&shrunk)
            || (inside(&grown) && !inside(&shrunk))
            || near_t_max
            || near_tip,
        floor,
    }
}

/// Largest |object coordinate| of a shape (≥ 1).
fn extent(kind: ObjectKind) -> f64 {
    match kind {
        ObjectKind::Cone { zmin, zmax } => 1f64.max(zmin.abs() as f64).max(zmax.abs() as f64),
        _ => 1.0,
    }
}

// ---------------------------------------------------------------------------------------
// 1. Agreement with the oracle.

/// Hits and misses each more than a tenth of the checked rays.
const BOTH_TENTHS: MinMix = MinMix {
    hits: 10,
    misses: 10,
};

const CASES: u64 = 1600;
const RAYS_PER_CASE: usize = 25;

/// One random shape and `RAYS_PER_CASE` rays at it: most from far (1e-2..1e4 sizes, so
/// some start inside), some parallel to the axis, some through the tip, some from a point
/// on the surface; t_max finite for 30%.
fn case(cone: bool, seed: u64, stats: &mut Agreement) {
    let mut rng = Rng(seed);
    let kind = if cone {
        random_cone(&mut rng)
    } else {
        ObjectKind::Cylinder
    };
    let (m, scale) = random_transform(&mut rng);
    let ext = extent(kind);
    let size = scale * ext;
    let packed = pack_one(kind, m);
    let inst = &packed.instances[0];
    let inv = m.inverse();
    let min_scale = m
        .x_axis
        .length()
        .min(m.y_axis.length())
        .min(m.z_axis.length());
    let world_extent = mag(m.w_axis.truncate())
        + 2.0
            * ext
            * m.x_axis
                .length()
                .max(m.y_axis.length())
                .max(m.z_axis.length());
    let (zlo, zhi) = match kind {
        ObjectKind::Cone { zmin, zmax } => (zmin as f64, zmax as f64),
        _ => (0.0, 1.0),
    };
    let h = zhi - zlo;
    for _ in 0..RAYS_PER_CASE {
        let target_obj = DVec3::new(
            rng.range(-1.3, 1.3) * ext,
            rng.range(-1.3, 1.3) * ext,
            rng.range(zlo - 0.3 * h, zhi + 0.3 * h),
        );
        let target = m.transform_point3(target_obj);
        let (o, d) = match rng.below(10) {
            // Parallel to the axis (in object space; exact in f32 only up to rounding).
            0 => {
                let axis = m.transform_vector3(DVec3::Z).normalize();
                let sign = if rng.f64() < 0.5 { 1.0 } else { -1.0 };
                let dist = size * rng.log_uniform(1e-2, 1e4);
                (v32(target - axis * sign * dist), v32(axis * sign))
            }
            // Through the tip (cones) or the axis.
            1 => {
                let tip = m.transform_point3(DVec3::ZERO);
                let origin = tip + rng.unit_vector() * size * rng.log_uniform(1e-2, 1e4);
                aim(origin, tip)
            }
            // From a point on the surface (the exact hit of a random ray, rounded).
            2 => {
                let origin = target + rng.unit_vector() * size * rng.log_uniform(3.0, 30.0);
                let (o0, d0) = aim(origin, target);
                let (oo, od) = (
                    inv.transform_point3(v64(o0)),
                    inv.transform_vector3(v64(d0)),
                );
                match nearest_end(&pieces(kind, 0.0), oo, od, f64::INFINITY) {
                    Some(t) => (v32(v64(o0) + v64(d0) * t), v32(rng.unit_vector())),
                    None => (o0, d0),
                }
            }
            _ => aim(
                target + rng.unit_vector() * size * rng.log_uniform(1e-2, 1e4),
                target,
            ),
        };
        let dist = (v64(o) - target).length();
        let t_max = if rng.f64() < 0.3 {
            (dist * rng.range(0.3, 3.0)) as f32
        } else {
            T_MISS
        };
        let t = intersect_instance(inst, o, d, t_max);
        assert_legal_t(t, t_max, "intersect_instance", seed);
        let (oo, od) = (inv.transform_point3(v64(o)), inv.transform_vector3(v64(d)));
        let floor = f32_floor(mag(v64(o)).max(world_extent));
        let margin = (MARGIN * size + floor) / min_scale;
        let oracle = oracle(kind, oo, od, t_max as f64, margin, floor);
        stats.record(seed, &oracle, t, || {
            format!("{kind:?}, scale {scale:e}, o {o}, d {d}, t_max {t_max}, object o {oo}, d {od}")
        });
    }
}

#[test]
fn cylinder_agrees_with_f64_oracle() {
    let salt = 0xC1_11DE;
    let mut stats = Agreement::default();
    for i in 0..CASES {
        case(false, case_seed(salt, i), &mut stats);
    }
    stats.check("cylinder", &format!("salt {salt:#x}"), Some(BOTH_TENTHS));
}

#[test]
fn cone_agrees_with_f64_oracle() {
    let salt = 0xC0_7E;
    let mut stats = Agreement::default();
    for i in 0..CASES {
        case(true, case_seed(salt, i), &mut stats);
    }
    stats.check("cone", &format!("salt {salt:#x}"), Some(BOTH_TENTHS));
}

// ---------------------------------------------------------------------------------------
// 2. Exactly axis-parallel rays, rays exactly through the tip, rays in the cap planes:
//    never NaN, never a t outside (0, t_max); where unambiguous, the oracle's answer.

#[test]
fn degenerate_rays_are_legal_and_exact() {
    let salt = 0xDE6E_C0C1;
    let mut checked = 0usize;
    for i in 0..4000u64 {
        let seed = case_seed(salt, i);
        let mut rng = Rng(seed);
        let kind = if i % 2 == 0 {
            ObjectKind::Cylinder
        } else {
            random_cone(&mut rng)
        };
        let (zlo, zhi) = match kind {
            ObjectKind::Cone { zmin, zmax } => (zmin, zmax),
            _ => (0.0, 1.0),
        };
        let ext = extent(kind) as f32;
        let pick_z = |rng: &mut Rng| match rng.below(5) {
            0 => zlo,
            1 => zhi,
            2 => 0.0,
            _ => rng.range(zlo as f64 - 1.0, zhi as f64 + 1.0) as f32,
        };
        let (o, d) = match rng.below(3) {
            // Parallel to the axis, x and y exact.
            0 => {
                let o = Vec3::new(
                    (rng.range(-1.5, 1.5) * ext as f64) as f32,
                    [0.0, 1.0, -1.0, rng.range(-1.5, 1.5) as f32][rng.below(4)] * ext,
                    pick_z(&mut rng),
                );
                let dz = if rng.f64() < 0.5 { 1.0 } else { -1.0 };
                (o, Vec3::new(0.0, 0.0, dz))
            }
            // Exactly through the tip (the origin): o = −k·d.
            1 => {
                let d = v32(rng.unit_vector());
                (d * -(rng.range(0.5, 5.0) as f32), d)
            }
            // In a cap plane (d.z = 0, o.z a cap's z exactly).
            _ => {
                let mut d = v32(rng.unit_vector());
                d.z = 0.0;
                let o = Vec3::new(
                    (rng.range(-3.0, 3.0) * ext as f64) as f32,
                    (rng.range(-3.0, 3.0) * ext as f64) as f32,
                    pick_z(&mut rng),
                );
                (o, d.normalize_or(Vec3::X))
            }
        };
        let d = d * rng.log_uniform(1e-3, 1e3) as f32;
        let t_max = if rng.f64() < 0.5 {
            T_MISS
        } else {
            rng.range(0.1, 5.0) as f32
        };
        let t = match kind {
            ObjectKind::Cone { zmin, zmax } => intersect_cone(o, d, zmin, zmax, t_max),
            _ => intersect_cylinder(o, d, t_max),
        };
        assert!(
            !t.is_nan(),
            "{kind:?}: NaN for o {o}, d {d} (seed {seed:#x})"
        );
        assert_legal_t(t, t_max, &format!("{kind:?}"), seed);
        let margin = 1e-4 * ext as f64;
        let o_ = oracle(kind, v64(o), v64(d), t_max as f64, margin, 0.0);
        if !o_.grazing {
            checked += 1;
            match o_.t {
                None => assert_eq!(t, T_MISS, "{kind:?}: o {o}, d {d}, t_max {t_max} (seed {seed:#x})"),
                Some(t_ref) => assert!(
                    (t as f64 - t_ref).abs() <= 1e-5 * t_ref,
                    "{kind:?}: o {o}, d {d}, t_max {t_max}: expected {t_ref}, got {t} (seed {seed:#x})"
                ),
            }
        }
    }
    println!("degenerate rays: {checked} unambiguous rays agree with the oracle");
    assert!(checked > 1000);
}

// ---------------------------------------------------------------------------------------
// 3. Leaving a convex surface (the cylinder; the cone with zmin ≥ 0) never re-hits it.

fn leave_case(cone: bool, seed: u64, stats: &mut (usize, usize, Vec<String>)) {
    let mut rng = Rng(seed);
    let kind = if cone {
        let zmin = if rng.f64() < 0.3 {
            0.0
        } else {
            rng.range(0.0, 2.0)
        };
        ObjectKind::Cone {
            zmin: zmin as f32,
            zmax: (zmin + rng.log_uniform(0.05, 3.0)) as f32,
        }
    } else {
        ObjectKind::Cylinder
    };
    let (m, scale) = random_transform(&mut rng);
    let size = scale * extent(kind);
    let packed = pack_one(kind, m);
    let inst = &packed.instances[0];
    let (zlo, zhi) = match kind {
        ObjectKind::Cone { zmin, zmax } => (zmin as f64, zmax as f64),
        _ => (0.0, 1.0),
    };
    for _ in 0..5 {
        // A target inside: on the axis, at a random height.
        let target = m.transform_point3(DVec3::new(0.0, 0.0, rng.range(zlo, zhi)));
        let origin = target + rng.unit_vector() * (size * rng.log_uniform(3.0, 1e4));
        let (o, d) = aim(origin, target);
        let t = intersect_instance(inst, o, d, T_MISS);
        if t == T_MISS {
            continue;
        }
        let ray = Ray { origin: o, dir: d };
        let hit = Hit {
            t,
            item: 0,
            ..hit_miss()
        };
        let s = surface_at(&packed, &ray, &hit);
        let origin = offset_ray(s.p, s.normal, s.magnitude);
        stats.0 += 1;
        for k in 0..20 {
            let cos = if k < 3 {
                1e-4
            } else {
                rng.log_uniform(1e-4, 1.0)
            };
            let n = v64(s.normal);
            let (t1, t2) = n.any_orthonormal_pair();
            let phi = rng.range(0.0, std::f64::consts::TAU);
            let sin = (1.0 - cos * cos).max(0.0).sqrt();
            let dir = v32(n * cos + (t1 * phi.cos() + t2 * phi.sin()) * sin).normalize();
            let t2 = intersect_instance(inst, origin, dir, T_MISS);
            assert_legal_t(t2, T_MISS, "intersect_instance", seed);
            stats.1 += 1;
            if t2 != T_MISS && stats.2.len() < 8 {
                stats.2.push(format!(
                    "seed {seed:#x}: {kind:?} scale {scale:e}, hit p {} n {}, origin {origin}, \
                     dir {dir} (cos {cos:e}), got t {t2}",
                    s.p, s.normal
                ));
            }
        }
    }
}

fn run_leave(cone: bool, salt: u64, what: &str) {
    let mut stats = (0, 0, Vec::new());
    for i in 0..1000 {
        leave_case(cone, case_seed(salt, i), &mut stats);
    }
    println!(
        "{what}: {} surfaces, {} rays, {} failures",
        stats.0,
        stats.1,
        stats.2.len()
    );
    for e in &stats.2 {
        println!("  {e}");
    }
    assert!(stats.0 > 2000, "{what}: too few hits (salt {salt:#x})");
    assert!(stats.2.is_empty(), "{what} (salt {salt:#x}): {:?}", stats.2);
}

#[test]
fn rays_leaving_cylinder_never_rehit_it() {
    run_leave(false, 0x1EAF_C711, "cylinder, leaving outward");
}

#[test]
fn rays_leaving_cone_never_rehit_it() {
    run_leave(true, 0x1EAF_C07E, "cone (zmin ≥ 0), leaving outward");
}

// ---------------------------------------------------------------------------------------
// 4. Surfaces: points on the surface, unit outward normals, UVs in [0, 1], and a tangent
//    frame whose cross product is along the normal (±, caps included).

#[test]
fn surfaces_are_on_the_shape_with_consistent_frames() {
    let mut rng = Rng(0x5EF_ACE);
    for i in 0..4000 {
        let kind = if i % 2 == 0 {
            ObjectKind::Cylinder
        } else {
            random_cone(&mut rng)
        };
        let ext = extent(kind);
        let (zlo, zhi) = match kind {
            ObjectKind::Cone { zmin, zmax } => (zmin as f64, zmax as f64),
            _ => (0.0, 1.0),
        };
        let p = DVec3::new(
            rng.range(-1.2, 1.2) * ext,
            rng.range(-1.2, 1.2) * ext,
            rng.range(zlo - 0.1, zhi + 0.1),
        );
        let s = match kind {
            ObjectKind::Cone { zmin, zmax } => cone_surface(v32(p), zmin, zmax),
            _ => cylinder_surface(v32(p)),
        };
        let q = v64(s.p);
        let what = format!("{kind:?} at {p}: {s:?}");
        // On the boundary: inside the grown shape, outside the shrunk one.
        let tol = 1e-5 * ext;
        assert!(pieces(kind, tol).iter().any(|pc| pc.contains(q)), "{what}");
        assert!(
            !pieces(kind, -tol).iter().any(|pc| pc.contains(q)),
            "{what}"
        );
        assert!((s.normal.length() - 1.0).abs() < 1e-5, "{what}");
        assert!(
            (0.0..=1.0).contains(&s.uv.x) && (0.0..=1.0).contains(&s.uv.y),
            "{what}"
        );
        let cross = s.dpdu.cross(s.dpdv);
        if cross.length() > 1e-6 {
            assert!(cross.normalize().dot(s.normal).abs() > 0.999, "{what}");
        }
    }
}
