// traverse.wgsl — scene traversal: closest hit and any hit, through the uniform grid by
// 3D-DDA (Amanatides & Woo 1987) when the scene has one (GRID), else by brute force. A
// closest hit found in a cell is accepted only if it lies inside that cell (an item may
// span several cells, and a nearer item may wait in the next one). Unlike the CPU tracer,
// the choice between grid and brute force is made when the shader is specialised: the
// GRID feature is set exactly when `grid_enabled` is 1.

// The nearest hit: distance, item (instances first, then triangles), for triangles the
// barycentric weights of p1 and p2, and for a CSG item the surface hit (part: leaf
// instance index, with CSG_FLIP when its normal is negated; NO_ITEM otherwise).
// Mirror of src/cpu/traverse.rs::Hit — change both.
struct Hit {
    t: f32,
    item: u32,
    b1: f32,
    b2: f32,
    part: u32,
}

// Mirror of src/cpu/traverse.rs::Hit::MISS — change both.
fn hit_miss() -> Hit {
    return Hit(T_MISS, NO_ITEM, 0.0, 0.0, NO_ITEM);
}

// Mirror of src/cpu/traverse.rs::Hit::is_hit — change both.
fn is_hit(hit: Hit) -> bool {
    return hit.item != NO_ITEM;
}

// Tests one item: its hit (t = T_MISS on a miss).
// Mirror of src/cpu/traverse.rs::intersect_item — change both.
fn intersect_item(item: u32, ray: Ray, tri_ray: TriangleRay, t_max: f32) -> Hit {
    let num_instances = globals.num_instances;
// #if SPHERE|CUBE|CYLINDER|CONE|TORUS
    if item < num_instances {
        let inst = instances[item];
// #if CSG
        if inst.kind == KIND_CSG {
            let h = intersect_csg(inst, ray.origin, ray.dir, t_max);
            return Hit(h.t, item, 0.0, 0.0, h.part);
        }
// #endif
        let t = intersect_instance(inst, ray.origin, ray.dir, t_max);
        return Hit(t, item, 0.0, 0.0, NO_ITEM);
    }
// #endif
// #if MESH
    let tri = triangles[item - num_instances];
    let h = intersect_triangle(tri_ray, tri.p0, tri.p1, tri.p2, t_max);
    return Hit(h.x, item, h.y, h.z, NO_ITEM);
// #else
    return hit_miss();
// #endif
}

// The i-th of the items a traversal step tests: the grid cell's item list, or every item
// in turn (brute force).
// Mirror of the `items` iterators in src/cpu/traverse.rs::closest_hit — change both.
fn item_at(i: u32) -> u32 {
// #if GRID
    return cell_items[i];
// #else
    return i;
// #endif
}

// Tests the items item_at(first..last) and keeps the nearest hit below best.t.
// Mirror of src/cpu/traverse.rs::test_items — change both.
fn test_items(first: u32, last: u32, ray: Ray, tri_ray: TriangleRay, best_in: Hit) -> Hit {
    var best = best_in;
    for (var i = first; i < last; i++) {
        let h = intersect_item(item_at(i), ray, tri_ray, best.t);
        if h.t < best.t {
            best = h;
        }
    }
    return best;
}

// Whether any of the items item_at(first..last) is hit in (0, t_max).
// Mirror of src/cpu/traverse.rs::any_item_hit — change both.
fn any_item_hit(first: u32, last: u32, ray: Ray, tri_ray: TriangleRay, t_max: f32) -> bool {
    for (var i = first; i < last; i++) {
        if intersect_item(item_at(i), ray, tri_ray, t_max).t < t_max {
            return true;
        }
    }
    return false;
}

// Per-ray triangle set-up (unused, and left zero, when the scene has no triangles).
// Mirror of the triangle_ray_setup call in src/cpu/traverse.rs::closest_hit — change both.
fn traversal_triangle_ray(ray: Ray) -> TriangleRay {
// #if MESH
    return triangle_ray_setup(ray.origin, ray.dir);
// #else
    return TriangleRay();
// #endif
}

// #if GRID
// The grid's state for one ray: current cell, per-axis step, next boundary t and t per
// cell; `valid` is false when the ray misses the grid bounds (Rust's None).
// Mirror of src/cpu/traverse.rs::Dda — change both.
struct Dda {
    cell: vec3<i32>,
    step: vec3<i32>,
    t_next: vec3<f32>,
    t_delta: vec3<f32>,
    t_exit: f32,
    valid: bool,
}

// Cells along each axis, signed.
// Mirror of src/cpu/traverse.rs::grid_dims_i32 — change both.
fn grid_dims_i32() -> vec3<i32> {
    return vec3<i32>(globals.grid_dims);
}

// Clips the ray to the grid bounds and finds its first cell, or valid = false if it
// misses them.
// Mirror of src/cpu/traverse.rs::dda_setup — change both.
fn dda_setup(ray: Ray, t_max: f32) -> Dda {
    let g = globals;
    let grid_min = g.grid_min;
    let cell_size = g.grid_cell_size;
    let dims = grid_dims_i32();
    let inv = safe_rcp3(ray.dir);
    let t0 = (grid_min - ray.origin) * inv;
    let t1 = (g.grid_max - ray.origin) * inv;
    let t_enter = max(max_element(min(t0, t1)), 0.0);
    let t_exit = min(min_element(max(t0, t1)), t_max);
    var dda: Dda;
    dda.valid = false;
    if t_enter > t_exit {
        return dda;
    }
    let p = ray.origin + ray.dir * t_enter;
    let cell = clamp(vec3<i32>(floor((p - grid_min) / cell_size)), vec3<i32>(0), dims - 1);
    var step = vec3<i32>(0);
    var t_next = vec3<f32>(0.0);
    var t_delta = vec3<f32>(0.0);
    for (var axis = 0u; axis < 3u; axis++) {
        if ray.dir[axis] == 0.0 {
            // Parallel to this axis's planes: never step along it.
            step[axis] = 0;
            t_next[axis] = T_MISS;
            t_delta[axis] = T_MISS;
        } else {
            step[axis] = select(-1, 1, ray.dir[axis] > 0.0);
            let boundary_cell = cell[axis] + select(0, 1, ray.dir[axis] > 0.0);
            let boundary = grid_min[axis] + f32(boundary_cell) * cell_size[axis];
            t_next[axis] = (boundary - ray.origin[axis]) * inv[axis];
            t_delta[axis] = cell_size[axis] * abs(inv[axis]);
        }
    }
    return Dda(cell, step, t_next, t_delta, t_exit, true);
}

// Index of the smallest component.
// Mirror of src/cpu/traverse.rs::min_axis — change both.
fn min_axis(v: vec3<f32>) -> u32 {
    if v.x <= v.y && v.x <= v.z {
        return 0u;
    } else if v.y <= v.z {
        return 1u;
    }
    return 2u;
}

// Index of a cell in the cell arrays (x fastest).
// Mirror of src/cpu/traverse.rs::cell_index — change both.
fn cell_index(cell: vec3<i32>, dims: vec3<i32>) -> u32 {
    return u32(cell.x + dims.x * (cell.y + dims.y * cell.z));
}
// #endif

// A ray moved to where it enters the scene bounds (valid = false: it misses them).
// Mirror of src/cpu/traverse.rs::EnteredRay — change both.
struct EnteredRay {
    ray: Ray,
    t_moved: f32,
    t_max: f32,
    valid: bool,
}

// A ray that starts outside the scene bounds, moved to where it enters them, so that the
// grid walk and the item tests all work from an origin near the geometry (a far origin's
// rounding is taken once, here).
// Mirror of src/cpu/traverse.rs::enter_scene — change both.
fn enter_scene(ray: Ray, t_max: f32) -> EnteredRay {
    let inv = safe_rcp3(ray.dir);
    let t0 = (globals.grid_min - ray.origin) * inv;
    let t1 = (globals.grid_max - ray.origin) * inv;
    let t_enter = max(max_element(min(t0, t1)), 0.0);
    let t_exit = min(min_element(max(t0, t1)), t_max);
    if t_enter > t_exit {
        return EnteredRay(ray, 0.0, t_max, false);
    }
    // Stop short of the bounds by more than the rounding of the moved origin.
    let t_move = t_enter - max_element(abs(ray.origin)) * ENTER_MARGIN_RELATIVE;
    if t_move <= 0.0 {
        return EnteredRay(ray, 0.0, t_max, true);
    }
    return EnteredRay(Ray(ray.origin + ray.dir * t_move, ray.dir), t_move, t_max - t_move, true);
}

// Nearest hit along ray in (0, t_max).
// Mirror of src/cpu/traverse.rs::closest_hit — change both.
fn closest_hit(ray: Ray, t_max: f32) -> Hit {
    let entered = enter_scene(ray, t_max);
    if !entered.valid {
        return hit_miss();
    }
    var hit = closest_hit_inside(entered.ray, entered.t_max);
    if is_hit(hit) {
        hit.t += entered.t_moved;
    }
    return hit;
}

// Nearest hit along a ray that starts inside the scene bounds (see enter_scene).
// Mirror of src/cpu/traverse.rs::closest_hit_inside — change both.
fn closest_hit_inside(ray: Ray, t_max: f32) -> Hit {
    let tri_ray = traversal_triangle_ray(ray);
    var best = hit_miss();
    best.t = t_max;
// #if GRID
    var dda = dda_setup(ray, t_max);
    if !dda.valid {
        return hit_miss();
    }
    let dims = grid_dims_i32();
    loop {
        let cell = cell_index(dda.cell, dims);
        best = test_items(cell_start[cell], cell_start[cell + 1u], ray, tri_ray, best);
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
// #else
    let n = globals.num_instances + globals.num_triangles;
    best = test_items(0u, n, ray, tri_ray, best);
// #endif
    if is_hit(best) {
        return best;
    }
    return hit_miss();
}

// Whether anything blocks ray in (0, t_max) (shadow rays).
// Mirror of src/cpu/traverse.rs::any_hit — change both.
fn any_hit(ray: Ray, t_max: f32) -> bool {
    let entered = enter_scene(ray, t_max);
    if !entered.valid {
        return false;
    }
    return any_hit_inside(entered.ray, entered.t_max);
}

// Whether anything blocks a ray that starts inside the scene bounds.
// Mirror of src/cpu/traverse.rs::any_hit_inside — change both.
fn any_hit_inside(ray: Ray, t_max: f32) -> bool {
    let tri_ray = traversal_triangle_ray(ray);
// #if GRID
    var dda = dda_setup(ray, t_max);
    if !dda.valid {
        return false;
    }
    let dims = grid_dims_i32();
    // (naga wants a return after the loop, so the loop breaks where Rust returns false.)
    loop {
        let cell = cell_index(dda.cell, dims);
        if any_item_hit(cell_start[cell], cell_start[cell + 1u], ray, tri_ray, t_max) {
            return true;
        }
        let axis = min_axis(dda.t_next);
        if dda.t_next[axis] >= dda.t_exit {
            break;
        }
        dda.cell[axis] += dda.step[axis];
        if dda.cell[axis] < 0 || dda.cell[axis] >= dims[axis] {
            break;
        }
        dda.t_next[axis] += dda.t_delta[axis];
    }
    return false;
// #else
    return any_item_hit(0u, globals.num_instances + globals.num_triangles, ray, tri_ray, t_max);
// #endif
}
