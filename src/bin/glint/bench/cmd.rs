//! `glint bench`: the grid's worth, measured in one run on this machine.
//! 1. Primary rays on `macho-cows.lua` at 512×512, with the grid and by brute force; the
//!    error is the number of pixels whose nearest item differs between the two (must be 0).
//! 2. N random triangles, N = 10³…10⁶: time per ray, grid build time, memory per
//!    triangle; the error is the share of rays whose hit differs from brute force.
//! 3. Optionally (`--densities`), time per ray against the grid density λ.
//!
//! `--torus` runs only the ray–torus solver comparison (`bench_torus`); `--sweep` only the
//! error-against-time sweep of the sampling settings (`bench_sweep`); `--trace SCENE` only
//! the traversal benchmark of one scene, beside Embree (`bench_trace`).

use super::common::{load_scene, with_grid, BenchArgs};
use super::timing::fastest;
use glam::{DVec3, Vec3};
use glint::accel::aabb::Aabb;
use glint::accel::grid::{Grid, DEFAULT_DENSITY, MESH_DEFAULT_DENSITY};
use glint::bench::splitmix::SplitMix;
use glint::pack::PackedScene;
use glint::pipeline::pack_scene;
use glint::scene::flatten::{FlatScene, Triangle};
use glint::scene::{Camera, GridMode, RenderOptions};
use glint::tracer::base::ray::camera_ray;
use glint::tracer::base::ray::Ray;
use glint::tracer::geometry::intersect::triangle_vertices;
use glint::tracer::traversal::traverse::{closest_hit, NoCounters};
use rayon::prelude::*;
use std::time::Duration;

pub fn run_bench(args: &BenchArgs) -> anyhow::Result<()> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0) as usize)
        .build()?;
    pool.install(|| run_bench_on_pool(args))
}

fn run_bench_on_pool(args: &BenchArgs) -> anyhow::Result<()> {
    // --trace prints its three result lines first (its thread count follows them).
    if let Some(scene) = &args.trace {
        return super::trace::bench_trace(&super::trace::TraceBenchArgs {
            scene: scene.clone(),
            width: args.width,
            height: args.height,
            repeat: args.repeat,
            dump_rays: args.dump_rays.clone(),
            script: args.script_settings()?,
        });
    }
    println!("glint bench on {} threads", rayon::current_num_threads());
    if args.gpu {
        return super::gpu::bench_gpu(args);
    }
    if args.torus {
        return super::torus::bench_torus(args);
    }
    if args.sweep {
        return super::sweep::bench_sweep(args);
    }
    bench_macho_cows(args)?;
    bench_random_triangles(args);
    if args.densities {
        bench_densities(args)?;
    }
    Ok(())
}

/// Nearest item and part (for a mesh instance, the triangle) along each ray (in parallel).
fn trace_all(scene: &PackedScene, rays: &[Ray]) -> Vec<(u32, u32)> {
    rays.par_iter()
        .map(|r| {
            let hit = closest_hit(scene, r, f32::MAX, &mut NoCounters);
            (hit.item, hit.part)
        })
        .collect()
}

/// Builds a grid over the stored triangles of `packed` (what packing builds per mesh).
fn build_triangle_grid(packed: &PackedScene) -> Grid {
    let corners: Vec<[Vec3; 3]> = packed.triangles.iter().map(triangle_vertices).collect();
    let bounds: Vec<Aabb> = corners.iter().map(Aabb::of_triangle).collect();
    Grid::build(bounds, Some(&|i| corners[i]), Some(MESH_DEFAULT_DENSITY))
}

fn bench_macho_cows(args: &BenchArgs) -> anyhow::Result<()> {
    let path = args.cs488.join("a4-2021plus/macho-cows.lua");
    let scene = load_scene(&path, 512, 512)?;
    let grid = with_grid(&scene, GridMode::Auto)?;
    let brute = with_grid(&scene, GridMode::Off)?;
    let g = &grid.globals;
    let rays: Vec<Ray> = (0..g.width * g.height)
        .map(|i| camera_ray(g, (i % g.width) as f32 + 0.5, (i / g.width) as f32 + 0.5))
        .collect();
    let (t_grid, hits_grid) = fastest(args.repeat, || trace_all(&grid, &rays));
    // Brute force is a few hundred times slower: once, on every 8th row of the image.
    let width = g.width as usize;
    let rows: Vec<Ray> = rays.chunks(width).step_by(8).flatten().copied().collect();
    let (t_brute, hits_brute) = fastest(1, || trace_all(&brute, &rows));
    let differing = hits_grid
        .chunks(width)
        .step_by(8)
        .flatten()
        .zip(&hits_brute)
        .filter(|(a, b)| a != b)
        .count();
    let mrays = |t: Duration, n: usize| n as f64 / t.as_secs_f64() / 1e6;
    println!(
        "\n## Primary rays, macho-cows.lua at 512×512 ({} items, {} stored triangles)",
        grid.grid_stats.items, grid.mesh_grid_stats.items
    );
    println!("| tracer | rays | time | Mrays/s |");
    println!("| --- | ---: | ---: | ---: |");
    println!(
        "| grids (λ = {DEFAULT_DENSITY} over items, {MESH_DEFAULT_DENSITY} per mesh) | {} | {:.1} ms | {:.3} |",
        rays.len(),
        t_grid.as_secs_f64() * 1e3,
        mrays(t_grid, rays.len())
    );
    println!(
        "| brute force (every 8th row) | {} | {:.1} ms | {:.4} |",
        rows.len(),
        t_brute.as_secs_f64() * 1e3,
        mrays(t_brute, rows.len())
    );
    println!(
        "grid speed-up {:.0}×; pixels whose nearest item differs from brute force: {differing} of {}",
        mrays(t_grid, rays.len()) / mrays(t_brute, rows.len()),
        rows.len()
    );
    Ok(())
}

/// `n` random triangles in the unit cube, each about as large as the mean spacing
/// (so every N has the same depth complexity), and a scene around them.
pub fn random_triangle_scene(n: usize, seed: u64) -> FlatScene {
    let mut rng = SplitMix(seed);
    let size = (n as f64).cbrt().recip();
    let triangles = (0..n)
        .map(|_| {
            let centre = rng.vec();
            Triangle {
                positions: [0, 1, 2].map(|_| centre + (rng.vec() - 0.5) * size),
                material: 0,
                uvs: [[0.0; 2]; 3],
            }
        })
        .collect();
    FlatScene {
        objects: Vec::new(),
        triangles,
        meshes: Vec::new(),
        mesh_instances: Vec::new(),
        csg: Vec::new(),
        materials: vec![glint::scene::Material::default()],
        textures: Vec::new(),
        lights: Vec::new(),
        camera: Camera {
            eye: DVec3::new(0.5, 0.5, 3.0),
            view: DVec3::new(0.0, 0.0, -1.0),
            up: DVec3::Y,
            fov_deg: 40.0,
        },
        ambient: [0.1; 3],
        width: 64,
        height: 64,
        options: RenderOptions::default(),
    }
}

/// Rays from a sphere of radius 2 around the cube's centre towards random points in it.
fn random_rays(count: usize, seed: u64) -> Vec<Ray> {
    let mut rng = SplitMix(seed);
    (0..count)
        .map(|_| {
            let target = rng.vec();
            let dir = loop {
                let v = rng.vec() * 2.0 - 1.0;
                if v.length_squared() > 1e-6 && v.length_squared() <= 1.0 {
                    break v.normalize();
                }
            };
            let origin = DVec3::splat(0.5) + dir * 2.0;
            Ray {
                origin: origin.as_vec3(),
                dir: (target - origin).normalize().as_vec3(),
            }
        })
        .collect()
}

/// Camera rays of a `side`×`side` view of the unit cube, row by row (coherent, as a
/// render traces them).
fn camera_rays(side: u32) -> Vec<Ray> {
    let mut scene = random_triangle_scene(1, 1);
    scene.width = side;
    scene.height = side;
    let packed = pack_scene(&scene).expect("one triangle packs");
    let g = &packed.globals;
    (0..side * side)
        .map(|i| camera_ray(g, (i % side) as f32 + 0.5, (i / side) as f32 + 0.5))
        .collect()
}

fn bench_random_triangles(args: &BenchArgs) {
    let side = (args.rays as f64).sqrt() as u32;
    let rays = camera_rays(side);
    let incoherent = random_rays(args.rays, 7);
    println!(
        "\n## Random triangles in the unit cube: {} camera rays ({side}×{side}) and {} random rays per N",
        rays.len(),
        incoherent.len()
    );
    println!("| N | grid cells | build | camera ns/ray | vs N=10³ | random ns/ray | vs N=10³ | bytes/triangle | rays differing from brute force |");
    println!("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    let mut base = None;
    let mut base_incoherent = None;
    let mut n = 1000;
    while n <= args.max_triangles {
        let scene = random_triangle_scene(n, n as u64);
        let packed = with_grid(&scene, GridMode::Auto).expect("random scene packs");
        let (build, grid) = fastest(args.repeat, || build_triangle_grid(&packed));
        let (time, hits) = fastest(args.repeat, || trace_all(&packed, &rays));
        let per_ray = time.as_secs_f64() * 1e9 / rays.len() as f64;
        let base_cost = *base.get_or_insert(per_ray);
        let (time_incoherent, _) = fastest(args.repeat, || trace_all(&packed, &incoherent));
        let per_ray_incoherent = time_incoherent.as_secs_f64() * 1e9 / incoherent.len() as f64;
        let base_incoherent_cost = *base_incoherent.get_or_insert(per_ray_incoherent);
        // Brute force on every k-th ray keeps the check affordable at 10⁶.
        let stride = (n * rays.len() / 1_000_000_000).max(1);
        let brute = with_grid(&scene, GridMode::Off).expect("random scene packs");
        let sample: Vec<Ray> = rays.iter().step_by(stride).copied().collect();
        let brute_hits = trace_all(&brute, &sample);
        let differing = hits
            .iter()
            .step_by(stride)
            .zip(&brute_hits)
            .filter(|(a, b)| a != b)
            .count();
        let (bytes, _) = packed.accel_memory();
        println!(
            "| {n} | {} | {:.1} ms | {per_ray:.0} | {:.2}× | {per_ray_incoherent:.0} | {:.2}× | {:.1} | {differing} of {} |",
            grid.stats.cells,
            build.as_secs_f64() * 1e3,
            per_ray / base_cost,
            per_ray_incoherent / base_incoherent_cost,
            bytes as f64 / n as f64,
            sample.len(),
        );
        n *= 10;
    }
}

fn bench_densities(args: &BenchArgs) -> anyhow::Result<()> {
    let cows = load_scene(&args.cs488.join("a4-2021plus/macho-cows.lua"), 256, 256)?;
    let tris = random_triangle_scene(100_000, 5);
    let rays = random_rays(args.rays, 9);
    println!(
        "\n## Grid density λ (time per ray, fastest of {})",
        args.repeat
    );
    println!("| λ | macho-cows primary ns/ray | grid bytes/item | 10⁵ random triangles ns/ray | grid bytes/item |");
    println!("| ---: | ---: | ---: | ---: | ---: |");
    for density in [0.5f32, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0] {
        let packed = with_grid(&cows, GridMode::Density(density))?;
        let g = &packed.globals;
        let primary: Vec<Ray> = (0..g.width * g.height)
            .map(|i| camera_ray(g, (i % g.width) as f32 + 0.5, (i / g.width) as f32 + 0.5))
            .collect();
        let (t_cows, _) = fastest(args.repeat, || trace_all(&packed, &primary));
        let packed_tris = with_grid(&tris, GridMode::Density(density))?;
        let (t_tris, _) = fastest(args.repeat, || trace_all(&packed_tris, &rays));
        let bytes_per_item = |p: &PackedScene| {
            let items = p.grid_stats.items + p.mesh_grid_stats.items;
            (p.grid_stats.memory_bytes + p.mesh_grid_stats.memory_bytes) as f64 / items as f64
        };
        println!(
            "| {density} | {:.0} | {:.1} | {:.0} | {:.1} |",
            t_cows.as_secs_f64() * 1e9 / primary.len() as f64,
            bytes_per_item(&packed),
            t_tris.as_secs_f64() * 1e9 / rays.len() as f64,
            bytes_per_item(&packed_tris),
        );
    }
    Ok(())
}
