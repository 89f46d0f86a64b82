//! One uniform grid walked by 3D-DDA (Amanatides & Woo 1987), for either level: the scene
//! grid (placement in `PackedGlobals`) or a mesh's own grid (in its `PackedMesh`, mesh space).
//! Also the move of a ray's origin to where it enters a box, which both levels use.

use crate::constants::{
    DDA_STEPS_BITS, DDA_STEPS_MASK, ENTER_MARGIN_RELATIVE, F32_MIN_POSITIVE, T_MISS,
};
use crate::pack::{PackedGlobals, PackedMesh};
use crate::tracer::base::math::{safe_rcp3, Axis};
use crate::tracer::base::ray::Ray;
use glam::{IVec3, UVec3, Vec3};

/// A grid's placement: bounds, cell size, cells per axis and its first cell in
/// `PackedScene::cell_start`.
// Mirror of src/tracer/traversal/dda.wgsl::GridView — change both.
#[derive(Clone, Copy, Debug)]
pub struct GridView {
    pub min: Vec3,
    pub max: Vec3,
    pub cell_size: Vec3,
    pub dims: IVec3,
    pub first_cell: u32,
}

/// The scene grid (its cells come first in `cell_start`).
// Mirror of src/tracer/traversal/dda.wgsl::scene_grid — change both.
pub fn scene_grid(g: &PackedGlobals) -> GridView {
    grid_view(g.grid_min, g.grid_max, g.grid_cell_size, g.grid_dims, 0)
}

/// A mesh's own grid, in the mesh's space.
// Mirror of src/tracer/traversal/dda.wgsl::mesh_grid — change both.
pub fn mesh_grid(mesh: &PackedMesh) -> GridView {
    grid_view(
        mesh.grid_min,
        mesh.grid_max,
        mesh.grid_cell_size,
        mesh.grid_dims,
        mesh.first_cell,
    )
}

/// The `GridView` of a grid's placement as the packed records hold it (the WGSL twins
/// build it with the struct's constructor).
fn grid_view(
    min: [f32; 3],
    max: [f32; 3],
    cell_size: [f32; 3],
    dims: [u32; 3],
    first_cell: u32,
) -> GridView {
    GridView {
        min: Vec3::from(min),
        max: Vec3::from(max),
        cell_size: Vec3::from(cell_size),
        dims: UVec3::from(dims).as_ivec3(),
        first_cell,
    }
}

/// A grid's state for one ray: the current cell, as its index in `cell_start`, and per
/// axis what a step adds to that index, the steps left before the grid ends, the next
/// boundary's t and t per cell. (The index moves by a stride per step rather than being
/// recomputed from coordinates: two dependent multiplies fewer before each cell's load.
/// Arrays rather than glam vectors: `dda_setup` fills them by a runtime axis.) The steps
/// left are one word, [`DDA_STEPS_BITS`] per axis from x in the lowest bits: on the GPU a
/// walk's state is live across every test it makes, and the two registers this spares
/// per walk (scene and mesh level) took RADV's closest-hit kernels of textures.lua and
/// scrabble.lua from 112 VGPRs to 96 (docs/journal/2026-12-02-traversal-registers.md).
// Mirror of src/tracer/traversal/dda.wgsl::Dda — change both.
#[derive(Clone, Copy, Debug)]
pub struct Dda {
    pub cell: u32,
    pub cell_step: [i32; 3],
    pub steps_left: u32,
    pub t_next: [f32; 3],
    pub t_delta: [f32; 3],
    pub t_exit: f32,
}

/// Clips the ray to the grid bounds and finds its first cell, or None if it misses them.
/// `inv` is `safe_rcp3(ray.dir)`, already computed by `enter_bounds` for the same
/// direction (the divisions are a good part of a set-up).
// Mirror of src/tracer/traversal/dda.wgsl::dda_setup — change both.
#[inline(always)]
pub fn dda_setup(grid: &GridView, ray: &Ray, inv: Vec3, t_max: f32) -> Option<Dda> {
    let t0 = (grid.min - ray.origin) * inv;
    let t1 = (grid.max - ray.origin) * inv;
    let t_enter = t0.min(t1).max_element().max(0.0);
    let t_exit = t0.max(t1).min_element().min(t_max);
    if t_enter > t_exit {
        return None;
    }
    let p = ray.origin + ray.dir * t_enter;
    // Truncation, not floor: the two differ only below 0, which the clamp takes to cell 0
    // either way (and floor is a library call on x86-64 without SSE4.1).
    let cell = ((p - grid.min) / grid.cell_size)
        .as_ivec3()
        .clamp(IVec3::ZERO, grid.dims - 1)
        .to_array();
    let (dir, origin, inv) = (ray.dir.to_array(), ray.origin.to_array(), inv.to_array());
    let (min, cell_size) = (grid.min.to_array(), grid.cell_size.to_array());
    let dims = grid.dims.to_array();
    let strides = [1, dims[0], dims[0] * dims[1]];
    let mut dda = Dda {
        cell: cell_index(grid, IVec3::from(cell)) as u32,
        cell_step: [0; 3],
        steps_left: 0,
        t_next: [0.0; 3],
        t_delta: [0.0; 3],
        t_exit,
    };
    for axis in 0..3 {
        if dir[axis] == 0.0 {
            // Parallel to this axis's planes: never step along it.
            dda.cell_step[axis] = 0;
            dda.t_next[axis] = T_MISS;
            dda.t_delta[axis] = T_MISS;
        } else {
            let forward = dir[axis] > 0.0;
            dda.cell_step[axis] = if forward {
                strides[axis]
            } else {
                -strides[axis]
            };
            let steps_left = if forward {
                dims[axis] - 1 - cell[axis]
            } else {
                cell[axis]
            } as u32;
            dda.steps_left |= steps_left << (DDA_STEPS_BITS * axis as u32);
            let boundary_cell = cell[axis] + if forward { 1 } else { 0 };
            let boundary = min[axis] + boundary_cell as f32 * cell_size[axis];
            dda.t_next[axis] = (boundary - origin[axis]) * inv[axis];
            dda.t_delta[axis] = cell_size[axis] * inv[axis].abs();
        }
    }
    Some(dda)
}

/// Index of the DDA's current cell in `cell_start` (x fastest).
// Mirror of src/tracer/traversal/dda.wgsl::cell_index — change both.
pub fn cell_index(grid: &GridView, cell: IVec3) -> usize {
    let dims = grid.dims;
    grid.first_cell as usize + (cell.x + dims.x * (cell.y + dims.y * cell.z)) as usize
}

/// Index of the smallest component.
// Mirror of src/tracer/traversal/dda.wgsl::min_axis — change both.
pub fn min_axis(v: Vec3) -> Axis {
    if v.x <= v.y && v.x <= v.z {
        Axis::X
    } else if v.y <= v.z {
        Axis::Y
    } else {
        Axis::Z
    }
}

/// Steps the DDA to the next cell; the t where the current cell is left, or None when
/// the ray leaves the grid or passes t_exit there.
// Mirror of src/tracer/traversal/dda.wgsl::dda_step — change both.
pub fn dda_step(dda: &mut Dda) -> Option<f32> {
    // (One branch per axis with constant indices, so the walk's `Dda` can live in
    // registers instead of being indexed in memory: on cow.obj, one thread, camera rays
    // −18% and shadow rays −8% of their time.)
    match min_axis(Vec3::from(dda.t_next)) {
        Axis::X => step_axis::<0>(dda),
        Axis::Y => step_axis::<1>(dda),
        Axis::Z => step_axis::<2>(dda),
    }
}

/// `dda_step` along axis `AXIS`.
#[inline(always)]
fn step_axis<const AXIS: usize>(dda: &mut Dda) -> Option<f32> {
    let t_cell_exit = dda.t_next[AXIS];
    let shift = DDA_STEPS_BITS * AXIS as u32;
    if t_cell_exit >= dda.t_exit || (dda.steps_left >> shift) & DDA_STEPS_MASK == 0 {
        return None;
    }
    dda.steps_left -= 1 << shift;
    dda.cell = dda.cell.wrapping_add_signed(dda.cell_step[AXIS]);
    dda.t_next[AXIS] += dda.t_delta[AXIS];
    Some(t_cell_exit)
}

/// A ray moved to where it enters a box.
// Mirror of src/tracer/traversal/dda.wgsl::EnteredRay — change both.
#[derive(Clone, Copy, Debug)]
pub struct EnteredRay {
    pub ray: Ray,
    /// How far the origin moved along the ray (0 when it started inside the bounds).
    pub t_moved: f32,
    /// The caller's t_max, measured from the moved origin.
    pub t_max: f32,
    /// `safe_rcp3(ray.dir)`, for `dda_setup` (the direction does not move).
    pub inv_dir: Vec3,
}

/// A ray that starts outside the box [min, max], moved to `margin` (in t) before where
/// it enters it; None when it misses the box before t_max. Every later step (grid walk
/// and item tests alike) then works from an origin near the geometry: a far origin's
/// rounding (an ulp of 10⁷ is a whole unit) is taken once, here, instead of differently
/// by the cell walk and by each item test, which could otherwise disagree on which cell
/// a hit lies in and lose it.
// Mirror of src/tracer/traversal/dda.wgsl::enter_bounds — change both.
#[inline(always)]
pub fn enter_bounds(
    min: Vec3,
    max: Vec3,
    ray: &Ray,
    t_max: f32,
    margin: f32,
) -> Option<EnteredRay> {
    let inv = safe_rcp3(ray.dir);
    let t0 = (min - ray.origin) * inv;
    let t1 = (max - ray.origin) * inv;
    let t_enter = t0.min(t1).max_element().max(0.0);
    let t_exit = t0.max(t1).min_element().min(t_max);
    if t_enter > t_exit {
        return None;
    }
    let t_move = t_enter - margin;
    if t_move <= 0.0 {
        return Some(EnteredRay {
            ray: *ray,
            t_moved: 0.0,
            t_max,
            inv_dir: inv,
        });
    }
    Some(EnteredRay {
        ray: Ray {
            origin: ray.origin + ray.dir * t_move,
            dir: ray.dir,
        },
        t_moved: t_move,
        t_max: t_max - t_move,
        inv_dir: inv,
    })
}

/// The ray moved to where it enters the scene bounds (see [`enter_bounds`]; world rays
/// have unit directions, so the margin is a distance: more than the rounding of the
/// moved origin). Brute force does the same, so both give the same hits.
// Mirror of src/tracer/traversal/dda.wgsl::enter_scene — change both.
#[inline(always)]
pub fn enter_scene(g: &PackedGlobals, ray: &Ray, t_max: f32) -> Option<EnteredRay> {
    let margin = ray.origin.abs().max_element() * ENTER_MARGIN_RELATIVE;
    let (min, max) = (Vec3::from(g.grid_min), Vec3::from(g.grid_max));
    enter_bounds(min, max, ray, t_max, margin)
}

/// The mesh-space ray moved to where it enters the mesh's grid bounds. Its direction is
/// not a unit vector (the instance's transform scales it), so the margin is the scene's
/// relative margin of the origin divided by the direction's largest component: at least
/// the distance margin, in t.
// Mirror of src/tracer/traversal/dda.wgsl::enter_mesh — change both.
#[inline(always)]
pub fn enter_mesh(mesh: &PackedMesh, ray: &Ray, t_max: f32) -> Option<EnteredRay> {
    let margin = ray.origin.abs().max_element() * ENTER_MARGIN_RELATIVE
        / ray.dir.abs().max_element().max(F32_MIN_POSITIVE);
    let (min, max) = (Vec3::from(mesh.grid_min), Vec3::from(mesh.grid_max));
    enter_bounds(min, max, ray, t_max, margin)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cells a walk visits from its first: their (x, y, z) recovered from the index.
    fn walk(grid: &GridView, ray: &Ray) -> Vec<IVec3> {
        let mut dda = dda_setup(grid, ray, safe_rcp3(ray.dir), T_MISS).expect("enters the grid");
        let mut cells = Vec::new();
        loop {
            let i = dda.cell as i32 - grid.first_cell as i32;
            let (dx, dxy) = (grid.dims.x, grid.dims.x * grid.dims.y);
            cells.push(IVec3::new(i % dx, (i % dxy) / dx, i / dxy));
            if dda_step(&mut dda).is_none() {
                return cells;
            }
        }
    }

    /// Walks through grids of the most cells an axis allows (`MAX_AXIS_CELLS`), along each
    /// axis both ways and across all three, so that each packed steps-left counter runs from
    /// its largest value to zero beside the others: every walk visits one neighbouring cell
    /// after another, from the entry cell to the cell opposite. (With a counter a bit too
    /// narrow a 1024-cell walk stops half-way or steps another axis; with a wrong shift the
    /// walk along y or z stops at once or runs off the grid.)
    #[test]
    fn packed_step_counters_walk_every_cell_of_the_largest_grids() {
        use crate::accel::grid::MAX_AXIS_CELLS;
        let n = MAX_AXIS_CELLS as i32;
        for dims in [
            IVec3::new(n, 2, 3),
            IVec3::new(3, n, 2),
            IVec3::new(2, 3, n),
        ] {
            let grid = GridView {
                min: Vec3::ZERO,
                max: dims.as_vec3(),
                cell_size: Vec3::ONE,
                dims,
                first_cell: 7,
            };
            let centre = dims.as_vec3() * 0.5 + Vec3::new(0.25, 0.125, 0.0625);
            for axis in 0..3 {
                for sign in [1.0, -1.0] {
                    let mut dir = Vec3::ZERO;
                    dir[axis] = sign;
                    let origin = centre - dir * (dims[axis] as f32 + 1.0) * 0.5 - dir;
                    let cells = walk(&grid, &Ray { origin, dir });
                    assert_eq!(
                        cells.len() as i32,
                        dims[axis],
                        "{dims} axis {axis} sign {sign}"
                    );
                    let mut expected = centre.as_ivec3();
                    expected[axis] = if sign > 0.0 { 0 } else { dims[axis] - 1 };
                    for cell in cells {
                        assert_eq!(cell, expected, "{dims} axis {axis} sign {sign}");
                        expected[axis] += sign as i32;
                    }
                }
            }
            // Corner to corner: every step moves one axis by one, and the walk ends in the
            // far corner's cell having stepped each axis all the way.
            let dir = dims.as_vec3().normalize();
            let origin = Vec3::splat(1e-3) - dir;
            let cells = walk(&grid, &Ray { origin, dir });
            assert_eq!(
                cells.len() as i32,
                dims.x + dims.y + dims.z - 2,
                "{dims} diagonal"
            );
            for pair in cells.windows(2) {
                let d = (pair[1] - pair[0]).abs();
                assert_eq!(
                    d.x + d.y + d.z,
                    1,
                    "{dims} diagonal: {} → {}",
                    pair[0],
                    pair[1]
                );
            }
            assert_eq!(*cells.last().unwrap(), dims - 1, "{dims} diagonal");
        }
    }
}
