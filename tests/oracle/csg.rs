//! CSG on the CPU tracer: point classification against analytic answers (union,
//! intersection, difference, nested, with tori and double cones), the first hit against an
//! f64 oracle over scales 1e-3…1e4, no speckles where a difference's caps are coplanar,
//! flipped normals on subtracted surfaces, grid bounds, scale invariance of whole images,
//! and the scene language: materials, transforms, instancing, and every error.

use crate::common;
use crate::oracle_support;

use glam::{DMat4, DQuat, DVec3, Vec3};
use glint::constants::{CSG_FLIP, CSG_INDEX_MASK, T_MISS};
use glint::pack::{pack, PackedScene};
use glint::scene::flatten::{CsgObject, CsgStep, FlatScene, Object, ObjectKind};
use glint::scene::{Camera, CsgOp, Material, RenderOptions};
use glint::tracer::base::ray::Ray;
use glint::tracer::traversal::traverse::{closest_hit, NoCounters};
use oracle_support::Rng;

fn leaf(kind: ObjectKind, object_to_world: DMat4, material: usize) -> CsgStep {
    CsgStep::Leaf(Object {
        name: String::from("leaf"),
        kind,
        object_to_world,
        material,
    })
}

/// A scene of CSG objects (and nothing else), one material per index used.
fn csg_scene(programs: Vec<Vec<CsgStep>>) -> FlatScene {
    FlatScene {
        objects: Vec::new(),
        csg: programs
            .into_iter()
            .map(|program| CsgObject {
                name: String::from("csg"),
                program,
                material: 0,
            })
            .collect(),
        triangles: Vec::new(),
        meshes: Vec::new(),
        mesh_instances: Vec::new(),
        materials: vec![Material::default(); 4],
        textures: Vec::new(),
        lights: Vec::new(),
        camera: Camera {
            eye: DVec3::new(0.0, 0.0, 10.0),
            view: DVec3::NEG_Z,
            up: DVec3::Y,
            fov_deg: 50.0,
        },
        ambient: [0.1; 3],
        width: 8,
        height: 8,
        options: RenderOptions::default(),
    }
}

/// A cup: the unit cylinder under `m` minus a narrower one (radius 0.6) whose top cap is
/// coplanar with the outer's (z = 1); with `tube`, the inner runs the full height, so both
/// caps are coplanar.
fn cup(m: DMat4, tube: bool) -> PackedScene {
    let inner = if tube {
        DMat4::from_scale(DVec3::new(0.6, 0.6, 1.0))
    } else {
        DMat4::from_translation(DVec3::new(0.0, 0.0, 0.2))
            * DMat4::from_scale(DVec3::new(0.6, 0.6, 0.8))
    };
    pack(&csg_scene(vec![vec![
        leaf(ObjectKind::Cylinder, m, 0),
        leaf(ObjectKind::Cylinder, m * inner, 1),
        CsgStep::Op(CsgOp::Difference),
    ]]))
    .expect("pack")
}

/// Speckles among `n` rays at `elevation` degrees to a coplanar cap of `cup(m, tube)`,
/// aimed inside the hole: hits on the outer cylinder's cap (a zero-width sliver of it).
fn speckles(m: DMat4, tube: bool, elevation: f64, n: usize, rng: &mut Rng) -> usize {
    let packed = cup(m, tube);
    let outer = packed.globals.num_instances;
    let to_object = m.inverse();
    let axis = m.transform_vector3(DVec3::Z).normalize();
    let size = m.transform_vector3(DVec3::X).length();
    let (sin_e, cos_e) = elevation.to_radians().sin_cos();
    let mut count = 0;
    for i in 0..n {
        // Alternate caps on a tube (rays from above the top, from below the bottom).
        let top = !tube || i % 2 == 0;
        let (cap_z, side) = if top { (1.0, 1.0) } else { (0.0, -1.0) };
        let phi = rng.range(0.0, std::f64::consts::TAU);
        let r = 0.6 * 0.98 * rng.f64().sqrt();
        let target = m.transform_point3(DVec3::new(r * phi.cos(), r * phi.sin(), cap_z));
        let across = axis.any_orthonormal_vector();
        let across = DQuat::from_axis_angle(axis, rng.range(0.0, std::f64::consts::TAU)) * across;
        let d = (-side * sin_e * axis + cos_e * across).normalize();
        let origin = target - d * (4.0 * size);
        let ray = Ray {
            origin: origin.as_vec3(),
            dir: d.as_vec3(),
        };
        let hit = closest_hit(&packed, &ray, T_MISS, &mut NoCounters);
        if !hit.is_hit() || hit.part & CSG_INDEX_MASK != outer || hit.part & CSG_FLIP != 0 {
            continue;
        }
        let p = ray.origin.as_dvec3() + ray.dir.as_dvec3() * hit.t as f64;
        let q = to_object.transform_point3(p);
        if (q.z - cap_z).abs() < 1e-3 && q.x.hypot(q.y) < 0.6 * 0.99 {
            count += 1;
        }
    }
    count
}

/// Placements of the cup: scales 1e-3…1e4, random rotations, centres up to 100 sizes away.
fn placements(rng: &mut Rng) -> Vec<DMat4> {
    let mut out = Vec::new();
    for scale in [1e-3, 1.0, 1e3, 1e4] {
        for distance in [0.0, 3.0, 100.0] {
            for _ in 0..3 {
                let centre = rng.unit_vector() * distance * scale;
                out.push(DMat4::from_scale_rotation_translation(
                    DVec3::splat(scale),
                    rng.rotation(),
                    centre,
                ));
            }
        }
    }
    out
}

// ---- trees and closed forms ------------------------------------------------------------

/// A CSG tree for the tests, with closed forms for membership and (spheres, boxes and
/// cylinders) the exact inside intervals of a line.
#[derive(Clone, Debug)]
enum Tree {
    Leaf(ObjectKind, DMat4),
    Op(CsgOp, Box<Tree>, Box<Tree>),
}

fn op(op: CsgOp, a: Tree, b: Tree) -> Tree {
    Tree::Op(op, Box::new(a), Box::new(b))
}

impl Tree {
    /// The post-order program; leaf k (in post-order) gets material k % 4.
    fn program(&self) -> Vec<CsgStep> {
        fn walk(t: &Tree, out: &mut Vec<CsgStep>, leaves: &mut usize) {
            match t {
                Tree::Leaf(kind, m) => {
                    out.push(leaf(*kind, *m, *leaves % 4));
                    *leaves += 1;
                }
                Tree::Op(o, a, b) => {
                    walk(a, out, leaves);
                    walk(b, out, leaves);
                    out.push(CsgStep::Op(*o));
                }
            }
        }
        let mut out = Vec::new();
        walk(self, &mut out, &mut 0);
        out
    }

    fn packed(&self) -> PackedScene {
        pack(&csg_scene(vec![self.program()])).expect("pack")
    }

    /// Whether the world point `p` is inside (closed forms in each leaf's object space).
    fn inside(&self, p: DVec3) -> bool {
        match self {
            Tree::Leaf(kind, m) => inside_leaf(*kind, m.inverse().transform_point3(p)),
            Tree::Op(o, a, b) => {
                let (ia, ib) = (a.inside(p), b.inside(p));
                match o {
                    CsgOp::Union => ia || ib,
                    CsgOp::Intersection => ia && ib,
                    CsgOp::Difference => ia && !ib,
                }
            }
        }
    }

    /// The exact (f64) inside intervals of the line o + t·d as ends (t, leaf ordinal |
    /// CSG_FLIP), combined exactly (no tolerance); leaf ordinals count from `next`.
    fn oracle(&self, o: DVec3, d: DVec3, next: &mut u32) -> Vec<(f64, u32)> {
        match self {
            Tree::Leaf(kind, m) => {
                let tag = *next;
                *next += 1;
                let inv = m.inverse();
                let (oo, od) = (inv.transform_point3(o), inv.transform_vector3(d));
                leaf_oracle(*kind, oo, od)
                    .into_iter()
                    .flat_map(|(lo, hi)| [(lo, tag), (hi, tag)])
                    .collect()
            }
            Tree::Op(op, a, b) => {
                let la = a.oracle(o, d, next);
                let lb = b.oracle(o, d, next);
                combine_exact(*op, &la, &lb)
            }
        }
    }
}

fn inside_leaf(kind: ObjectKind, p: DVec3) -> bool {
    match kind {
        ObjectKind::Sphere => p.length_squared() <= 1.0,
        ObjectKind::Cube => p.cmpge(DVec3::ZERO).all() && p.cmple(DVec3::ONE).all(),
        ObjectKind::Cylinder => p.x * p.x + p.y * p.y <= 1.0 && (0.0..=1.0).contains(&p.z),
        ObjectKind::Cone { zmin, zmax } => {
            p.x * p.x + p.y * p.y <= p.z * p.z && p.z >= zmin as f64 && p.z <= zmax as f64
        }
        ObjectKind::Torus { rin, rout } => {
            // The quartic's sign: for a spindle torus, the apple minus the lemon.
            let (r_mid, r_tube) = (rin as f64, rout as f64);
            let k = p.length_squared() + r_mid * r_mid - r_tube * r_tube;
            k * k - 4.0 * r_mid * r_mid * (p.x * p.x + p.y * p.y) <= 0.0
        }
    }
}

/// The slab [lo, hi] of o + t·d between the planes x_axis = a and = b (all t when
/// parallel and between them, none when outside).
fn slab(o: f64, d: f64, a: f64, b: f64) -> (f64, f64) {
    if d == 0.0 {
        return if o >= a && o <= b {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            (f64::INFINITY, f64::NEG_INFINITY)
        };
    }
    let (t0, t1) = ((a - o) / d, (b - o) / d);
    (t0.min(t1), t0.max(t1))
}

/// Roots of a·t² + 2b·t + c ≤ 0 as an interval (a > 0), if any.
fn quadratic_inside(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    let disc = b * b - a * c;
    if disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    Some(((-b - s) / a, (-b + s) / a))
}

fn leaf_oracle(kind: ObjectKind, o: DVec3, d: DVec3) -> Vec<(f64, f64)> {
    let interval = match kind {
        ObjectKind::Sphere => quadratic_inside(d.dot(d), o.dot(d), o.dot(o) - 1.0),
        ObjectKind::Cube => {
            let s = [0, 1, 2].map(|k| slab(o[k], d[k], 0.0, 1.0));
            Some((
                s.iter().map(|s| s.0).fold(f64::NEG_INFINITY, f64::max),
                s.iter().map(|s| s.1).fold(f64::INFINITY, f64::min),
            ))
        }
        ObjectKind::Cylinder => {
            let a = d.x * d.x + d.y * d.y;
            let b = o.x * d.x + o.y * d.y;
            let c = o.x * o.x + o.y * o.y - 1.0;
            let side = if a == 0.0 {
                (c <= 0.0).then_some((f64::NEG_INFINITY, f64::INFINITY))
            } else {
                quadratic_inside(a, b, c)
            };
            side.map(|(lo, hi)| {
                let z = slab(o.z, d.z, 0.0, 1.0);
                (lo.max(z.0), hi.min(z.1))
            })
        }
        _ => panic!("no oracle for {kind:?}"),
    };
    interval.into_iter().filter(|(lo, hi)| lo <= hi).collect()
}

/// Exact combination of two end lists (an end of each at the same t changes both).
fn combine_exact(op: CsgOp, a: &[(f64, u32)], b: &[(f64, u32)]) -> Vec<(f64, u32)> {
    let (mut ia, mut ib) = (0, 0);
    let (mut in_a, mut in_b, mut inside) = (false, false, false);
    let mut out = Vec::new();
    while ia < a.len() || ib < b.len() {
        let ta = a.get(ia).map_or(f64::INFINITY, |e| e.0);
        let tb = b.get(ib).map_or(f64::INFINITY, |e| e.0);
        let (take_a, take_b) = (ta <= tb, tb <= ta);
        let mut end = (ta, 0);
        if take_a {
            end = a[ia];
            in_a = !in_a;
            ia += 1;
        }
        if take_b {
            if !take_a {
                end = b[ib];
                if op == CsgOp::Difference {
                    end.1 ^= CSG_FLIP;
                }
            }
            in_b = !in_b;
            ib += 1;
        }
        let now = match op {
            CsgOp::Union => in_a || in_b,
            CsgOp::Intersection => in_a && in_b,
            CsgOp::Difference => in_a && !in_b,
        };
        if now != inside {
            out.push(end);
            inside = now;
        }
    }
    out
}

/// Whether t lies inside the intervals of an end list.
fn in_list(ends: &[(f32, u32)], t: f32) -> bool {
    ends.chunks(2).any(|pair| t >= pair[0].0 && t <= pair[1].0)
}

// ---- point classification against analytic answers ---------------------------------------

/// Shapes of known size around the origin: a unit sphere, a box, a cylinder through the
/// sphere along x, a torus around it (axis z) and a double cone along x.
fn shapes() -> [Tree; 5] {
    let rot_y = DMat4::from_rotation_y(std::f64::consts::FRAC_PI_2);
    [
        Tree::Leaf(ObjectKind::Sphere, DMat4::IDENTITY),
        Tree::Leaf(
            ObjectKind::Cube,
            DMat4::from_translation(DVec3::splat(-0.2)) * DMat4::from_scale(DVec3::splat(1.3)),
        ),
        Tree::Leaf(
            ObjectKind::Cylinder,
            rot_y
                * DMat4::from_scale(DVec3::new(0.45, 0.45, 3.0))
                * DMat4::from_translation(DVec3::new(0.0, 0.0, -0.5)),
        ),
        Tree::Leaf(
            ObjectKind::Torus {
                rin: 0.9,
                rout: 0.3,
            },
            DMat4::IDENTITY,
        ),
        Tree::Leaf(
            ObjectKind::Cone {
                zmin: -1.3,
                zmax: 1.1,
            },
            rot_y * DMat4::from_scale(DVec3::new(0.6, 0.6, 1.0)),
        ),
    ]
}

/// Samples points along random lines through `tree` and compares the inside intervals
/// the tracer computes (their parity) with the closed forms. Points whose closed-form
/// answer changes within 1e-4 along the line (a boundary) are not counted.
fn classify(name: &str, tree: &Tree, seed: u64) {
    let packed = tree.packed();
    let first_leaf = packed.globals.num_instances;
    let mut rng = Rng::new(seed);
    let (mut agree, mut total, mut ends_checked) = (0, 0, 0);
    for _ in 0..2000 {
        let o = rng.unit_vector() * rng.range(2.5, 4.0);
        let target = DVec3::new(
            rng.range(-1.3, 1.3),
            rng.range(-1.3, 1.3),
            rng.range(-1.3, 1.3),
        );
        let (o32, d32) = (o.as_vec3(), (target - o).normalize().as_vec3());
        let (o, d) = (o32.as_dvec3(), d32.as_dvec3());
        let ends = glint::testing::csg_interval_ends(&packed, 0, o32, d32);
        assert!(ends.len().is_multiple_of(2), "{name}: odd list {ends:?}");
        assert!(
            ends.windows(2).all(|w| w[0].0 <= w[1].0),
            "{name}: unsorted list {ends:?}"
        );
        for &(t, tag) in &ends {
            // Each end lies on (within 1e-4 of) its leaf's surface: the closed form changes
            // across it.
            let leaf = (tag & CSG_INDEX_MASK) - first_leaf;
            let tree_leaf = nth_leaf(tree, leaf as usize);
            if let Tree::Leaf(kind, m) = tree_leaf {
                let inv = m.inverse();
                let at = |t: f64| inside_leaf(*kind, inv.transform_point3(o + d * t));
                assert!(
                    at(t as f64 - 1e-4) != at(t as f64 + 1e-4),
                    "{name}: end t = {t} is not on leaf {leaf}'s surface"
                );
                ends_checked += 1;
            }
        }
        for k in 0..64 {
            let t = (k as f64 + rng.f64()) / 64.0 * 8.0;
            let truth = tree.inside(o + d * t);
            if tree.inside(o + d * (t - 1e-4)) != truth || tree.inside(o + d * (t + 1e-4)) != truth
            {
                continue;
            }
            total += 1;
            if in_list(&ends, t as f32) == truth {
                agree += 1;
            }
        }
    }
    println!("{name}: {agree}/{total} points agree, {ends_checked} ends on their leaf");
    assert_eq!(agree, total, "{name}: classification disagrees");
    assert!(total > 50_000, "{name}: too few points");
}

fn nth_leaf(tree: &Tree, n: usize) -> &Tree {
    fn walk<'a>(t: &'a Tree, n: usize, seen: &mut usize) -> Option<&'a Tree> {
        match t {
            Tree::Leaf(..) => {
                *seen += 1;
                (*seen - 1 == n).then_some(t)
            }
            Tree::Op(_, a, b) => walk(a, n, seen).or_else(|| walk(b, n, seen)),
        }
    }
    walk(tree, n, &mut 0).expect("leaf")
}

#[test]
fn classification_matches_closed_forms() {
    let [sphere, cube, cylinder, torus, cone] = shapes();
    use CsgOp::*;
    classify(
        "sphere ∪ cylinder",
        &op(Union, sphere.clone(), cylinder.clone()),
        1,
    );
    classify(
        "sphere ∩ box",
        &op(Intersection, sphere.clone(), cube.clone()),
        2,
    );
    classify(
        "sphere − cylinder",
        &op(Difference, sphere.clone(), cylinder.clone()),
        3,
    );
    classify(
        "torus − double cone",
        &op(Difference, torus.clone(), cone.clone()),
        4,
    );
    classify(
        "double cone ∩ torus",
        &op(Intersection, cone.clone(), torus.clone()),
        5,
    );
    // Nested: ((sphere ∩ box) − cylinder) ∪ (torus − double cone), and a deeper chain.
    let nested = op(
        Union,
        op(
            Difference,
            op(Intersection, sphere.clone(), cube.clone()),
            cylinder.clone(),
        ),
        op(Difference, torus.clone(), cone.clone()),
    );
    classify("nested", &nested, 6);
    let chain = op(
        Difference,
        op(Intersection, op(Union, torus, cylinder), cube),
        op(Intersection, sphere, cone),
    );
    classify("nested chain", &chain, 7);
}

// ---- the first hit against an f64 oracle -------------------------------------------------

/// A random tree of spheres, boxes and cylinders, `depth` operations deep at most, of size
/// about `size` around `centre`.
fn random_tree(rng: &mut Rng, depth: u32, centre: DVec3, size: f64) -> Tree {
    if depth == 0 || rng.f64() < 0.25 {
        let kind = [ObjectKind::Sphere, ObjectKind::Cube, ObjectKind::Cylinder][rng.below(3)];
        let scale = DVec3::new(
            rng.range(0.4, 1.0),
            rng.range(0.4, 1.0),
            rng.range(0.4, 1.0),
        ) * size;
        // Centre each primitive on its placement (the box and cylinder start at 0).
        let to_centre = match kind {
            ObjectKind::Cube => DMat4::from_translation(DVec3::splat(-0.5)),
            ObjectKind::Cylinder => DMat4::from_translation(DVec3::new(0.0, 0.0, -0.5)),
            _ => DMat4::IDENTITY,
        };
        let place = centre + rng.unit_vector() * rng.range(0.0, 0.6) * size;
        let m = DMat4::from_scale_rotation_translation(scale, rng.rotation(), place) * to_centre;
        return Tree::Leaf(kind, m);
    }
    let o = [CsgOp::Union, CsgOp::Intersection, CsgOp::Difference][rng.below(3)];
    op(
        o,
        random_tree(rng, depth - 1, centre, size),
        random_tree(rng, depth - 1, centre, size),
    )
}

/// Every leaf's own ends along o + t·d (leaf ordinal tags), before combining.
fn leaf_ends(tree: &Tree, o: DVec3, d: DVec3) -> Vec<(f64, u32)> {
    let mut out = Vec::new();
    let mut k = 0;
    while let Some(Tree::Leaf(kind, m)) = nth_leaf_opt(tree, k) {
        let inv = m.inverse();
        for (lo, hi) in leaf_oracle(*kind, inv.transform_point3(o), inv.transform_vector3(d)) {
            out.extend([(lo, k as u32), (hi, k as u32)]);
        }
        k += 1;
    }
    out
}

fn nth_leaf_opt(tree: &Tree, n: usize) -> Option<&Tree> {
    let count = tree
        .program()
        .iter()
        .filter(|s| matches!(s, CsgStep::Leaf(_)))
        .count();
    (n < count).then(|| nth_leaf(tree, n))
}

/// The oracle's first end past the origin: (t, tag), or None.
fn oracle_hit(tree: &Tree, o: DVec3, d: DVec3) -> Option<(f64, u32)> {
    tree.oracle(o, d, &mut 0).into_iter().find(|e| e.0 > 0.0)
}

#[test]
fn first_hit_matches_f64_oracle_over_scales() {
    let (mut agree, mut total, mut band, mut hits) = (0usize, 0usize, 0usize, 0usize);
    let mut worst_dt = 0.0f64;
    let mut first_bad = None;
    for case in 0..400u64 {
        let mut rng = Rng::new(oracle_support::case_seed(0xC5C0, case));
        let size = rng.log_uniform(1e-3, 1e4);
        let centre = rng.unit_vector() * rng.range(0.0, 3.0) * size;
        let tree = random_tree(&mut rng, 3, centre, size);
        let packed = tree.packed();
        let first_leaf = packed.globals.num_instances;
        for i in 0..100 {
            // Origins 2 to 10⁴ sizes away, one in ten inside the object's region.
            let origin = if i % 10 == 0 {
                centre + rng.unit_vector() * rng.range(0.0, 0.8) * size
            } else {
                centre + rng.unit_vector() * rng.log_uniform(2.0, 1e4) * size
            };
            let target = centre + rng.unit_vector() * rng.range(0.0, 1.2) * size;
            let (o32, d32) = oracle_support::aim(origin, target);
            let (o, d) = (o32.as_dvec3(), d32.as_dvec3());
            let expected = oracle_hit(&tree, o, d);
            // The silhouette band: jittering the origin by 1e-4 sizes changes the answer, or
            // the hit is within 1e-4 sizes of another leaf's surface (an edge where two
            // surfaces meet, which either may claim).
            let (u, v) = d.any_orthonormal_pair();
            let jitter = 1e-4 * size;
            let on_edge = expected.is_some_and(|(t, tag)| {
                leaf_ends(&tree, o, d)
                    .iter()
                    .any(|e| e.1 != tag & !CSG_FLIP && (e.0 - t).abs() <= jitter)
            });
            let in_band = on_edge
                || [u, -u, v, -v].iter().any(|&j| {
                    let other = oracle_hit(&tree, o + j * jitter, d);
                    match (expected, other) {
                        (None, None) => false,
                        (Some(a), Some(b)) => a.1 != b.1 || (a.0 - b.0).abs() > 1e-3 * a.0.abs(),
                        _ => true,
                    }
                });
            let hit = closest_hit(
                &packed,
                &Ray {
                    origin: o32,
                    dir: d32,
                },
                T_MISS,
                &mut NoCounters,
            );
            oracle_support::assert_legal_t(hit.t, T_MISS, "closest_hit", case);
            if in_band {
                band += 1;
                continue;
            }
            total += 1;
            let got = hit.is_hit().then(|| {
                (
                    hit.t as f64,
                    ((hit.part & CSG_INDEX_MASK) - first_leaf) | (hit.part & CSG_FLIP),
                )
            });
            let ok = match (expected, got) {
                (None, None) => true,
                (Some(e), Some(g)) => {
                    hits += 1;
                    let dt = (e.0 - g.0).abs() / e.0;
                    if e.1 == g.1 {
                        worst_dt = worst_dt.max(dt);
                    }
                    e.1 == g.1 && dt <= 1e-4
                }
                _ => false,
            };
            if ok {
                agree += 1;
            } else if first_bad.is_none() {
                first_bad = Some(format!(
                    "case {case} ray {i}: expected {expected:?}, got {got:?} (size {size:e})"
                ));
            }
        }
    }
    let rate = agree as f64 / total as f64;
    println!(
        "{agree}/{total} agree ({:.4}%), {hits} hits, {band} in the silhouette band, worst |Δt|/t {worst_dt:.1e}; first disagreement: {first_bad:?}",
        rate * 100.0
    );
    assert!(
        rate >= 0.9999,
        "agreement {:.4}%; first: {}",
        rate * 100.0,
        first_bad.unwrap_or_default()
    );
    assert!(worst_dt <= 1e-4);
    assert!(hits > total / 4, "too few hits ({hits})");
}

// ---- coplanar caps: no speckles ----------------------------------------------------------

/// A difference of two cylinders with coplanar caps (a cup, and a tube with both caps
/// coplanar), placed at scales 1e-3…1e4, rotated at random, up to 100 sizes from the
/// origin, seen at angles from 90° down to 0.25° to the cap: no ray aimed into the hole
/// may stop on the outer cylinder's cap (a zero-width sliver of it, a speckle) at 1° and
/// above. Below that the two caps' rounding (~2 ulps / sin θ) outgrows the coincidence
/// tolerance; the counts there are printed, not asserted.
#[test]
fn coplanar_caps_leave_no_speckles() {
    let mut rng = Rng::new(7);
    let places = placements(&mut rng);
    let mut report = Vec::new();
    for elevation in [0.25, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 45.0, 70.0, 90.0] {
        let (mut total, mut rays) = (0, 0);
        for (i, m) in places.iter().enumerate() {
            total += speckles(*m, i % 2 == 1, elevation, 400, &mut rng);
            rays += 400;
        }
        println!("elevation {elevation:5.2}°: {total} speckles of {rays} rays");
        if elevation >= 1.0 {
            report.push((elevation, total));
        }
    }
    assert!(
        report.iter().all(|&(_, n)| n == 0),
        "speckles at ≥ 1°: {report:?}"
    );
}

// ---- normals ---------------------------------------------------------------------------

/// Whether object-space point q of a leaf lies within `eps` of two of its faces (an edge).
fn near_own_edge(kind: ObjectKind, q: DVec3, eps: f64) -> bool {
    match kind {
        ObjectKind::Cube => {
            let near = |v: f64| v.abs() < eps || (v - 1.0).abs() < eps;
            [q.x, q.y, q.z].iter().filter(|&&v| near(v)).count() >= 2
        }
        ObjectKind::Cylinder => {
            (q.x.hypot(q.y) - 1.0).abs() < eps && (q.z.abs() < eps || (q.z - 1.0).abs() < eps)
        }
        _ => false,
    }
}

/// Every CSG hit's normal points out of the result: p + δn is outside it, p − δn inside;
/// on a subtracted surface (CSG_FLIP) that is into the subtracted leaf. Hits within 3δ of
/// an edge (of their leaf, or where another leaf's surface passes) are not counted.
fn check_normals(name: &str, tree: &Tree, seed: u64) {
    let packed = tree.packed();
    let first_leaf = packed.globals.num_instances;
    let leaves: Vec<(ObjectKind, DMat4)> = (0..)
        .map_while(|k| match nth_leaf_opt(tree, k) {
            Some(Tree::Leaf(kind, m)) => Some((*kind, m.inverse())),
            _ => None,
        })
        .collect();
    let mut rng = Rng::new(seed);
    let (mut checked, mut flipped) = (0, 0);
    let delta = 1e-3;
    for _ in 0..20_000 {
        let o = rng.unit_vector() * rng.range(3.0, 5.0);
        let target = rng.unit_vector() * rng.range(0.0, 1.2);
        let ray = Ray {
            origin: o.as_vec3(),
            dir: (target - o).normalize().as_vec3(),
        };
        let hit = closest_hit(&packed, &ray, T_MISS, &mut NoCounters);
        if !hit.is_hit() {
            continue;
        }
        let s = glint::tracer::shading::surface::surface_at(&packed, &ray, &hit);
        let (p, n) = (s.p.as_dvec3(), s.normal.as_dvec3());
        let own = ((hit.part & CSG_INDEX_MASK) - first_leaf) as usize;
        let edge = leaves.iter().enumerate().any(|(k, (kind, inv))| {
            let q = inv.transform_point3(p);
            if k == own {
                return near_own_edge(*kind, q, 3.0 * delta);
            }
            // Another leaf's surface passes within 3δ.
            let here = inside_leaf(*kind, q);
            [DVec3::X, DVec3::Y, DVec3::Z].iter().any(|&e| {
                inside_leaf(*kind, inv.transform_point3(p + e * 3.0 * delta)) != here
                    || inside_leaf(*kind, inv.transform_point3(p - e * 3.0 * delta)) != here
            })
        });
        if edge {
            continue;
        }
        checked += 1;
        assert!(
            !tree.inside(p + n * delta) && tree.inside(p - n * delta),
            "{name}: the normal {n} at {p} (part {:#x}) does not point out of the result",
            hit.part
        );
        if hit.part & CSG_FLIP != 0 {
            flipped += 1;
            let (kind, inv) = leaves[own];
            assert!(
                inside_leaf(kind, inv.transform_point3(p + n * delta)),
                "{name}: a flipped normal at {p} does not point into the subtracted leaf"
            );
        }
    }
    println!("{name}: {checked} normals checked, {flipped} flipped");
    assert!(checked > 5000 && flipped > 500, "{name}: too few hits");
}

#[test]
fn normals_point_out_of_the_result() {
    use CsgOp::*;
    let cyl = |r: f64, z0: f64, z1: f64| {
        Tree::Leaf(
            ObjectKind::Cylinder,
            DMat4::from_translation(DVec3::new(0.0, 0.0, z0))
                * DMat4::from_scale(DVec3::new(r, r, z1 - z0)),
        )
    };
    // A cup (coplanar top caps) seen from all sides.
    let cup = op(Difference, cyl(1.0, -0.8, 0.8), cyl(0.6, -0.5, 0.8));
    check_normals("cup", &cup, 11);
    // Nested differences flip twice: a − (b − c), c's surfaces face out unflipped.
    let nested = op(
        Difference,
        cyl(1.0, -0.8, 0.8),
        op(Difference, cyl(0.7, -0.5, 1.0), cyl(0.3, -0.9, 1.2)),
    );
    check_normals("a − (b − c)", &nested, 12);
    let [sphere, cube, cylinder, ..] = shapes();
    check_normals(
        "(sphere ∩ box) − cylinder",
        &op(Difference, op(Intersection, sphere, cube), cylinder),
        13,
    );
}

// ---- grid bounds -----------------------------------------------------------------------

#[test]
fn grid_bounds_follow_the_tree() {
    use glint::accel::aabb::Aabb;
    use glint::pack::bounds::csg_bounds;
    let sphere_at = |x: f64| {
        Tree::Leaf(
            ObjectKind::Sphere,
            DMat4::from_translation(DVec3::new(x, 0.0, 0.0)),
        )
    };
    let bounds = |tree: &Tree| {
        let packed = tree.packed();
        let inst = &packed.instances[0];
        let (start, len) = (inst.params[0] as usize, inst.params[1] as usize);
        csg_bounds(&packed.csg_program[start..start + len], &packed.instances)
    };
    let close = |b: Aabb, min: [f32; 3], max: [f32; 3]| {
        (b.min - Vec3::from(min)).abs().max_element() < 1e-5
            && (b.max - Vec3::from(max)).abs().max_element() < 1e-5
    };
    use CsgOp::*;
    let u = bounds(&op(Union, sphere_at(0.0), sphere_at(1.5)));
    assert!(close(u, [-1.0, -1.0, -1.0], [2.5, 1.0, 1.0]), "{u:?}");
    let i = bounds(&op(Intersection, sphere_at(0.0), sphere_at(1.5)));
    assert!(close(i, [0.5, -1.0, -1.0], [1.0, 1.0, 1.0]), "{i:?}");
    let d = bounds(&op(Difference, sphere_at(0.0), sphere_at(1.5)));
    assert!(close(d, [-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]), "{d:?}");
    // Disjoint operands of an intersection: empty, in no grid cell, never hit.
    let empty_tree = op(Intersection, sphere_at(0.0), sphere_at(3.0));
    assert!(bounds(&empty_tree).is_empty());
    let mut scene = csg_scene(vec![
        empty_tree.program(),
        op(Union, sphere_at(-3.0), sphere_at(-5.0)).program(),
    ]);
    scene.options.grid = glint::scene::GridMode::Auto;
    let packed = pack(&scene).unwrap();
    assert!(packed.globals.grid_enabled == 1);
    assert!(
        !packed.cell_items.contains(&0),
        "the empty item is in a cell"
    );
    assert!(packed.cell_items.contains(&1));
    let ray = Ray {
        origin: Vec3::new(0.0, 0.0, 5.0),
        dir: Vec3::NEG_Z,
    };
    assert!(!closest_hit(&packed, &ray, T_MISS, &mut NoCounters).is_hit());
}

// ---- the scene language ------------------------------------------------------------------

const RENDER: &str = "gr.render(root, 'out.png', 8, 8, {0,0,5}, {0,0,-1}, {0,1,0}, 50, {0.1,0.1,0.1}, {gr.light({5,5,5}, {1,1,1}, {1,0,0})})\n";

/// Runs `source` (plus a render of `root`), flattening each render; the scenes or the
/// error message.
fn run(source: &str) -> Result<Vec<FlatScene>, String> {
    let mut scenes = Vec::new();
    glint::scene::lua::run_scene_source(
        "scene.lua",
        &format!("{source}\n{RENDER}"),
        &common::corpus().join("a4-2021plus"),
        &glint::scene::lua::ScriptConfig::default(),
        &mut |graph, request| {
            scenes.push(glint::scene::flatten::flatten(graph, request)?);
            Ok(())
        },
    )
    .map_err(|e| e.to_string())?;
    Ok(scenes)
}

fn leaves_of(c: &CsgObject) -> Vec<&Object> {
    c.program
        .iter()
        .filter_map(|s| match s {
            CsgStep::Leaf(o) => Some(o),
            CsgStep::Op(_) => None,
        })
        .collect()
}

#[test]
fn materials_default_from_the_csg_node() {
    let scenes = run("
        m1 = gr.material({1,0,0}, {0,0,0}, 1)
        m2 = gr.material({0,1,0}, {0,0,0}, 1)
        m3 = gr.material({0,0,1}, {0,0,0}, 1)
        root = gr.node('root')
        a = gr.sphere('a') a:set_material(m2)
        b = gr.cube('b')
        c = gr.cylinder('c')
        d = gr.cone('d', 0, 1) d:set_material(m3)
        inner = gr.csg('inner', 'u', c, d)
        outer = gr.csg('outer', 'd', gr.csg('ab', 'i', a, b), inner)
        outer:set_material(m1)
        plain = gr.csg('plain', 'u', gr.torus('t', 1, 0.2), gr.sphere('s'))
        root:add_child(outer)
        root:add_child(plain)
    ")
    .unwrap();
    let scene = &scenes[0];
    assert_eq!(scene.csg.len(), 2);
    let default = scene.materials.len() - 1;
    let materials: Vec<usize> = leaves_of(&scene.csg[0])
        .iter()
        .map(|o| o.material)
        .collect();
    // a: its own; b: outer's (via 'ab'); c: outer's (via 'inner'); d: its own.
    assert_eq!(materials, vec![1, 0, 0, 2]);
    assert_eq!(scene.csg[0].material, 0);
    let materials: Vec<usize> = leaves_of(&scene.csg[1])
        .iter()
        .map(|o| o.material)
        .collect();
    assert_eq!(materials, vec![default, default]);
    let ops: Vec<String> = scene.csg[0]
        .program
        .iter()
        .map(|s| match s {
            CsgStep::Leaf(o) => o.name.rsplit('/').next().unwrap().to_string(),
            CsgStep::Op(o) => format!("{o:?}"),
        })
        .collect();
    assert_eq!(
        ops,
        ["a", "b", "Intersection", "c", "d", "Union", "Difference"]
    );
}

#[test]
fn transforms_compose_and_csg_nodes_instance() {
    let scenes = run("
        root = gr.node('root')
        left = gr.node('left') left:translate(-2, 0, 0)
        right = gr.node('right') right:translate(2, 0, 0) right:rotate('z', 90)
        a = gr.nh_sphere('a', {0, 1, 0}, 0.5)
        a:scale(2, 1, 1)
        b = gr.cube('b')
        thing = gr.csg('thing', 'u', a, b)
        thing:scale(3, 3, 3)
        left:add_child(thing)
        right:add_child(thing)
        root:add_child(left)
        root:add_child(right)
    ")
    .unwrap();
    let scene = &scenes[0];
    assert_eq!(scene.csg.len(), 2, "one CSG object per path");
    let a_local = DMat4::from_scale(DVec3::new(2.0, 1.0, 1.0))
        * DMat4::from_translation(DVec3::new(0.0, 1.0, 0.0))
        * DMat4::from_scale(DVec3::splat(0.5));
    let thing = DMat4::from_scale(DVec3::splat(3.0));
    let left = DMat4::from_translation(DVec3::new(-2.0, 0.0, 0.0));
    // Pre order: translate, then rotate: R·T.
    let right = DMat4::from_rotation_z(std::f64::consts::FRAC_PI_2)
        * DMat4::from_translation(DVec3::new(2.0, 0.0, 0.0));
    for (c, parent) in scene.csg.iter().zip([left, right]) {
        let l = leaves_of(c);
        assert!(l[0]
            .object_to_world
            .abs_diff_eq(parent * thing * a_local, 1e-12));
        assert!(l[1].object_to_world.abs_diff_eq(parent * thing, 1e-12));
        assert!(l[0].name.ends_with("thing/a"), "{}", l[0].name);
    }
}

#[test]
fn depth_limit() {
    let chain = |depth: usize| {
        let mut src = String::from("root = gr.node('root')\nn = gr.sphere('s0')\n");
        for i in 1..=depth {
            src += &format!("n = gr.csg('c{i}', 'u', n, gr.nh_sphere('s{i}', {{{i}, 0, 0}}, 1))\n");
        }
        src + "root:add_child(n)\n"
    };
    // 16 levels of unions of spheres: 17 intervals, 68 ends at most: renders.
    let scenes = run(&chain(16)).unwrap();
    assert_eq!(leaves_of(&scenes[0].csg[0]).len(), 17);
    let e = run(&chain(17)).unwrap_err();
    assert!(
        e.contains("scene.lua:")
            && e.contains("gr.render")
            && e.contains(
                "CSG node 'root/c17' nests CSG operations deeper than 16 levels (at 'root/c17/c16/"
            )
            && e.ends_with("/c1')"),
        "{e}"
    );
}

#[test]
fn interval_capacity_limit() {
    let tori = |n: usize| {
        let mut src = String::from("root = gr.node('root')\nn = gr.torus('t0', 1, 0.2)\n");
        for i in 1..n {
            src += &format!(
                "t = gr.torus('t{i}', 1, 0.2) t:translate({i}, 0, 0)\nn = gr.csg('c{i}', 'u', n, t)\n"
            );
        }
        src + "root:add_child(n)\n"
    };
    // A union of 16 tori needs 128 interval ends at most: the capacity exactly.
    run(&tori(16)).unwrap();
    let e = run(&tori(17)).unwrap_err();
    assert!(
        e.contains("CSG node 'root/c16' may hold up to 136 interval ends per ray")
            && e.contains("capacity of 128"),
        "{e}"
    );
}

#[test]
fn bad_operands_are_scene_errors() {
    let cases: [(&str, &[&str]); 8] = [
        (
            "m = gr.mesh('m', {{0,0,0},{1,0,0},{0,1,0}}, {{0,1,2}})\nc = gr.csg('c', 'u', m, gr.sphere('s'))",
            &["scene.lua:2: gr.csg: argument 3 (a) must be a primitive or CSG node", "got mesh node 'm' (meshes cannot be CSG operands)"],
        ),
        (
            "c = gr.csg('c', 'd', gr.sphere('s'), 3)",
            &["scene.lua:1: gr.csg: argument 4 (b) must be a node, got 3"],
        ),
        (
            "g = gr.node('group')\ng:add_child(gr.sphere('s'))\nc = gr.csg('c', 'i', g, gr.sphere('t'))",
            &["scene.lua:3: gr.csg: argument 3 (a)", "got transform node 'group' (a transform node is a group, not a solid"],
        ),
        (
            "c = gr.csg('c', 'u', gr.sphere('s'))",
            &["gr.csg: argument 4 (b) must be a node, got nil"],
        ),
        (
            "c = gr.csg('c', 'x', gr.sphere('s'), gr.cube('b'))",
            &["gr.csg: argument 2 (op) must be 'u' (union), 'i' (intersection) or 'd' (difference, a minus b), got 'x'"],
        ),
        (
            "c = gr.csg('c', gr.sphere('s'), gr.cube('b'))",
            &["gr.csg: argument 2 (op) must be"],
        ),
        (
            "s = gr.sphere('s')\nc = gr.csg('c', 'u', s, gr.cube('b'))\ns:add_child(c)",
            &["scene.lua:3: node:add_child: argument 1 (child): adding node 'c' under node 's' would make a cycle"],
        ),
        (
            "s = gr.sphere('s')\ns:add_child(gr.cube('b'))\nroot = gr.node('root')\nroot:add_child(gr.csg('c', 'u', s, gr.cube('k')))",
            &["gr.render: CSG node 'root/c': operand 's' has children; an operand is only its own solid"],
        ),
    ];
    for (source, needles) in cases {
        let e = match run(source) {
            Err(e) => e,
            Ok(_) => panic!("no error for {source}"),
        };
        for needle in needles {
            assert!(e.contains(needle), "{source}:\n{e}\nlacks {needle}");
        }
    }
}

// ---- scale invariance ------------------------------------------------------------------

/// scenes/csg.lua (a torus, a cone, a cylinder, the CSG glass and more) with everything,
/// camera and lights included, scaled by 1e-3 and 1e3 renders the same image as at scale
/// 1 (FLIP mean < 0.005, ≥ 99.9% of pixels within 2/255), with no NaN, and rays into the
/// glass (cut with coplanar caps; refractive) find no speckle at any scale.
#[test]
fn csg_scene_is_scale_invariant() {
    let overrides = glint::scene::OptionOverrides {
        width: Some(128),
        height: Some(80),
        ..Default::default()
    };
    let path = common::root().join("scenes/csg.lua");
    let scene = &common::load_scenes(&path, &overrides)[0];
    let reference = common::render_cpu(&pack(scene).unwrap());
    for s in [1.0, 1e-3, 1e3] {
        let scaled = common::scaled_scene(scene, s);
        let packed = pack(&scaled).unwrap();
        let probe = common::GlassProbe::new(&scaled, 4000);
        let results: Vec<_> = probe
            .rays
            .iter()
            .map(|r| glint::testing::probe::probe(&packed, r))
            .collect();
        let hits = results.iter().filter(|r| r.hit == 1).count();
        assert_eq!(
            hits,
            results.len(),
            "scale {s}: a ray into the glass missed"
        );
        assert_eq!(
            probe.speckles(&results),
            0,
            "scale {s}: speckles in the glass"
        );
        if s == 1.0 {
            continue;
        }
        let film = common::render_cpu(&packed);
        assert!(
            film.pixels.iter().flatten().all(|v| v.is_finite()),
            "NaN at scale {s}"
        );
        let name = format!("scale-{s}-csg");
        let report = glint::diff::assert_images_match(
            &name,
            &film,
            &reference,
            0.005,
            0.999,
            &common::failure_dir(),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        println!("{name}: {report}");
    }
}
