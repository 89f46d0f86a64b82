//! Uniform grid build: resolution after Cleary & Wyvill (cells ≈ λ·N, cubical cells over
//! the scene bounds), each item listed in every cell its (padded) bounds overlap; mesh
//! triangles are individual items and skip cells their plane misses. Cells are stored
//! CSR-style (`cell_start`, `cell_items`), items in ascending order inside each cell so
//! the build is deterministic. A CSG object is one item whose bounds follow its tree
//! ([`csg_bounds`]).

use crate::constants::{
    CSG_DIFFERENCE, CSG_INDEX_MASK, CSG_INTERSECTION, CSG_LEAF, CSG_OP_SHIFT, KIND_CONE, KIND_CUBE,
    KIND_CYLINDER, KIND_SPHERE, KIND_TORUS,
};
use crate::pack::{GpuInstance, GpuTriangle};
use glam::Vec3;
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// λ, the cells-per-item density of `grid = 'auto'`, chosen by `glint bench grid`
/// (see the README's performance section).
pub const DEFAULT_DENSITY: f32 = 8.0;
/// Most cells along one axis.
pub const MAX_AXIS_CELLS: u32 = 1024;
/// Most cells in all (bounds memory: 4 bytes per cell).
pub const MAX_CELLS: u64 = 1 << 24;
/// Item bounds grow by this fraction of their magnitude, so that a hit point computed
/// with rounding error still falls in a cell that lists the item.
const BOUNDS_PAD: f32 = 1.0e-5;

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

/// An axis-aligned box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Vec3,
    pub max: Vec3,
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::MAX),
        max: Vec3::splat(f32::MIN),
    };

    pub fn union(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// The common part (empty when they do not overlap).
    pub fn intersection(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.max(other.min),
            max: self.max.min(other.max),
        }
    }

    /// Whether the box holds no point (min > max on some axis).
    pub fn is_empty(self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    /// Grown by `BOUNDS_PAD` of its largest coordinate magnitude and extent (an empty box
    /// stays empty).
    fn padded(self) -> Aabb {
        if self.is_empty() {
            return Aabb::EMPTY;
        }
        let magnitude = self.min.abs().max(self.max.abs()).max_element();
        let pad = BOUNDS_PAD * (magnitude + (self.max - self.min).max_element());
        Aabb {
            min: self.min - Vec3::splat(pad),
            max: self.max + Vec3::splat(pad),
        }
    }
}

/// World bounds of an instance: the unit sphere, unit cube, cylinder, cone or torus under
/// its transform.
pub fn instance_bounds(inst: &GpuInstance) -> Aabb {
    let rows = inst.object_to_world.map(|r| Vec3::new(r[0], r[1], r[2]));
    let translation = Vec3::new(
        inst.object_to_world[0][3],
        inst.object_to_world[1][3],
        inst.object_to_world[2][3],
    );
    let (centre, half) = match inst.kind {
        // Ellipsoid: the extent along world axis i is the length of row i.
        KIND_SPHERE => (
            translation,
            Vec3::new(rows[0].length(), rows[1].length(), rows[2].length()),
        ),
        // Unit cube around (½,½,½): half-extent ½·Σ|row i|.
        KIND_CUBE => (
            translation
                + Vec3::new(
                    rows[0].dot(Vec3::splat(0.5)),
                    rows[1].dot(Vec3::splat(0.5)),
                    rows[2].dot(Vec3::splat(0.5)),
                ),
            0.5 * Vec3::new(
                rows[0].abs().element_sum(),
                rows[1].abs().element_sum(),
                rows[2].abs().element_sum(),
            ),
        ),
        // Cylinder and cone: their object-space box (centre c, half-extent h) under the
        // transform, half-extent Σ_j |row i|_j · h_j (conservative).
        KIND_CYLINDER | KIND_CONE => {
            let (c, h) = if inst.kind == KIND_CYLINDER {
                (Vec3::new(0.0, 0.0, 0.5), Vec3::new(1.0, 1.0, 0.5))
            } else {
                let [zmin, zmax] = inst.params;
                let r = zmin.abs().max(zmax.abs());
                (
                    Vec3::new(0.0, 0.0, 0.5 * (zmin + zmax)),
                    Vec3::new(r, r, 0.5 * (zmax - zmin)),
                )
            };
            (
                translation + Vec3::new(rows[0].dot(c), rows[1].dot(c), rows[2].dot(c)),
                Vec3::new(
                    rows[0].abs().dot(h),
                    rows[1].abs().dot(h),
                    rows[2].abs().dot(h),
                ),
            )
        }
        // Box [−R, R]² × [−rout, rout] (R = rin + rout) around the origin: half-extent
        // Σ|row i|·(R, R, rout).
        KIND_TORUS => {
            let [rin, rout] = inst.params;
            let extent = Vec3::new(rin + rout, rin + rout, rout);
            (
                translation,
                Vec3::new(
                    rows[0].abs().dot(extent),
                    rows[1].abs().dot(extent),
                    rows[2].abs().dot(extent),
                ),
            )
        }
        other => unreachable!("instance kind {other} has no bounds"),
    };
    Aabb {
        min: centre - half,
        max: centre + half,
    }
}

/// World bounds of a CSG object from its post-order `program` (entries as in
/// `PackedScene::csg_program`; leaves index `instances`): a union is bounded by the union
/// of its operands' bounds, an intersection by their intersection, a difference by a's.
/// Empty when an intersection's operands cannot overlap (the object is then in no cell).
pub fn csg_bounds(program: &[u32], instances: &[GpuInstance]) -> Aabb {
    let mut stack: Vec<Aabb> = Vec::new();
    for &entry in program {
        let op = entry >> CSG_OP_SHIFT;
        if op == CSG_LEAF {
            stack.push(instance_bounds(
                &instances[(entry & CSG_INDEX_MASK) as usize],
            ));
            continue;
        }
        let b = stack.pop().expect("CSG program: operand b");
        let a = stack.pop().expect("CSG program: operand a");
        stack.push(match op {
            CSG_INTERSECTION => a.intersection(b),
            CSG_DIFFERENCE => a,
            _ => a.union(b),
        });
    }
    let bounds = stack.pop().expect("CSG program: result");
    if bounds.is_empty() {
        Aabb::EMPTY
    } else {
        bounds
    }
}

pub fn triangle_bounds(tri: &GpuTriangle) -> Aabb {
    let [a, b, c] = [tri.p0, tri.p1, tri.p2].map(Vec3::from);
    Aabb {
        min: a.min(b).min(c),
        max: a.max(b).max(c),
    }
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

impl Grid {
    /// Builds the grid over every instance and triangle (no CSG objects: see
    /// [`Grid::build_items`]); `density` None means brute force.
    pub fn build(
        instances: &[GpuInstance],
        triangles: &[GpuTriangle],
        density: Option<f32>,
    ) -> Grid {
        let bounds = instances.par_iter().map(instance_bounds).collect();
        Grid::build_items(bounds, triangles, density)
    }

    /// Builds the grid over items with the given instance bounds (one per instance item,
    /// CSG objects included), then the triangles. An item with empty bounds is in no cell.
    pub fn build_items(
        instance_bounds: Vec<Aabb>,
        triangles: &[GpuTriangle],
        density: Option<f32>,
    ) -> Grid {
        let start = Instant::now();
        let num_instances = instance_bounds.len();
        let bounds: Vec<Aabb> = instance_bounds
            .into_par_iter()
            .chain(triangles.par_iter().map(triangle_bounds))
            .map(Aabb::padded)
            .collect();
        let scene_bounds = bounds.iter().fold(Aabb::EMPTY, |a, &b| a.union(b));
        let item_count = bounds.len();
        // (Items with empty bounds alone: nothing to grid, and nothing to hit.)
        let Some(density) = density.filter(|_| item_count > 0 && !scene_bounds.is_empty()) else {
            return Grid::brute_force(scene_bounds, item_count);
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

        // (cell, item) references, produced in parallel chunks kept in item order.
        const CHUNK: usize = 1 << 14;
        let pairs: Vec<(u32, u32)> = bounds
            .par_chunks(CHUNK)
            .enumerate()
            .flat_map_iter(|(chunk, chunk_bounds)| {
                let mut out = Vec::new();
                for (k, b) in chunk_bounds.iter().enumerate() {
                    let item = chunk * CHUNK + k;
                    if b.is_empty() {
                        continue;
                    }
                    let triangle = item.checked_sub(num_instances).map(|t| &triangles[t]);
                    geometry.for_each_cell(b, triangle, |cell| out.push((cell, item as u32)));
                }
                out.into_iter()
            })
            .collect();

        // Counting sort by cell; stable, so each cell lists its items in ascending order.
        let cells = dims.iter().map(|&d| d as usize).product::<usize>();
        let mut cell_start = vec![0u32; cells + 1];
        for &(cell, _) in &pairs {
            cell_start[cell as usize + 1] += 1;
        }
        for c in 0..cells {
            cell_start[c + 1] += cell_start[c];
        }
        let mut cursor = cell_start.clone();
        let mut cell_items = vec![0u32; pairs.len()];
        for &(cell, item) in &pairs {
            let slot = &mut cursor[cell as usize];
            cell_items[*slot as usize] = item;
            *slot += 1;
        }
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

    /// No grid: one conceptual cell holding every item, traversed by brute force.
    fn brute_force(bounds: Aabb, items: usize) -> Grid {
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
            // Storage buffers may not be empty: one cell with no items.
            cell_start: vec![0, 0],
            cell_items: vec![0],
            stats: GridBuildStats {
                items,
                cells: 1,
                ..Default::default()
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
/// from above (a triangle's plane test only removes cells).
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
    /// that its plane passes through).
    fn for_each_cell(&self, bounds: &Aabb, triangle: Option<&GpuTriangle>, mut f: impl FnMut(u32)) {
        let lo = [0, 1, 2].map(|a| self.cell_coord(bounds.min, a));
        let hi = [0, 1, 2].map(|a| self.cell_coord(bounds.max, a));
        let single = lo == hi;
        let plane = triangle.filter(|_| !single).map(|t| {
            let p0 = Vec3::from(t.p0);
            let normal = (Vec3::from(t.p1) - p0).cross(Vec3::from(t.p2) - p0);
            (p0, normal)
        });
        // Cells grow by the same relative pad as the item bounds for the plane test.
        let half = self.cell_size * (0.5 + BOUNDS_PAD);
        for z in lo[2]..=hi[2] {
            for y in lo[1]..=hi[1] {
                for x in lo[0]..=hi[0] {
                    if let Some((p0, normal)) = plane {
                        let centre = self.min
                            + (Vec3::new(x as f32, y as f32, z as f32) + 0.5) * self.cell_size;
                        // Plane–box overlap: the box's projected radius on the normal
                        // must reach the plane.
                        let radius = half.dot(normal.abs());
                        let distance = normal.dot(centre - p0);
                        let slack = BOUNDS_PAD
                            * (normal.length()
                                * (centre.abs().max_element() + p0.abs().max_element()));
                        if distance.abs() > radius + slack {
                            continue;
                        }
                    }
                    f(x + self.dims[0] * (y + self.dims[1] * z));
                }
            }
        }
    }
}
