//! Numerical stress test of the f32 ray–torus intersection (`tracer::geometry::torus`) against an f64
//! oracle, in the style of `intersect_oracle.rs`: seeded tori at all scales (1e-3..1e4,
//! log-uniform), tube ratios rout/rin from 0.02 to 2 (spindle tori included), random
//! rotations and placements, rays from up to 1e4 sizes away, and the hard families:
//! rays tangent to the tube, through the hole, along the axis, in the torus plane, and
//! rays leaving the surface.
//!
//! The oracle: in f64, move the origin to the ray's closest approach to the centre and
//! sample F(p) = ((ρ−R)² + z² − r²)·((ρ+R)² + z² − r²) (the torus's quartic, factored so
//! it does not cancel near the surface) at 1024 points along the bounding sphere's
//! chord, then bisect the first sign change to the last bit. Two roots closer than a
//! sample spacing (≈ 0.002 of the size) are missed, which happens only within ~1e-5 of
//! the size from tangency: inside the grazing band below.
//!
//! A ray is "grazing" (skipped from the agreement count, but still checked for a legal
//! result) when its answer changes between the torus with the tube grown and shrunk by
//! the margin (1e-4 of the size, plus the f32 floor of the coordinates: any f32 tracer
//! places the ray only to a few ulps of the origin's magnitude), or its hit is within
//! the margin of t_max. Seeds are in the messages.

use crate::oracle_support;
use oracle_support::*;

use glam::{DMat4, DVec3, Vec3};
use glint::constants::T_MISS;
use glint::pack::{pack, PackedInstance, PackedScene};
use glint::scene::flatten::{FlatScene, Object, ObjectKind};
use glint::scene::{Camera, GridMode, Material, RenderOptions};
use glint::tracer::base::ray::offset_ray;
use glint::tracer::geometry::intersect::intersect_instance;
use glint::tracer::shading::surface::surface_at;
use glint::tracer::traversal::traverse::{hit_miss, Hit};

// ---------------------------------------------------------------------------------------
// The f64 oracle.

/// The torus's implicit function, factored (negative inside the solid).
fn torus_f(p: DVec3, rin: f64, rout: f64) -> f64 {
    let rho = (p.x * p.x + p.y * p.y).sqrt();
    let q = ((rho - rin) * (rho - rin) + p.z * p.z).sqrt();
    let far = (rho + rin) * (rho + rin) + p.z * p.z - rout * rout;
    (q - rout) * (q + rout) * far
}

/// First t in (t_min, t_max) where o + t·d (object space, f64) crosses the torus.
fn oracle_root(o: DVec3, d: DVec3, rin: f64, rout: f64, t_min: f64, t_max: f64) -> Option<f64> {
    if rout <= 0.0 {
        return None;
    }
    let speed = d.length();
    let dn = d / speed;
    // Closest approach to the centre, and the bounding sphere's chord around it.
    let s_c = -o.dot(dn);
    let c = o + dn * s_c;
    let bound = (rin + rout) * 1.001;
    let h2 = bound * bound - c.length_squared();
    if h2 <= 0.0 {
        return None;
    }
    let h = h2.sqrt();
    // u is the parameter from c: s = s_c + u, t = s / speed.
    let u_lo = (-h).max(t_min * speed - s_c);
    let u_hi = h.min(t_max * speed - s_c);
    if u_lo >= u_hi {
        return None;
    }
    const N: usize = 1024;
    let f = |u: f64| torus_f(c + dn * u, rin, rout);
    let mut a = u_lo;
    let mut fa = f(a);
    for i in 1..=N {
        let b = u_lo + (u_hi - u_lo) * (i as f64 / N as f64);
        let fb = f(b);
        if (fa < 0.0) != (fb < 0.0) {
            let (mut lo, mut hi, lo_negative) = (a, b, fa < 0.0);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                if (f(mid) < 0.0) == lo_negative {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let t = (s_c + 0.5 * (lo + hi)) / speed;
            return (t > t_min && t < t_max).then_some(t);
        }
        a = b;
        fa = fb;
    }
    None
}

/// See `oracle`: hits whose t moves by more than this many margins when the tube grows
/// or shrinks by one margin count as grazing.
const JUMP: f64 = 100.0;

#[allow(clippy::too_many_arguments)]
fn oracle(
    o: DVec3,
    d: DVec3,
    rin: f64,
    rout: f64,
    t_min: f64,
    t_max: f64,
    margin: f64,
    floor: f64,
) -> Oracle {
    let t = oracle_root(o, d, rin, rout, t_min, t_max);
    let grown = oracle_root(o, d, rin, rout + margin, t_min, t_max);
    let shrunk = oracle_root(o, d, rin, rout - margin, t_min, t_max);
    let speed = d.length();
    // The answer jumps (a silhouette, or a nicked tube before a farther hit): it moves
    // by more than JUMP × the margin between grown and shrunk (at normal incidence it
    // moves by 2×; JUMP/2 is 1/|cos| of the steepest incidence counted).
    let jumps = match (grown, shrunk) {
        (Some(a), Some(b)) => (a - b).abs() * speed > JUMP * margin,
        (None, None) => false,
        _ => true,
    };
    let near_t_max = t.is_some_and(|t| (t - t_max).abs() <= 1e-4 * t + floor);
    // Incidence at the hit (object space; the torus's gradient is the normal).
    let cos = t.map_or(1.0, |t| {
        let p = o + d * t;
        let g = p * (p.length_squared() + rin * rin - rout * rout)
            - DVec3::new(p.x, p.y, 0.0) * (2.0 * rin * rin);
        (g.normalize().dot(d / speed)).abs().max(1e-3)
    });
    Oracle {
        t,
        grazing: jumps || near_t_max,
        floor: floor / cos,
    }
}

// ---------------------------------------------------------------------------------------
// Scenes and rays.

fn pack_torus(rin: f64, rout: f64, m: DMat4) -> PackedScene {
    pack(&FlatScene {
        objects: vec![Object {
            name: String::from("torus"),
            kind: ObjectKind::Torus {
                rin: rin as f32,
                rout: rout as f32,
            },
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
            grid: GridMode::Off,
            ..RenderOptions::default()
        },
    })
    .expect("pack")
}

/// A random torus: (rin, rout, object-to-world, size = world bounding radius).
fn random_torus(rng: &mut Rng) -> (f64, f64, DMat4, f64) {
    let s = rng.log_uniform(1e-3, 1e4);
    let rin = 1.0;
    // Mostly ring tori, some spindles.
    let rout = if rng.f64() < 0.85 {
        rng.log_uniform(0.02, 0.9)
    } else {
        rng.range(1.0, 2.0)
    };
    let aniso = if rng.f64() < 0.5 {
        DVec3::ONE
    } else {
        DVec3::new(
            rng.log_uniform(0.5, 2.0),
            rng.log_uniform(0.5, 2.0),
            rng.log_uniform(0.5, 2.0),
        )
    };
    let size = s * (rin + rout);
    let centre = rng.unit_vector() * (size * rng.range(0.0, 3.0));
    let m = DMat4::from_scale_rotation_translation(aniso * s, rng.rotation(), centre);
    (rin, rout, m, size)
}

/// Hits more than a tenth and misses more than a twentieth of the checked rays.
const HITS_AND_MISSES: MinMix = MinMix {
    hits: 10,
    misses: 20,
};

/// Ray families.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Family {
    /// From 1e-2..1e4 sizes away towards a random point near the torus.
    Random,
    /// Tangent to the tube (through a point a hair outside a random surface point, along
    /// a tangent).
    Tangent,
    /// Through the hole, at a random angle.
    Hole,
    /// Along the axis (or nearly).
    Axis,
    /// In the torus plane.
    Plane,
}

/// World ray (f32 origin, unit f32 direction), t_max and t_min for one family, with the
/// object-space target point the ray is aimed at.
fn family_ray(
    rng: &mut Rng,
    family: Family,
    rin: f64,
    rout: f64,
    m: &DMat4,
    size: f64,
) -> (Vec3, Vec3, f32) {
    let dist = size * rng.log_uniform(1e-2, 1e4);
    let (target_obj, dir_obj) = match family {
        Family::Random => (
            DVec3::new(
                rng.range(-1.3, 1.3) * (rin + rout),
                rng.range(-1.3, 1.3) * (rin + rout),
                rng.range(-1.5, 1.5) * rout,
            ),
            None,
        ),
        Family::Tangent => {
            let theta = rng.range(0.0, std::f64::consts::TAU);
            let phi = rng.range(0.0, std::f64::consts::TAU);
            let radial = DVec3::new(theta.cos(), theta.sin(), 0.0);
            let n = radial * phi.cos() + DVec3::Z * phi.sin();
            let p = radial * rin + n * rout;
            // A tangent direction: random in the plane perpendicular to n.
            let t = rng.unit_vector();
            let tangent = (t - n * t.dot(n)).normalize();
            (p + n * (rout * rng.range(-1e-3, 1e-3)), Some(tangent))
        }
        Family::Hole => {
            let r = (rin - rout).abs() * rng.range(0.0, 0.9);
            let a = rng.range(0.0, std::f64::consts::TAU);
            (DVec3::new(r * a.cos(), r * a.sin(), 0.0), None)
        }
        Family::Axis => {
            let jitter = DVec3::new(rng.range(-1e-3, 1e-3), rng.range(-1e-3, 1e-3), 1.0);
            let sign = if rng.f64() < 0.5 { 1.0 } else { -1.0 };
            (
                DVec3::new(rng.range(-0.1, 0.1), rng.range(-0.1, 0.1), 0.0) * rin,
                Some(jitter.normalize() * sign),
            )
        }
        Family::Plane => {
            let a = rng.range(0.0, std::f64::consts::TAU);
            let r = rng.range(0.0, 1.2) * (rin + rout);
            let b = rng.range(0.0, std::f64::consts::TAU);
            (
                DVec3::new(r * a.cos(), r * a.sin(), 0.0),
                Some(DVec3::new(b.cos(), b.sin(), 0.0)),
            )
        }
    };
    let target = m.transform_point3(target_obj);
    let dir = match dir_obj {
        Some(d) => m.transform_vector3(d).normalize(),
        None => rng.unit_vector(),
    };
    let origin = target - dir * dist;
    let o = origin.as_vec3();
    let d = (target.as_vec3().as_dvec3() - o.as_dvec3())
        .normalize()
        .as_vec3()
        .normalize();
    let t_max = if rng.f64() < 0.3 {
        (dist * rng.range(0.3, 3.0)) as f32
    } else {
        T_MISS
    };
    (o, d, t_max)
}

fn object_ray(m: &DMat4, o: Vec3, d: Vec3) -> (DVec3, DVec3) {
    let inv = m.inverse();
    (
        inv.transform_point3(o.as_dvec3()),
        inv.transform_vector3(d.as_dvec3()),
    )
}

/// A lower bound of the smallest world length of a unit object vector (1 / the
/// Frobenius norm of the inverse's linear part), for conservative object-space margins.
fn min_scale(m: &DMat4) -> f64 {
    let inv = glam::DMat3::from_mat4(m.inverse());
    let frobenius =
        (inv.x_axis.length_squared() + inv.y_axis.length_squared() + inv.z_axis.length_squared())
            .sqrt();
    1.0 / frobenius
}

const CASES: u64 = 1200;
const RAYS_PER_CASE: usize = 30;

fn run_family(family: Family, salt: u64) -> Agreement {
    let mut stats = Agreement::default();
    for i in 0..CASES {
        let seed = case_seed(salt, i);
        let mut rng = Rng(seed);
        let (rin, rout, m, size) = random_torus(&mut rng);
        let packed = pack_torus(rin, rout, m);
        let inst: &PackedInstance = &packed.instances[0];
        // The tracer sees the f32 radii: so does the oracle.
        let (rin, rout) = (inst.params[0] as f64, inst.params[1] as f64);
        let shrink = min_scale(&m);
        let extent = m.w_axis.truncate().abs().max_element() + size * 4.0;
        for _ in 0..RAYS_PER_CASE {
            let (o, d, t_max) = family_ray(&mut rng, family, rin, rout, &m, size);
            let t = intersect_instance(inst, o, d, t_max);
            assert!(
                t == T_MISS || (t > 0.0 && t < t_max),
                "{family:?}: illegal t {t} (t_max {t_max}, seed {seed:#x})"
            );
            let (oo, od) = object_ray(&m, o, d);
            let floor = 8.0 * f32::EPSILON as f64 * o.as_dvec3().abs().max_element().max(extent);
            let margin = (1e-4 * size + floor) / shrink;
            let oracle = oracle(oo, od, rin, rout, 0.0, t_max as f64, margin, floor);
            stats.record(seed, &oracle, t, || {
                format!("rin {rin}, rout {rout}, size {size:e}, o {o}, d {d}, t_max {t_max}, object o {oo} d {od}")
            });
        }
    }
    stats
}

#[test]
fn torus_random_rays_agree_with_oracle() {
    run_family(Family::Random, 0x7012_5000).check(
        "torus, random rays",
        "salt 0x70125000",
        Some(HITS_AND_MISSES),
    );
}

#[test]
fn torus_hard_rays_agree_with_oracle() {
    for (family, salt, min_hits) in [
        (Family::Tangent, 0x7012_5001, false),
        (Family::Hole, 0x7012_5002, false),
        (Family::Axis, 0x7012_5003, false),
        (Family::Plane, 0x7012_5004, true),
    ] {
        run_family(family, salt).check(
            &format!("torus, {family:?}"),
            &format!("salt {salt:#x}"),
            min_hits.then_some(HITS_AND_MISSES),
        );
    }
}

/// Rays leaving the surface (origin moved off by `offset_ray`, as the tracer does),
/// outward within 87° of the normal: they must not hit the torus at the origin again,
/// and must agree with the oracle on hitting it elsewhere (it is not convex).
#[test]
fn torus_rays_leaving_the_surface() {
    let mut stats = Agreement::default();
    let mut self_hits = 0;
    for i in 0..CASES {
        let seed = case_seed(0x7012_5005, i);
        let mut rng = Rng(seed);
        let (rin, rout, m, size) = random_torus(&mut rng);
        let packed = pack_torus(rin, rout, m);
        let inst = &packed.instances[0];
        let (rin, rout) = (inst.params[0] as f64, inst.params[1] as f64);
        let shrink = min_scale(&m);
        for _ in 0..RAYS_PER_CASE {
            // A hit on the torus from a random ray, then its surface as the tracer sees it.
            let (o, d, _) = family_ray(&mut rng, Family::Random, rin, rout, &m, size);
            let t = intersect_instance(inst, o, d, T_MISS);
            if t == T_MISS {
                continue;
            }
            let ray = glint::tracer::base::ray::Ray { origin: o, dir: d };
            let hit = Hit {
                t,
                item: 0,
                ..hit_miss()
            };
            let s = surface_at(&packed, &ray, &hit);
            let n = s.normal.as_dvec3();
            let dir = loop {
                let v = rng.unit_vector();
                let v = if v.dot(n) < 0.0 { -v } else { v };
                if v.dot(n) > 0.05 {
                    break v;
                }
            };
            let origin = offset_ray(s.p, s.normal, s.magnitude);
            let d2 = dir.as_vec3().normalize();
            let t2 = intersect_instance(inst, origin, d2, T_MISS);
            let (oo, od) = object_ray(&m, origin, d2);
            let floor = 8.0 * f32::EPSILON as f64 * origin.as_dvec3().abs().max_element().max(size);
            let margin = (1e-4 * size + floor) / shrink;
            // Roots nearer than a few margins are the surface the ray leaves.
            let t_min = 8.0 * (1e-4 * size + floor);
            if t2 != T_MISS && (t2 as f64) < t_min {
                self_hits += 1;
            }
            let oracle = oracle(oo, od, rin, rout, t_min, f32::MAX as f64, margin, floor);
            stats.record(
                seed,
                &oracle,
                if (t2 as f64) < t_min { T_MISS } else { t2 },
                || format!("rin {rin}, rout {rout}, size {size:e}, from {origin} along {d2}"),
            );
        }
    }
    println!("self-hits: {self_hits}");
    stats.check("torus, leaving the surface", "leaving rays", None);
    assert!(
        self_hits as f64 <= 1e-4 * stats.rays as f64,
        "{self_hits} of {} leaving rays hit the surface they leave",
        stats.rays
    );
}
