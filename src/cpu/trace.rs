//! Whitted tracing without recursion: an explicit, fixed-size stack of secondary rays,
//! each with the weight of its contribution to the pixel and its depth.

use super::ray::{offset_ray, Ray};
use super::rng::SampleSeed;
use super::shade::{background, shade_phong, surface_at};
use super::texture::shading_normal;
use super::traverse::{closest_hit, TraversalCounters};
use crate::constants::{DEBUG_VIEW_UV, MATERIAL_REFLECTIVE, RAY_STACK_SIZE, T_MISS};
use crate::pack::{PackedScene, SceneFeatures};
use glam::Vec3;

#[derive(Clone, Copy, Debug)]
struct StackEntry {
    ray: Ray,
    weight: Vec3,
    depth: u32,
}

/// Colour seen along a primary ray, mirrors included (down to `max_depth` bounces or
/// `min_weight` contribution). `seed` names the camera sample (its `depth` is ignored:
/// each shading point gets its own ray's depth).
// Mirror of shaders/trace.wgsl::trace_ray — change both.
pub fn trace_ray(
    scene: &PackedScene,
    primary: Ray,
    seed: SampleSeed,
    counters: &mut impl TraversalCounters,
) -> Vec3 {
    let g = &scene.globals;
    let mut stack = [StackEntry {
        ray: primary,
        weight: Vec3::ONE,
        depth: 0,
    }; RAY_STACK_SIZE as usize];
    let mut size = 1;
    let mut colour = Vec3::ZERO;
    while size > 0 {
        size -= 1;
        let entry = stack[size];
        let ray = entry.ray;
        let hit = closest_hit(scene, &ray, T_MISS, counters);
        if !hit.is_hit() {
            colour += entry.weight * background(g, ray.dir);
            continue;
        }
        let s = surface_at(scene, &ray, &hit);
        // The UV debug view (pack turns on TEXTURE for it): (u mod 1, v mod 1, 0).
        if g.debug_view == DEBUG_VIEW_UV {
            let uv = s.uv - s.uv.floor();
            colour += entry.weight * Vec3::new(uv.x, uv.y, 0.0);
            continue;
        }
        // Two-sided shading: the normal faces the incoming ray.
        let mut n = if s.normal.dot(ray.dir) > 0.0 {
            -s.normal
        } else {
            s.normal
        };
        if scene.features.contains(SceneFeatures::BUMP) {
            n = shading_normal(scene, &s, n);
        }
        let v = -ray.dir;
        let shade_seed = SampleSeed {
            depth: entry.depth,
            ..seed
        };
        colour += entry.weight * shade_phong(scene, &s, n, v, shade_seed, counters);
        let m = &scene.materials[s.material as usize];
        if m.flags & MATERIAL_REFLECTIVE != 0 && entry.depth < g.max_depth {
            let weight = entry.weight * Vec3::from(m.reflection);
            if weight.max_element() >= g.min_weight && size < RAY_STACK_SIZE as usize {
                let dir = ray.dir - n * (2.0 * ray.dir.dot(n));
                stack[size] = StackEntry {
                    ray: Ray {
                        origin: offset_ray(s.p, n, s.magnitude),
                        dir: dir.normalize(),
                    },
                    weight,
                    depth: entry.depth + 1,
                };
                size += 1;
            }
        }
    }
    colour
}
