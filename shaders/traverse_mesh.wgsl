// traverse_mesh.wgsl — the second level: a mesh instance traversed through its mesh's own
// grid. The ray goes to the mesh's space through the instance's world→object rows
// (direction not normalised, so t carries over), enters the mesh's grid bounds and walks
// its cells, testing the triangles listed there with the watertight test.

// #if MESH
// The mesh of a KIND_MESH instance.
// Mirror of src/cpu/traverse_mesh.rs::instance_mesh — change both.
fn instance_mesh(inst: GpuInstance) -> GpuMesh {
    return meshes[u32(inst.params.x)];
}

// Nearest hit in (0, t_max) with mesh instance `item` (inst): t, the barycentrics and the
// triangle as part; hit_miss() (t = T_MISS) when nothing is hit.
// Mirror of src/cpu/traverse_mesh.rs::intersect_mesh — change both.
fn intersect_mesh(inst: GpuInstance, item: u32, ray: Ray, t_max: f32) -> Hit {
    let mesh = instance_mesh(inst);
    let entered = enter_mesh(mesh, to_object_space(inst, ray.origin, ray.dir), t_max);
    if !entered.valid {
        return hit_miss();
    }
    let grid = mesh_grid(mesh);
    var dda = dda_setup(grid, entered.ray, entered.t_max);
    if !dda.valid {
        return hit_miss();
    }
    let tri_ray = triangle_ray_setup(entered.ray.origin, entered.ray.dir);
    var best = hit_miss();
    best.t = entered.t_max;
    loop {
        let cell = cell_index(grid, dda.cell);
        for (var i = cell_start[cell]; i < cell_start[cell + 1u]; i++) {
            let triangle = mesh.first_triangle + cell_items[i];
            let p = triangle_vertices(triangles[triangle]);
            let h = intersect_triangle(tri_ray, p[0], p[1], p[2], best.t);
            if h.x < best.t {
                best = Hit(h.x, item, h.y, h.z, triangle);
            }
        }
        // A hit inside this cell is final; so is leaving the grid or passing t_max.
        let step = dda_step(grid, &dda);
        if !step.valid || best.t <= step.t_cell_exit {
            break;
        }
    }
    if is_hit(best) {
        best.t += entered.t_moved;
        return best;
    }
    return hit_miss();
}

// Whether any triangle of mesh instance inst is hit in (0, t_max) (shadow rays: stops at
// the first one found).
// Mirror of src/cpu/traverse_mesh.rs::mesh_occludes — change both.
fn mesh_occludes(inst: GpuInstance, ray: Ray, t_max: f32) -> bool {
    let mesh = instance_mesh(inst);
    let entered = enter_mesh(mesh, to_object_space(inst, ray.origin, ray.dir), t_max);
    if !entered.valid {
        return false;
    }
    let grid = mesh_grid(mesh);
    var dda = dda_setup(grid, entered.ray, entered.t_max);
    if !dda.valid {
        return false;
    }
    let tri_ray = triangle_ray_setup(entered.ray.origin, entered.ray.dir);
    // (naga wants a return after the loop, so the loop breaks where Rust returns false.)
    loop {
        let cell = cell_index(grid, dda.cell);
        for (var i = cell_start[cell]; i < cell_start[cell + 1u]; i++) {
            let p = triangle_vertices(triangles[mesh.first_triangle + cell_items[i]]);
            if intersect_triangle(tri_ray, p[0], p[1], p[2], entered.t_max).x < entered.t_max {
                return true;
            }
        }
        if !dda_step(grid, &dda).valid {
            break;
        }
    }
    return false;
}
// #endif
