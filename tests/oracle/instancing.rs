//! Instanced meshes stored once, in their own space with their own grids, and the
//! two-level traversal through them: the same hits as the same triangles baked into world
//! space, the same hits through the grids as by brute force, and a dense mesh in a large
//! scene not tested triangle by triangle.

use crate::common;

use common::{corpus, load_scenes, temp_dir, Rng};
use glam::{DVec3, Vec3};
use glint::constants::KIND_MESH;
use glint::pack::{pack, PackedScene};
use glint::scene::flatten::{FlatScene, Triangle};
use glint::scene::{GridMode, OptionOverrides};
use glint::tracer::base::ray::{camera_ray, Ray};
use glint::tracer::shading::surface::surface_at;
use glint::tracer::traversal::traverse::{any_hit, closest_hit, Counters, NoCounters};

fn macho_cows(grid: GridMode) -> FlatScene {
    let overrides = OptionOverrides {
        grid: Some(grid),
        width: Some(64),
        height: Some(64),
        ..OptionOverrides::default()
    };
    load_scenes(&corpus().join("a4-2021plus/macho-cows.lua"), &overrides).remove(0)
}

/// The scene with every mesh instance baked into loose world-space triangles (in f64,
/// as flattening did before meshes were stored once).
fn baked(scene: &FlatScene) -> FlatScene {
    let mut out = scene.clone();
    for instance in &scene.mesh_instances {
        for t in scene.meshes[instance.mesh].triangles() {
            out.triangles.push(Triangle {
                positions: t
                    .positions
                    .map(|p| instance.object_to_world.transform_point3(p)),
                material: instance.material,
                uvs: t.uvs,
            });
        }
    }
    out.meshes.clear();
    out.mesh_instances.clear();
    out
}

fn below(rng: &mut Rng, n: usize) -> usize {
    (rng.next_u64() % n as u64) as usize
}

fn unit_vector(rng: &mut Rng) -> DVec3 {
    loop {
        let v = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        if v.length_squared() > 1e-6 && v.length_squared() <= 1.0 {
            return v.normalize();
        }
    }
}

/// Rays from random points around the scene at interior points (barycentrics in
/// [0.2, 0.6]) of random triangles of random instances, and the scene's camera rays.
fn rays(scene: &FlatScene, packed: &PackedScene, rng: &mut Rng, count: usize) -> Vec<Ray> {
    let g = &packed.globals;
    let mut rays: Vec<Ray> = (0..g.width * g.height)
        .map(|i| camera_ray(g, (i % g.width) as f32 + 0.5, (i / g.width) as f32 + 0.5))
        .collect();
    let centre = DVec3::from(Vec3::from(g.grid_min) + Vec3::from(g.grid_max)) * 0.5;
    let radius = (Vec3::from(g.grid_max) - Vec3::from(g.grid_min)).length() as f64;
    for _ in 0..count {
        let instance = &scene.mesh_instances[below(rng, scene.mesh_instances.len())];
        let mesh = &scene.meshes[instance.mesh];
        let t = mesh.triangle(below(rng, mesh.len()));
        let (b1, b2) = (rng.range(0.2, 0.4), rng.range(0.2, 0.4));
        let object = t.positions[0] * (1.0 - b1 - b2) + t.positions[1] * b1 + t.positions[2] * b2;
        let target = instance.object_to_world.transform_point3(object);
        let origin = centre + unit_vector(rng) * radius;
        rays.push(Ray {
            origin: origin.as_vec3(),
            dir: (target - origin).normalize().as_vec3(),
        });
    }
    rays
}

#[test]
fn an_instanced_mesh_is_stored_once() {
    let scene = macho_cows(GridMode::Auto);
    let packed = pack(&scene).unwrap();
    let stored: usize = scene.meshes.iter().map(|m| m.len()).sum();
    let placed: usize = scene
        .mesh_instances
        .iter()
        .map(|i| scene.meshes[i.mesh].len())
        .sum();
    assert!(
        scene.mesh_instances.len() > scene.meshes.len(),
        "no mesh is instanced"
    );
    assert!(packed.triangles.len() <= stored);
    assert!(
        placed > 2 * packed.triangles.len(),
        "{placed} placed, {} stored",
        packed.triangles.len()
    );
    let (bytes, triangles) = packed.accel_memory();
    assert_eq!(triangles, packed.triangles.len());
    let flat = pack(&baked(&scene)).unwrap();
    let (flat_bytes, flat_triangles) = flat.accel_memory();
    println!(
        "macho-cows: {triangles} stored triangles ({placed} placed), {:.1} bytes per stored triangle, {:.1} bytes per placed triangle; baked: {flat_triangles} triangles, {:.1} bytes per triangle",
        bytes as f64 / triangles as f64,
        bytes as f64 / placed as f64,
        flat_bytes as f64 / flat_triangles as f64,
    );
    assert!(bytes < flat_bytes / 2);
}

#[test]
fn instanced_hits_match_world_space_triangles() {
    let scene = macho_cows(GridMode::Auto);
    let instanced = pack(&scene).unwrap();
    let world = pack(&baked(&scene)).unwrap();
    let mut rng = Rng(0x1157_A7CE);
    let rays = rays(&scene, &instanced, &mut rng, 20_000);
    let (mut hits, mut worst_t, mut worst_normal) = (0usize, 0.0f64, 0.0f64);
    let mut mismatches = Vec::new();
    for (i, ray) in rays.iter().enumerate() {
        let a = closest_hit(&instanced, ray, f32::MAX, &mut NoCounters);
        let b = closest_hit(&world, ray, f32::MAX, &mut NoCounters);
        if a.is_hit() != b.is_hit() {
            mismatches.push(format!("ray {i}: instanced {a:?}, world {b:?}"));
            continue;
        }
        if !a.is_hit() {
            continue;
        }
        hits += 1;
        let dt = (a.t - b.t).abs() as f64 / (b.t as f64).max(1e-3);
        worst_t = worst_t.max(dt);
        let na = surface_at(&instanced, ray, &a).normal;
        let nb = surface_at(&world, ray, &b).normal;
        // Winding may flip under a mirroring transform; shading faces either side.
        worst_normal = worst_normal.max(1.0 - na.dot(nb).abs() as f64);
    }
    println!(
        "{} rays, {hits} hits; worst relative t difference {worst_t:.2e}, worst 1 − |n·n'| {worst_normal:.2e}; {} hit/miss mismatches",
        rays.len(),
        mismatches.len()
    );
    // A ray through a shared silhouette edge may round to either side in either frame;
    // rays aimed at triangle interiors and camera rays at 64² find none here.
    assert!(
        mismatches.is_empty(),
        "{}",
        mismatches[..mismatches.len().min(5)].join("\n")
    );
    assert!(worst_t < 1e-4, "t differs by {worst_t:e}");
    assert!(worst_normal < 1e-4, "normals differ by {worst_normal:e}");
    assert!(hits > 10_000);
}

#[test]
fn mesh_grids_and_brute_force_give_the_same_hits() {
    let scene = macho_cows(GridMode::Auto);
    let with_grid = pack(&scene).unwrap();
    let mut off = scene.clone();
    off.options.grid = GridMode::Off;
    let brute = pack(&off).unwrap();
    assert_eq!(brute.globals.grid_enabled, 0);
    let mut rng = Rng(0xB2D7_E0FF);
    let rays = rays(&scene, &with_grid, &mut rng, 3000);
    for (i, ray) in rays.iter().enumerate() {
        let a = closest_hit(&with_grid, ray, f32::MAX, &mut NoCounters);
        let b = closest_hit(&brute, ray, f32::MAX, &mut NoCounters);
        // Two triangles may share the nearest t (an edge): either is the nearest hit.
        assert_eq!(
            a.t.to_bits(),
            b.t.to_bits(),
            "ray {i}: grid {a:?}, brute force {b:?}"
        );
        // (A miss's t * 1.001 is infinity: past T_MISS, where no miss may count as a hit.)
        for t_max in [a.t * 0.5, a.t * 0.999, a.t * 1.001] {
            assert_eq!(
                any_hit(&with_grid, ray, t_max, &mut NoCounters),
                any_hit(&brute, ray, t_max, &mut NoCounters),
                "ray {i}, t_max {t_max}"
            );
        }
        assert_eq!(
            any_hit(&brute, ray, f32::INFINITY, &mut NoCounters),
            a.is_hit(),
            "ray {i}: any hit up to infinity"
        );
    }
}

/// The cow (5 804 triangles, 0.3 units across) on a 4000-unit floor among spheres: its
/// own grid keeps the triangles tested per camera ray small (a single grid over the whole
/// scene put the cow in one or two cells and tested thousands per ray).
#[test]
fn a_dense_mesh_in_a_large_scene_is_traversed_by_its_own_grid() {
    let dir = temp_dir("stadium");
    // A scene reads only under its own folder: the cow goes beside it.
    std::fs::copy(corpus().join("a4-2021plus/cow.obj"), dir.join("cow.obj")).unwrap();
    let script = r#"
hide = gr.material({0.84, 0.6, 0.53}, {0.3, 0.3, 0.3}, 20)
scene = gr.node('scene')
floor = gr.cube('floor')
floor:scale(4000, 1, 4000)
floor:translate(-2000, -1.0, -2000)
scene:add_child(floor)
cow = gr.mesh('cow', 'cow.obj')
cow:set_material(hide)
cow:scale(0.3, 0.3, 0.3)
scene:add_child(cow)
for i = 0, 21 do
  for j = 0, 19 do
    scene:add_child(gr.nh_sphere('s', {-1900 + i * 180, 10, -1900 + j * 190}, 10))
  end
end
gr.render(scene, 'stadium.png', 64, 48, {0, 1.2, 4}, {0, -0.25, -1}, {0, 1, 0}, 50,
  {0.3, 0.3, 0.3}, {gr.light({400, 800, 600}, {0.9, 0.9, 0.9}, {1, 0, 0})})
"#;
    let path = dir.join("stadium.lua");
    std::fs::write(&path, script).unwrap();
    let scene = load_scenes(&path, &OptionOverrides::default()).remove(0);
    let packed = pack(&scene).unwrap();
    let g = &packed.globals;
    let mut counters = Counters::default();
    let (mut hits, mut cow_hits) = (0, 0);
    for i in 0..g.width * g.height {
        let ray = camera_ray(g, (i % g.width) as f32 + 0.5, (i / g.width) as f32 + 0.5);
        let hit = closest_hit(&packed, &ray, f32::MAX, &mut counters);
        if hit.is_hit() {
            hits += 1;
            cow_hits += (packed.instances[hit.item as usize].kind == KIND_MESH) as u32;
        }
    }
    let rays = (g.width * g.height) as f64;
    let per_ray = counters.items_tested as f64 / rays;
    println!(
        "{hits} hits ({cow_hits} on the cow) of {rays} camera rays; {per_ray:.1} items tested and {:.1} cells visited per ray",
        counters.cells_visited as f64 / rays
    );
    // The floor fills the view below the horizon; the cow about a tenth of it.
    assert!(hits as f64 > 0.5 * rays);
    assert!(cow_hits as f64 > 0.05 * rays);
    assert!(per_ray < 50.0, "{per_ray} items tested per ray");
}

/// The scene walk collects the mesh instances it meets and walks them two at a time
/// (`PendingMeshes`): rays along the stacked frames' axis meet up to six instances before
/// their hit, so the list fills and the walk resumes after walking it, and the answers
/// are still those of brute force (closest hit: t bit for bit and the item; any hit under
/// t_max below, at and beyond the hit).
#[test]
fn pending_mesh_instances_give_brute_forces_answers() {
    let grid = |mode: GridMode| OptionOverrides {
        grid: Some(mode),
        ..OptionOverrides::default()
    };
    let source = common::stacked_frames_source();
    let with_grid = common::packed_from_source(&source, &grid(GridMode::Auto)).remove(0);
    let brute = common::packed_from_source(&source, &grid(GridMode::Off)).remove(0);
    assert_eq!(with_grid.globals.grid_enabled, 1);
    assert_eq!(with_grid.meshes.len(), 1, "the frame is stored once");
    let mut items_hit = std::collections::BTreeSet::new();
    for origin in common::stacked_frames_origins() {
        let ray = Ray {
            origin: Vec3::from(origin),
            dir: Vec3::new(0.0, 0.0, -1.0),
        };
        let x = origin[0];
        let a = closest_hit(&with_grid, &ray, f32::MAX, &mut NoCounters);
        let b = closest_hit(&brute, &ray, f32::MAX, &mut NoCounters);
        assert_eq!(
            (a.t.to_bits(), a.item),
            (b.t.to_bits(), b.item),
            "x = {x}: grid {a:?}, brute force {b:?}"
        );
        items_hit.insert(a.item);
        let t = if a.is_hit() { a.t } else { 100.0 };
        for t_max in [t * 0.5, t * 0.999, t * 1.001] {
            assert_eq!(
                any_hit(&with_grid, &ray, t_max, &mut NoCounters),
                any_hit(&brute, &ray, t_max, &mut NoCounters),
                "x = {x}, t_max {t_max}"
            );
        }
    }
    // Every frame and the ball stop some ray: the deepest frames only after the walk has
    // passed (and walked) the instances before them.
    assert_eq!(items_hit.len(), 7, "items hit: {items_hit:?}");
}
