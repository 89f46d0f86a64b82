// traverse.wgsl — scene traversal: closest hit and any hit, through the scene grid by
// 3D-DDA (Amanatides & Woo 1987) when the scene has one (GRID), else by brute force. The
// scene grid's items are instances: analytic primitives, CSG objects and mesh instances,
// the last traversed through their mesh's own grid (traverse_mesh.wgsl). A closest hit
// found in a cell is accepted only if it lies inside that cell; an item met again in a
// later cell (a mesh instance, a large sphere) is not tested again (Mailbox). Unlike the
// CPU tracer, the choice between grid and brute force is made when the shader is
// specialised: the GRID feature is set exactly when `grid_enabled` is 1. Through the
// grid, in scenes with meshes (MESH), the walk tests the analytic items it meets and only
// collects the mesh instances (PendingMeshes), which it walks when two are waiting and
// when it leaves a cell with some waiting: llvmpipe runs every branch of a loop body,
// taken or not, so a mesh walk inside the item loop cost every item tested a masked mesh
// walk (docs/journal/2026-11-30-mesh-walks-out-of-item-loop.md).
// Without MESH nothing is ever pending, and the cell-by-cell loop below makes the same
// tests in the same order as the CPU's walk.

// The items a ray has tested, as a direct-mapped cache of ITEM_MAILBOX_SIZE slots (item
// number modulo the size). Only kinds for which a second test is sure to change nothing
// go in (mailboxed). The MAILBOXES variant keeps every slot (in registers on a GPU: no
// adapter's choice, docs/gpu.md); LAST_ITEM_MAILBOX (every adapter's) only the last item
// tested, a scalar where llvmpipe would scatter and gather an array; with neither,
// every item is tested in every cell that lists it. The answers are the same.
// Mirror of src/tracer/traversal/traverse.rs::Mailbox — change both.
struct Mailbox {
// #if MAILBOXES
    items: array<u32, ITEM_MAILBOX_SIZE>,
// #else
    last: u32,
// #endif
}

// Mirror of src/tracer/traversal/traverse.rs::mailbox_new — change both.
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
// Mirror of src/tracer/traversal/traverse.rs::mailbox_seen — change both.
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
// Mirror of src/tracer/traversal/traverse.rs::mailboxed — change both.
fn mailboxed(kind: u32) -> bool {
    return kind != KIND_TORUS && kind != KIND_CSG;
}

// Tests one item: its hit (t = T_MISS on a miss). An item in the mailbox is a miss (its
// hit, if any, is already the best).
// Mirror of src/tracer/traversal/traverse.rs::intersect_item — change both.
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
// every branch, taken by a lane or not, under a lane mask (tools/examples/llvmpipe_branches.rs),
// so that walk's set-up, one cell and one triangle test ran, masked, beside mesh_occludes's
// for every item a shadow ray tested (within noise when removed, docs/journal/2026-11-30-every-branch-runs-on-llvmpipe.md).
// Mirror of src/tracer/traversal/traverse.rs::intersect_primitive_item — change both.
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
// Mirror of src/tracer/traversal/traverse.rs::item_at — change both.
fn item_at(i: u32) -> u32 {
// #if GRID
    return cell_item_at(i);
// #else
    return i;
// #endif
}

// Tests the items item_at(first..last) and keeps the nearest hit below best.t.
// Mirror of src/tracer/traversal/traverse.rs::test_items — change both.
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

// Nearest hit along ray in (0, t_max). A t_max past T_MISS (infinity) is taken as T_MISS:
// a miss's t, T_MISS, must not count as a hit.
// Mirror of src/tracer/traversal/traverse.rs::closest_hit — change both.
fn closest_hit(ray: Ray, t_max: f32) -> Hit {
    let entered = enter_scene(ray, min(t_max, T_MISS));
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
// Mirror of src/tracer/traversal/traverse.rs::closest_hit_inside — change both.
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
// #if MESH
    var walk = scene_walk_start(dda);
    var pending = pending_meshes_new();
    loop {
        closest_walk(&walk, ray, &best, &mailbox, &pending);
        best = walk_pending_meshes(pending, ray, best);
        pending = pending_meshes_new();
        if walk.done {
            break;
        }
    }
// #else
    loop {
        let cell = dda.cell;
        best = test_items(cell_start_at(cell), cell_start_at(cell + 1u), ray, best, &mailbox);
        // A hit inside this cell is final; so is leaving the grid or passing t_max.
        let step = dda_step(&dda);
        if !step.valid || best.t <= step.t_cell_exit {
            break;
        }
    }
// #endif
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
// Mirror of src/tracer/traversal/traverse.rs::item_occludes — change both.
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
// Mirror of src/tracer/traversal/traverse.rs::any_item_hit — change both.
fn any_item_hit(first: u32, last: u32, ray: Ray, t_max: f32, mailbox: ptr<function, Mailbox>) -> bool {
    for (var i = first; i < last; i++) {
        if item_occludes(item_at(i), ray, t_max, mailbox) {
            return true;
        }
    }
    return false;
}

// Whether anything blocks ray in (0, t_max) (shadow rays). A t_max past T_MISS is taken
// as T_MISS, as in closest_hit.
// Mirror of src/tracer/traversal/traverse.rs::any_hit — change both.
fn any_hit(ray: Ray, t_max: f32) -> bool {
    let entered = enter_scene(ray, min(t_max, T_MISS));
    if !entered.valid {
        return false;
    }
    return any_hit_inside(entered);
}

// Whether anything blocks a ray that starts inside the scene bounds.
// Mirror of src/tracer/traversal/traverse.rs::any_hit_inside — change both.
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
// #if MESH
    var walk = scene_walk_start(dda);
    var pending = pending_meshes_new();
    // (naga wants a return after the loop, so the loop breaks where Rust returns false.)
// #if ANY_HIT_ONE_LOOP
    // One loop (the hardware variant's): each turn is one step of the CPU's occlusion_walk
    // loop, then, where that loop returns false, the same pending walk. One loop level
    // fewer around the analytic tests: RADV's NAVI21 any-hit kernel of scrabble.lua spilled
    // 6 SGPRs in wave64 with the loop inside a loop (docs/journal/2026-12-02-traversal-registers.md);
    // on llvmpipe, which runs every branch of a loop body, the mesh walks would run masked
    // beside every item test (docs/journal/2026-11-30-mesh-walks-out-of-item-loop.md).
    loop {
        let step = occlusion_walk(&walk, ray, t_max, &mailbox, &pending);
        if step == NO_ITEM {
            continue;
        }
        if step != WALK_FULL || pending_meshes_occlude(pending, ray, t_max) {
            return true;
        }
        pending = pending_meshes_new();
        if walk.done {
            break;
        }
    }
// #else
    loop {
        let occluded = occlusion_walk(&walk, ray, t_max, &mailbox, &pending);
        if occluded || pending_meshes_occlude(pending, ray, t_max) {
            return true;
        }
        pending = pending_meshes_new();
        if walk.done {
            break;
        }
    }
// #endif
    return false;
// #else
    // (naga wants a return after the loop, so the loop breaks where Rust returns false.)
    loop {
        let cell = dda.cell;
        if any_item_hit(cell_start_at(cell), cell_start_at(cell + 1u), ray, t_max, &mailbox) {
            return true;
        }
        if !dda_step(&dda).valid {
            break;
        }
    }
    return false;
// #endif
// #else
    return any_item_hit(0u, globals.num_instances, ray, t_max, &mailbox);
// #endif
}

// #if GRID
// #if MESH
// The mesh instances a scene walk has met and not walked yet: two at most (two scalars:
// llvmpipe would keep a dynamically indexed array in memory, per lane).
// Mirror of src/tracer/traversal/traverse.rs::PendingMeshes — change both.
struct PendingMeshes {
    first: u32,
    second: u32,
    count: u32,
}

// None pending.
// Mirror of src/tracer/traversal/traverse.rs::pending_meshes_new — change both.
fn pending_meshes_new() -> PendingMeshes {
    return PendingMeshes(NO_ITEM, NO_ITEM, 0u);
}

// Whether two are pending (a third waits for them to be walked).
// Mirror of src/tracer/traversal/traverse.rs::pending_meshes_full — change both.
fn pending_meshes_full(pending: PendingMeshes) -> bool {
    return pending.count == 2u;
}

// Appends mesh instance item (not full).
// Mirror of src/tracer/traversal/traverse.rs::pending_meshes_push — change both.
fn pending_meshes_push(pending: ptr<function, PendingMeshes>, item: u32) {
    if (*pending).count == 0u {
        (*pending).first = item;
    } else {
        (*pending).second = item;
    }
    (*pending).count += 1u;
}

// The k-th pending instance (k < count).
// Mirror of src/tracer/traversal/traverse.rs::pending_meshes_item — change both.
fn pending_meshes_item(pending: PendingMeshes, k: u32) -> u32 {
    return select(pending.second, pending.first, k == 0u);
}

// Where a walk of the scene grid stands: its DDA, the rest of the current cell's item list
// (cell_items[next..end]), and whether it has ended (left the grid, passed t_max, or kept
// a hit inside the cell it left).
// Mirror of src/tracer/traversal/traverse.rs::SceneWalk — change both.
struct SceneWalk {
    dda: Dda,
    next: u32,
    end: u32,
    done: bool,
}

// A walk standing at the start of the DDA's first cell.
// Mirror of src/tracer/traversal/traverse.rs::scene_walk_start — change both.
fn scene_walk_start(dda: Dda) -> SceneWalk {
    var walk = SceneWalk(dda, 0u, 0u, false);
    scene_walk_enter_cell(&walk);
    return walk;
}

// Points walk at the item list of the cell its DDA stands in.
// Mirror of src/tracer/traversal/traverse.rs::scene_walk_enter_cell — change both.
fn scene_walk_enter_cell(walk: ptr<function, SceneWalk>) {
    let cell = (*walk).dda.cell;
    (*walk).next = cell_start_at(cell);
    (*walk).end = cell_start_at(cell + 1u);
}

// Takes the walk's next item (walk.next < walk.end): the item to test when it is an
// analytic one; NO_ITEM when it was passed over (in the mailbox, or a mesh instance, now
// pending); WALK_FULL, without taking it, when it is a mesh instance and two are pending
// already.
// Mirror of src/tracer/traversal/traverse.rs::scene_walk_take — change both.
fn scene_walk_take(
    walk: ptr<function, SceneWalk>,
    mailbox: ptr<function, Mailbox>,
    pending: ptr<function, PendingMeshes>,
) -> u32 {
    let item = cell_item_at((*walk).next);
    let kind = load_instance(item).kind;
    if kind == KIND_MESH && pending_meshes_full(*pending) {
        return WALK_FULL;
    }
    (*walk).next += 1u;
    if mailboxed(kind) && mailbox_seen(mailbox, item) {
        return NO_ITEM;
    }
    if kind == KIND_MESH {
        pending_meshes_push(pending, item);
        return NO_ITEM;
    }
    return item;
}

// Walks the scene grid on from where walk stands, keeping in best the nearest hit of the
// analytic items it meets and collecting the mesh instances in pending, until the walk
// ends (walk.done), a third instance waits (walk then stands on it) or the cell is done
// with instances pending.
// Mirror of src/tracer/traversal/traverse.rs::closest_walk — change both.
fn closest_walk(
    walk: ptr<function, SceneWalk>,
    ray: Ray,
    best: ptr<function, Hit>,
    mailbox: ptr<function, Mailbox>,
    pending: ptr<function, PendingMeshes>,
) {
    loop {
        if (*walk).next < (*walk).end {
            let item = scene_walk_take(walk, mailbox, pending);
            if item == WALK_FULL {
                return;
            }
            if item == NO_ITEM {
                continue;
            }
            let inst = load_instance(item);
            let h = intersect_primitive_item(inst, item, ray, (*best).t);
            if h.t < (*best).t {
                *best = h;
            }
            continue;
        }
        // The cell's pending instances are walked before the walk leaves it, so that a hit
        // inside this cell is final, theirs or not; so is leaving the grid or passing t_max.
        if (*pending).count > 0u {
            return;
        }
        var dda = (*walk).dda;
        let step = dda_step(&dda);
        (*walk).dda = dda;
        if !step.valid || (*best).t <= step.t_cell_exit {
            (*walk).done = true;
            return;
        }
        scene_walk_enter_cell(walk);
    }
}

// best, or the nearest hit below best.t of the pending mesh instances, walked in the order
// met.
// Mirror of src/tracer/traversal/traverse.rs::walk_pending_meshes — change both.
fn walk_pending_meshes(pending: PendingMeshes, ray: Ray, best_in: Hit) -> Hit {
    var best = best_in;
    for (var k = 0u; k < pending.count; k++) {
        let item = pending_meshes_item(pending, k);
        let h = intersect_mesh(load_instance(item), item, ray, best.t);
        if h.t < best.t {
            best = h;
        }
    }
    return best;
}

// #if ANY_HIT_ONE_LOOP
// One turn of the CPU twin's loop, for any_hit_inside's one loop (ANY_HIT_ONE_LOOP): the
// item an analytic test found hit in (0, t_max) where the CPU returns true; NO_ITEM where
// its loop goes on (an item passed over, or tested and missed, or the next cell entered);
// WALK_FULL where it returns false: a third mesh instance waits (walk then stands on it),
// the cell is done with instances pending, or the walk has left the grid (walk.done).
// Mirror of src/tracer/traversal/traverse.rs::occlusion_walk — change both.
fn occlusion_walk(
    walk: ptr<function, SceneWalk>,
    ray: Ray,
    t_max: f32,
    mailbox: ptr<function, Mailbox>,
    pending: ptr<function, PendingMeshes>,
) -> u32 {
    if (*walk).next < (*walk).end {
        let item = scene_walk_take(walk, mailbox, pending);
        if item == WALK_FULL || item == NO_ITEM {
            return item;
        }
        let inst = load_instance(item);
        if intersect_primitive_item(inst, item, ray, t_max).t < t_max {
            return item;
        }
        return NO_ITEM;
    }
    // The cell's pending instances are walked before the walk leaves it.
    if (*pending).count > 0u {
        return WALK_FULL;
    }
    var dda = (*walk).dda;
    let step = dda_step(&dda);
    (*walk).dda = dda;
    if !step.valid {
        (*walk).done = true;
        return WALK_FULL;
    }
    scene_walk_enter_cell(walk);
    return NO_ITEM;
}
// #else
// Walks the scene grid on from where walk stands until an analytic item it meets is hit in
// (0, t_max) (true), the walk leaves the grid (walk.done), a third mesh instance waits
// (walk then stands on it) or the cell is done with instances pending, collecting the
// instances in pending.
// Mirror of src/tracer/traversal/traverse.rs::occlusion_walk — change both.
fn occlusion_walk(
    walk: ptr<function, SceneWalk>,
    ray: Ray,
    t_max: f32,
    mailbox: ptr<function, Mailbox>,
    pending: ptr<function, PendingMeshes>,
) -> bool {
    loop {
        if (*walk).next < (*walk).end {
            let item = scene_walk_take(walk, mailbox, pending);
            if item == WALK_FULL {
                return false;
            }
            if item == NO_ITEM {
                continue;
            }
            let inst = load_instance(item);
            if intersect_primitive_item(inst, item, ray, t_max).t < t_max {
                return true;
            }
            continue;
        }
        // The cell's pending instances are walked before the walk leaves it.
        if (*pending).count > 0u {
            return false;
        }
        var dda = (*walk).dda;
        let step = dda_step(&dda);
        (*walk).dda = dda;
        if !step.valid {
            (*walk).done = true;
            return false;
        }
        scene_walk_enter_cell(walk);
    }
    return false;
}
// #endif

// Whether one of the pending mesh instances is hit in (0, t_max).
// Mirror of src/tracer/traversal/traverse.rs::pending_meshes_occlude — change both.
fn pending_meshes_occlude(pending: PendingMeshes, ray: Ray, t_max: f32) -> bool {
    for (var k = 0u; k < pending.count; k++) {
        if mesh_occludes(load_instance(pending_meshes_item(pending, k)), ray, t_max) {
            return true;
        }
    }
    return false;
}
// #endif
// #endif
