//! Surface reconstruction at a hit, A4 Phong shading with shadow rays, and the background.

use super::cylinder_cone::{cone_surface, cylinder_surface};
use super::intersect::{to_object_space, triangle_vertices};
use super::ray::{offset_ray, Ray};
use super::rng::{shadow_random, SampleSeed};
use super::torus::torus_surface;
use super::traverse::{any_hit, Hit, TraversalCounters};
use crate::constants::{
    CSG_FLIP, CSG_INDEX_MASK, KIND_CONE, KIND_CSG, KIND_CYLINDER, KIND_SPHERE, KIND_TORUS,
    LIGHT_AREA,
};
use crate::pack::{GpuGlobals, GpuInstance, GpuLight, PackedScene};
use glam::Vec3;

/// What shading needs to know about a hit point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// World-space point, reprojected onto the surface.
    pub p: Vec3,
    /// Unit geometric normal in world space (outward for analytic primitives, by winding
    /// for triangles; not yet turned towards the viewer).
    pub normal: Vec3,
    /// Largest coordinate magnitude that went into `p` (for `offset_ray`).
    pub magnitude: f32,
    pub material: u32,
}

/// Largest |entry| sum over the rows of an affine 3×4 matrix: bounds the magnitude of
/// the world coordinates it produces from a point in the unit box.
// Mirror of shaders/shade.wgsl::affine_magnitude — change both.
fn affine_magnitude(rows: &[[f32; 4]; 3]) -> f32 {
    rows.iter()
        .map(|r| r[0].abs() + r[1].abs() + r[2].abs() + r[3].abs())
        .fold(0.0, f32::max)
}

/// Point, normal and magnitude of an instance hit, computed in object space (where the
/// point is snapped onto the exact surface) and mapped to world space.
// Mirror of shaders/shade.wgsl::instance_surface — change both.
fn instance_surface(inst: &GpuInstance, ray: &Ray, t: f32) -> Surface {
    let (oo, od) = to_object_space(inst, ray.origin, ray.dir);
    let mut p_obj = oo + od * t;
    let n_obj;
    if inst.kind == KIND_CYLINDER {
        let s = cylinder_surface(p_obj);
        p_obj = s.p;
        n_obj = s.normal;
    } else if inst.kind == KIND_CONE {
        let [zmin, zmax] = inst.params;
        let s = cone_surface(p_obj, zmin, zmax);
        p_obj = s.p;
        n_obj = s.normal;
    } else if inst.kind == KIND_SPHERE {
        // Reproject onto the unit sphere.
        p_obj = p_obj.normalize();
        n_obj = p_obj;
    } else if inst.kind == KIND_TORUS {
        // Project onto the tube (the tangent frame and UV are unused until bump mapping).
        let s = torus_surface(p_obj, inst.params[0], inst.params[1]);
        p_obj = s.p;
        n_obj = s.normal;
    } else {
        // The face nearest the point: snap the point onto it.
        let dist = p_obj.abs().min((p_obj - Vec3::ONE).abs());
        let axis = if dist.x <= dist.y && dist.x <= dist.z {
            0
        } else if dist.y <= dist.z {
            1
        } else {
            2
        };
        let upper = p_obj[axis] > 0.5;
        p_obj[axis] = if upper { 1.0 } else { 0.0 };
        let mut n = Vec3::ZERO;
        n[axis] = if upper { 1.0 } else { -1.0 };
        n_obj = n;
    }
    let o2w = &inst.object_to_world;
    let p = Vec3::new(
        Vec3::new(o2w[0][0], o2w[0][1], o2w[0][2]).dot(p_obj) + o2w[0][3],
        Vec3::new(o2w[1][0], o2w[1][1], o2w[1][2]).dot(p_obj) + o2w[1][3],
        Vec3::new(o2w[2][0], o2w[2][1], o2w[2][2]).dot(p_obj) + o2w[2][3],
    );
    // Normals transform by the inverse transpose: Σ n_obj[i] · (row i of world→object).
    let w2o = &inst.world_to_object;
    let normal = (Vec3::new(w2o[0][0], w2o[0][1], w2o[0][2]) * n_obj.x
        + Vec3::new(w2o[1][0], w2o[1][1], w2o[1][2]) * n_obj.y
        + Vec3::new(w2o[2][0], w2o[2][1], w2o[2][2]) * n_obj.z)
        .normalize();
    Surface {
        p,
        normal,
        // Object points may lie beyond the unit box (a torus reaches rin + rout).
        magnitude: affine_magnitude(o2w) * p_obj.abs().max_element().max(1.0),
        material: inst.material,
    }
}

/// The surface at a hit (instances first, then triangles, as in the grid's items).
// Mirror of shaders/shade.wgsl::surface_at — change both.
pub fn surface_at(scene: &PackedScene, ray: &Ray, hit: &Hit) -> Surface {
    let num_instances = scene.globals.num_instances;
    if hit.item < num_instances {
        let inst = &scene.instances[hit.item as usize];
        if inst.kind == KIND_CSG {
            return csg_surface(scene, ray, hit);
        }
        return instance_surface(inst, ray, hit.t);
    }
    let tri = &scene.triangles[(hit.item - num_instances) as usize];
    let [p0, p1, p2] = triangle_vertices(tri);
    // The barycentric point is exact to a few ulps of the vertices (unlike o + t·d).
    let p = p0 * (1.0 - hit.b1 - hit.b2) + p1 * hit.b1 + p2 * hit.b2;
    let magnitude = p0.abs().max(p1.abs()).max(p2.abs()).max_element();
    Surface {
        p,
        normal: (p1 - p0).cross(p2 - p0).normalize(),
        magnitude,
        material: tri.material,
    }
}

/// The surface of a CSG hit: that of the leaf it lies on (point, material — and, with
/// them, the UV and tangent frame a texture or bump map will read), the normal negated
/// on a subtracted operand's surface, which bounds the result from the other side.
// Mirror of shaders/shade.wgsl::csg_surface — change both.
fn csg_surface(scene: &PackedScene, ray: &Ray, hit: &Hit) -> Surface {
    let leaf = &scene.instances[(hit.part & CSG_INDEX_MASK) as usize];
    let mut s = instance_surface(leaf, ray, hit.t);
    if hit.part & CSG_FLIP != 0 {
        // (When Surface gains uv/dpdu/dpdv, they stay the leaf's; only the normal flips.)
        s.normal = -s.normal;
    }
    s
}

/// `base^exponent` for base in [0, 1] without NaN or overflow for any exponent ≥ 0
/// (shininess can be 5e7): zero unless base > 0.
// Mirror of shaders/shade.wgsl::phong_power — change both.
pub fn phong_power(base: f32, exponent: f32) -> f32 {
    if base > 0.0 {
        (exponent * base.min(1.0).log2()).exp2()
    } else {
        0.0
    }
}

/// A4 lighting at a surface point: kd·ambient plus, for each light a shadow ray reaches,
/// (kd·max(0,N·L) + ks·max(0,R·V)^shininess)·I/(c0 + c1·d + c2·d²). `n` faces the viewer;
/// `v` points to the viewer. An area light is n×n such point lights, one jittered point
/// per stratum of its parallelogram (random numbers from `seed`), each with 1/n² of its
/// colour.
// Mirror of shaders/shade.wgsl::shade_phong — change both.
pub fn shade_phong(
    scene: &PackedScene,
    s: &Surface,
    n: Vec3,
    v: Vec3,
    seed: SampleSeed,
    counters: &mut impl TraversalCounters,
) -> Vec3 {
    let m = &scene.materials[s.material as usize];
    let mut colour = Vec3::from(m.kd) * Vec3::from(scene.globals.ambient);
    let origin = offset_ray(s.p, n, s.magnitude);
    for (index, light) in scene.lights[..scene.globals.num_lights as usize]
        .iter()
        .enumerate()
    {
        if light.kind == LIGHT_AREA {
            colour += area_light(scene, s, n, v, origin, light, index as u32, seed, counters);
        } else {
            colour += point_light(
                scene,
                s,
                n,
                v,
                origin,
                Vec3::from(light.position),
                light,
                counters,
            );
        }
    }
    colour
}

/// Light from a point at `position` with `light`'s colour and falloff: the A4 term, or
/// zero when the point is behind the surface or a shadow ray from `origin` is blocked.
// Mirror of shaders/shade.wgsl::point_light — change both.
#[allow(clippy::too_many_arguments)]
fn point_light(
    scene: &PackedScene,
    s: &Surface,
    n: Vec3,
    v: Vec3,
    origin: Vec3,
    position: Vec3,
    light: &GpuLight,
    counters: &mut impl TraversalCounters,
) -> Vec3 {
    let m = &scene.materials[s.material as usize];
    let to_light = position - s.p;
    let distance = to_light.length();
    let l = to_light / distance;
    let n_dot_l = n.dot(l);
    // Lights behind the surface (as seen from the viewer's side) add nothing.
    if n_dot_l.is_nan() || n_dot_l <= 0.0 {
        return Vec3::ZERO;
    }
    let shadow_dir = position - origin;
    let shadow_distance = shadow_dir.length();
    let shadow_ray = Ray {
        origin,
        dir: shadow_dir / shadow_distance,
    };
    if any_hit(scene, &shadow_ray, shadow_distance, counters) {
        return Vec3::ZERO;
    }
    let r = n * (2.0 * n_dot_l) - l;
    let specular = phong_power(r.dot(v), m.shininess);
    let [c0, c1, c2] = light.falloff;
    let attenuation = 1.0 / (c0 + distance * (c1 + distance * c2));
    (Vec3::from(m.kd) * n_dot_l + Vec3::from(m.ks) * specular)
        * Vec3::from(light.colour)
        * attenuation
}

/// Light from area light number `index`: the mean of [`point_light`] over one jittered
/// point in each of the n×n strata of its parallelogram, stratum k = (k mod n, k div n).
// Mirror of shaders/shade.wgsl::area_light — change both.
#[allow(clippy::too_many_arguments)]
fn area_light(
    scene: &PackedScene,
    s: &Surface,
    n: Vec3,
    v: Vec3,
    origin: Vec3,
    light: &GpuLight,
    index: u32,
    seed: SampleSeed,
    counters: &mut impl TraversalCounters,
) -> Vec3 {
    let k = light.samples;
    let scale = 1.0 / k as f32;
    let (centre, u, w) = (
        Vec3::from(light.position),
        Vec3::from(light.edge_u),
        Vec3::from(light.edge_v),
    );
    let mut sum = Vec3::ZERO;
    for stratum in 0..k * k {
        let a = ((stratum % k) as f32 + shadow_random(seed, index, stratum, 0)) * scale - 0.5;
        let b = ((stratum / k) as f32 + shadow_random(seed, index, stratum, 1)) * scale - 0.5;
        let position = centre + u * a + w * b;
        sum += point_light(scene, s, n, v, origin, position, light, counters);
    }
    sum * (scale * scale)
}

/// Colour of a ray that hits nothing: the vertical gradient by direction (solid when
/// top = bottom), "up" being the camera's up.
// Mirror of shaders/shade.wgsl::background — change both.
pub fn background(g: &GpuGlobals, dir: Vec3) -> Vec3 {
    let t = 0.5 * (dir.dot(Vec3::from(g.up)) + 1.0);
    Vec3::from(g.background_bottom) * (1.0 - t) + Vec3::from(g.background_top) * t
}
