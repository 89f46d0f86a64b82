//! The CPU's four-lane triangle test (`tracer::geometry::triangle4`) against the scalar watertight test
//! it must equal: per lane the same hit or miss and the same t, bit for bit, on seeded
//! random triangles at all scales, rays aimed at vertices and along shared edges (where
//! the edge functions are zero and only their sign of zero differs between the two
//! forms), grazing and in-plane rays; and the batch walk's nearest hit equal to the
//! scalar loop's, ties included (the first triangle in order wins).

use crate::oracle_support;
use oracle_support::*;

use glam::{DVec3, Vec3};
use glint::constants::NO_ITEM;
use glint::pack::PackedTriangle;
use glint::tracer::geometry::intersect::{intersect_triangle, triangle_vertices};
use glint::tracer::geometry::triangle4::{
    intersect_triangles4, NearestTriangle, TriangleBatch, TriangleRays, LANES,
};

fn packed(p: [DVec3; 3]) -> PackedTriangle {
    PackedTriangle {
        p0: v32(p[0]).to_array(),
        p1: v32(p[1]).to_array(),
        p2: v32(p[2]).to_array(),
    }
}

/// A random triangle of size `scale` around `centre`.
fn random_triangle(rng: &mut Rng, centre: DVec3, scale: f64) -> [DVec3; 3] {
    [0, 1, 2].map(|_| centre + rng.unit_vector() * scale * rng.range(0.2, 1.0))
}

/// A point the ray is aimed at on or near triangle `p`: a vertex, a point of an edge,
/// an inside point, or a point beside it.
fn aim_point(rng: &mut Rng, p: &[DVec3; 3]) -> DVec3 {
    match rng.below(4) {
        0 => p[rng.below(3)],
        1 => {
            let (a, b) = (p[rng.below(3)], p[rng.below(3)]);
            a.lerp(b, rng.f64())
        }
        2 => {
            let (b1, b2) = (rng.f64(), rng.f64());
            let (b1, b2) = if b1 + b2 > 1.0 {
                (1.0 - b1, 1.0 - b2)
            } else {
                (b1, b2)
            };
            p[0] + (p[1] - p[0]) * b1 + (p[2] - p[0]) * b2
        }
        _ => p[0] + (p[1] - p[0]) * rng.range(-1.0, 2.0) + (p[2] - p[0]) * rng.range(-1.0, 2.0),
    }
}

/// The scalar test on each of `tris`: (hit bits, t of each lane).
fn scalar_lanes(
    rays: &TriangleRays,
    tris: &[PackedTriangle; LANES],
    t_max: f32,
) -> (u32, [f32; 4]) {
    let mut bits = 0;
    let mut t = [0.0; 4];
    for (k, tri) in tris.iter().enumerate() {
        let [p0, p1, p2] = triangle_vertices(tri);
        let h = intersect_triangle(&rays.scalar, p0, p1, p2, t_max);
        if h.x < t_max {
            bits |= 1 << k;
            t[k] = h.x;
        }
    }
    (bits, t)
}

/// Four triangles sharing edges and vertices (a fan around `centre`), or four random
/// ones, or a mix with repeats; and a ray from up to 1e4 sizes away aimed at one of them.
fn case(seed: u64) -> ([PackedTriangle; LANES], Vec3, Vec3, f32) {
    let mut rng = Rng::new(seed);
    let scale = rng.log_uniform(1e-3, 1e4);
    let centre = rng.unit_vector() * scale * rng.log_uniform(1e-2, 1e3);
    let tris: [[DVec3; 3]; LANES] = match rng.below(3) {
        0 => {
            let hub = centre;
            let rim: Vec<DVec3> = (0..5).map(|_| centre + rng.unit_vector() * scale).collect();
            [0, 1, 2, 3].map(|k| [hub, rim[k], rim[k + 1]])
        }
        1 => [0, 1, 2, 3].map(|_| random_triangle(&mut rng, centre, scale)),
        _ => {
            let a = random_triangle(&mut rng, centre, scale);
            let b = [a[1], a[0], centre + rng.unit_vector() * scale];
            [a, b, a, b]
        }
    };
    let aimed = rng.below(LANES);
    let target = aim_point(&mut rng, &tris[aimed]);
    let origin = if rng.below(16) == 0 {
        // On a vertex: t = 0 for the triangles through it, which is no hit.
        v64(v32(tris[0][0]))
    } else if rng.below(4) == 0 {
        // Grazing: from far along the plane of a triangle.
        let t = &tris[0];
        let in_plane = (t[1] - t[0]).normalize_or_zero();
        target
            + in_plane
                * scale
                * rng.log_uniform(1.0, 1e4)
                * if rng.below(2) == 0 { 1.0 } else { -1.0 }
    } else {
        target + rng.unit_vector() * scale * rng.log_uniform(1e-2, 1e4)
    };
    let (o, d) = aim(origin, target);
    let t_max = if rng.below(3) == 0 {
        (mag(target - origin) * rng.range(0.5, 1.5)) as f32
    } else {
        f32::MAX
    };
    (tris.map(packed), o, d, t_max)
}

#[test]
fn four_lanes_equal_the_scalar_test_bit_for_bit() {
    let mut hits = 0;
    for i in 0..200_000 {
        let seed = case_seed(0x7214, i);
        let (tris, o, d, t_max) = case(seed);
        let rays = TriangleRays::new(o, d);
        let refs = [&tris[0], &tris[1], &tris[2], &tris[3]];
        let (bits, t) = intersect_triangles4(&rays.lanes, &refs, t_max);
        let (want_bits, want_t) = scalar_lanes(&rays, &tris, t_max);
        assert_eq!(bits, want_bits, "seed {seed}: hit lanes differ");
        let t = t.to_array();
        for k in 0..LANES {
            if bits & (1 << k) != 0 {
                assert_eq!(
                    t[k].to_bits(),
                    want_t[k].to_bits(),
                    "seed {seed}: lane {k} t"
                );
            }
        }
        hits += bits.count_ones();
        // Again with t_max at the nearest lane's own t, which is then no hit.
        if bits != 0 {
            let nearest = (0..LANES).filter(|k| bits & (1 << k) != 0).map(|k| t[k]);
            let t_max = nearest.fold(f32::MAX, f32::min);
            let (bits, _) = intersect_triangles4(&rays.lanes, &refs, t_max);
            assert_eq!(
                bits,
                scalar_lanes(&rays, &tris, t_max).0,
                "seed {seed}: at t_max"
            );
        }
    }
    // The cases must exercise both answers.
    assert!(
        hits > 100_000 && hits < 700_000,
        "{hits} lane hits of 800 000"
    );
}

/// The batch walk over `locals` (in order, batches of four), as `traverse_mesh` runs it.
fn batch_nearest(
    rays: &TriangleRays,
    tris: &[PackedTriangle],
    locals: &[u32],
    t_max: f32,
) -> NearestTriangle {
    let mut best = NearestTriangle::none(t_max);
    let mut batch = TriangleBatch::EMPTY;
    for &local in locals {
        if batch.push(local) {
            batch.keep_nearest(rays, tris, &mut best);
        }
    }
    batch.keep_nearest(rays, tris, &mut best);
    best
}

/// The scalar loop the batches replace: test in order, keep a strictly nearer hit.
fn scalar_nearest(
    rays: &TriangleRays,
    tris: &[PackedTriangle],
    locals: &[u32],
    t_max: f32,
) -> NearestTriangle {
    let mut best = NearestTriangle::none(t_max);
    for &local in locals {
        let [p0, p1, p2] = triangle_vertices(&tris[local as usize]);
        let h = intersect_triangle(&rays.scalar, p0, p1, p2, best.t);
        if h.x < best.t {
            best = NearestTriangle {
                t: h.x,
                local,
                b1: h.y,
                b2: h.z,
            };
        }
    }
    best
}

#[test]
fn batches_keep_the_scalar_loops_nearest_hit_and_its_barycentrics() {
    let mut kept = 0;
    for i in 0..50_000 {
        let seed = case_seed(0x7215, i);
        let (four, o, d, t_max) = case(seed);
        let mut rng = Rng::new(seed ^ 0x5eed);
        // 1–11 triangles drawn from the four (repeats make exact ties in t).
        let tris = four.to_vec();
        let locals: Vec<u32> = (0..1 + rng.below(11))
            .map(|_| rng.below(LANES) as u32)
            .collect();
        let rays = TriangleRays::new(o, d);
        let got = batch_nearest(&rays, &tris, &locals, t_max);
        let want = scalar_nearest(&rays, &tris, &locals, t_max);
        assert_eq!(got.local, want.local, "seed {seed}: nearest triangle");
        assert_eq!(
            [got.t, got.b1, got.b2].map(f32::to_bits),
            [want.t, want.b1, want.b2].map(f32::to_bits),
            "seed {seed}: t and barycentrics"
        );
        kept += (got.local != NO_ITEM) as u32;
    }
    assert!(kept > 10_000 && kept < 45_000, "{kept} of 50 000 cases hit");
}

#[test]
fn any_hit_of_a_batch_is_the_scalar_answer() {
    for i in 0..50_000 {
        let seed = case_seed(0x7216, i);
        let (four, o, d, t_max) = case(seed);
        let rays = TriangleRays::new(o, d);
        let tris = four.to_vec();
        for len in 0..=LANES {
            let mut batch = TriangleBatch::EMPTY;
            for local in 0..len as u32 {
                batch.push(local);
            }
            let want = scalar_nearest(&rays, &tris, &(0..len as u32).collect::<Vec<_>>(), t_max);
            assert_eq!(
                batch.any_hit(&rays, &tris, t_max),
                want.local != NO_ITEM,
                "seed {seed}, {len} triangles"
            );
        }
    }
}
