//! Scene traversal: closest hit and any hit, through the scene grid by 3D-DDA (Amanatides
//! & Woo 1987) or by brute force when the grid is off. The scene grid's items are
//! instances: analytic primitives, CSG objects and mesh instances, the last traversed
//! through their mesh's own grid (`traverse_mesh`). A closest hit found in a cell is
//! accepted only if it lies inside that cell (an item may span several cells, and a
//! nearer item may wait in the next one); an item met again in a later cell (a mesh
//! instance, a large sphere) is not tested again (its nearest hit does not depend on the
//! cell: [`Mailbox`]). Through the grid, the walk tests the analytic items it meets and
//! only collects the mesh instances ([`PendingMeshes`]), which it walks when two are
//! waiting and when it leaves a cell with some waiting: on llvmpipe every branch of a
//! loop body runs, taken or not, so a mesh walk inside the item loop cost every item
//! tested a masked mesh walk (docs/journal/2026-11-30-mesh-walks-out-of-item-loop.md); out of it, the GPU runs that code once per
//! cell that held an instance.

use super::dda::{dda_setup, dda_step, scene_grid, Dda};
pub use super::dda::{enter_scene, EnteredRay};
use super::hit::Slots;
pub use super::hit::{hit_miss, Counters, Hit, NoCounters, TraversalCounters};
use super::traverse_mesh::{intersect_mesh, mesh_occludes};
use crate::constants::{
    ITEM_MAILBOX_SIZE, KIND_CSG, KIND_MESH, KIND_TORUS, NO_ITEM, T_MISS, WALK_FULL,
};
use crate::pack::{
    cell_item_at, cell_start_at, load_instance, PackedInstance, PackedScene, SceneFeatures,
};
use crate::tracer::base::ray::Ray;
use crate::tracer::geometry::csg::intersect_csg;
use crate::tracer::geometry::intersect::intersect_instance;

/// The items a ray has tested, as a direct-mapped cache of `ITEM_MAILBOX_SIZE` slots
/// (item number modulo the size: one compare). Only kinds for which a second test is
/// sure to change nothing go in ([`mailboxed`]). `PackedScene::mailboxes` picks the
/// variant, the twin of the GPU kernel's: all the slots (`Mailboxes::Full`), only the
/// first, so the last item tested (`LastItem`: the GPU's `LAST_ITEM_MAILBOX`), or none
/// (`Off`: every item is tested in every cell that lists it). The answers are the same.
/// (Free functions `mailbox_new`, `mailbox_seen`, as the WGSL twins are named.)
// Mirror of src/tracer/traversal/traverse.wgsl::Mailbox — change both.
pub struct Mailbox(Slots<{ ITEM_MAILBOX_SIZE as usize }>);

/// An empty mailbox of the variant `scene.mailboxes` names (on the GPU the switch is the
/// module's `MAILBOXES` or `LAST_ITEM_MAILBOX` specialisation).
// Mirror of src/tracer/traversal/traverse.wgsl::mailbox_new — change both.
pub fn mailbox_new(scene: &PackedScene) -> Mailbox {
    Mailbox(Slots::new(scene.mailboxes.item_slot_mask()))
}

/// Whether `item` was tested already (as far as its slot remembers); if not, it is now
/// remembered in its slot.
// Mirror of src/tracer/traversal/traverse.wgsl::mailbox_seen — change both.
#[inline(always)]
pub fn mailbox_seen(mailbox: &mut Mailbox, item: u32) -> bool {
    mailbox.0.seen(item)
}

/// Whether items of `kind` go through the mailbox: those whose answer is the nearest end
/// of intervals found without t_max (sphere, box, cylinder, cone; a mesh's nearest
/// triangle), so that a second test under the same or a smaller t_max gives a miss or
/// the same hit, which the caller already holds. A torus clips its root search to t_max
/// and a CSG object its interval lists, so their t may move in the last bits with it:
/// they are tested in every cell.
// Mirror of src/tracer/traversal/traverse.wgsl::mailboxed — change both.
pub fn mailboxed(kind: u32) -> bool {
    kind != KIND_TORUS && kind != KIND_CSG
}

/// Item `item`, unless `mailbox` says it was tested already (None). The first step of
/// `intersect_item` and `item_occludes` (which the WGSL twins each write out).
#[inline(always)]
fn untested_item<'a>(
    scene: &'a PackedScene,
    item: u32,
    mailbox: &mut Mailbox,
) -> Option<&'a PackedInstance> {
    let inst = load_instance(scene, item);
    if mailboxed(inst.kind) && mailbox_seen(mailbox, item) {
        return None;
    }
    Some(inst)
}

/// Tests one item: its hit (t = T_MISS on a miss). An item in `mailbox` is a miss (its
/// hit, if any, is already the best).
// Mirror of src/tracer/traversal/traverse.wgsl::intersect_item — change both.
fn intersect_item(
    scene: &PackedScene,
    item: u32,
    ray: &Ray,
    t_max: f32,
    mailbox: &mut Mailbox,
    counters: &mut impl TraversalCounters,
) -> Hit {
    let Some(inst) = untested_item(scene, item, mailbox) else {
        return hit_miss();
    };
    if inst.kind == KIND_MESH {
        return intersect_mesh(scene, inst, item, ray, t_max, counters);
    }
    intersect_primitive_item(scene, inst, item, ray, t_max, counters)
}

/// Tests one item that is not a mesh instance (an analytic primitive or a CSG object):
/// its hit (t = T_MISS on a miss). Its own function so that a shadow ray's test of such an
/// item does not pass through the mesh walk (on llvmpipe every branch's code runs, taken or
/// not: src/tracer/traversal/traverse.wgsl).
// Mirror of src/tracer/traversal/traverse.wgsl::intersect_primitive_item — change both.
fn intersect_primitive_item(
    scene: &PackedScene,
    inst: &PackedInstance,
    item: u32,
    ray: &Ray,
    t_max: f32,
    counters: &mut impl TraversalCounters,
) -> Hit {
    counters.item_tested();
    if inst.kind == KIND_CSG {
        let h = intersect_csg(scene, inst, ray.origin, ray.dir, t_max);
        return Hit {
            t: h.t,
            item,
            part: h.part,
            ..hit_miss()
        };
    }
    let t = intersect_instance(inst, ray.origin, ray.dir, t_max);
    Hit {
        t,
        item,
        ..hit_miss()
    }
}

/// The i-th of the items a traversal step tests: a scene cell's item list
/// (`cell_items[i]`, i from the cell's start), or with the grid off every item in turn
/// (brute force). (The GPU makes the choice when the kernel is specialised: `GRID`.)
// Mirror of src/tracer/traversal/traverse.wgsl::item_at — change both.
#[inline(always)]
fn item_at(scene: &PackedScene, i: u32) -> u32 {
    if scene.globals.grid_enabled != 0 {
        cell_item_at(scene, i)
    } else {
        i
    }
}

/// Tests the items `item_at(first..last)` and keeps the nearest hit below `best.t`.
// Mirror of src/tracer/traversal/traverse.wgsl::test_items — change both.
fn test_items(
    scene: &PackedScene,
    first: u32,
    last: u32,
    ray: &Ray,
    best: &mut Hit,
    mailbox: &mut Mailbox,
    counters: &mut impl TraversalCounters,
) {
    for i in first..last {
        let h = intersect_item(scene, item_at(scene, i), ray, best.t, mailbox, counters);
        if h.t < best.t {
            *best = h;
        }
    }
}

/// Nearest hit along `ray` in (0, t_max). A t_max past [`T_MISS`] (infinity) is taken as
/// T_MISS: the tests below keep an item's t when it is below the best so far, and a
/// miss's t, T_MISS, must not count as a hit.
// Mirror of src/tracer/traversal/traverse.wgsl::closest_hit — change both.
pub fn closest_hit(
    scene: &PackedScene,
    ray: &Ray,
    t_max: f32,
    counters: &mut impl TraversalCounters,
) -> Hit {
    counters.traversal_started();
    let Some(entered) = enter_scene(&scene.globals, ray, t_max.min(T_MISS)) else {
        return hit_miss();
    };
    let mut hit = closest_hit_inside(scene, &entered, counters);
    if hit.is_hit() {
        hit.t += entered.t_moved;
    }
    hit
}

/// Nearest hit along a ray that starts inside the scene bounds (see `enter_scene`).
// Mirror of src/tracer/traversal/traverse.wgsl::closest_hit_inside — change both.
fn closest_hit_inside(
    scene: &PackedScene,
    entered: &EnteredRay,
    counters: &mut impl TraversalCounters,
) -> Hit {
    let (ray, t_max) = (&entered.ray, entered.t_max);
    let mut best = Hit {
        t: t_max,
        ..hit_miss()
    };
    let mut mailbox = mailbox_new(scene);
    let g = &scene.globals;
    if g.grid_enabled == 0 {
        counters.cell_visited();
        test_items(
            scene,
            0,
            g.num_instances,
            ray,
            &mut best,
            &mut mailbox,
            counters,
        );
        return if best.is_hit() { best } else { hit_miss() };
    }
    let grid = scene_grid(g);
    let Some(dda) = dda_setup(&grid, ray, entered.inv_dir, t_max) else {
        return hit_miss();
    };
    if scene.features.contains(SceneFeatures::MESH) {
        let mut walk = scene_walk_start(scene, dda, counters);
        let mut pending = pending_meshes_new();
        loop {
            closest_walk(
                scene,
                &mut walk,
                ray,
                &mut best,
                &mut mailbox,
                &mut pending,
                counters,
            );
            best = walk_pending_meshes(scene, &pending, ray, best, counters);
            pending = pending_meshes_new();
            if walk.done {
                break;
            }
        }
    } else {
        // Without mesh instances there is nothing to collect: the cells' items are tested
        // as the DDA meets them (the specialisation the GPU compiles for such scenes).
        let mut dda = dda;
        loop {
            counters.cell_visited();
            let cell = dda.cell;
            test_items(
                scene,
                cell_start_at(scene, cell),
                cell_start_at(scene, cell + 1),
                ray,
                &mut best,
                &mut mailbox,
                counters,
            );
            // A hit inside this cell is final; so is leaving the grid or passing t_max.
            match dda_step(&mut dda) {
                Some(t_cell_exit) if best.t > t_cell_exit => {}
                _ => break,
            }
        }
    }
    if best.is_hit() {
        best
    } else {
        hit_miss()
    }
}

/// The mesh instances a scene walk has met and not walked yet: two at most (two scalars
/// on the GPU, where llvmpipe would keep a dynamically indexed array in memory, per lane).
// Mirror of src/tracer/traversal/traverse.wgsl::PendingMeshes — change both.
struct PendingMeshes {
    first: u32,
    second: u32,
    count: u32,
}

/// None pending.
// Mirror of src/tracer/traversal/traverse.wgsl::pending_meshes_new — change both.
fn pending_meshes_new() -> PendingMeshes {
    PendingMeshes {
        first: NO_ITEM,
        second: NO_ITEM,
        count: 0,
    }
}

/// Whether two are pending (a third waits for them to be walked).
// Mirror of src/tracer/traversal/traverse.wgsl::pending_meshes_full — change both.
#[inline(always)]
fn pending_meshes_full(pending: &PendingMeshes) -> bool {
    pending.count == 2
}

/// Appends mesh instance `item` (not full).
// Mirror of src/tracer/traversal/traverse.wgsl::pending_meshes_push — change both.
#[inline(always)]
fn pending_meshes_push(pending: &mut PendingMeshes, item: u32) {
    if pending.count == 0 {
        pending.first = item;
    } else {
        pending.second = item;
    }
    pending.count += 1;
}

/// The k-th pending instance (k < count).
// Mirror of src/tracer/traversal/traverse.wgsl::pending_meshes_item — change both.
fn pending_meshes_item(pending: &PendingMeshes, k: u32) -> u32 {
    if k == 0 {
        pending.first
    } else {
        pending.second
    }
}

/// Where a walk of the scene grid stands: its DDA, the rest of the current cell's item
/// list (`cell_items[next..end]`), and whether it has ended (left the grid, passed t_max,
/// or kept a hit inside the cell it left).
// Mirror of src/tracer/traversal/traverse.wgsl::SceneWalk — change both.
struct SceneWalk {
    dda: Dda,
    next: u32,
    end: u32,
    done: bool,
}

/// A walk standing at the start of the DDA's first cell.
// Mirror of src/tracer/traversal/traverse.wgsl::scene_walk_start — change both.
fn scene_walk_start(
    scene: &PackedScene,
    dda: Dda,
    counters: &mut impl TraversalCounters,
) -> SceneWalk {
    let mut walk = SceneWalk {
        dda,
        next: 0,
        end: 0,
        done: false,
    };
    scene_walk_enter_cell(scene, &mut walk, counters);
    walk
}

/// Points `walk` at the item list of the cell its DDA stands in.
// Mirror of src/tracer/traversal/traverse.wgsl::scene_walk_enter_cell — change both.
// (This and the walk functions below are forced inline: they run per item and per cell
// of every ray. Without the hint one alternated round of `glint bench --trace` gave 8%
// fewer primary rays/s than the walk before; with it the rates were within noise.)
#[inline(always)]
fn scene_walk_enter_cell(
    scene: &PackedScene,
    walk: &mut SceneWalk,
    counters: &mut impl TraversalCounters,
) {
    counters.cell_visited();
    let cell = walk.dda.cell;
    walk.next = cell_start_at(scene, cell);
    walk.end = cell_start_at(scene, cell + 1);
}

/// Takes the walk's next item (`walk.next < walk.end`): the item to test when it is an
/// analytic one; `NO_ITEM` when it was passed over (in the mailbox, or a mesh instance,
/// now pending); `WALK_FULL`, without taking it, when it is a mesh instance and two are
/// pending already.
// Mirror of src/tracer/traversal/traverse.wgsl::scene_walk_take — change both.
#[inline(always)]
fn scene_walk_take(
    scene: &PackedScene,
    walk: &mut SceneWalk,
    mailbox: &mut Mailbox,
    pending: &mut PendingMeshes,
) -> u32 {
    let item = cell_item_at(scene, walk.next);
    let kind = load_instance(scene, item).kind;
    if kind == KIND_MESH && pending_meshes_full(pending) {
        return WALK_FULL;
    }
    walk.next += 1;
    if mailboxed(kind) && mailbox_seen(mailbox, item) {
        return NO_ITEM;
    }
    if kind == KIND_MESH {
        pending_meshes_push(pending, item);
        return NO_ITEM;
    }
    item
}

/// Walks the scene grid on from where `walk` stands, keeping in `best` the nearest hit
/// of the analytic items it meets and collecting the mesh instances in `pending`, until
/// the walk ends (`walk.done`), a third instance waits (`walk` then stands on it) or the
/// cell is done with instances pending.
// Mirror of src/tracer/traversal/traverse.wgsl::closest_walk — change both.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn closest_walk(
    scene: &PackedScene,
    walk: &mut SceneWalk,
    ray: &Ray,
    best: &mut Hit,
    mailbox: &mut Mailbox,
    pending: &mut PendingMeshes,
    counters: &mut impl TraversalCounters,
) {
    loop {
        if walk.next < walk.end {
            let item = scene_walk_take(scene, walk, mailbox, pending);
            if item == WALK_FULL {
                return;
            }
            if item == NO_ITEM {
                continue;
            }
            let inst = load_instance(scene, item);
            let h = intersect_primitive_item(scene, inst, item, ray, best.t, counters);
            if h.t < best.t {
                *best = h;
            }
            continue;
        }
        // The cell's pending instances are walked before the walk leaves it, so that a
        // hit inside this cell is final, theirs or not; so is leaving the grid or passing
        // t_max.
        if pending.count > 0 {
            return;
        }
        match dda_step(&mut walk.dda) {
            Some(t_cell_exit) if best.t > t_cell_exit => {
                scene_walk_enter_cell(scene, walk, counters)
            }
            _ => {
                walk.done = true;
                return;
            }
        }
    }
}

/// `best`, or the nearest hit below `best.t` of the pending mesh instances, walked in the
/// order met.
// Mirror of src/tracer/traversal/traverse.wgsl::walk_pending_meshes — change both.
fn walk_pending_meshes(
    scene: &PackedScene,
    pending: &PendingMeshes,
    ray: &Ray,
    mut best: Hit,
    counters: &mut impl TraversalCounters,
) -> Hit {
    for k in 0..pending.count {
        let item = pending_meshes_item(pending, k);
        let inst = load_instance(scene, item);
        let h = intersect_mesh(scene, inst, item, ray, best.t, counters);
        if h.t < best.t {
            best = h;
        }
    }
    best
}

/// Whether item `item` is hit in (0, t_max); an item in `mailbox` is not tested again (it
/// was not hit, or the search would have stopped).
// Mirror of src/tracer/traversal/traverse.wgsl::item_occludes — change both.
fn item_occludes(
    scene: &PackedScene,
    item: u32,
    ray: &Ray,
    t_max: f32,
    mailbox: &mut Mailbox,
    counters: &mut impl TraversalCounters,
) -> bool {
    let Some(inst) = untested_item(scene, item, mailbox) else {
        return false;
    };
    if inst.kind == KIND_MESH {
        return mesh_occludes(scene, inst, ray, t_max, counters);
    }
    intersect_primitive_item(scene, inst, item, ray, t_max, counters).t < t_max
}

/// Whether any of the items `item_at(first..last)` is hit in (0, t_max).
// Mirror of src/tracer/traversal/traverse.wgsl::any_item_hit — change both.
fn any_item_hit(
    scene: &PackedScene,
    first: u32,
    last: u32,
    ray: &Ray,
    t_max: f32,
    mailbox: &mut Mailbox,
    counters: &mut impl TraversalCounters,
) -> bool {
    for i in first..last {
        if item_occludes(scene, item_at(scene, i), ray, t_max, mailbox, counters) {
            return true;
        }
    }
    false
}

/// Whether anything blocks `ray` in (0, t_max) (shadow rays). A t_max past [`T_MISS`] is
/// taken as T_MISS, as in [`closest_hit`].
// Mirror of src/tracer/traversal/traverse.wgsl::any_hit — change both.
pub fn any_hit(
    scene: &PackedScene,
    ray: &Ray,
    t_max: f32,
    counters: &mut impl TraversalCounters,
) -> bool {
    counters.traversal_started();
    match enter_scene(&scene.globals, ray, t_max.min(T_MISS)) {
        Some(entered) => any_hit_inside(scene, &entered, counters),
        None => false,
    }
}

/// Whether anything blocks a ray that starts inside the scene bounds.
// Mirror of src/tracer/traversal/traverse.wgsl::any_hit_inside — change both.
fn any_hit_inside(
    scene: &PackedScene,
    entered: &EnteredRay,
    counters: &mut impl TraversalCounters,
) -> bool {
    let (ray, t_max) = (&entered.ray, entered.t_max);
    let mut mailbox = mailbox_new(scene);
    let g = &scene.globals;
    if g.grid_enabled == 0 {
        counters.cell_visited();
        let items = g.num_instances;
        return any_item_hit(scene, 0, items, ray, t_max, &mut mailbox, counters);
    }
    let grid = scene_grid(g);
    let Some(dda) = dda_setup(&grid, ray, entered.inv_dir, t_max) else {
        return false;
    };
    if !scene.features.contains(SceneFeatures::MESH) {
        // Without mesh instances: the cells' items as the DDA meets them (see
        // closest_hit_inside).
        let mut dda = dda;
        loop {
            counters.cell_visited();
            let (first, last) = (
                cell_start_at(scene, dda.cell),
                cell_start_at(scene, dda.cell + 1),
            );
            if any_item_hit(scene, first, last, ray, t_max, &mut mailbox, counters) {
                return true;
            }
            if dda_step(&mut dda).is_none() {
                return false;
            }
        }
    }
    let mut walk = scene_walk_start(scene, dda, counters);
    let mut pending = pending_meshes_new();
    loop {
        let occluded = occlusion_walk(
            scene,
            &mut walk,
            ray,
            t_max,
            &mut mailbox,
            &mut pending,
            counters,
        );
        if occluded || pending_meshes_occlude(scene, &pending, ray, t_max, counters) {
            return true;
        }
        pending = pending_meshes_new();
        if walk.done {
            return false;
        }
    }
}

/// Walks the scene grid on from where `walk` stands until an analytic item it meets is hit
/// in (0, t_max) (true), the walk leaves the grid (`walk.done`), a third mesh instance
/// waits (`walk` then stands on it) or the cell is done with instances pending,
/// collecting the instances in `pending`.
// Mirror of src/tracer/traversal/traverse.wgsl::occlusion_walk — change both.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn occlusion_walk(
    scene: &PackedScene,
    walk: &mut SceneWalk,
    ray: &Ray,
    t_max: f32,
    mailbox: &mut Mailbox,
    pending: &mut PendingMeshes,
    counters: &mut impl TraversalCounters,
) -> bool {
    loop {
        if walk.next < walk.end {
            let item = scene_walk_take(scene, walk, mailbox, pending);
            if item == WALK_FULL {
                return false;
            }
            if item == NO_ITEM {
                continue;
            }
            let inst = load_instance(scene, item);
            if intersect_primitive_item(scene, inst, item, ray, t_max, counters).t < t_max {
                return true;
            }
            continue;
        }
        // The cell's pending instances are walked before the walk leaves it.
        if pending.count > 0 {
            return false;
        }
        if dda_step(&mut walk.dda).is_none() {
            walk.done = true;
            return false;
        }
        scene_walk_enter_cell(scene, walk, counters);
    }
}

/// Whether one of the pending mesh instances is hit in (0, t_max).
// Mirror of src/tracer/traversal/traverse.wgsl::pending_meshes_occlude — change both.
fn pending_meshes_occlude(
    scene: &PackedScene,
    pending: &PendingMeshes,
    ray: &Ray,
    t_max: f32,
    counters: &mut impl TraversalCounters,
) -> bool {
    for k in 0..pending.count {
        let inst = load_instance(scene, pending_meshes_item(pending, k));
        if mesh_occludes(scene, inst, ray, t_max, counters) {
            return true;
        }
    }
    false
}
