//! Numerical stress tests of the f32 intersection routines against f64 oracles, in the
//! style of pbrt-v4's `shapes_test.cpp`: seeded random shapes at all scales (1e-3..1e4,
//! log-uniform), random rotations and placements, rays from up to 1e4 sizes away.
//!
//! Every assertion message carries the seed of its case; rerun one case by calling the
//! case function with that seed.

use crate::oracle_support;
use oracle_support::*;

use glam::{DMat4, DQuat, DVec3, Vec3};
use glint::constants::T_MISS;
use glint::pack::{pack, PackedScene};
use glint::scene::flatten::{FlatScene, Object, ObjectKind, Triangle};
use glint::scene::{Camera, GridMode, Material, RenderOptions};
use glint::tracer::base::ray::{offset_ray, Ray};
use glint::tracer::geometry::intersect::{
    intersect_box, intersect_instance, intersect_sphere, intersect_triangle, triangle_ray_setup,
    triangle_vertices,
};
use glint::tracer::shading::surface::surface_at;
use glint::tracer::traversal::traverse::{closest_hit, hit_miss, Hit, NoCounters};

// ---------------------------------------------------------------------------------------
// Seeded randomness (splitmix64).

// ---------------------------------------------------------------------------------------
// Scenes, built the way the tracer gets them: `flatten::FlatScene` → `pack`.

fn scene(objects: Vec<Object>, triangles: Vec<Triangle>, grid: GridMode) -> FlatScene {
    FlatScene {
        objects,
        triangles,
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
            grid,
            ..RenderOptions::default()
        },
    }
}

fn object(kind: ObjectKind, object_to_world: DMat4) -> Object {
    Object {
        name: String::from("shape"),
        kind,
        object_to_world,
        material: 0,
    }
}

fn pack_one(kind: ObjectKind, m: DMat4) -> PackedScene {
    pack(&scene(vec![object(kind, m)], Vec::new(), GridMode::Auto)).expect("pack")
}

/// A random placement: translate · rotate · scale, base scale log-uniform in 1e-3..1e4,
/// per-axis anisotropy in [1/2, 2] when `anisotropic`, centre up to 3 sizes from the origin.
/// Returns the matrix and the base scale ("size").
fn random_transform(rng: &mut Rng, anisotropic: bool) -> (DMat4, f64) {
    let s = rng.log_uniform(1e-3, 1e4);
    let scale = if anisotropic {
        DVec3::new(
            s * rng.log_uniform(0.5, 2.0),
            s * rng.log_uniform(0.5, 2.0),
            s * rng.log_uniform(0.5, 2.0),
        )
    } else {
        DVec3::splat(s)
    };
    let centre = rng.unit_vector() * (s * rng.range(0.0, 3.0));
    (
        DMat4::from_scale_rotation_translation(scale, rng.rotation(), centre),
        s,
    )
}

// ---------------------------------------------------------------------------------------
// f64 oracles. Each returns the nearest t in (0, t_max) (None = miss) and whether the ray
// is "grazing": within `margin` of a silhouette or edge, starting within `margin` of the
// surface, or hitting within a relative 1e-4 of t_max.
//
// The margin is 1e-4 of the shape's size plus the f32 floor: any f32 tracer subtracts
// coordinates of magnitude M (the ray origin, up to 1e4 sizes away, and the shape's
// placement), so it can only place the ray relative to the shape to a few ulps of M.
// The same floor is added to the 1e-4·t tolerance on t.

fn nearest_positive(roots: [f64; 2], t_max: f64) -> Option<f64> {
    roots.into_iter().find(|&t| t > 0.0 && t < t_max)
}

fn near_t_max(t: Option<f64>, t_max: f64, floor: f64) -> bool {
    t.is_some_and(|t| (t - t_max).abs() <= MARGIN * t + floor)
}

/// Unit sphere in object space; `margin` in object units, `floor` in world (t) units.
fn oracle_sphere(o: DVec3, d: DVec3, t_max: f64, margin: f64, floor: f64) -> Oracle {
    let a = d.dot(d);
    let b = o.dot(d);
    let c = o.dot(o) - 1.0;
    let l = o - d * (b / a);
    let line = l.length();
    let starts_on_surface = (o.length() - 1.0).abs() < margin;
    let silhouette = (line - 1.0).abs() < margin;
    let disc = a * (1.0 - l.dot(l));
    let t = if disc < 0.0 {
        None
    } else {
        let q = -b - disc.sqrt().copysign(b);
        let (r0, r1) = (c / q, q / a);
        nearest_positive([r0.min(r1), r0.max(r1)], t_max)
    };
    Oracle {
        t,
        grazing: starts_on_surface || silhouette || near_t_max(t, t_max, floor),
        floor,
    }
}

/// Slab test against [lo, hi]³ in f64 (nearest t in (0, t_max)).
fn slab(o: DVec3, d: DVec3, lo: f64, hi: f64, t_max: f64) -> Option<f64> {
    let mut t_near = f64::NEG_INFINITY;
    let mut t_far = f64::INFINITY;
    for k in 0..3 {
        if d[k] == 0.0 {
            if o[k] < lo || o[k] > hi {
                return None;
            }
            continue;
        }
        let (t0, t1) = ((lo - o[k]) / d[k], (hi - o[k]) / d[k]);
        t_near = t_near.max(t0.min(t1));
        t_far = t_far.min(t0.max(t1));
    }
    if t_near > t_far {
        return None;
    }
    [t_near, t_far].into_iter().find(|&t| t > 0.0 && t < t_max)
}

/// Box [0,1]³ in object space. Grazing when the answer changes between the box grown and
/// shrunk by the margin (edges, corners, silhouettes) or the origin lies between them.
fn oracle_box(o: DVec3, d: DVec3, t_max: f64, margin: f64, floor: f64) -> Oracle {
    let t = slab(o, d, 0.0, 1.0, t_max);
    let inside = |lo: f64, hi: f64| (0..3).all(|k| o[k] >= lo && o[k] <= hi);
    let grown = slab(o, d, -margin, 1.0 + margin, f64::INFINITY).is_some();
    let shrunk = slab(o, d, margin, 1.0 - margin, f64::INFINITY).is_some();
    let starts_on_surface = inside(-margin, 1.0 + margin) && !inside(margin, 1.0 - margin);
    Oracle {
        t,
        grazing: grown != shrunk || starts_on_surface || near_t_max(t, t_max, floor),
        floor,
    }
}

/// Triangle in world space (Möller–Trumbore in f64, two-sided). Grazing when the ray
/// passes within the margin (1e-4 of the longest edge plus the f32 floor) of an edge
/// line, the origin is within the margin of the plane, or the ray is within 1e-3 rad of
/// the plane.
fn oracle_triangle(p: [DVec3; 3], o: DVec3, d: DVec3, t_max: f64) -> Oracle {
    let e1 = p[1] - p[0];
    let e2 = p[2] - p[0];
    let n = e1.cross(e2);
    let size = e1.length().max(e2.length()).max((p[2] - p[1]).length());
    let floor = f32_floor(mag(o).max(mag(p[0])).max(mag(p[1])).max(mag(p[2])));
    let margin = MARGIN * size + floor;
    let pvec = d.cross(e2);
    let det = e1.dot(pvec);
    let plane_dist = (o - p[0]).dot(n) / n.length();
    let cos = n.dot(d).abs() / (n.length() * d.length());
    let mut grazing = plane_dist.abs() < margin || cos < 1e-3;
    let t = if det == 0.0 {
        None
    } else {
        let s = o - p[0];
        let b1 = s.dot(pvec) / det;
        let qvec = s.cross(e1);
        let b2 = d.dot(qvec) / det;
        let t = e2.dot(qvec) / det;
        let b0 = 1.0 - b1 - b2;
        // The test decides in projection along the ray, where an oblique triangle is
        // foreshortened: measure how near the ray passes each edge line (line–line
        // distance), not how near its plane hit lies to the edge in the plane.
        for i in 0..3 {
            let e = p[(i + 1) % 3] - p[i];
            let c = d.cross(e);
            let dist = if c.length() > 1e-9 * e.length() * d.length() {
                (p[i] - o).dot(c).abs() / c.length()
            } else {
                (p[i] - o).cross(d).length() / d.length()
            };
            if dist < margin {
                grazing = true;
            }
        }
        (b0 >= 0.0 && b1 >= 0.0 && b2 >= 0.0 && t > 0.0 && t < t_max).then_some(t)
    };
    Oracle {
        t,
        grazing: grazing || near_t_max(t, t_max, floor),
        floor,
    }
}

// ---------------------------------------------------------------------------------------
// 1. Agreement with the oracles.

/// Hits and misses each more than a tenth of the checked rays.
const BOTH_TENTHS: MinMix = MinMix {
    hits: 10,
    misses: 10,
};

const CASES: u64 = 1600;
const RAYS_PER_CASE: usize = 25;

/// A random ray towards a point near the shape: origin log-uniformly 1e-2..1e4 sizes from
/// the target (so some start inside), and t_max finite for 30% of rays.
fn random_ray(rng: &mut Rng, target: DVec3, size: f64) -> (Vec3, Vec3, f32) {
    let dist = size * rng.log_uniform(1e-2, 1e4);
    let origin = target + rng.unit_vector() * dist;
    let (o, d) = aim(origin, target);
    let t_max = if rng.f64() < 0.3 {
        (dist * rng.range(0.3, 3.0)) as f32
    } else {
        T_MISS
    };
    (o, d, t_max)
}

fn analytic_case(kind: ObjectKind, seed: u64, stats: &mut Agreement) {
    let mut rng = Rng::new(seed);
    let (m, size) = random_transform(&mut rng, true);
    let packed = pack_one(kind, m);
    let inst = &packed.instances[0];
    let inv = m.inverse();
    let min_scale = m
        .x_axis
        .length()
        .min(m.y_axis.length())
        .min(m.z_axis.length());
    // Magnitude of the shape's world coordinates.
    let extent = mag(m.w_axis.truncate())
        + 2.0
            * m.x_axis
                .length()
                .max(m.y_axis.length())
                .max(m.z_axis.length());
    for _ in 0..RAYS_PER_CASE {
        // Targets uniform in a box around the shape, in object space.
        let target_obj = match kind {
            ObjectKind::Sphere => DVec3::new(
                rng.range(-1.5, 1.5),
                rng.range(-1.5, 1.5),
                rng.range(-1.5, 1.5),
            ),
            ObjectKind::Cube => DVec3::new(
                rng.range(-0.3, 1.3),
                rng.range(-0.3, 1.3),
                rng.range(-0.3, 1.3),
            ),
            _ => unreachable!("cylinders and cones: tests/oracle/cylinder_cone_oracle.rs"),
        };
        let (o, d, t_max) = random_ray(&mut rng, m.transform_point3(target_obj), size);
        let t = intersect_instance(inst, o, d, t_max);
        assert_legal_t(t, t_max, "intersect_instance", seed);
        let (oo, od) = (inv.transform_point3(v64(o)), inv.transform_vector3(v64(d)));
        // World-space margin, in object units of the shortest axis (conservative).
        let floor = f32_floor(mag(v64(o)).max(extent));
        let margin = (MARGIN * size + floor) / min_scale;
        let oracle = match kind {
            ObjectKind::Sphere => oracle_sphere(oo, od, t_max as f64, margin, floor),
            ObjectKind::Cube => oracle_box(oo, od, t_max as f64, margin, floor),
            _ => unreachable!("cylinders and cones: tests/oracle/cylinder_cone_oracle.rs"),
        };
        stats.record(seed, &oracle, t, || {
            format!("size {size:e}, o {o}, d {d}, t_max {t_max}, object-space o {oo}")
        });
    }
}

#[test]
fn sphere_agrees_with_f64_oracle() {
    let salt = 0x5EED_5FE1;
    let mut stats = Agreement::default();
    for i in 0..CASES {
        analytic_case(ObjectKind::Sphere, case_seed(salt, i), &mut stats);
    }
    stats.check("sphere", &format!("salt {salt:#x}"), Some(BOTH_TENTHS));
}

#[test]
fn box_agrees_with_f64_oracle() {
    let salt = 0x5EED_B0C5;
    let mut stats = Agreement::default();
    for i in 0..CASES {
        analytic_case(ObjectKind::Cube, case_seed(salt, i), &mut stats);
    }
    stats.check("box", &format!("salt {salt:#x}"), Some(BOTH_TENTHS));
}

#[test]
fn triangle_agrees_with_f64_oracle() {
    let salt = 0x5EED_7121;
    let mut stats = Agreement::default();
    for i in 0..CASES {
        let seed = case_seed(salt, i);
        let mut rng = Rng::new(seed);
        let (m, size) = random_transform(&mut rng, false);
        // Vertices: random points of the unit disc's neighbourhood, placed by m.
        let positions = [0; 3].map(|_| {
            m.transform_point3(DVec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-0.2, 0.2),
            ))
        });
        let packed = pack(&scene(
            Vec::new(),
            vec![Triangle {
                positions,
                material: 0,
                uvs: [[0.0; 2]; 3],
            }],
            GridMode::Auto,
        ))
        .expect("pack");
        if packed.triangles.is_empty() {
            continue; // Degenerate after rounding.
        }
        let p = triangle_vertices(&packed.triangles[0]);
        let p64 = p.map(v64);
        for _ in 0..RAYS_PER_CASE {
            // Targets with barycentrics in [-0.25, 1.25], slightly off the plane too.
            let (b1, b2) = (rng.range(-0.25, 1.25), rng.range(-0.25, 1.25));
            let target = p64[0] * (1.0 - b1 - b2) + p64[1] * b1 + p64[2] * b2;
            let (o, d, t_max) = random_ray(&mut rng, target, size);
            let r = triangle_ray_setup(o, d);
            let t = intersect_triangle(&r, p[0], p[1], p[2], t_max).x;
            assert_legal_t(t, t_max, "intersect_triangle", seed);
            let oracle = oracle_triangle(p64, v64(o), v64(d), t_max as f64);
            stats.record(seed, &oracle, t, || {
                format!("size {size:e}, vertices {p:?}, o {o}, d {d}, t_max {t_max}")
            });
        }
    }
    stats.check("triangle", &format!("salt {salt:#x}"), Some(BOTH_TENTHS));
}

// ---------------------------------------------------------------------------------------
// 2. Leaving a convex surface: no re-hit outside; no escape from inside a sphere.

/// A unit f32 direction at `cos` from the unit normal `n`, random azimuth.
fn direction_at(rng: &mut Rng, n: DVec3, cos: f64) -> Vec3 {
    let (t1, t2) = n.any_orthonormal_pair();
    let phi = rng.range(0.0, std::f64::consts::TAU);
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    v32(n * cos + (t1 * phi.cos() + t2 * phi.sin()) * sin).normalize()
}

#[derive(Default)]
struct LeaveStats {
    surfaces: usize,
    rays: usize,
    failures: usize,
    examples: Vec<String>,
}

/// From outside: rays leave `inside == false` surfaces outward and must not hit again.
/// From inside (sphere only): rays leave the far wall inward and must hit again.
fn leave_case(kind: ObjectKind, from_inside: bool, seed: u64, stats: &mut LeaveStats) {
    let mut rng = Rng::new(seed);
    let (m, size) = random_transform(&mut rng, true);
    let packed = pack_one(kind, m);
    let inst = &packed.instances[0];
    for _ in 0..5 {
        let centre = match kind {
            ObjectKind::Sphere => DVec3::ZERO,
            ObjectKind::Cube => DVec3::splat(0.5),
            _ => unreachable!("cylinders and cones: tests/oracle/cylinder_cone_oracle.rs"),
        };
        let (o, d) = if from_inside {
            // From a random inside point (at most 0.9 of the radius) to the far wall.
            let inner = rng.unit_vector() * rng.range(0.0, 0.9);
            let o = v32(m.transform_point3(inner));
            (o, v32(m.transform_vector3(rng.unit_vector())).normalize())
        } else {
            let target = m.transform_point3(centre + rng.unit_vector() * 0.45);
            let origin = target + rng.unit_vector() * (size * rng.log_uniform(3.0, 1e4));
            aim(origin, target)
        };
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
        let n = if from_inside { -s.normal } else { s.normal };
        let origin = offset_ray(s.p, n, s.magnitude);
        stats.surfaces += 1;
        for k in 0..20 {
            // cos from 1 down to 1e-4, log-uniform; the first few exactly grazing.
            let cos = if k < 3 {
                1e-4
            } else {
                rng.log_uniform(1e-4, 1.0)
            };
            let dir = direction_at(&mut rng, v64(n), cos);
            let t2 = intersect_instance(inst, origin, dir, T_MISS);
            assert_legal_t(t2, T_MISS, "intersect_instance", seed);
            stats.rays += 1;
            let failed = if from_inside {
                t2 == T_MISS
            } else {
                t2 != T_MISS
            };
            if failed {
                stats.failures += 1;
                if stats.examples.len() < 8 {
                    stats.examples.push(format!(
                        "seed {seed:#x}: size {size:e}, hit p {} n {} magnitude {}, \
                         origin {origin}, dir {dir} (cos {cos:e}), got t {t2}",
                        s.p, s.normal, s.magnitude
                    ));
                }
            }
        }
    }
}

fn run_leave(kind: ObjectKind, from_inside: bool, salt: u64, what: &str) {
    let mut stats = LeaveStats::default();
    for i in 0..1000 {
        leave_case(kind, from_inside, case_seed(salt, i), &mut stats);
    }
    println!(
        "{what}: {} surfaces, {} rays, {} failures",
        stats.surfaces, stats.rays, stats.failures
    );
    for e in &stats.examples {
        println!("  {e}");
    }
    assert!(
        stats.surfaces > 2000,
        "{what}: too few hits (salt {salt:#x})"
    );
    assert_eq!(
        stats.failures, 0,
        "{what} (salt {salt:#x}): {:?}",
        stats.examples
    );
}

#[test]
fn rays_leaving_sphere_never_rehit_it() {
    run_leave(
        ObjectKind::Sphere,
        false,
        0x1EAF_5FE1,
        "sphere, leaving outward",
    );
}

#[test]
fn rays_leaving_box_never_rehit_it() {
    run_leave(ObjectKind::Cube, false, 0x1EAF_B0C5, "box, leaving outward");
}

#[test]
fn rays_inside_sphere_never_escape() {
    run_leave(
        ObjectKind::Sphere,
        true,
        0x1EAF_1251,
        "sphere, continuing inward",
    );
}

// ---------------------------------------------------------------------------------------
// 3. Watertight meshes: no ray aimed inside the footprint leaks, with or without the grid.

const GRID_N: usize = 50;

/// A GRID_N×GRID_N heightfield in object space [0,1]²×small z, interior vertices jittered,
/// each quad split along a random diagonal. Returns world-space triangles and the f32
/// vertex grid as `pack` rounds it.
fn jittered_grid(rng: &mut Rng, m: DMat4) -> (Vec<Triangle>, Vec<Vec<Vec3>>) {
    let h = 1.0 / GRID_N as f64;
    let mut world = vec![vec![DVec3::ZERO; GRID_N + 1]; GRID_N + 1];
    for (i, row) in world.iter_mut().enumerate() {
        for (j, w) in row.iter_mut().enumerate() {
            let interior = i > 0 && i < GRID_N && j > 0 && j < GRID_N;
            let (jx, jy) = if interior {
                (rng.range(-0.3, 0.3), rng.range(-0.3, 0.3))
            } else {
                (0.0, 0.0)
            };
            let z = rng.range(-0.05, 0.05) * h;
            *w = m.transform_point3(DVec3::new((i as f64 + jx) * h, (j as f64 + jy) * h, z));
        }
    }
    let mut triangles = Vec::new();
    for i in 0..GRID_N {
        for j in 0..GRID_N {
            let (a, b, c, d) = (
                world[i][j],
                world[i + 1][j],
                world[i + 1][j + 1],
                world[i][j + 1],
            );
            let tris = if rng.f64() < 0.5 {
                [[a, b, c], [a, c, d]]
            } else {
                [[a, b, d], [b, c, d]]
            };
            triangles.extend(tris.map(|positions| Triangle {
                positions,
                material: 0,
                uvs: [[0.0; 2]; 3],
            }));
        }
    }
    let verts = world
        .iter()
        .map(|row| row.iter().map(|&p| v32(p)).collect())
        .collect();
    (triangles, verts)
}

#[test]
fn jittered_grid_mesh_is_watertight() {
    let salt = 0x3A7E_0717;
    let (mut rays, mut leaks, mut t_mismatch) = (0usize, 0usize, 0usize);
    let mut by_kind = [0usize; 3];
    let mut worst = 0.0f64;
    let mut examples = Vec::new();
    let mut axis_parallel = 0usize;
    for case in 0..14 {
        let seed = case_seed(salt, case);
        let mut rng = Rng::new(seed);
        // The last cases are axis-aligned (scale + translate), for rays with exactly zero
        // direction components, which take the DDA's "parallel to this axis" path.
        let aligned = case >= 10;
        let (m, size) = if aligned {
            let s = rng.log_uniform(1e-3, 1e4);
            let centre = rng.unit_vector() * (s * rng.range(0.0, 3.0));
            (
                DMat4::from_scale_rotation_translation(DVec3::splat(s), DQuat::IDENTITY, centre),
                s,
            )
        } else {
            random_transform(&mut rng, false)
        };
        let normal = m.transform_vector3(DVec3::Z).normalize();
        let (triangles, verts) = jittered_grid(&mut rng, m);
        // The triangles as f32, in input order (`pack` reorders them spatially), two per
        // quad, row by row.
        let ordered: Vec<[Vec3; 3]> = triangles
            .iter()
            .map(|t| t.positions.map(|p| p.as_vec3()))
            .collect();
        let with_grid = pack(&scene(Vec::new(), triangles.clone(), GridMode::Auto)).expect("pack");
        let brute = pack(&scene(Vec::new(), triangles, GridMode::Off)).expect("pack");
        // One mesh: under Auto the scene has no grid of its own (one item, nothing to
        // cull), and the ray walks the mesh's grid; Off gives the mesh one cell.
        let cells = |p: &glint::pack::PackedScene| p.meshes[0].grid_dims.iter().product::<u32>();
        assert!(cells(&with_grid) > 1, "seed {seed:#x}: no mesh grid");
        assert_eq!(cells(&brute), 1, "seed {seed:#x}");
        assert_eq!(brute.globals.grid_enabled, 0, "seed {seed:#x}");
        assert_eq!(
            brute.triangles.len(),
            2 * GRID_N * GRID_N,
            "seed {seed:#x}: a triangle was dropped as degenerate"
        );
        for _ in 0..1000 {
            // Interior vertex indices (targets stay at least one cell from the border).
            let (i, j) = (1 + rng.below(GRID_N - 1), 1 + rng.below(GRID_N - 1));
            let kind = rng.below(3);
            by_kind[kind] += 1;
            let target = match kind {
                // A shared vertex, exactly.
                0 => verts[i][j],
                // A point on an edge of a triangle of an interior quad (every such edge is
                // shared by two triangles), interpolated in f32 between its two vertices.
                1 => {
                    let (i, j) = (i.min(GRID_N - 2), j.min(GRID_N - 2));
                    let p = ordered[2 * (i * GRID_N + j) + rng.below(2)];
                    let e = rng.below(3);
                    let (a, b) = (p[e], p[(e + 1) % 3]);
                    let u = if rng.f64() < 0.3 {
                        0.5
                    } else {
                        rng.f64() as f32
                    };
                    a + (b - a) * u
                }
                // A random point of a triangle of quad (i, j)–(i+1, j+1), interpolated in
                // f32.
                _ => {
                    let (i, j) = (i.min(GRID_N - 2), j.min(GRID_N - 2));
                    let [p0, p1, p2] = ordered[2 * (i * GRID_N + j) + rng.below(2)];
                    let (mut u, mut v) = (rng.f64() as f32, rng.f64() as f32);
                    if u + v > 1.0 {
                        (u, v) = (1.0 - u, 1.0 - v);
                    }
                    p0 + (p1 - p0) * u + (p2 - p0) * v
                }
            };
            // From either side, at least ~17° off the mesh plane.
            let side = if rng.f64() < 0.5 { 1.0 } else { -1.0 };
            let cos = rng.range(0.3, 1.0);
            let out = direction_at(&mut rng, normal * side, cos);
            let dist = size * rng.log_uniform(1e-2, 1e4);
            let (o, d) = if aligned && rng.f64() < 0.6 {
                // Zero x, y or both exactly; the origin shares those coordinates with the
                // target exactly.
                let mut out = out;
                match rng.below(3) {
                    0 => out.x = 0.0,
                    1 => out.y = 0.0,
                    _ => (out.x, out.y) = (0.0, 0.0),
                }
                let out = out.normalize();
                axis_parallel += 1;
                (target + out * dist as f32, -out)
            } else {
                aim(v64(target) + v64(out) * dist, v64(target))
            };
            let ray = Ray { origin: o, dir: d };
            let h_grid = closest_hit(&with_grid, &ray, T_MISS, &mut NoCounters);
            let h_brute = closest_hit(&brute, &ray, T_MISS, &mut NoCounters);
            rays += 1;
            assert_legal_t(h_grid.t, T_MISS, "closest_hit (grid)", seed);
            assert_legal_t(h_brute.t, T_MISS, "closest_hit (off)", seed);
            if !h_grid.is_hit() || !h_brute.is_hit() {
                leaks += 1;
                if examples.len() < 8 {
                    examples.push(format!(
                        "seed {seed:#x}: leak, target kind {kind} at {target}, o {o}, d {d}, \
                         grid {h_grid:?}, off {h_brute:?}"
                    ));
                }
                continue;
            }
            let rel = (h_grid.t as f64 - h_brute.t as f64).abs() / h_brute.t as f64;
            worst = worst.max(rel);
            // The hit cannot lie beyond the target (up to the f32 floor of the coordinates).
            let t_target = (v64(target) - v64(o)).length();
            let floor = f32_floor(mag(v64(o)).max(mag(v64(target))));
            if rel > 1e-5 || h_brute.t as f64 > t_target * (1.0 + 1e-4) + floor {
                t_mismatch += 1;
                if examples.len() < 8 {
                    examples.push(format!(
                        "seed {seed:#x}: t grid {} vs off {} (target at {t_target})",
                        h_grid.t, h_brute.t
                    ));
                }
            }
        }
    }
    println!(
        "grid mesh: {rays} rays (vertex/edge/interior targets {by_kind:?}, {axis_parallel} \
         with zero direction components), {leaks} leaks, \
         {t_mismatch} t mismatches, worst grid-vs-off |Δt|/t {worst:.3e}"
    );
    for e in &examples {
        println!("  {e}");
    }
    assert_eq!(leaks + t_mismatch, 0, "salt {salt:#x}: {examples:?}");
}

// ---------------------------------------------------------------------------------------
// 4. Grazing and edge-on rays: never NaN, never a t outside (0, t_max).

#[test]
fn axis_parallel_rays_against_box() {
    let salt = 0xED6E_B0C5;
    let mut checked = 0usize;
    for i in 0..3000u64 {
        let seed = case_seed(salt, i);
        let mut rng = Rng::new(seed);
        // Coordinates drawn from a set that includes the slab planes exactly.
        let pick = |rng: &mut Rng| match rng.below(6) {
            0 => 0.0f32,
            1 => 1.0,
            2 => -0.0,
            3 => rng.range(-2.0, 3.0) as f32,
            4 => rng.range(0.0, 1.0) as f32,
            _ => [f32::EPSILON, 1.0 - f32::EPSILON / 2.0, 1.0 + f32::EPSILON][rng.below(3)],
        };
        let o = Vec3::new(pick(&mut rng), pick(&mut rng), pick(&mut rng));
        let mut d = v32(rng.unit_vector());
        // One or two components exactly zero (±0).
        let zeros = 1 + rng.below(2);
        for _ in 0..zeros {
            d[rng.below(3)] = if rng.f64() < 0.5 { 0.0 } else { -0.0 };
        }
        if d.length_squared() == 0.0 {
            continue;
        }
        let d = d * rng.log_uniform(1e-3, 1e3) as f32;
        let t_max = if rng.f64() < 0.5 {
            T_MISS
        } else {
            rng.range(0.1, 5.0) as f32
        };
        let t = intersect_box(o, d, t_max);
        assert!(
            !t.is_nan(),
            "intersect_box NaN: o {o}, d {d} (seed {seed:#x})"
        );
        assert_legal_t(t, t_max, "intersect_box", seed);
        // Strictly inside or outside every parallel slab: the answer is not ambiguous.
        let clear = (0..3).all(|k| d[k] != 0.0 || (o[k] != 0.0 && o[k] != 1.0));
        let oracle = slab(v64(o), v64(d), 0.0, 1.0, t_max as f64);
        let on_surface = (0..3).any(|k| o[k] == 0.0 || o[k] == 1.0);
        if clear && !on_surface && !near_t_max(oracle, t_max as f64, 0.0) {
            checked += 1;
            match oracle {
                None => assert_eq!(t, T_MISS, "o {o}, d {d}, t_max {t_max} (seed {seed:#x})"),
                Some(t_ref) => assert!(
                    (t as f64 - t_ref).abs() <= 1e-5 * t_ref,
                    "o {o}, d {d}, t_max {t_max}: expected {t_ref}, got {t} (seed {seed:#x})"
                ),
            }
        }
    }
    println!("axis-parallel box rays: {checked} unambiguous rays agree with the oracle");
    assert!(checked > 300);
}

#[test]
fn tangent_rays_against_sphere() {
    let salt = 0xED6E_5FE1;
    for i in 0..2000u64 {
        let seed = case_seed(salt, i);
        let mut rng = Rng::new(seed);
        // A tangent line (exactly, for axis-aligned ones): o = (x, 1, 0) along ±x, etc.
        let axis = rng.below(3);
        let side = (axis + 1 + rng.below(2)) % 3;
        let mut o = Vec3::ZERO;
        o[axis] = rng.range(-5.0, 5.0) as f32;
        o[side] = if rng.f64() < 0.5 { 1.0 } else { -1.0 };
        let mut d = Vec3::ZERO;
        d[axis] = (if rng.f64() < 0.5 { 1.0 } else { -1.0 }) * rng.log_uniform(1e-3, 1e3) as f32;
        let t_max = if rng.f64() < 0.5 {
            T_MISS
        } else {
            rng.range(0.1, 10.0) as f32
        };
        let t = intersect_sphere(o, d, t_max);
        assert!(
            !t.is_nan(),
            "intersect_sphere NaN: o {o}, d {d} (seed {seed:#x})"
        );
        assert_legal_t(t, t_max, "intersect_sphere", seed);
    }
}

#[test]
fn in_plane_rays_against_triangle() {
    let salt = 0xED6E_7121;
    for i in 0..4000u64 {
        let seed = case_seed(salt, i);
        let mut rng = Rng::new(seed);
        let (m, size) = random_transform(&mut rng, false);
        let axis_aligned = rng.f64() < 0.5;
        // Axis-aligned: a triangle in the plane z = c and a ray with d.z = 0, o.z = c
        // (exactly in the plane in f32). Otherwise a random plane (in it up to rounding).
        let (p, o, d) = if axis_aligned {
            let c = (rng.range(-3.0, 3.0) * size) as f32;
            let mut q = || {
                Vec3::new(
                    (rng.range(-1.0, 1.0) * size) as f32,
                    (rng.range(-1.0, 1.0) * size) as f32,
                    c,
                )
            };
            let p = [q(), q(), q()];
            let o = q() * Vec3::new(3.0, 3.0, 1.0);
            let target = q();
            let mut d = target - o;
            d.z = 0.0;
            (p, o, d.normalize_or(Vec3::X))
        } else {
            let q = |rng: &mut Rng| {
                m.transform_point3(DVec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), 0.0))
            };
            let p = [q(&mut rng), q(&mut rng), q(&mut rng)];
            let origin =
                m.transform_point3(DVec3::new(rng.range(-3.0, 3.0), rng.range(-3.0, 3.0), 0.0));
            let target = q(&mut rng);
            let (o, d) = aim(origin, target);
            (p.map(v32), o, d)
        };
        let t_max = if rng.f64() < 0.5 {
            T_MISS
        } else {
            (rng.range(0.1, 5.0) * size) as f32
        };
        let r = triangle_ray_setup(o, d);
        let h = intersect_triangle(&r, p[0], p[1], p[2], t_max);
        assert!(
            !h.x.is_nan(),
            "intersect_triangle NaN t: p {p:?}, o {o}, d {d} (seed {seed:#x})"
        );
        assert_legal_t(h.x, t_max, "intersect_triangle", seed);
        if h.x != T_MISS {
            assert!(
                h.y.is_finite() && h.z.is_finite(),
                "intersect_triangle non-finite barycentrics {h}: p {p:?}, o {o}, d {d} \
                 (seed {seed:#x})"
            );
        }
    }
}
