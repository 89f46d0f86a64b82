//! Uniform grid build: resolution after Cleary & Wyvill (cells ≈ λ·N, cubical cells over
//! the items' bounds), each item listed in every cell its (padded) bounds overlap; a
//! triangle item also skips the cells it does not overlap (`overlap`). Cells are stored CSR-style
//! (`cell_start`, `cell_items`), items in ascending order inside each cell so the build
//! is deterministic. Items are plain bounds (and, for triangles, corners) with ids
//! 0..n: what an item is, is the caller's business.

use super::aabb::{Aabb, BOUNDS_PAD};
use super::overlap::TriangleOverlap;
use glam::Vec3;
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// λ, the cells-per-item density of `grid = 'auto'`, chosen by `glint bench grid`
/// (see docs/journal/2026-11-22-uniform-grid-against-brute-force.md).
pub const DEFAULT_DENSITY: f32 = 8.0;
/// λ of each mesh's own grid under `grid = 'auto'`: 2 keeps the structure within 64
/// bytes per stored triangle (see docs/acceleration.md for the measurements).
pub const MESH_DEFAULT_DENSITY: f32 = 2.0;
/// Most cells along one axis.
pub const MAX_AXIS_CELLS: u32 = 1024;
// A DDA packs its three steps-left counters (at most MAX_AXIS_CELLS − 1 each) into one u32.
const _: () = assert!(MAX_AXIS_CELLS - 1 <= crate::constants::DDA_STEPS_MASK);
/// Most cells in all (bounds memory: 4 bytes per cell).
pub const MAX_CELLS: u64 = 1 << 24;

/// Counters of a grid build, for `--stats` and the benchmark.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GridBuildStats {
    pub items: usize,
    pub cells: usize,
    pub empty_cells: usize,
    /// Item references in all cells (an item spanning k cells counts k times).
    pub references: usize,
    pub max_items_in_cell: usize,
    pub build_time: Duration,
    /// Bytes of `cell_start` + `cell_items`.
    pub memory_bytes: usize,
}

impl GridBuildStats {
    pub fn empty_share(&self) -> f64 {
        self.empty_cells as f64 / self.cells.max(1) as f64
    }

    /// Mean items per non-empty cell.
    pub fn mean_items_per_full_cell(&self) -> f64 {
        self.references as f64 / (self.cells - self.empty_cells).max(1) as f64
    }
}

/// A built grid (or, when `enabled` is false, the trivial "brute force" stand-in).
#[derive(Clone, Debug)]
pub struct Grid {
    pub enabled: bool,
    pub min: [f32; 3],
    pub max: [f32; 3],
    pub cell_size: [f32; 3],
    pub dims: [u32; 3],
    pub cell_start: Vec<u32>,
    pub cell_items: Vec<u32>,
    pub stats: GridBuildStats,
}

/// Cells per axis for `items` items over `extent` with density λ (Cleary–Wyvill: cubical
/// cells, λ·N of them), clamped to the grid limits.
pub fn grid_resolution(extent: Vec3, items: usize, density: f32) -> [u32; 3] {
    let volume = extent.x * extent.y * extent.z;
    let target_cells = (density as f64 * items as f64).clamp(1.0, MAX_CELLS as f64);
    let cell_side = (volume as f64 / target_cells).cbrt();
    let mut dims = extent
        .to_array()
        .map(|e| ((e as f64 / cell_side).round() as u32).clamp(1, MAX_AXIS_CELLS));
    while dims.iter().map(|&d| d as u64).product::<u64>() > MAX_CELLS {
        dims = dims.map(|d| (d * 7 / 8).max(1));
    }
    dims
}

/// Item `i`'s triangle corners, for a grid over triangles: read from wherever the caller
/// keeps them (packing's own triangles), so the grid holds no copy.
pub type TriangleCorners<'a> = dyn Fn(usize) -> [Vec3; 3] + Sync + 'a;

impl Grid {
    /// Builds the grid over items with the given bounds; with `triangles` (item `i`'s
    /// corners), each item is that triangle and skips the cells its plane misses. An item
    /// with empty bounds is in no cell. `density` None means brute force: one cell that
    /// lists every item.
    pub fn build(
        mut bounds: Vec<Aabb>,
        triangles: Option<&TriangleCorners<'_>>,
        density: Option<f32>,
    ) -> Grid {
        let start = Instant::now();
        // Padded in place: a big mesh's boxes are not held twice.
        bounds.par_iter_mut().for_each(|b| *b = b.padded());
        let scene_bounds = bounds.iter().fold(Aabb::EMPTY, |a, &b| a.union(b));
        let item_count = bounds.len();
        // (Items with empty bounds alone: nothing to grid, and nothing to hit.)
        let Some(density) = density.filter(|_| item_count > 0 && !scene_bounds.is_empty()) else {
            return Grid::brute_force(scene_bounds, item_count, start);
        };
        // A flat scene (all items in a plane) still needs a non-zero extent on every axis.
        let raw_extent = scene_bounds.max - scene_bounds.min;
        let min_extent = (raw_extent.max_element() * 1e-3).max(f32::MIN_POSITIVE);
        let grow = (Vec3::splat(min_extent) - raw_extent).max(Vec3::ZERO) * 0.5;
        let min = scene_bounds.min - grow;
        let max = scene_bounds.max + grow;
        let extent = max - min;
        let geometry = bounded_geometry(min, extent, &bounds, item_count, density);
        let dims = geometry.dims;
        let cell_size = geometry.cell_size;

        // (cell, item) references, produced in parallel chunks kept in item order, each
        // chunk's list exact (no growth slack) and never joined into one: a big mesh's
        // references are held once while they are sorted.
        const CHUNK: usize = 1 << 14;
        let chunks: Vec<Vec<(u32, u32)>> = bounds
            .par_chunks(CHUNK)
            .enumerate()
            .map(|(chunk, chunk_bounds)| {
                let mut out = Vec::new();
                for (k, b) in chunk_bounds.iter().enumerate() {
                    let item = chunk * CHUNK + k;
                    if b.is_empty() {
                        continue;
                    }
                    let triangle = triangles.map(|t| t(item));
                    geometry
                        .for_each_cell(b, triangle.as_ref(), |cell| out.push((cell, item as u32)));
                }
                out.shrink_to_fit();
                out
            })
            .collect();
        drop(bounds);

        // Counting sort by cell; stable, so each cell lists its items in ascending order:
        // `cell_start[c]` first holds cell c's end, and the references, placed from the
        // last back, move it down to the cell's start (no second array of cursors).
        let cells = dims.iter().map(|&d| d as usize).product::<usize>();
        let mut cell_start = vec![0u32; cells + 1];
        for &(cell, _) in chunks.iter().flatten() {
            cell_start[cell as usize] += 1;
        }
        for c in 1..cells {
            cell_start[c] += cell_start[c - 1];
        }
        let references = cell_start[cells - 1] as usize;
        cell_start[cells] = references as u32;
        let mut cell_items = vec![0u32; references];
        for &(cell, item) in chunks.iter().rev().flat_map(|c| c.iter().rev()) {
            let end = &mut cell_start[cell as usize];
            *end -= 1;
            cell_items[*end as usize] = item;
        }
        drop(chunks);
        let empty_cells = (0..cells)
            .filter(|&c| cell_start[c] == cell_start[c + 1])
            .count();
        let max_items_in_cell = (0..cells)
            .map(|c| (cell_start[c + 1] - cell_start[c]) as usize)
            .max()
            .unwrap_or(0);
        let stats = GridBuildStats {
            items: item_count,
            cells,
            empty_cells,
            references: cell_items.len(),
            max_items_in_cell,
            build_time: start.elapsed(),
            memory_bytes: 4 * (cell_start.len() + cell_items.len()),
        };
        Grid {
            enabled: true,
            min: min.to_array(),
            max: max.to_array(),
            cell_size: cell_size.to_array(),
            dims,
            cell_start,
            cell_items,
            stats,
        }
    }

    /// No grid: one cell listing every item, traversed by brute force.
    fn brute_force(bounds: Aabb, items: usize, start: Instant) -> Grid {
        let (min, max) = if items == 0 || bounds.is_empty() {
            (Vec3::ZERO, Vec3::ZERO)
        } else {
            (bounds.min, bounds.max)
        };
        Grid {
            enabled: false,
            min: min.to_array(),
            max: max.to_array(),
            cell_size: (max - min).to_array(),
            dims: [1, 1, 1],
            cell_start: vec![0, items as u32],
            cell_items: (0..items as u32).collect(),
            stats: GridBuildStats {
                items,
                cells: 1,
                empty_cells: (items == 0) as usize,
                references: items,
                max_items_in_cell: items,
                build_time: start.elapsed(),
                memory_bytes: 4 * (2 + items),
            },
        }
    }
}

/// Most (cell, item) references a grid may hold (8 bytes each while building, 4 after):
/// big items overlapping many cells (a fan-triangulated disk of thousands of corners,
/// thousands of concentric spheres) would otherwise ask for gigabytes.
pub const MAX_REFERENCES: u64 = 1 << 25;

/// The grid's placement for λ = `density`, made coarser (7/8 per axis at a time) while
/// the items' bounding boxes would overlap more than [`MAX_REFERENCES`] cells in all.
/// Counted from the boxes, before any reference is made; the boxes bound the references
/// from above (a triangle's overlap test only removes cells).
fn bounded_geometry(
    min: Vec3,
    extent: Vec3,
    bounds: &[Aabb],
    items: usize,
    density: f32,
) -> CellGeometry {
    let mut dims = grid_resolution(extent, items, density);
    loop {
        let dims_v = Vec3::new(dims[0] as f32, dims[1] as f32, dims[2] as f32);
        let geometry = CellGeometry {
            min,
            cell_size: extent / dims_v,
            dims,
        };
        let references: u64 = bounds
            .par_iter()
            .filter(|b| !b.is_empty())
            .map(|b| {
                (0..3)
                    .map(|a| {
                        u64::from(geometry.cell_coord(b.max, a) - geometry.cell_coord(b.min, a) + 1)
                    })
                    .product::<u64>()
            })
            .sum();
        if references <= MAX_REFERENCES || dims == [1, 1, 1] {
            return geometry;
        }
        dims = dims.map(|d| (d * 7 / 8).max(1));
    }
}

/// Grid placement, for mapping bounds to cells.
struct CellGeometry {
    min: Vec3,
    cell_size: Vec3,
    dims: [u32; 3],
}

impl CellGeometry {
    fn cell_coord(&self, p: Vec3, axis: usize) -> u32 {
        let c = ((p[axis] - self.min[axis]) / self.cell_size[axis]).floor();
        (c.max(0.0) as u32).min(self.dims[axis] - 1)
    }

    /// Calls `f` with the index of every cell that `bounds` overlaps (and, for a triangle,
    /// that the triangle itself may overlap: [`TriangleOverlap`]).
    fn for_each_cell(&self, bounds: &Aabb, triangle: Option<&[Vec3; 3]>, mut f: impl FnMut(u32)) {
        let lo = [0, 1, 2].map(|a| self.cell_coord(bounds.min, a));
        let hi = [0, 1, 2].map(|a| self.cell_coord(bounds.max, a));
        let single = lo == hi;
        let overlap = triangle.filter(|_| !single).map(TriangleOverlap::new);
        // Cells grow by the same relative pad as the item bounds.
        let half = self.cell_size * (0.5 + BOUNDS_PAD);
        for z in lo[2]..=hi[2] {
            for y in lo[1]..=hi[1] {
                for x in lo[0]..=hi[0] {
                    if let Some(overlap) = &overlap {
                        let centre = self.min
                            + (Vec3::new(x as f32, y as f32, z as f32) + 0.5) * self.cell_size;
                        if !overlap.overlaps(centre, half) {
                            continue;
                        }
                    }
                    f(x + self.dims[0] * (y + self.dims[1] * z));
                }
            }
        }
    }
}
