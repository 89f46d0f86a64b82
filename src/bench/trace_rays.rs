//! The rays of the trace benchmark (`bench_trace`) and their answers: camera rays, one
//! per pixel through its centre; shadow rays, one per hit and light in front of the hit
//! surface; both traced by the CPU tracer's `closest_hit` / `any_hit`, and summarised by
//! counts and a checksum of the hit items.

use crate::constants::{KIND_MESH, NO_ITEM, T_MISS};
use crate::pack::PackedScene;
use crate::scene::flatten::{flatten, FlatScene};
use crate::script_driver::{run_script, ScriptSettings};
use crate::tracer::base::ray::{camera_ray, offset_ray, Ray};
use crate::tracer::shading::surface::surface_at;
use crate::tracer::traversal::traverse::{
    any_hit, closest_hit, hit_miss, Counters, Hit, NoCounters,
};
use crate::tracer::traversal::traverse_mesh::instance_mesh;
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
    /// Σ (item + 1) over the primary rays that hit, wrapping, items numbered as in
    /// [`ItemNumbering`].
    pub hit_checksum: u64,
}

/// The flat item numbers that `--dump-rays` and the checksum use, the same for any
/// tracer given the same geometry: the instances that are not meshes first, in packed
/// order, then every mesh instance's triangles (world space, one copy per instance), in
/// instance order and then the mesh's triangle order.
pub struct ItemNumbering {
    /// Per packed instance: its number (not a mesh), or its first triangle's (a mesh).
    first_number: Vec<u32>,
}

impl ItemNumbering {
    pub fn new(scene: &PackedScene) -> ItemNumbering {
        let instances = &scene.instances[..scene.globals.num_instances as usize];
        let not_meshes = instances.iter().filter(|i| i.kind != KIND_MESH).count() as u32;
        let (mut next_instance, mut next_triangle) = (0u32, not_meshes);
        let first_number = instances
            .iter()
            .map(|inst| {
                let number = if inst.kind == KIND_MESH {
                    next_triangle += instance_mesh(scene, inst).num_triangles;
                    next_triangle - instance_mesh(scene, inst).num_triangles
                } else {
                    next_instance += 1;
                    next_instance - 1
                };
                number
            })
            .collect();
        ItemNumbering { first_number }
    }

    /// The number of what `hit` hit, or `NO_ITEM` on a miss.
    pub fn of(&self, scene: &PackedScene, hit: &Hit) -> u32 {
        if !hit.is_hit() {
            return NO_ITEM;
        }
        let inst = &scene.instances[hit.item as usize];
        let first = self.first_number[hit.item as usize];
        if inst.kind == KIND_MESH {
            first + hit.part - instance_mesh(scene, inst).first_triangle
        } else {
            first
        }
    }
}

/// Runs the script under `settings` and flattens its first `gr.render` call, at
/// `width`×`height` when given.
pub fn load_first_render(
    path: &Path,
    width: Option<u32>,
    height: Option<u32>,
    settings: &ScriptSettings,
) -> anyhow::Result<FlatScene> {
    let mut scene = None;
    run_script(path, settings, &mut |graph, request| {
        if scene.is_none() {
            let mut request = request.clone();
            request.width = width.unwrap_or(request.width);
            request.height = height.unwrap_or(request.height);
            scene = Some(flatten(graph, &request)?);
        }
        Ok(())
    })?;
    scene.ok_or_else(|| {
        anyhow::anyhow!("{} never calls gr.render", crate::display_path::shown(path))
    })
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
    let mut hits = vec![hit_miss(); rays.len()];
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

/// The traversal's work per ray, untimed: cells visited and primitives tested, summed
/// over the camera rays and over the shadow rays.
pub fn count_work(scene: &PackedScene, primary: &[Ray], shadow: &[ShadowRay]) -> [Counters; 2] {
    [
        count_each(primary, |r, c| {
            closest_hit(scene, r, T_MISS, c);
        }),
        count_each(shadow, |s, c| {
            any_hit(scene, &s.ray, s.t_max, c);
        }),
    ]
}

/// The counters of `trace` over every ray, summed.
fn count_each<R: Sync>(rays: &[R], trace: impl Fn(&R, &mut Counters) + Sync) -> Counters {
    rays.par_iter()
        .map(|r| {
            let mut c = Counters::default();
            trace(r, &mut c);
            c
        })
        .reduce(Counters::default, |a, b| Counters {
            cells_visited: a.cells_visited + b.cells_visited,
            items_tested: a.items_tested + b.items_tested,
        })
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

/// Counts of rays, hits and occluded shadow rays, and the checksum of the hit items.
pub fn summarise(scene: &PackedScene, hits: &[Hit], occluded: &[bool]) -> TraceSummary {
    let numbering = ItemNumbering::new(scene);
    let hit_items = hits.iter().filter(|h| h.is_hit());
    TraceSummary {
        primary_rays: hits.len(),
        primary_hits: hit_items.clone().count(),
        shadow_rays: occluded.len(),
        shadow_occluded: occluded.iter().filter(|&&o| o).count(),
        hit_checksum: hit_items.fold(0u64, |sum, h| {
            sum.wrapping_add(numbering.of(scene, h) as u64 + 1)
        }),
    }
}
