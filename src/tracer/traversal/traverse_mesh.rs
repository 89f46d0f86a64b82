//! The second level: a mesh instance traversed through its mesh's own grid. The ray goes
//! to the mesh's space through the instance's world→object rows (direction not
//! normalised, so t carries over), enters the mesh's grid bounds and walks its cells
//! (runs of empty cells in a loop of their own), testing the triangles listed there with
//! the watertight test: on the CPU four at a time (`triangle4`: the same answers, bit for
//! bit, as the WGSL twins' one by one).

use super::dda::{dda_setup, dda_step, enter_mesh, mesh_grid, Dda, EnteredRay};
use super::hit::{hit_miss, Hit, Slots, TraversalCounters};
use crate::constants::TRIANGLE_MAILBOX_SIZE;
use crate::pack::{
    cell_item_at, cell_start_at, load_mesh, PackedInstance, PackedMesh, PackedScene, PackedTriangle,
};
use crate::tracer::base::ray::Ray;
use crate::tracer::geometry::intersect::to_object_space;
use crate::tracer::geometry::triangle4::{NearestTriangle, TriangleBatch, TriangleRays};

/// The mesh of a `KIND_MESH` instance.
// Mirror of src/tracer/traversal/traverse_mesh.wgsl::instance_mesh — change both.
pub fn instance_mesh<'a>(scene: &'a PackedScene, inst: &PackedInstance) -> &'a PackedMesh {
    load_mesh(scene, inst.params[0] as u32)
}

/// The triangles a ray has tested in one mesh, as a direct-mapped cache of
/// `TRIANGLE_MAILBOX_SIZE` slots (triangle number modulo the size: one compare, where a
/// ring of the last n tested needs n). A triangle spans 3–4 cells of its mesh's grid on
/// average, so a ray often meets it again in the next cell; testing it again would give
/// the same answer (a miss stays a miss under the same or a smaller t_max, and a hit is
/// not nearer than itself), so skipping it changes no result. Triangles are stored in
/// Morton order, so the triangles near a ray have nearby numbers and seldom share a slot.
/// Only `Mailboxes::Full` keeps one (`PackedScene::mailboxes`; the GPU's `MAILBOXES`
/// variant); otherwise it remembers nothing. (Free functions `triangle_mailbox_new`,
/// `triangle_mailbox_seen`, as the WGSL twins are named.)
// Mirror of src/tracer/traversal/traverse_mesh.wgsl::TriangleMailbox — change both.
pub struct TriangleMailbox(Slots<{ TRIANGLE_MAILBOX_SIZE as usize }>);

/// An empty mailbox, kept as `scene.mailboxes` says (on the GPU the switch is the module's
/// `MAILBOXES` specialisation).
// Mirror of src/tracer/traversal/traverse_mesh.wgsl::triangle_mailbox_new — change both.
pub fn triangle_mailbox_new(scene: &PackedScene) -> TriangleMailbox {
    TriangleMailbox(Slots::new(scene.mailboxes.triangle_slot_mask()))
}

/// Whether `triangle` was tested already (as far as its slot remembers); if not, it is
/// now remembered in its slot.
// Mirror of src/tracer/traversal/traverse_mesh.wgsl::triangle_mailbox_seen — change both.
#[inline(always)]
pub fn triangle_mailbox_seen(mailbox: &mut TriangleMailbox, triangle: u32) -> bool {
    mailbox.0.seen(triangle)
}

/// A walk through a mesh instance's own grid: the ray in the mesh's space, entered into
/// the grid's bounds, its DDA, the ray as the triangle tests take it, the mesh's
/// triangles and the triangle mailbox.
struct MeshWalk<'a> {
    mesh: &'a PackedMesh,
    entered: EnteredRay,
    dda: Dda,
    tri_rays: TriangleRays,
    triangles: &'a [PackedTriangle],
    mailbox: TriangleMailbox,
}

/// The walk of mesh instance `inst` for `ray` in (0, t_max), standing in its first cell;
/// None when the ray misses the mesh's grid. The set-up `intersect_mesh` and
/// `mesh_occludes` share. (The WGSL twins each keep these lines: the same set-up as a WGSL
/// function returning the walk as a struct made naga 30's SPIR-V writer panic, "Expression
/// is not cached", where a member of the walk went to a function by pointer; with the
/// walk's DDA and mailbox copied to variables of their own it compiled, but then 40 rows
/// of `kernel_budget_combinations` broke RADV's NAVI21 budgets where 33 are known, the
/// new ones wave32 traversal kernels at 112 VGPRs, budget 96.)
#[inline(always)]
fn mesh_walk_start<'a>(
    scene: &'a PackedScene,
    inst: &PackedInstance,
    ray: &Ray,
    t_max: f32,
) -> Option<MeshWalk<'a>> {
    let mesh = instance_mesh(scene, inst);
    let (origin, dir) = to_object_space(inst, ray.origin, ray.dir);
    let entered = enter_mesh(mesh, &Ray { origin, dir }, t_max)?;
    let grid = mesh_grid(mesh);
    let dda = dda_setup(&grid, &entered.ray, entered.inv_dir, entered.t_max)?;
    Some(MeshWalk {
        mesh,
        dda,
        tri_rays: TriangleRays::new(entered.ray.origin, entered.ray.dir),
        triangles: mesh_triangles(scene, mesh),
        mailbox: triangle_mailbox_new(scene),
        entered,
    })
}

/// Nearest hit in (0, t_max) with mesh instance `item` (`inst`): t, the barycentrics and
/// the triangle as `part`; `hit_miss()` (t = T_MISS) when nothing is hit.
// Mirror of src/tracer/traversal/traverse_mesh.wgsl::intersect_mesh — change both.
pub fn intersect_mesh(
    scene: &PackedScene,
    inst: &PackedInstance,
    item: u32,
    ray: &Ray,
    t_max: f32,
    counters: &mut impl TraversalCounters,
) -> Hit {
    let Some(walk) = mesh_walk_start(scene, inst, ray, t_max) else {
        return hit_miss();
    };
    let (mesh, t_moved) = (walk.mesh, walk.entered.t_moved);
    let mut best = NearestTriangle::none(walk.entered.t_max);
    walk_mesh_cells::<false>(scene, walk, &mut best, counters);
    if !best.is_hit() {
        return hit_miss();
    }
    Hit {
        t: best.t + t_moved,
        item,
        b1: best.b1,
        b2: best.b2,
        part: mesh.first_triangle + best.local,
    }
}

/// Tests `batch` (emptying it): with `ANY_HIT`, whether one of its triangles is hit in
/// (0, best.t), which stops the walk; else keeps its nearest hit below `best.t` in `best`
/// and says false (a nearer hit may wait in the cell's next batch).
#[inline(always)]
fn test_batch<const ANY_HIT: bool>(
    batch: &mut TriangleBatch,
    tri_rays: &TriangleRays,
    triangles: &[PackedTriangle],
    best: &mut NearestTriangle,
) -> bool {
    if ANY_HIT {
        return batch.any_hit(tri_rays, triangles, best.t);
    }
    batch.keep_nearest(tri_rays, triangles, best);
    false
}

/// Walks `walk`'s cells, testing each cell's untested triangles in batches of four lanes,
/// in list order, until a batch stops it (true: `ANY_HIT`, a shadow ray's walk, and a
/// triangle is hit in (0, best.t)) or the walk ends (false): it leaves the grid, or
/// leaves a cell past `best.t` (a hit inside a cell is final). Written once for the
/// nearest-hit and the any-hit walk: `ANY_HIT` is a constant, so each compiles to its own
/// loop, as when the two were written out (scrabble.lua on the CPU, five alternated pairs:
/// 1.010 of their CPU time, 0.999–1.016; one walk taking the batch test as a closure had
/// stayed out of line, at 0.913 of their speed). An any-hit walk's `best.t` stays its
/// t_max, and any step the walk takes ends before the DDA's t_exit ≤ t_max, so there
/// t_max stops nothing.
// (The walk's parts are taken apart into locals: the loop keeps its `Dda` in registers
// only so.)
#[inline(always)]
fn walk_mesh_cells<const ANY_HIT: bool>(
    scene: &PackedScene,
    walk: MeshWalk,
    best: &mut NearestTriangle,
    counters: &mut impl TraversalCounters,
) -> bool {
    let MeshWalk {
        mut dda,
        tri_rays,
        triangles,
        mut mailbox,
        ..
    } = walk;
    while skip_empty_cells(scene, &mut dda, best.t, counters) {
        let cell = dda.cell;
        counters.cell_visited();
        let next = step_and_prefetch(scene, &mut dda);
        let mut batch = TriangleBatch::EMPTY;
        for i in cell_start_at(scene, cell)..cell_start_at(scene, cell + 1) {
            let local = cell_item_at(scene, i);
            if triangle_mailbox_seen(&mut mailbox, local) {
                continue;
            }
            counters.item_tested();
            if batch.push(local) && test_batch::<ANY_HIT>(&mut batch, &tri_rays, triangles, best) {
                return true;
            }
        }
        if test_batch::<ANY_HIT>(&mut batch, &tri_rays, triangles, best) {
            return true;
        }
        // A hit inside this cell is final; so is leaving the grid or passing t_max.
        match next {
            Some(t_cell_exit) if best.t > t_cell_exit => {}
            _ => return false,
        }
    }
    false
}

/// Steps `dda` on past empty cells, from the cell it stands in, until one lists something
/// (true) or the walk ends (false): it leaves the grid, passes t_exit, or leaves a cell
/// past `t_stop` (a closest hit below `t_stop` is final there). The same cells and the same
/// stop as testing each empty cell's nothing in the walk's loop, but in a loop small enough
/// for the `Dda` to stay in registers (the full loop spills it to the stack).
// Mirror of src/tracer/traversal/traverse_mesh.wgsl::skip_empty_cells — change both.
#[inline(always)]
fn skip_empty_cells(
    scene: &PackedScene,
    dda: &mut Dda,
    t_stop: f32,
    counters: &mut impl TraversalCounters,
) -> bool {
    loop {
        let cell = dda.cell;
        if cell_start_at(scene, cell) != cell_start_at(scene, cell + 1) {
            return true;
        }
        counters.cell_visited();
        match dda_step(dda) {
            Some(t_cell_exit) if t_stop > t_cell_exit => {}
            _ => return false,
        }
    }
}

/// Steps the DDA to the next cell (`dda_step`) before the current cell's triangles are
/// tested, and asks the cache for the next cell's range meanwhile: in a large mesh that
/// load misses the cache, and the tests of this cell hide its latency.
#[inline(always)]
fn step_and_prefetch(scene: &PackedScene, dda: &mut Dda) -> Option<f32> {
    let next = dda_step(dda);
    if next.is_some() {
        // (No bounds check: the cell is inside the grid, and a prefetch of any address is
        // harmless.)
        prefetch(scene.cell_start.as_ptr().wrapping_add(dda.cell as usize));
    }
    next
}

/// A hint to fetch the cache line at `address` (no effect on results; none off x86-64).
#[inline(always)]
fn prefetch<T>(address: *const T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch never faults, whatever the address, and reads nothing into the
    // program.
    unsafe {
        std::arch::x86_64::_mm_prefetch::<{ std::arch::x86_64::_MM_HINT_T0 }>(address.cast::<i8>());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = address;
}

/// The mesh's triangles, indexed by the mesh-local numbers its cells list.
fn mesh_triangles<'a>(scene: &'a PackedScene, mesh: &PackedMesh) -> &'a [PackedTriangle] {
    let first = mesh.first_triangle as usize;
    &scene.triangles[first..first + mesh.num_triangles as usize]
}

/// Whether any triangle of mesh instance `inst` is hit in (0, t_max) (shadow rays: stops
/// at the first one found).
// Mirror of src/tracer/traversal/traverse_mesh.wgsl::mesh_occludes — change both.
pub fn mesh_occludes(
    scene: &PackedScene,
    inst: &PackedInstance,
    ray: &Ray,
    t_max: f32,
    counters: &mut impl TraversalCounters,
) -> bool {
    let Some(walk) = mesh_walk_start(scene, inst, ray, t_max) else {
        return false;
    };
    let mut best = NearestTriangle::none(walk.entered.t_max);
    walk_mesh_cells::<true>(scene, walk, &mut best, counters)
}
