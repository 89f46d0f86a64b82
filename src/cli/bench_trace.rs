//! `glint bench --trace SCENE.lua`: the CPU tracer's traversal alone, in rays per second,
//! for comparison with Embree on the same rays (`benches/embree/`).
//!
//! One camera ray per pixel through the pixel centre (no anti-aliasing), traced with
//! `closest_hit`; then, for every hit and every light in front of the hit surface, one
//! shadow ray (`any_hit`) from the offset hit point to the light (an area light's
//! centre), as shading would trace it. Nothing is shaded. Ray generation and the shadow
//! rays' set-up are not timed; each phase is timed over all rays, fastest of `--repeat`.
//! The hits are summarised by counts and a checksum of the hit items, so that another
//! tracer given the same rays (`--dump-rays`) can be checked to find the same hits.

use super::timing::fastest;
use super::trace_dump::{check_dumpable, write_trace_dump};
use crate::constants::{NO_ITEM, T_MISS};
use crate::cpu::ray::{camera_ray, offset_ray, Ray};
use crate::cpu::shade::surface_at;
use crate::cpu::traverse::{any_hit, closest_hit, Hit, NoCounters};
use crate::pack::{pack, GpuTriangle, PackedScene};
use crate::scene::flatten::{flatten, Scene};
use crate::scene::lua::{run_scene_file, ScriptConfig};
use glam::Vec3;
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// What `--trace` needs from the command line.
#[derive(Clone, Debug)]
pub struct TraceBenchArgs {
    pub scene: PathBuf,
    pub width: Option<u32>,
    pub height: Option<u32>,
    pub repeat: usize,
    pub dump_rays: Option<PathBuf>,
}

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

pub fn bench_trace(args: &TraceBenchArgs) -> anyhow::Result<()> {
    let scene = load_first_render(&args.scene, args.width, args.height)?;
    let build_start = Instant::now();
    let packed = pack(&scene)?;
    let build = build_start.elapsed();
    if args.dump_rays.is_some() {
        check_dumpable(&packed)?;
    }
    let primary = camera_rays(&packed);
    // The answers go to buffers written once before timing (as the Embree harness does),
    // so the timings hold no first-touch page faults.
    let mut hits = vec![Hit::MISS; primary.len()];
    let (t_primary, ()) = fastest(args.repeat, || {
        trace_primary_into(&packed, &primary, &mut hits)
    });
    let shadow = shadow_rays(&packed, &primary, &hits);
    let mut occluded = vec![false; shadow.len()];
    let (t_shadow, ()) = fastest(args.repeat, || {
        trace_shadow_into(&packed, &shadow, &mut occluded)
    });
    let summary = summarise(&hits, &occluded);
    let triangles = packed.triangles.len();
    println!("primary: {} Mrays/s", rate(mrays(primary.len(), t_primary)));
    println!("shadow: {} Mrays/s", rate(mrays(shadow.len(), t_shadow)));
    println!(
        "memory: {:.1} bytes per triangle",
        accel_memory_bytes(&packed) as f64 / triangles.max(1) as f64
    );
    print_details(&packed, &summary, build, t_primary, t_shadow, args.repeat);
    if let Some(path) = &args.dump_rays {
        write_trace_dump(path, &packed, &primary, &hits, &shadow, &occluded)?;
        println!("rays and geometry written to {}", path.display());
    }
    Ok(())
}

/// Bytes of the acceleration structure and the triangles it indexes: grid cells, item
/// lists and the triangle array. (The structure's own `accel_memory()` replaces this
/// when the structure has one.)
pub fn accel_memory_bytes(scene: &PackedScene) -> usize {
    std::mem::size_of::<u32>() * (scene.cell_start.len() + scene.cell_items.len())
        + std::mem::size_of::<GpuTriangle>() * scene.triangles.len()
}

fn print_details(
    packed: &PackedScene,
    s: &TraceSummary,
    build: Duration,
    t_primary: Duration,
    t_shadow: Duration,
    repeat: usize,
) {
    let g = &packed.globals;
    println!(
        "image: {}×{}, {} triangles, {} other items, {} lights, {} threads",
        g.width,
        g.height,
        packed.triangles.len(),
        g.num_instances,
        g.num_lights,
        rayon::current_num_threads()
    );
    println!(
        "primary rays: {} ({} hit) in {:.1} ms",
        s.primary_rays,
        s.primary_hits,
        t_primary.as_secs_f64() * 1e3
    );
    println!(
        "shadow rays: {} ({} occluded) in {:.1} ms",
        s.shadow_rays,
        s.shadow_occluded,
        t_shadow.as_secs_f64() * 1e3
    );
    println!("hit checksum: {}", s.hit_checksum);
    println!(
        "build (pack + grid): {:.1} ms; times: fastest of {}",
        build.as_secs_f64() * 1e3,
        repeat.max(1)
    );
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

/// A rate with three decimals, or three significant digits below 1 (the slow scenes run
/// at thousandths of a Mray/s). Plain decimal, never exponent notation.
pub fn rate(x: f64) -> String {
    let decimals = if x > 0.0 && x < 1.0 {
        (2 - x.log10().floor() as i32).max(3) as usize
    } else {
        3
    };
    format!("{x:.decimals$}")
}

fn mrays(rays: usize, time: Duration) -> f64 {
    rays as f64 / time.as_secs_f64().max(1e-9) / 1e6
}
