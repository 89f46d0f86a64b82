// dda.wgsl — one uniform grid walked by 3D-DDA (Amanatides & Woo 1987), for either level:
// the scene grid (placement in globals) or a mesh's own grid (in its PackedMesh, mesh space).
// Also the move of a ray's origin to where it enters a box, which both levels use.

// #if GRID|MESH
// A grid's placement: bounds, cell size, cells per axis and its first cell in cell_start.
// Mirror of src/tracer/traversal/dda.rs::GridView — change both.
struct GridView {
    min: vec3<f32>,
    max: vec3<f32>,
    cell_size: vec3<f32>,
    dims: vec3<i32>,
    first_cell: u32,
}

// The scene grid (its cells come first in cell_start).
// Mirror of src/tracer/traversal/dda.rs::scene_grid — change both.
fn scene_grid() -> GridView {
    let g = globals;
    return GridView(g.grid_min, g.grid_max, g.grid_cell_size, vec3<i32>(g.grid_dims), 0u);
}

// #if MESH
// A mesh's own grid, in the mesh's space.
// Mirror of src/tracer/traversal/dda.rs::mesh_grid — change both.
fn mesh_grid(mesh: PackedMesh) -> GridView {
    return GridView(
        mesh.grid_min,
        mesh.grid_max,
        mesh.grid_cell_size,
        vec3<i32>(mesh.grid_dims),
        mesh.first_cell,
    );
}
// #endif

// A grid's state for one ray: the current cell, as its index in cell_start, and per axis
// what a step adds to that index, the steps left before the grid ends, the next
// boundary's t and t per cell; `valid` is false when the ray misses the grid bounds
// (Rust's None). (The index moves by a stride per step rather than being recomputed from
// coordinates, as on the CPU.) The steps left are one word, DDA_STEPS_BITS per axis from x
// in the lowest bits: a walk's state stays live across every test it makes, and the two
// registers spared per walk (scene and mesh level) took RADV's NAVI21 closest-hit kernels
// of textures.lua and scrabble.lua from 112 VGPRs to 96
// (docs/journal/2026-12-02-traversal-registers.md).
// Mirror of src/tracer/traversal/dda.rs::Dda — change both.
struct Dda {
    cell: u32,
    cell_step: vec3<i32>,
    steps_left: u32,
    t_next: vec3<f32>,
    t_delta: vec3<f32>,
    t_exit: f32,
    valid: bool,
}

// Clips the ray to the grid bounds and finds its first cell, or valid = false if it
// misses them. inv is safe_rcp3(ray.dir), already computed by enter_bounds for the same
// direction.
// Mirror of src/tracer/traversal/dda.rs::dda_setup — change both.
fn dda_setup(grid: GridView, ray: Ray, inv: vec3<f32>, t_max: f32) -> Dda {
    let t0 = (grid.min - ray.origin) * inv;
    let t1 = (grid.max - ray.origin) * inv;
    let t_enter = max(max_element(min(t0, t1)), 0.0);
    let t_exit = min(min_element(max(t0, t1)), t_max);
    var dda: Dda;
    dda.valid = false;
    if t_enter > t_exit {
        return dda;
    }
    let p = ray.origin + ray.dir * t_enter;
    // Truncation, not floor: the two differ only below 0, which the clamp takes to cell 0
    // either way (as on the CPU, where floor is a library call).
    let cell = clamp(vec3<i32>((p - grid.min) / grid.cell_size), vec3<i32>(0), grid.dims - 1);
    let strides = vec3<i32>(1, grid.dims.x, grid.dims.x * grid.dims.y);
    var cell_step = vec3<i32>(0);
    var steps_left = 0u;
    var t_next = vec3<f32>(0.0);
    var t_delta = vec3<f32>(0.0);
    for (var axis = 0u; axis < 3u; axis++) {
        if ray.dir[axis] == 0.0 {
            // Parallel to this axis's planes: never step along it.
            cell_step[axis] = 0;
            t_next[axis] = T_MISS;
            t_delta[axis] = T_MISS;
        } else {
            let forward = ray.dir[axis] > 0.0;
            cell_step[axis] = select(-strides[axis], strides[axis], forward);
            let axis_steps = u32(select(cell[axis], grid.dims[axis] - 1 - cell[axis], forward));
            steps_left |= axis_steps << (DDA_STEPS_BITS * axis);
            let boundary_cell = cell[axis] + select(0, 1, forward);
            let boundary = grid.min[axis] + f32(boundary_cell) * grid.cell_size[axis];
            t_next[axis] = (boundary - ray.origin[axis]) * inv[axis];
            t_delta[axis] = grid.cell_size[axis] * abs(inv[axis]);
        }
    }
    return Dda(cell_index(grid, cell), cell_step, steps_left, t_next, t_delta, t_exit, true);
}

// Index of the DDA's current cell in cell_start (x fastest).
// Mirror of src/tracer/traversal/dda.rs::cell_index — change both.
fn cell_index(grid: GridView, cell: vec3<i32>) -> u32 {
    let dims = grid.dims;
    return grid.first_cell + u32(cell.x + dims.x * (cell.y + dims.y * cell.z));
}

// Index of the smallest component.
// Mirror of src/tracer/traversal/dda.rs::min_axis — change both.
fn min_axis(v: vec3<f32>) -> u32 {
    if v.x <= v.y && v.x <= v.z {
        return 0u;
    } else if v.y <= v.z {
        return 1u;
    }
    return 2u;
}

// What dda_step found: the t where the cell it left ends, or valid = false when the ray
// leaves the grid or passes t_exit there (Rust's None).
// Mirror of the Option<f32> of src/tracer/traversal/dda.rs::dda_step — change both.
struct DdaStep {
    t_cell_exit: f32,
    valid: bool,
}

// Steps the DDA to the next cell.
// Mirror of src/tracer/traversal/dda.rs::dda_step — change both.
fn dda_step(dda: ptr<function, Dda>) -> DdaStep {
    let axis = min_axis((*dda).t_next);
    let t_cell_exit = (*dda).t_next[axis];
    let shift = DDA_STEPS_BITS * axis;
    if t_cell_exit >= (*dda).t_exit || (((*dda).steps_left >> shift) & DDA_STEPS_MASK) == 0u {
        return DdaStep(t_cell_exit, false);
    }
    (*dda).steps_left -= 1u << shift;
    // (u32 arithmetic wraps, as the CPU's wrapping_add_signed: a negative stride subtracts.)
    (*dda).cell += bitcast<u32>((*dda).cell_step[axis]);
    (*dda).t_next[axis] += (*dda).t_delta[axis];
    return DdaStep(t_cell_exit, true);
}

// #endif

// A ray moved to where it enters a box (valid = false: it misses it).
// Mirror of src/tracer/traversal/dda.rs::EnteredRay — change both.
struct EnteredRay {
    ray: Ray,
    t_moved: f32,
    t_max: f32,
    // safe_rcp3(ray.dir), for dda_setup (the direction does not move).
    inv_dir: vec3<f32>,
    valid: bool,
}

// A ray that starts outside the box [lo, hi], moved to margin (in t) before where it
// enters it, so that the grid walk and the item tests all work from an origin near the
// geometry (a far origin's rounding is taken once, here).
// Mirror of src/tracer/traversal/dda.rs::enter_bounds — change both.
fn enter_bounds(lo: vec3<f32>, hi: vec3<f32>, ray: Ray, t_max: f32, margin: f32) -> EnteredRay {
    let inv = safe_rcp3(ray.dir);
    let t0 = (lo - ray.origin) * inv;
    let t1 = (hi - ray.origin) * inv;
    let t_enter = max(max_element(min(t0, t1)), 0.0);
    let t_exit = min(min_element(max(t0, t1)), t_max);
    if t_enter > t_exit {
        return EnteredRay(ray, 0.0, t_max, inv, false);
    }
    let t_move = t_enter - margin;
    if t_move <= 0.0 {
        return EnteredRay(ray, 0.0, t_max, inv, true);
    }
    return EnteredRay(Ray(ray.origin + ray.dir * t_move, ray.dir), t_move, t_max - t_move, inv, true);
}

// The ray moved to where it enters the scene bounds (world rays have unit directions, so
// the margin is a distance: more than the rounding of the moved origin).
// Mirror of src/tracer/traversal/dda.rs::enter_scene — change both.
fn enter_scene(ray: Ray, t_max: f32) -> EnteredRay {
    let margin = max_element(abs(ray.origin)) * ENTER_MARGIN_RELATIVE;
    return enter_bounds(globals.grid_min, globals.grid_max, ray, t_max, margin);
}

// #if MESH
// The mesh-space ray moved to where it enters the mesh's grid bounds (its direction is
// not a unit vector: the margin is divided by its largest component).
// Mirror of src/tracer/traversal/dda.rs::enter_mesh — change both.
fn enter_mesh(mesh: PackedMesh, ray: Ray, t_max: f32) -> EnteredRay {
    let margin = max_element(abs(ray.origin)) * ENTER_MARGIN_RELATIVE
        / max(max_element(abs(ray.dir)), F32_MIN_POSITIVE);
    return enter_bounds(mesh.grid_min, mesh.grid_max, ray, t_max, margin);
}
// #endif
