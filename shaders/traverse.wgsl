// traverse.wgsl — scene traversal: closest hit and any hit, through the scene grid by
// 3D-DDA (Amanatides & Woo 1987) when the scene has one (GRID), else by brute force. The
// scene grid's items are instances: analytic primitives, CSG objects and mesh instances,
// the last traversed through their mesh's own grid (traverse_mesh.wgsl). A closest hit
// found in a cell is accepted only if it lies inside that cell; an item met again in a
// later cell (a mesh instance, a large sphere) is not tested again (Mailbox). Unlike the
// CPU tracer, the choice between grid and brute force is made when the shader is
// specialised: the GRID feature is set exactly when `grid_enabled` is 1.

// The items a ray has tested, as a direct-mapped cache of ITEM_MAILBOX_SIZE slots (item
// number modulo the size). Only kinds for which a second test is sure to change nothing
// go in (mailboxed). The MAILBOXES variant (hardware adapters) keeps every slot; the
// LAST_ITEM_MAILBOX variant (software adapters) only the last item tested, a scalar
// where llvmpipe would scatter and gather an array indexed at run time; with neither,
// every item is tested in every cell that lists it. The answers are the same.
// Mirror of src/cpu/traverse.rs::Mailbox — change both.
struct Mailbox {
// #if MAILBOXES
    items: array<u32, ITEM_MAILBOX_SIZE>,
// #else
    last: u32,
// #endif
}

// Mirror of src/cpu/traverse.rs::Mailbox::new — change both.
fn mailbox_new() -> Mailbox {
    var mailbox: Mailbox;
// #if MAILBOXES
    for (var i = 0u; i < ITEM_MAILBOX_SIZE; i++) {
        mailbox.items[i] = NO_ITEM;
    }
// #else
    mailbox.last = NO_ITEM;
// #endif
    return mailbox;
}

// Whether item was tested already (as far as its slot remembers); if not, it is now
// remembered in its slot.
// Mirror of src/cpu/traverse.rs::Mailbox::seen — change both.
fn mailbox_seen(mailbox: ptr<function, Mailbox>, item: u32) -> bool {
// #if MAILBOXES
    let slot = item & (ITEM_MAILBOX_SIZE - 1u);
    if (*mailbox).items[slot] == item {
        return true;
    }
    (*mailbox).items[slot] = item;
// #endif
// #if LAST_ITEM_MAILBOX
    // Slot item & 0, the only one (the CPU twin's mask).
    if (*mailbox).last == item {
        return true;
    }
    (*mailbox).last = item;
// #endif
    return false;
}

// Whether items of kind go through the mailbox: those whose answer is the nearest end of
// intervals found without t_max (sphere, box, cylinder, cone; a mesh's nearest triangle).
// A torus and a CSG object use t_max inside their search: they are tested in every cell.
// Mirror of src/cpu/traverse.rs::mailboxed — change both.
fn mailboxed(kind: u32) -> bool {
    return kind != KIND_TORUS && kind != KIND_CSG;
}

// Tests one item: its hit (t = T_MISS on a miss). An item in the mailbox is a miss (its
// hit, if any, is already the best).
// Mirror of src/cpu/traverse.rs::intersect_item — change both.
fn intersect_item(item: u32, ray: Ray, t_max: f32, mailbox: ptr<function, Mailbox>) -> Hit {
    let inst = load_instance(item);
    if mailboxed(inst.kind) && mailbox_seen(mailbox, item) {
        return hit_miss();
    }
// #if MESH
    if inst.kind == KIND_MESH {
        return intersect_mesh(inst, item, ray, t_max);
    }
// #endif
    return intersect_primitive_item(inst, item, ray, t_max);
}

// Tests one item that is not a mesh instance (an analytic primitive or a CSG object): its
// hit (t = T_MISS on a miss). Its own function so that a shadow ray's test of such an item
// does not pass through intersect_item's mesh walk: llvmpipe (Mesa 22.3) runs the code of
// every branch, taken by a lane or not, under a lane mask (examples/llvmpipe_branches.rs),
// so that walk's set-up, one cell and one triangle test ran, masked, beside mesh_occludes's
// for every item a shadow ray tested (within noise when removed, docs/gpu.md).
// Mirror of src/cpu/traverse.rs::intersect_primitive_item — change both.
fn intersect_primitive_item(inst: PackedInstance, item: u32, ray: Ray, t_max: f32) -> Hit {
// #if SPHERE|CUBE|CYLINDER|CONE|TORUS
// #if CSG
    if inst.kind == KIND_CSG {
        let h = intersect_csg(inst, ray.origin, ray.dir, t_max);
        return Hit(h.t, item, 0.0, 0.0, h.part);
    }
// #endif
    let t = intersect_instance(inst, ray.origin, ray.dir, t_max);
    return Hit(t, item, 0.0, 0.0, NO_ITEM);
// #else
    return hit_miss();
// #endif
}

// The i-th of the items a traversal step tests: the grid cell's item list, or every item
// in turn (brute force).
// Mirror of the `items` iterators in src/cpu/traverse.rs::closest_hit — change both.
fn item_at(i: u32) -> u32 {
// #if GRID
    return cell_item_at(i);
// #else
    return i;
// #endif
}

// Tests the items item_at(first..last) and keeps the nearest hit below best.t.
// Mirror of src/cpu/traverse.rs::test_items — change both.
fn test_items(first: u32, last: u32, ray: Ray, best_in: Hit, mailbox: ptr<function, Mailbox>) -> Hit {
    var best = best_in;
    for (var i = first; i < last; i++) {
        let h = intersect_item(item_at(i), ray, best.t, mailbox);
        if h.t < best.t {
            best = h;
        }
    }
    return best;
}

// Nearest hit along ray in (0, t_max).
// Mirror of src/cpu/traverse.rs::closest_hit — change both.
fn closest_hit(ray: Ray, t_max: f32) -> Hit {
    let entered = enter_scene(ray, t_max);
    if !entered.valid {
        return hit_miss();
    }
    var hit = closest_hit_inside(entered);
    if is_hit(hit) {
        hit.t += entered.t_moved;
    }
    return hit;
}

// Nearest hit along a ray that starts inside the scene bounds (see enter_scene).
// Mirror of src/cpu/traverse.rs::closest_hit_inside — change both.
fn closest_hit_inside(entered: EnteredRay) -> Hit {
    let ray = entered.ray;
    let t_max = entered.t_max;
    var best = hit_miss();
    best.t = t_max;
    var mailbox = mailbox_new();
// #if GRID
    let grid = scene_grid();
    var dda = dda_setup(grid, ray, entered.inv_dir, t_max);
    if !dda.valid {
        return hit_miss();
    }
    loop {
        let cell = cell_index(grid, dda.cell);
        best = test_items(cell_start_at(cell), cell_start_at(cell + 1u), ray, best, &mailbox);
        // A hit inside this cell is final; so is leaving the grid or passing t_max.
        let step = dda_step(grid, &dda);
        if !step.valid || best.t <= step.t_cell_exit {
            break;
        }
    }
// #else
    best = test_items(0u, globals.num_instances, ray, best, &mailbox);
// #endif
    if is_hit(best) {
        return best;
    }
    return hit_miss();
}

// Whether item `item` is hit in (0, t_max); an item in the mailbox is not tested again
// (it was not hit, or the search would have stopped).
// Mirror of src/cpu/traverse.rs::item_occludes — change both.
fn item_occludes(item: u32, ray: Ray, t_max: f32, mailbox: ptr<function, Mailbox>) -> bool {
    let inst = load_instance(item);
    if mailboxed(inst.kind) && mailbox_seen(mailbox, item) {
        return false;
    }
// #if MESH
    if inst.kind == KIND_MESH {
        return mesh_occludes(inst, ray, t_max);
    }
// #endif
    return intersect_primitive_item(inst, item, ray, t_max).t < t_max;
}

// Whether any of the items item_at(first..last) is hit in (0, t_max).
// Mirror of src/cpu/traverse.rs::any_item_hit — change both.
fn any_item_hit(first: u32, last: u32, ray: Ray, t_max: f32, mailbox: ptr<function, Mailbox>) -> bool {
    for (var i = first; i < last; i++) {
        if item_occludes(item_at(i), ray, t_max, mailbox) {
            return true;
        }
    }
    return false;
}

// Whether anything blocks ray in (0, t_max) (shadow rays).
// Mirror of src/cpu/traverse.rs::any_hit — change both.
fn any_hit(ray: Ray, t_max: f32) -> bool {
    let entered = enter_scene(ray, t_max);
    if !entered.valid {
        return false;
    }
    return any_hit_inside(entered);
}

// Whether anything blocks a ray that starts inside the scene bounds.
// Mirror of src/cpu/traverse.rs::any_hit_inside — change both.
fn any_hit_inside(entered: EnteredRay) -> bool {
    let ray = entered.ray;
    let t_max = entered.t_max;
    var mailbox = mailbox_new();
// #if GRID
    let grid = scene_grid();
    var dda = dda_setup(grid, ray, entered.inv_dir, t_max);
    if !dda.valid {
        return false;
    }
    // (naga wants a return after the loop, so the loop breaks where Rust returns false.)
    loop {
        let cell = cell_index(grid, dda.cell);
        if any_item_hit(cell_start_at(cell), cell_start_at(cell + 1u), ray, t_max, &mailbox) {
            return true;
        }
        if !dda_step(grid, &dda).valid {
            break;
        }
    }
    return false;
// #else
    return any_item_hit(0u, globals.num_instances, ray, t_max, &mailbox);
// #endif
}
