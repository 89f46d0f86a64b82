//! The rays of the trace benchmark (`bench_trace`) and their answers: camera rays, one
//! per pixel through its centre; shadow rays, one per hit and light in front of the hit
//! surface; both traced by the CPU tracer's `closest_hit` / `any_hit`, and summarised by
//! counts and a checksum of the hit items.

use crate::constants::{NO_ITEM, T_MISS};
use crate::cpu::ray::{camera_ray, offset_ray, Ray};
use crate::cpu::surface::surface_at;
use crate::cpu::traverse::{any_hit, closest_hit, Hit, NoCounters};
use crate::pack::PackedScene;
use crate::scene::flatten::{flatten, Scene};
use crate::scene::lua::{run_scene_file, ScriptConfig};
use glam::Vec3;
use rayon::prelude::*;
use std::path::Path;

/// A shadow ray: towards a light, blocked if anything lies in (0, t_max).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowRay {
    pub ray: Ray,
    pub t_max: f32,
}

/// The counts and checksum of one trace run (also what `--dump-rays` lets Embree match).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TraceSummary {
    pub primary_rays: usize,
    pub primary_hits: usize,
    pub shadow_rays: usize,
    pub shadow_occluded: usize,
    /// Σ (item + 1) over the primary rays that hit, wrapping (items: instances first,
    /// then triangles, as in the packed scene).
    pub hit_checksum: u64,
}

/// Runs the script and flattens its first `gr.render` call, at `width`×`height` when
/// given.
pub fn load_first_render(
    path: &Path,
    width: Option<u32>,
    height: Option<u32>,
) -> anyhow::Result<Scene> {
    let mut scene = None;
    run_scene_file(path, &ScriptConfig::default(), &mut |graph, request| {
        if scene.is_none() {
            let mut request = request.clone();
            request.width = width.unwrap_or(request.width);
            request.height = height.unwrap_or(request.height);
            scene = Some(flatten(graph, &request)?);
        }
        Ok(())
    })?;
    scene.ok_or_else(|| anyhow::anyhow!("{} never calls gr.render", path.display()))
}

/// One ray per pixel through its centre, row by row.
pub fn camera_rays(scene: &PackedScene) -> Vec<Ray> {
    let g = &scene.globals;
    (0..g.width * g.height)
        .into_par_iter()
        .map(|i| camera_ray(g, (i % g.width) as f32 + 0.5, (i / g.width) as f32 + 0.5))
        .collect()
}

/// The nearest hit of each ray.
pub fn trace_primary(scene: &PackedScene, rays: &[Ray]) -> Vec<Hit> {
    let mut hits = vec![Hit::MISS; rays.len()];
    trace_primary_into(scene, rays, &mut hits);
    hits
}

/// The nearest hit of each ray, into `hits` (one per ray).
pub fn trace_primary_into(scene: &PackedScene, rays: &[Ray], hits: &mut [Hit]) {
    hits.par_iter_mut()
        .zip(rays)
        .for_each(|(hit, r)| *hit = closest_hit(scene, r, T_MISS, &mut NoCounters));
}

/// Whether each shadow ray is blocked.
pub fn trace_shadow(scene: &PackedScene, rays: &[ShadowRay]) -> Vec<bool> {
    let mut occluded = vec![false; rays.len()];
    trace_shadow_into(scene, rays, &mut occluded);
    occluded
}

/// Whether each shadow ray is blocked, into `occluded` (one per ray).
pub fn trace_shadow_into(scene: &PackedScene, rays: &[ShadowRay], occluded: &mut [bool]) {
    occluded
        .par_iter_mut()
        .zip(rays)
        .for_each(|(o, s)| *o = any_hit(scene, &s.ray, s.t_max, &mut NoCounters));
}

/// The shadow rays of every hit, in pixel order and light order: from the hit point
/// offset to the side the primary ray came from, to each light in front of the surface
/// (`shade_phong` traces no others), an area light at its centre.
pub fn shadow_rays(scene: &PackedScene, primary: &[Ray], hits: &[Hit]) -> Vec<ShadowRay> {
    let lights = &scene.lights[..scene.globals.num_lights as usize];
    primary
        .par_iter()
        .zip(hits)
        .flat_map_iter(|(ray, hit)| {
            let mut out = Vec::new();
            if hit.is_hit() {
                let s = surface_at(scene, ray, hit);
                let n = if s.normal.dot(ray.dir) > 0.0 {
                    -s.normal
                } else {
                    s.normal
                };
                let origin = offset_ray(s.p, n, s.magnitude);
                for light in lights {
                    // A point light's position; an area light's centre.
                    let position = Vec3::from(light.position);
                    if n.dot(position - s.p) <= 0.0 {
                        continue;
                    }
                    let to_light = position - origin;
                    let distance = to_light.length();
                    out.push(ShadowRay {
                        ray: Ray {
                            origin,
                            dir: to_light / distance,
                        },
                        t_max: distance,
                    });
                }
            }
            out
        })
        .collect()
}

pub fn summarise(hits: &[Hit], occluded: &[bool]) -> TraceSummary {
    let hit_items = hits.iter().filter(|h| h.item != NO_ITEM);
    TraceSummary {
        primary_rays: hits.len(),
        primary_hits: hit_items.clone().count(),
        shadow_rays: occluded.len(),
        shadow_occluded: occluded.iter().filter(|&&o| o).count(),
        hit_checksum: hit_items.fold(0u64, |sum, h| sum.wrapping_add(h.item as u64 + 1)),
    }
}
