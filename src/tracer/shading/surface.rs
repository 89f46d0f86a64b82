//! Surface reconstruction at a hit ([`surface_at`]: point, normal, material, UV and
//! tangent frame) and the Phong colours there ([`Phong`]): what texturing, dielectrics and
//! shading read about a hit point.

use crate::constants::{
    CSG_FLIP, CSG_INDEX_MASK, KIND_CONE, KIND_CSG, KIND_CYLINDER, KIND_MESH, KIND_SPHERE,
    KIND_TORUS,
};
use crate::pack::{load_instance, load_triangle_uv, PackedInstance, PackedScene};
use crate::tracer::base::ray::Ray;
use crate::tracer::geometry::cylinder_cone::{cone_surface, cylinder_surface};
use crate::tracer::geometry::intersect::{to_object_space, triangle_vertices};
use crate::tracer::geometry::torus::torus_surface;
use crate::tracer::geometry::uv::{cube_surface, sphere_surface, triangle_frame};
use crate::tracer::traversal::traverse::Hit;
use glam::{Vec2, Vec3};

/// What shading needs to know about a hit point.
// Mirror of src/tracer/shading/surface.wgsl::Surface — change both.
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
    /// Texture coordinates (conventions in `tracer::geometry::uv`; zero on triangles of scenes without
    /// textures or bump maps, which pack no triangle UVs).
    pub uv: Vec2,
    /// World-space ∂p/∂u and ∂p/∂v (the tangent frame of bump mapping; unnormalised).
    pub dpdu: Vec3,
    pub dpdv: Vec3,
    /// Width, in uv, of the patch one pixel covers here (`texture::texture_footprint`):
    /// the texture filter's footprint. `surface_at` leaves it 0 (no filtering); tracing
    /// sets it in scenes with textures or bump maps.
    pub footprint: f32,
    /// The point in the primitive's own space (before its nodes' transforms: the mesh's
    /// for a triangle, the leaf's for CSG), where procedural textures are evaluated.
    pub p_object: Vec3,
    /// The instance whose object space `p_object` is in.
    pub instance: u32,
    /// Width, in world units, of the patch one pixel covers here (the procedural
    /// textures' footprint, `texture::pixel_footprint`): 0 from `surface_at`; tracing
    /// sets it in scenes with procedural textures.
    pub world_footprint: f32,
}

/// The Phong colours at a shading point (the material's, or its textures' at the UV).
// Mirror of src/tracer/shading/surface.wgsl::Phong — change both.
#[derive(Clone, Copy, Debug)]
pub struct Phong {
    pub kd: Vec3,
    pub ks: Vec3,
}

/// Largest |entry| sum over the rows of an affine 3×4 matrix: bounds the magnitude of
/// the world coordinates it produces from a point in the unit box.
// Mirror of src/tracer/shading/surface.wgsl::affine_magnitude — change both.
fn affine_magnitude(rows: &[[f32; 4]; 3]) -> f32 {
    rows.iter()
        .map(|r| r[0].abs() + r[1].abs() + r[2].abs() + r[3].abs())
        .fold(0.0, f32::max)
}

/// Point, normal and magnitude of an instance hit, computed in object space (where the
/// point is snapped onto the exact surface) and mapped to world space.
// Mirror of src/tracer/shading/surface.wgsl::instance_surface — change both.
fn instance_surface(inst: &PackedInstance, ray: &Ray, t: f32) -> Surface {
    let (oo, od) = to_object_space(inst, ray.origin, ray.dir);
    let p_hit = oo + od * t;
    // Every kind snaps the point onto its surface.
    let s = if inst.kind == KIND_CYLINDER {
        cylinder_surface(p_hit)
    } else if inst.kind == KIND_CONE {
        cone_surface(p_hit, inst.params[0], inst.params[1])
    } else if inst.kind == KIND_SPHERE {
        sphere_surface(p_hit)
    } else if inst.kind == KIND_TORUS {
        torus_surface(p_hit, inst.params[0], inst.params[1])
    } else {
        cube_surface(p_hit)
    };
    let (p_obj, n_obj) = (s.p, s.normal);
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
    // Tangents transform like directions: the linear part of object→world.
    let to_world = |d: Vec3| {
        Vec3::new(
            Vec3::new(o2w[0][0], o2w[0][1], o2w[0][2]).dot(d),
            Vec3::new(o2w[1][0], o2w[1][1], o2w[1][2]).dot(d),
            Vec3::new(o2w[2][0], o2w[2][1], o2w[2][2]).dot(d),
        )
    };
    Surface {
        p,
        normal,
        // Object points may lie beyond the unit box (a torus reaches rin + rout).
        magnitude: affine_magnitude(o2w) * p_obj.abs().max_element().max(1.0),
        material: inst.material,
        uv: s.uv,
        dpdu: to_world(s.dpdu),
        dpdv: to_world(s.dpdv),
        footprint: 0.0,
        p_object: p_obj,
        instance: 0,
        world_footprint: 0.0,
    }
}

/// The surface at a hit: an analytic instance's, a CSG object's or a mesh triangle's.
// Mirror of src/tracer/shading/surface.wgsl::surface_at — change both.
pub fn surface_at(scene: &PackedScene, ray: &Ray, hit: &Hit) -> Surface {
    let inst = load_instance(scene, hit.item);
    if inst.kind == KIND_CSG {
        return csg_surface(scene, ray, hit);
    }
    if inst.kind == KIND_MESH {
        return mesh_surface(scene, inst, hit);
    }
    let mut s = instance_surface(inst, ray, hit.t);
    s.instance = hit.item;
    s
}

/// Largest world coordinate magnitude an affine map (rows) gives a point whose
/// coordinates are at most `magnitude`: max over rows of Σ|linear|·magnitude + |w|
/// (exactly `magnitude` under the identity).
// Mirror of src/tracer/shading/surface.wgsl::mapped_magnitude — change both.
fn mapped_magnitude(rows: &[[f32; 4]; 3], magnitude: f32) -> f32 {
    rows.iter()
        .map(|r| (r[0].abs() + r[1].abs() + r[2].abs()) * magnitude + r[3].abs())
        .fold(0.0, f32::max)
}

/// The surface of a mesh hit: triangle `hit.part` of the instance's mesh at the hit's
/// barycentrics, computed in the mesh's space and mapped to world space (point and
/// tangents through object→world, the normal through the transpose of world→object).
// Mirror of src/tracer/shading/surface.wgsl::mesh_surface — change both.
fn mesh_surface(scene: &PackedScene, inst: &PackedInstance, hit: &Hit) -> Surface {
    let index = hit.part as usize;
    let [p0, p1, p2] = triangle_vertices(&scene.triangles[index]);
    // The barycentric point is exact to a few ulps of the vertices (unlike o + t·d).
    let b0 = 1.0 - hit.b1 - hit.b2;
    let p_obj = p0 * b0 + p1 * hit.b1 + p2 * hit.b2;
    let magnitude_obj = p0.abs().max(p1.abs()).max(p2.abs()).max_element();
    let n_obj = (p1 - p0).cross(p2 - p0);
    let (mut uv, mut dpdu, mut dpdv) = (Vec2::ZERO, Vec3::ZERO, Vec3::ZERO);
    // Triangle UVs are packed only for scenes that use them.
    if scene.features.uses_textures() {
        let t = load_triangle_uv(scene, index as u32);
        let (uv0, uv1, uv2) = (Vec2::from(t.uv0), Vec2::from(t.uv1), Vec2::from(t.uv2));
        uv = uv0 * b0 + uv1 * hit.b1 + uv2 * hit.b2;
        (dpdu, dpdv) = triangle_frame([p0, p1, p2], [uv0, uv1, uv2], n_obj.normalize());
    }
    let o2w = &inst.object_to_world;
    let row = |r: &[f32; 4]| Vec3::new(r[0], r[1], r[2]);
    let to_world = |d: Vec3| {
        Vec3::new(
            row(&o2w[0]).dot(d),
            row(&o2w[1]).dot(d),
            row(&o2w[2]).dot(d),
        )
    };
    let w2o = &inst.world_to_object;
    let normal =
        (row(&w2o[0]) * n_obj.x + row(&w2o[1]) * n_obj.y + row(&w2o[2]) * n_obj.z).normalize();
    Surface {
        p: to_world(p_obj) + Vec3::new(o2w[0][3], o2w[1][3], o2w[2][3]),
        normal,
        magnitude: mapped_magnitude(o2w, magnitude_obj),
        material: inst.material,
        uv,
        dpdu: to_world(dpdu),
        dpdv: to_world(dpdv),
        footprint: 0.0,
        p_object: p_obj,
        instance: hit.item,
        world_footprint: 0.0,
    }
}

/// The surface of a CSG hit: that of the leaf it lies on (point, material — and, with
/// them, the UV and tangent frame a texture or bump map will read), the normal negated
/// on a subtracted operand's surface, which bounds the result from the other side.
// Mirror of src/tracer/shading/surface.wgsl::csg_surface — change both.
fn csg_surface(scene: &PackedScene, ray: &Ray, hit: &Hit) -> Surface {
    let leaf = load_instance(scene, hit.part & CSG_INDEX_MASK);
    let mut s = instance_surface(leaf, ray, hit.t);
    s.instance = hit.part & CSG_INDEX_MASK;
    if hit.part & CSG_FLIP != 0 {
        // (When Surface gains uv/dpdu/dpdv, they stay the leaf's; only the normal flips.)
        s.normal = -s.normal;
    }
    s
}
