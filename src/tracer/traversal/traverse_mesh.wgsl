// traverse_mesh.wgsl — the second level: a mesh instance traversed through its mesh's own
// grid. The ray goes to the mesh's space through the instance's world→object rows
// (direction not normalised, so t carries over), enters the mesh's grid bounds and walks
// its cells (runs of empty cells in a loop of their own), testing the triangles listed
// there with the watertight test.

// #if MESH
// The triangles a ray has tested in one mesh, as a direct-mapped cache of
// TRIANGLE_MAILBOX_SIZE slots (triangle number modulo the size): testing one again would
// give the same answer, so a triangle listed in several cells is tested once unless
// another took its slot in between. Kept only in the MAILBOXES variant (no adapter's
// choice: docs/gpu.md): without it a triangle is tested in every cell that lists it, with the same
// answers (and the struct holds no array, so there is none to zero per mesh walk).
// Mirror of src/tracer/traversal/traverse_mesh.rs::TriangleMailbox — change both.
struct TriangleMailbox {
// #if MAILBOXES
    triangles: array<u32, TRIANGLE_MAILBOX_SIZE>,
// #else
    unused: u32,
// #endif
}

// Mirror of src/tracer/traversal/traverse_mesh.rs::triangle_mailbox_new — change both.
fn triangle_mailbox_new() -> TriangleMailbox {
    var mailbox: TriangleMailbox;
// #if MAILBOXES
    for (var i = 0u; i < TRIANGLE_MAILBOX_SIZE; i++) {
        mailbox.triangles[i] = NO_ITEM;
    }
// #endif
    return mailbox;
}

// Whether triangle was tested already (as far as its slot remembers); if not, it is now
// remembered in its slot.
// Mirror of src/tracer/traversal/traverse_mesh.rs::triangle_mailbox_seen — change both.
fn triangle_mailbox_seen(mailbox: ptr<function, TriangleMailbox>, triangle: u32) -> bool {
// #if MAILBOXES
    let slot = triangle & (TRIANGLE_MAILBOX_SIZE - 1u);
    if (*mailbox).triangles[slot] == triangle {
        return true;
    }
    (*mailbox).triangles[slot] = triangle;
// #endif
    return false;
}

// The mesh of a KIND_MESH instance.
// Mirror of src/tracer/traversal/traverse_mesh.rs::instance_mesh — change both.
fn instance_mesh(inst: PackedInstance) -> PackedMesh {
    return load_mesh(u32(inst.params.x));
}

// Steps dda on past empty cells, from the cell it stands in, until one lists something
// (true) or the walk ends (false): it leaves the grid, passes t_exit, or leaves a cell past
// t_stop (a closest hit below t_stop is final there). The same cells and the same stop as
// testing each empty cell's nothing in the walk's loop (on the CPU the small loop keeps the
// Dda in registers).
// Mirror of src/tracer/traversal/traverse_mesh.rs::skip_empty_cells — change both.
fn skip_empty_cells(dda: ptr<function, Dda>, t_stop: f32) -> bool {
    // (naga wants a return after the loop, so the loop breaks where Rust returns.)
    var found = false;
    loop {
        let cell = (*dda).cell;
        if cell_start_at(cell) != cell_start_at(cell + 1u) {
            found = true;
            break;
        }
        let step = dda_step(dda);
        if !step.valid || t_stop <= step.t_cell_exit {
            break;
        }
    }
    return found;
}

// Nearest hit in (0, t_max) with mesh instance `item` (inst): t, the barycentrics and the
// triangle as part; hit_miss() (t = T_MISS) when nothing is hit. (Its set-up, the lines up
// to the mailbox, is mesh_occludes's too; the CPU shares it, traverse_mesh.rs::
// mesh_walk_start, but the same set-up as a WGSL function returning the walk as a struct
// made naga 30's SPIR-V writer panic, and with the walk's DDA and mailbox then copied to
// variables of their own 40 rows of the feature combinations' kernels broke RADV's NAVI21
// budgets where 33 are known (wave32 traversal kernels at 112 VGPRs, budget 96): each
// keeps its copy.)
// Mirror of src/tracer/traversal/traverse_mesh.rs::intersect_mesh — change both.
fn intersect_mesh(inst: PackedInstance, item: u32, ray: Ray, t_max: f32) -> Hit {
    let mesh = instance_mesh(inst);
    let entered = enter_mesh(mesh, to_object_space(inst, ray.origin, ray.dir), t_max);
    if !entered.valid {
        return hit_miss();
    }
    let grid = mesh_grid(mesh);
    var dda = dda_setup(grid, entered.ray, entered.inv_dir, entered.t_max);
    if !dda.valid {
        return hit_miss();
    }
    let tri_ray = triangle_ray_setup(entered.ray.origin, entered.ray.dir);
    var mailbox = triangle_mailbox_new();
    var best = hit_miss();
    best.t = entered.t_max;
    loop {
        if !skip_empty_cells(&dda, best.t) {
            break;
        }
        let cell = dda.cell;
        // The step comes before the cell's tests, as on the CPU (which prefetches the
        // next cell's range meanwhile).
        let step = dda_step(&dda);
        let end = cell_start_at(cell + 1u);
        for (var i = cell_start_at(cell); i < end; i++) {
            let local = cell_item_at(i);
            if triangle_mailbox_seen(&mailbox, local) {
                continue;
            }
            let triangle = mesh.first_triangle + local;
            let p = triangle_vertices(triangle);
            let h = intersect_triangle(tri_ray, p[0], p[1], p[2], best.t);
            if h.x < best.t {
                best = Hit(h.x, item, h.y, h.z, triangle);
            }
        }
        // A hit inside this cell is final; so is leaving the grid or passing t_max.
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
// Mirror of src/tracer/traversal/traverse_mesh.rs::mesh_occludes — change both.
fn mesh_occludes(inst: PackedInstance, ray: Ray, t_max: f32) -> bool {
    let mesh = instance_mesh(inst);
    let entered = enter_mesh(mesh, to_object_space(inst, ray.origin, ray.dir), t_max);
    if !entered.valid {
        return false;
    }
    let grid = mesh_grid(mesh);
    var dda = dda_setup(grid, entered.ray, entered.inv_dir, entered.t_max);
    if !dda.valid {
        return false;
    }
    let tri_ray = triangle_ray_setup(entered.ray.origin, entered.ray.dir);
    var mailbox = triangle_mailbox_new();
    // (naga wants a return after the loop, so the loop breaks where Rust returns false.)
    // (Any step the walk takes ends before t_exit <= t_max: t_max stops nothing.)
    loop {
        if !skip_empty_cells(&dda, entered.t_max) {
            break;
        }
        let cell = dda.cell;
        // The step comes before the cell's tests, as on the CPU.
        let step = dda_step(&dda);
        let end = cell_start_at(cell + 1u);
        for (var i = cell_start_at(cell); i < end; i++) {
            let local = cell_item_at(i);
            if triangle_mailbox_seen(&mailbox, local) {
                continue;
            }
            let p = triangle_vertices(mesh.first_triangle + local);
            if intersect_triangle(tri_ray, p[0], p[1], p[2], entered.t_max).x < entered.t_max {
                return true;
            }
        }
        if !step.valid {
            break;
        }
    }
    return false;
}
// #endif
