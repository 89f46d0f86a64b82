//! Scene traversal: closest hit and any hit, through the scene grid by 3D-DDA (Amanatides
//! & Woo 1987) or by brute force when the grid is off. The scene grid's items are
//! instances: analytic primitives, CSG objects and mesh instances, the last traversed
//! through their mesh's own grid (`traverse_mesh`). A closest hit found in a cell is
//! accepted only if it lies inside that cell (an item may span several cells, and a
//! nearer item may wait in the next one); an item met again in a later cell (a mesh
//! instance, a large sphere) is not tested again (its nearest hit does not depend on the
//! cell: [`Mailbox`]).

use super::csg::intersect_csg;
use super::dda::{cell_index, dda_setup, dda_step, scene_grid};
pub use super::dda::{enter_scene, EnteredRay};
pub use super::hit::{Counters, Hit, NoCounters, TraversalCounters};
use super::intersect::intersect_instance;
use super::ray::Ray;
use super::traverse_mesh::{intersect_mesh, mesh_occludes};
use crate::constants::{ITEM_MAILBOX_SIZE, KIND_CSG, KIND_MESH, KIND_TORUS, NO_ITEM};
use crate::pack::{PackedInstance, PackedScene};
use glam::IVec3;

/// The items a ray has tested, as a direct-mapped cache of `ITEM_MAILBOX_SIZE` slots
/// (item number modulo the size: one compare). Only kinds for which a second test is
/// sure to change nothing go in ([`mailboxed`]). `PackedScene::mailboxes` picks the
/// variant, the twin of the GPU kernel's: all the slots (`Mailboxes::Full`), only the
/// first, so the last item tested (`LastItem`: the GPU's `LAST_ITEM_MAILBOX`), or none
/// (`Off`: every item is tested in every cell that lists it). The answers are the same.
// Mirror of shaders/traverse.wgsl::Mailbox — change both.
pub struct Mailbox {
    items: [u32; ITEM_MAILBOX_SIZE as usize],
    slot_mask: Option<u32>,
}

impl Mailbox {
    /// An empty mailbox of the variant `scene.mailboxes` names (on the GPU the switch is
    /// the module's `MAILBOXES` or `LAST_ITEM_MAILBOX` specialisation).
    // Mirror of shaders/traverse.wgsl::mailbox_new — change both.
    pub fn new(scene: &PackedScene) -> Mailbox {
        Mailbox {
            items: [NO_ITEM; ITEM_MAILBOX_SIZE as usize],
            slot_mask: scene.mailboxes.item_slot_mask(),
        }
    }

    /// Whether `item` was tested already (as far as its slot remembers); if not, it is
    /// now remembered in its slot.
    // Mirror of shaders/traverse.wgsl::mailbox_seen — change both.
    pub fn seen(&mut self, item: u32) -> bool {
        if let Some(mask) = self.slot_mask {
            // (The constant mask too, so the index needs no bounds check.)
            let slot = &mut self.items[(item & mask & (ITEM_MAILBOX_SIZE - 1)) as usize];
            if *slot == item {
                return true;
            }
            *slot = item;
        }
        false
    }
}

/// Whether items of `kind` go through the mailbox: those whose answer is the nearest end
/// of intervals found without t_max (sphere, box, cylinder, cone; a mesh's nearest
/// triangle), so that a second test under the same or a smaller t_max gives a miss or
/// the same hit, which the caller already holds. A torus clips its root search to t_max
/// and a CSG object its interval lists, so their t may move in the last bits with it:
/// they are tested in every cell.
// Mirror of shaders/traverse.wgsl::mailboxed — change both.
pub fn mailboxed(kind: u32) -> bool {
    kind != KIND_TORUS && kind != KIND_CSG
}

/// Tests one item: its hit (t = T_MISS on a miss). An item in `mailbox` is a miss (its
/// hit, if any, is already the best).
// Mirror of shaders/traverse.wgsl::intersect_item — change both.
fn intersect_item(
    scene: &PackedScene,
    item: u32,
    ray: &Ray,
    t_max: f32,
    mailbox: &mut Mailbox,
    counters: &mut impl TraversalCounters,
) -> Hit {
    let inst = &scene.instances[item as usize];
    if mailboxed(inst.kind) && mailbox.seen(item) {
        return Hit::MISS;
    }
    if inst.kind == KIND_MESH {
        return intersect_mesh(scene, inst, item, ray, t_max, counters);
    }
    intersect_primitive_item(scene, inst, item, ray, t_max, counters)
}

/// Tests one item that is not a mesh instance (an analytic primitive or a CSG object):
/// its hit (t = T_MISS on a miss). Its own function so that a shadow ray's test of such an
/// item does not pass through the mesh walk (on llvmpipe every branch's code runs, taken or
/// not: shaders/traverse.wgsl).
// Mirror of shaders/traverse.wgsl::intersect_primitive_item — change both.
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
            ..Hit::MISS
        };
    }
    let t = intersect_instance(inst, ray.origin, ray.dir, t_max);
    Hit {
        t,
        item,
        ..Hit::MISS
    }
}

/// Tests the items `items` and keeps the nearest hit below `best.t`.
// Mirror of shaders/traverse.wgsl::test_items — change both.
fn test_items(
    scene: &PackedScene,
    items: impl Iterator<Item = u32>,
    ray: &Ray,
    best: &mut Hit,
    mailbox: &mut Mailbox,
    counters: &mut impl TraversalCounters,
) {
    for item in items {
        let h = intersect_item(scene, item, ray, best.t, mailbox, counters);
        if h.t < best.t {
            *best = h;
        }
    }
}

/// Nearest hit along `ray` in (0, t_max).
// Mirror of shaders/traverse.wgsl::closest_hit — change both.
pub fn closest_hit(
    scene: &PackedScene,
    ray: &Ray,
    t_max: f32,
    counters: &mut impl TraversalCounters,
) -> Hit {
    counters.traversal_started();
    let Some(entered) = enter_scene(&scene.globals, ray, t_max) else {
        return Hit::MISS;
    };
    let mut hit = closest_hit_inside(scene, &entered, counters);
    if hit.is_hit() {
        hit.t += entered.t_moved;
    }
    hit
}

/// Nearest hit along a ray that starts inside the scene bounds (see `enter_scene`).
// Mirror of shaders/traverse.wgsl::closest_hit_inside — change both.
fn closest_hit_inside(
    scene: &PackedScene,
    entered: &EnteredRay,
    counters: &mut impl TraversalCounters,
) -> Hit {
    let (ray, t_max) = (&entered.ray, entered.t_max);
    let mut best = Hit {
        t: t_max,
        ..Hit::MISS
    };
    let mut mailbox = Mailbox::new(scene);
    let g = &scene.globals;
    if g.grid_enabled == 0 {
        counters.cell_visited();
        test_items(
            scene,
            0..g.num_instances,
            ray,
            &mut best,
            &mut mailbox,
            counters,
        );
        return if best.is_hit() { best } else { Hit::MISS };
    }
    let grid = scene_grid(g);
    let Some(mut dda) = dda_setup(&grid, ray, entered.inv_dir, t_max) else {
        return Hit::MISS;
    };
    loop {
        counters.cell_visited();
        let cell = cell_index(&grid, IVec3::from(dda.cell));
        let range = scene.cell_start[cell]..scene.cell_start[cell + 1];
        test_items(
            scene,
            range.map(|i| scene.cell_items[i as usize]),
            ray,
            &mut best,
            &mut mailbox,
            counters,
        );
        // A hit inside this cell is final; so is leaving the grid or passing t_max.
        match dda_step(&grid, &mut dda) {
            Some(t_cell_exit) if best.t > t_cell_exit => {}
            _ => break,
        }
    }
    if best.is_hit() {
        best
    } else {
        Hit::MISS
    }
}

/// Whether item `item` is hit in (0, t_max); an item in `mailbox` is not tested again (it
/// was not hit, or the search would have stopped).
// Mirror of shaders/traverse.wgsl::item_occludes — change both.
fn item_occludes(
    scene: &PackedScene,
    item: u32,
    ray: &Ray,
    t_max: f32,
    mailbox: &mut Mailbox,
    counters: &mut impl TraversalCounters,
) -> bool {
    let inst = &scene.instances[item as usize];
    if mailboxed(inst.kind) && mailbox.seen(item) {
        return false;
    }
    if inst.kind == KIND_MESH {
        return mesh_occludes(scene, inst, ray, t_max, counters);
    }
    intersect_primitive_item(scene, inst, item, ray, t_max, counters).t < t_max
}

/// Whether any of `items` is hit in (0, t_max).
// Mirror of shaders/traverse.wgsl::any_item_hit — change both.
fn any_item_hit(
    scene: &PackedScene,
    items: impl Iterator<Item = u32>,
    ray: &Ray,
    t_max: f32,
    mailbox: &mut Mailbox,
    counters: &mut impl TraversalCounters,
) -> bool {
    for item in items {
        if item_occludes(scene, item, ray, t_max, mailbox, counters) {
            return true;
        }
    }
    false
}

/// Whether anything blocks `ray` in (0, t_max) (shadow rays).
// Mirror of shaders/traverse.wgsl::any_hit — change both.
pub fn any_hit(
    scene: &PackedScene,
    ray: &Ray,
    t_max: f32,
    counters: &mut impl TraversalCounters,
) -> bool {
    counters.traversal_started();
    match enter_scene(&scene.globals, ray, t_max) {
        Some(entered) => any_hit_inside(scene, &entered, counters),
        None => false,
    }
}

/// Whether anything blocks a ray that starts inside the scene bounds.
// Mirror of shaders/traverse.wgsl::any_hit_inside — change both.
fn any_hit_inside(
    scene: &PackedScene,
    entered: &EnteredRay,
    counters: &mut impl TraversalCounters,
) -> bool {
    let (ray, t_max) = (&entered.ray, entered.t_max);
    let mut mailbox = Mailbox::new(scene);
    let g = &scene.globals;
    if g.grid_enabled == 0 {
        counters.cell_visited();
        let items = 0..g.num_instances;
        return any_item_hit(scene, items, ray, t_max, &mut mailbox, counters);
    }
    let grid = scene_grid(g);
    let Some(mut dda) = dda_setup(&grid, ray, entered.inv_dir, t_max) else {
        return false;
    };
    loop {
        counters.cell_visited();
        let cell = cell_index(&grid, IVec3::from(dda.cell));
        let range = scene.cell_start[cell]..scene.cell_start[cell + 1];
        let items = range.map(|i| scene.cell_items[i as usize]);
        if any_item_hit(scene, items, ray, t_max, &mut mailbox, counters) {
            return true;
        }
        if dda_step(&grid, &mut dda).is_none() {
            return false;
        }
    }
}
