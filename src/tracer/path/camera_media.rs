//! The media that contain the camera: found once per scene after packing, by walking a
//! ray from the eye through every surface (see [`camera_media`]); the same walk finds an
//! opaque solid around the eye, a likely mistake ([`opaque_solid_around_eye`]).

use crate::constants::{KIND_MESH, MATERIAL_REFRACTIVE, T_MISS};
use crate::pack::PackedScene;
use crate::tracer::base::ray::{offset_ray, Ray};
use crate::tracer::shading::dielectric::{medium_push, MediumStack};
use crate::tracer::shading::surface::surface_at;
use crate::tracer::traversal::hit::Hit;
use crate::tracer::traversal::traverse::{closest_hit, NoCounters};
use glam::Vec3;

/// Direction of the ray that finds the media around the eye: fixed (so the result is
/// deterministic) and off every axis and diagonal (so it rarely grazes an edge).
const PARITY_RAY_DIR: Vec3 = Vec3::new(0.267_261_24, 0.534_522_5, 0.801_783_7);
/// Surfaces the eye's ray walks through at most.
const PARITY_RAY_STEPS: usize = 1024;

/// The medium stack primary rays start with: the dielectric solids that contain the eye,
/// outermost first (after `gr.render`, packing puts it in `PackedGlobals::camera_media`).
/// A ray from the eye walks through every surface; a solid contains the eye when the
/// first of its surfaces the ray meets is left rather than entered — the tracer's own
/// entering rule. A solid is an instance, or for triangles the set of triangles of one
/// material (a closed glass mesh). Nested solids are left innermost first, so sorting
/// by the distance to that first surface puts the outermost first.
pub fn camera_media(scene: &PackedScene) -> MediumStack {
    let g = &scene.globals;
    // (solid key, distance from the eye, left, ior) of each solid's first surface.
    let mut firsts: Vec<(u32, f32, bool, f32)> = Vec::new();
    let eye = Vec3::from(g.eye);
    walk_from_eye(scene, &mut |hit, s, left| {
        let m = &scene.materials[s.material as usize];
        if m.flags & MATERIAL_REFRACTIVE != 0 {
            // Triangles of one material form one solid; keys above the instances.
            let key = if scene.instances[hit.item as usize].kind == KIND_MESH {
                g.num_instances + s.material
            } else {
                hit.item
            };
            if !firsts.iter().any(|f| f.0 == key) {
                firsts.push((key, (s.p - eye).length(), left, m.ior));
            }
        }
        true
    });
    let mut containing: Vec<(f32, f32)> =
        firsts.iter().filter(|f| f.2).map(|f| (f.1, f.3)).collect();
    // Farthest first; ties (a shared surface) keep ray order.
    containing.sort_by(|a, b| b.0.total_cmp(&a.0));
    containing
        .iter()
        .fold(MediumStack::default(), |media, &(_, ior)| {
            medium_push(&media, ior)
        })
}

/// Walks [`PARITY_RAY_DIR`] from the eye through every surface, calling `visit` with
/// each hit, its surface and whether the ray leaves the surface there (runs against its
/// outward normal: the tracer's entering rule), until `visit` returns false.
fn walk_from_eye(
    scene: &PackedScene,
    visit: &mut dyn FnMut(&Hit, &crate::tracer::shading::surface::Surface, bool) -> bool,
) {
    let mut ray = Ray {
        origin: Vec3::from(scene.globals.eye),
        dir: PARITY_RAY_DIR,
    };
    for _ in 0..PARITY_RAY_STEPS {
        let hit = closest_hit(scene, &ray, T_MISS, &mut NoCounters);
        if !hit.is_hit() {
            break;
        }
        let s = surface_at(scene, &ray, &hit);
        let left = s.normal.dot(ray.dir) > 0.0;
        if !visit(&hit, &s, left) {
            break;
        }
        let beyond = if left { s.normal } else { -s.normal };
        ray.origin = offset_ray(s.p, beyond, s.magnitude);
    }
}

/// The grid item (a primitive or CSG object, not a mesh: a mesh need not be closed) of
/// an opaque material that contains the eye, if any: the first surface of it that the
/// eye's ray meets is left rather than entered. The camera then sees only its inside, a
/// likely mistake (an eye at the origin inside a box around the scene).
pub fn opaque_solid_around_eye(scene: &PackedScene) -> Option<u32> {
    let mut met: Vec<u32> = Vec::new();
    let mut inside = None;
    walk_from_eye(scene, &mut |hit, s, left| {
        let item = hit.item;
        let opaque = scene.materials[s.material as usize].flags & MATERIAL_REFRACTIVE == 0;
        if scene.instances[item as usize].kind == KIND_MESH || met.contains(&item) {
            return true;
        }
        met.push(item);
        if left && opaque {
            inside = Some(item);
            return false;
        }
        true
    });
    inside
}

/// Stores [`camera_media`] in the scene's globals, where both tracers read it.
pub fn fill_camera_media(packed: &mut PackedScene) {
    let media = camera_media(packed);
    packed.globals.camera_media = media.iors;
    packed.globals.camera_media_count = media.count;
}
