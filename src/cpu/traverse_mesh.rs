//! The second level: a mesh instance traversed through its mesh's own grid. The ray goes
//! to the mesh's space through the instance's world→object rows (direction not
//! normalised, so t carries over), enters the mesh's grid bounds and walks its cells,
//! testing the triangles listed there with the watertight test.

use super::dda::{cell_index, dda_setup, dda_step, enter_mesh, mesh_grid};
use super::hit::{Hit, TraversalCounters};
use super::intersect::{
    intersect_triangle, to_object_space, triangle_ray_setup, triangle_vertices,
};
use super::ray::Ray;
use crate::pack::{GpuInstance, GpuMesh, PackedScene};

/// The mesh of a `KIND_MESH` instance.
// Mirror of shaders/traverse_mesh.wgsl::instance_mesh — change both.
pub fn instance_mesh<'a>(scene: &'a PackedScene, inst: &GpuInstance) -> &'a GpuMesh {
    &scene.meshes[inst.params[0] as usize]
}

/// Nearest hit in (0, t_max) with mesh instance `item` (`inst`): t, the barycentrics and
/// the triangle as `part`; `Hit::MISS` (t = T_MISS) when nothing is hit.
// Mirror of shaders/traverse_mesh.wgsl::intersect_mesh — change both.
pub fn intersect_mesh(
    scene: &PackedScene,
    inst: &GpuInstance,
    item: u32,
    ray: &Ray,
    t_max: f32,
    counters: &mut impl TraversalCounters,
) -> Hit {
    let mesh = instance_mesh(scene, inst);
    let (origin, dir) = to_object_space(inst, ray.origin, ray.dir);
    let Some(entered) = enter_mesh(mesh, &Ray { origin, dir }, t_max) else {
        return Hit::MISS;
    };
    let grid = mesh_grid(mesh);
    let Some(mut dda) = dda_setup(&grid, &entered.ray, entered.t_max) else {
        return Hit::MISS;
    };
    let tri_ray = triangle_ray_setup(entered.ray.origin, entered.ray.dir);
    let mut best = Hit {
        t: entered.t_max,
        ..Hit::MISS
    };
    loop {
        counters.cell_visited();
        let cell = cell_index(&grid, dda.cell);
        for i in scene.cell_start[cell]..scene.cell_start[cell + 1] {
            counters.item_tested();
            let triangle = mesh.first_triangle + scene.cell_items[i as usize];
            let [p0, p1, p2] = triangle_vertices(&scene.triangles[triangle as usize]);
            let h = intersect_triangle(&tri_ray, p0, p1, p2, best.t);
            if h.x < best.t {
                best = Hit {
                    t: h.x,
                    item,
                    b1: h.y,
                    b2: h.z,
                    part: triangle,
                };
            }
        }
        // A hit inside this cell is final; so is leaving the grid or passing t_max.
        match dda_step(&grid, &mut dda) {
            Some(t_cell_exit) if best.t > t_cell_exit => {}
            _ => break,
        }
    }
    if best.is_hit() {
        best.t += entered.t_moved;
        best
    } else {
        Hit::MISS
    }
}

/// Whether any triangle of mesh instance `inst` is hit in (0, t_max) (shadow rays: stops
/// at the first one found).
// Mirror of shaders/traverse_mesh.wgsl::mesh_occludes — change both.
pub fn mesh_occludes(
    scene: &PackedScene,
    inst: &GpuInstance,
    ray: &Ray,
    t_max: f32,
    counters: &mut impl TraversalCounters,
) -> bool {
    let mesh = instance_mesh(scene, inst);
    let (origin, dir) = to_object_space(inst, ray.origin, ray.dir);
    let Some(entered) = enter_mesh(mesh, &Ray { origin, dir }, t_max) else {
        return false;
    };
    let grid = mesh_grid(mesh);
    let Some(mut dda) = dda_setup(&grid, &entered.ray, entered.t_max) else {
        return false;
    };
    let tri_ray = triangle_ray_setup(entered.ray.origin, entered.ray.dir);
    loop {
        counters.cell_visited();
        let cell = cell_index(&grid, dda.cell);
        for i in scene.cell_start[cell]..scene.cell_start[cell + 1] {
            counters.item_tested();
            let triangle = mesh.first_triangle + scene.cell_items[i as usize];
            let [p0, p1, p2] = triangle_vertices(&scene.triangles[triangle as usize]);
            if intersect_triangle(&tri_ray, p0, p1, p2, entered.t_max).x < entered.t_max {
                return true;
            }
        }
        if dda_step(&grid, &mut dda).is_none() {
            return false;
        }
    }
}
