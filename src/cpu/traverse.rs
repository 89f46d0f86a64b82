//! Scene traversal: closest hit and any hit, through the uniform grid by 3D-DDA
//! (Amanatides & Woo 1987) or by brute force when the grid is off. A closest hit found in
//! a cell is accepted only if it lies inside that cell (an item may span several cells,
//! and a nearer item may wait in the next one).

use super::csg::intersect_csg;
use super::intersect::{
    intersect_instance, intersect_triangle, triangle_ray_setup, triangle_vertices, TriangleRay,
};
use super::math::safe_rcp3;
use super::ray::Ray;
use crate::constants::{ENTER_MARGIN_RELATIVE, KIND_CSG, NO_ITEM, T_MISS};
use crate::pack::{GpuGlobals, PackedScene};
use glam::{IVec3, Vec3};

/// The nearest hit: distance, item (instances first, then triangles), for triangles the
/// barycentric weights of p1 and p2, and for a CSG item the surface hit (`part`: leaf
/// instance index, with `CSG_FLIP` when its normal is negated; `NO_ITEM` otherwise).
// Mirror of shaders/traverse.wgsl::Hit — change both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f32,
    pub item: u32,
    pub b1: f32,
    pub b2: f32,
    pub part: u32,
}

impl Hit {
    // Mirror of shaders/traverse.wgsl::hit_miss — change both.
    pub const MISS: Hit = Hit {
        t: T_MISS,
        item: NO_ITEM,
        b1: 0.0,
        b2: 0.0,
        part: NO_ITEM,
    };

    // Mirror of shaders/traverse.wgsl::is_hit — change both.
    pub fn is_hit(&self) -> bool {
        self.item != NO_ITEM
    }
}

/// Traversal counters (CPU only, for `--stats`); the no-op impl costs nothing.
pub trait TraversalCounters {
    fn traversal_started(&mut self) {}
    fn cell_visited(&mut self) {}
    fn item_tested(&mut self) {}
}

/// Counters that count nothing.
pub struct NoCounters;
impl TraversalCounters for NoCounters {}

/// Counters that count.
#[derive(Clone, Copy, Debug, Default)]
pub struct Counters {
    pub cells_visited: u64,
    pub items_tested: u64,
}
impl TraversalCounters for Counters {
    fn cell_visited(&mut self) {
        self.cells_visited += 1;
    }
    fn item_tested(&mut self) {
        self.items_tested += 1;
    }
}

/// Tests one item: its hit (t = T_MISS on a miss).
// Mirror of shaders/traverse.wgsl::intersect_item — change both.
fn intersect_item(
    scene: &PackedScene,
    item: u32,
    ray: &Ray,
    tri_ray: &TriangleRay,
    t_max: f32,
) -> Hit {
    let num_instances = scene.globals.num_instances;
    if item < num_instances {
        let inst = &scene.instances[item as usize];
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
    } else {
        let [p0, p1, p2] = triangle_vertices(&scene.triangles[(item - num_instances) as usize]);
        let h = intersect_triangle(tri_ray, p0, p1, p2, t_max);
        Hit {
            t: h.x,
            item,
            b1: h.y,
            b2: h.z,
            part: NO_ITEM,
        }
    }
}

/// Tests the items `items` and keeps the nearest hit below `best.t`.
// Mirror of shaders/traverse.wgsl::test_items — change both.
fn test_items(
    scene: &PackedScene,
    items: impl Iterator<Item = u32>,
    ray: &Ray,
    tri_ray: &TriangleRay,
    best: &mut Hit,
    counters: &mut impl TraversalCounters,
) {
    for item in items {
        counters.item_tested();
        let h = intersect_item(scene, item, ray, tri_ray, best.t);
        if h.t < best.t {
            *best = h;
        }
    }
}

/// The grid's state for one ray: current cell, per-axis step, next boundary t and t per cell.
// Mirror of shaders/traverse.wgsl::Dda — change both.
struct Dda {
    cell: IVec3,
    step: IVec3,
    t_next: Vec3,
    t_delta: Vec3,
    t_exit: f32,
}

/// Clips the ray to the grid bounds and finds its first cell, or None if it misses them.
// Mirror of shaders/traverse.wgsl::dda_setup — change both.
fn dda_setup(scene: &PackedScene, ray: &Ray, t_max: f32) -> Option<Dda> {
    let g = &scene.globals;
    let grid_min = Vec3::from(g.grid_min);
    let cell_size = Vec3::from(g.grid_cell_size);
    let dims = grid_dims_i32(g);
    let inv = safe_rcp3(ray.dir);
    let t0 = (grid_min - ray.origin) * inv;
    let t1 = (Vec3::from(g.grid_max) - ray.origin) * inv;
    let t_enter = t0.min(t1).max_element().max(0.0);
    let t_exit = t0.max(t1).min_element().min(t_max);
    if t_enter > t_exit {
        return None;
    }
    let p = ray.origin + ray.dir * t_enter;
    let cell = ((p - grid_min) / cell_size)
        .floor()
        .as_ivec3()
        .clamp(IVec3::ZERO, dims - 1);
    let mut step = IVec3::ZERO;
    let mut t_next = Vec3::ZERO;
    let mut t_delta = Vec3::ZERO;
    for axis in 0..3 {
        if ray.dir[axis] == 0.0 {
            // Parallel to this axis's planes: never step along it.
            step[axis] = 0;
            t_next[axis] = T_MISS;
            t_delta[axis] = T_MISS;
        } else {
            step[axis] = if ray.dir[axis] > 0.0 { 1 } else { -1 };
            let boundary_cell = cell[axis] + if ray.dir[axis] > 0.0 { 1 } else { 0 };
            let boundary = grid_min[axis] + boundary_cell as f32 * cell_size[axis];
            t_next[axis] = (boundary - ray.origin[axis]) * inv[axis];
            t_delta[axis] = cell_size[axis] * inv[axis].abs();
        }
    }
    Some(Dda {
        cell,
        step,
        t_next,
        t_delta,
        t_exit,
    })
}

/// Cells along each axis, signed.
// Mirror of shaders/traverse.wgsl::grid_dims_i32 — change both.
fn grid_dims_i32(g: &GpuGlobals) -> IVec3 {
    IVec3::new(
        g.grid_dims[0] as i32,
        g.grid_dims[1] as i32,
        g.grid_dims[2] as i32,
    )
}

/// Index of a cell in the cell arrays (x fastest).
// Mirror of shaders/traverse.wgsl::cell_index — change both.
fn cell_index(cell: IVec3, dims: IVec3) -> usize {
    (cell.x + dims.x * (cell.y + dims.y * cell.z)) as usize
}

/// Index of the smallest component.
// Mirror of shaders/traverse.wgsl::min_axis — change both.
fn min_axis(v: Vec3) -> usize {
    if v.x <= v.y && v.x <= v.z {
        0
    } else if v.y <= v.z {
        1
    } else {
        2
    }
}

/// A ray moved to where it enters the scene bounds.
// Mirror of shaders/traverse.wgsl::EnteredRay — change both.
#[derive(Clone, Copy, Debug)]
pub struct EnteredRay {
    pub ray: Ray,
    /// How far the origin moved along the ray (0 when it started inside the bounds).
    pub t_moved: f32,
    /// The caller's t_max, measured from the moved origin.
    pub t_max: f32,
}

/// A ray that starts outside the scene bounds, moved to where it enters them; None when
/// it misses them before t_max. Every later step (grid walk and item tests alike) then
/// works from an origin near the geometry: a far origin's rounding (an ulp of 10⁷ is a
/// whole unit) is taken once, here, instead of differently by the cell walk and by each
/// item test, which could otherwise disagree on which cell a hit lies in and lose it.
/// Brute force does the same, so both give the same hits.
// Mirror of shaders/traverse.wgsl::enter_scene — change both.
pub fn enter_scene(g: &GpuGlobals, ray: &Ray, t_max: f32) -> Option<EnteredRay> {
    let inv = safe_rcp3(ray.dir);
    let t0 = (Vec3::from(g.grid_min) - ray.origin) * inv;
    let t1 = (Vec3::from(g.grid_max) - ray.origin) * inv;
    let t_enter = t0.min(t1).max_element().max(0.0);
    let t_exit = t0.max(t1).min_element().min(t_max);
    if t_enter > t_exit {
        return None;
    }
    // Stop short of the bounds by more than the rounding of the moved origin.
    let t_move = t_enter - ray.origin.abs().max_element() * ENTER_MARGIN_RELATIVE;
    if t_move <= 0.0 {
        return Some(EnteredRay {
            ray: *ray,
            t_moved: 0.0,
            t_max,
        });
    }
    Some(EnteredRay {
        ray: Ray {
            origin: ray.origin + ray.dir * t_move,
            dir: ray.dir,
        },
        t_moved: t_move,
        t_max: t_max - t_move,
    })
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
    let mut hit = closest_hit_inside(scene, &entered.ray, entered.t_max, counters);
    if hit.is_hit() {
        hit.t += entered.t_moved;
    }
    hit
}

/// Nearest hit along a ray that starts inside the scene bounds (see `enter_scene`).
// Mirror of shaders/traverse.wgsl::closest_hit_inside — change both.
fn closest_hit_inside(
    scene: &PackedScene,
    ray: &Ray,
    t_max: f32,
    counters: &mut impl TraversalCounters,
) -> Hit {
    let tri_ray = triangle_ray_setup(ray.origin, ray.dir);
    let mut best = Hit {
        t: t_max,
        ..Hit::MISS
    };
    let g = &scene.globals;
    if g.grid_enabled == 0 {
        counters.cell_visited();
        let n = g.num_instances + g.num_triangles;
        test_items(scene, 0..n, ray, &tri_ray, &mut best, counters);
        return if best.is_hit() { best } else { Hit::MISS };
    }
    let Some(mut dda) = dda_setup(scene, ray, t_max) else {
        return Hit::MISS;
    };
    let dims = grid_dims_i32(g);
    loop {
        counters.cell_visited();
        let cell = cell_index(dda.cell, dims);
        let range = scene.cell_start[cell]..scene.cell_start[cell + 1];
        test_items(
            scene,
            range.map(|i| scene.cell_items[i as usize]),
            ray,
            &tri_ray,
            &mut best,
            counters,
        );
        let axis = min_axis(dda.t_next);
        let t_cell_exit = dda.t_next[axis];
        // A hit inside this cell is final; so is leaving the grid or passing t_max.
        if best.t <= t_cell_exit || t_cell_exit >= dda.t_exit {
            break;
        }
        dda.cell[axis] += dda.step[axis];
        if dda.cell[axis] < 0 || dda.cell[axis] >= dims[axis] {
            break;
        }
        dda.t_next[axis] += dda.t_delta[axis];
    }
    if best.is_hit() {
        best
    } else {
        Hit::MISS
    }
}

/// Whether any of `items` is hit in (0, t_max).
// Mirror of shaders/traverse.wgsl::any_item_hit — change both.
fn any_item_hit(
    scene: &PackedScene,
    items: impl Iterator<Item = u32>,
    ray: &Ray,
    tri_ray: &TriangleRay,
    t_max: f32,
    counters: &mut impl TraversalCounters,
) -> bool {
    for item in items {
        counters.item_tested();
        if intersect_item(scene, item, ray, tri_ray, t_max).t < t_max {
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
        Some(entered) => any_hit_inside(scene, &entered.ray, entered.t_max, counters),
        None => false,
    }
}

/// Whether anything blocks a ray that starts inside the scene bounds.
// Mirror of shaders/traverse.wgsl::any_hit_inside — change both.
fn any_hit_inside(
    scene: &PackedScene,
    ray: &Ray,
    t_max: f32,
    counters: &mut impl TraversalCounters,
) -> bool {
    let tri_ray = triangle_ray_setup(ray.origin, ray.dir);
    let g = &scene.globals;
    if g.grid_enabled == 0 {
        counters.cell_visited();
        return any_item_hit(
            scene,
            0..g.num_instances + g.num_triangles,
            ray,
            &tri_ray,
            t_max,
            counters,
        );
    }
    let Some(mut dda) = dda_setup(scene, ray, t_max) else {
        return false;
    };
    let dims = grid_dims_i32(g);
    loop {
        counters.cell_visited();
        let cell = cell_index(dda.cell, dims);
        let range = scene.cell_start[cell]..scene.cell_start[cell + 1];
        if any_item_hit(
            scene,
            range.map(|i| scene.cell_items[i as usize]),
            ray,
            &tri_ray,
            t_max,
            counters,
        ) {
            return true;
        }
        let axis = min_axis(dda.t_next);
        if dda.t_next[axis] >= dda.t_exit {
            return false;
        }
        dda.cell[axis] += dda.step[axis];
        if dda.cell[axis] < 0 || dda.cell[axis] >= dims[axis] {
            return false;
        }
        dda.t_next[axis] += dda.t_delta[axis];
    }
}
