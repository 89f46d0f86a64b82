//! Meshes packed: each mesh's triangles stored once (degenerate ones dropped, the rest in
//! Morton order), each mesh with its own uniform grid in its own space, and one
//! `KIND_MESH` instance per placement. Loose world-space triangles (tests, benchmarks)
//! become one world-space mesh per material.

use super::bounds::mesh_instance_bounds;
use super::layout::{
    PackedInstance, PackedMesh, PackedTriangle, PackedTriangleNormals, PackedTriangleUv,
};
use super::{affine_rows, PackError};
use crate::accel::aabb::Aabb;
use crate::accel::grid::{Grid, GridBuildStats};
use crate::constants::KIND_MESH;
use crate::scene::flatten::{FlatScene, MeshTriangle, SceneMesh};
use bytemuck::Zeroable;
use glam::{DMat4, DVec3, Vec3};
use rayon::prelude::*;

/// The packed meshes. `cell_start` / `cell_items` hold the meshes' grids one after the
/// other, with entries as if they started at offset 0 of both arrays: [`PackedMeshes::
/// append_cells`] moves them behind the scene grid's.
pub struct PackedMeshes {
    pub triangles: Vec<PackedTriangle>,
    /// Parallel to `triangles`.
    pub triangle_uvs: Vec<PackedTriangleUv>,
    /// Parallel to `triangles` (all zero on flat triangles).
    pub triangle_normals: Vec<PackedTriangleNormals>,
    /// Whether some triangle has vertex normals (the SMOOTH feature).
    pub smooth: bool,
    pub meshes: Vec<PackedMesh>,
    pub instances: Vec<PackedInstance>,
    /// World bounds of each instance (for the scene grid).
    pub instance_bounds: Vec<Aabb>,
    pub cell_start: Vec<u32>,
    pub cell_items: Vec<u32>,
    /// The meshes' grids, summed (build time, cells, references, memory).
    pub stats: GridBuildStats,
}

/// A mesh's triangles in its space, before packing: a stored mesh, read one triangle at
/// a time, or a group of loose triangles.
enum MeshSource<'a> {
    Stored(&'a SceneMesh),
    Loose(Vec<MeshTriangle>),
}

impl MeshSource<'_> {
    fn len(&self) -> usize {
        match self {
            MeshSource::Stored(mesh) => mesh.len(),
            MeshSource::Loose(triangles) => triangles.len(),
        }
    }

    fn positions(&self, i: usize) -> [DVec3; 3] {
        match self {
            MeshSource::Stored(mesh) => mesh.positions(i),
            MeshSource::Loose(triangles) => triangles[i].positions,
        }
    }

    fn triangle(&self, i: usize) -> MeshTriangle {
        match self {
            MeshSource::Stored(mesh) => mesh.triangle(i),
            MeshSource::Loose(triangles) => triangles[i].clone(),
        }
    }
}

/// Packs the meshes and mesh instances of `scene` (and its loose triangles) with grids of
/// density `density` (None: brute force, one cell per mesh); the triangles' UVs only
/// `with_uvs` (a scene that uses textures), since nothing else reads them.
pub fn pack_meshes(
    scene: &FlatScene,
    density: Option<f32>,
    with_uvs: bool,
) -> Result<PackedMeshes, PackError> {
    let mut sources: Vec<MeshSource> = scene.meshes.iter().map(MeshSource::Stored).collect();
    // (mesh, object→world, material) of every instance.
    let mut placements: Vec<(usize, DMat4, u32)> = scene
        .mesh_instances
        .iter()
        .map(|i| (i.mesh, i.object_to_world, i.material as u32))
        .collect();
    for (material, triangles) in loose_meshes(scene) {
        sources.push(MeshSource::Loose(triangles));
        placements.push((sources.len() - 1, DMat4::IDENTITY, material));
    }
    if sources.len() >= 1 << 24 {
        return Err(PackError::TooManyMeshes(sources.len()));
    }
    let mut out = PackedMeshes {
        triangles: Vec::new(),
        triangle_uvs: Vec::new(),
        triangle_normals: Vec::new(),
        smooth: false,
        meshes: Vec::new(),
        instances: Vec::new(),
        instance_bounds: Vec::new(),
        cell_start: Vec::new(),
        cell_items: Vec::new(),
        stats: GridBuildStats::default(),
    };
    let mut mesh_bounds = Vec::new();
    for source in &sources {
        mesh_bounds.push(out.push_mesh(source, density, with_uvs));
    }
    for (mesh, object_to_world, material) in placements {
        let instance = PackedInstance {
            world_to_object: affine_rows(&object_to_world.inverse()),
            object_to_world: affine_rows(&object_to_world),
            kind: KIND_MESH,
            material,
            // Exact as f32 below 2^24 (checked above).
            params: [mesh as f32, 0.0],
        };
        out.instance_bounds
            .push(mesh_instance_bounds(&instance, mesh_bounds[mesh]));
        out.instances.push(instance);
    }
    Ok(out)
}

/// The loose triangles grouped by material (in order of first appearance), as mesh
/// triangles.
fn loose_meshes(scene: &FlatScene) -> Vec<(u32, Vec<MeshTriangle>)> {
    let mut groups: Vec<(u32, Vec<MeshTriangle>)> = Vec::new();
    for t in &scene.triangles {
        let material = t.material as u32;
        let triangle = MeshTriangle {
            positions: t.positions,
            uvs: t.uvs,
            normals: [[0.0; 3]; 3],
        };
        match groups.iter_mut().find(|g| g.0 == material) {
            Some(group) => group.1.push(triangle),
            None => groups.push((material, vec![triangle])),
        }
    }
    groups
}

/// The triangles of `source` in Morton order of their (f64) centroids, degenerate ones
/// dropped: indices into `source`.
fn packing_order(source: &MeshSource) -> Vec<u32> {
    let centroids: Vec<DVec3> = (0..source.len())
        .into_par_iter()
        .map(|i| {
            let p = source.positions(i);
            (p[0] + p[1] + p[2]) / 3.0
        })
        .collect();
    let order = super::spatial_order(&centroids);
    drop(centroids);
    order
        .into_par_iter()
        .filter(|&i| !super::is_degenerate(&source.positions(i)))
        .map(|i| i as u32)
        .collect()
}

/// `part` of each triangle `order` of `source`, in order (made one triangle at a time).
fn per_triangle<'a, T: Send>(
    source: &'a MeshSource,
    order: &'a [u32],
    part: impl Fn(MeshTriangle) -> T + Sync + Send + 'a,
) -> impl IndexedParallelIterator<Item = T> + 'a {
    order
        .par_iter()
        .map(move |&i| part(source.triangle(i as usize)))
}

/// A packed triangle's corners.
fn triangle_vertices(t: &PackedTriangle) -> [Vec3; 3] {
    [t.p0, t.p1, t.p2].map(Vec3::from_array)
}

impl PackedMeshes {
    /// Packs one mesh and builds its grid; returns its bounds (empty without triangles).
    /// Each triangle is made from `source` as it is packed, straight into the packed
    /// arrays, and the grid reads the packed corners: no per-triangle copy outlives its
    /// step.
    fn push_mesh(&mut self, source: &MeshSource, density: Option<f32>, with_uvs: bool) -> Aabb {
        let order = packing_order(source);
        let first = self.triangles.len();
        self.triangles.par_extend(order.par_iter().map(|&i| {
            let [p0, p1, p2] = source.positions(i as usize).map(|p| p.as_vec3());
            PackedTriangle {
                p0: p0.to_array(),
                p1: p1.to_array(),
                p2: p2.to_array(),
            }
        }));
        let packed = &self.triangles[first..];
        let bounds: Vec<Aabb> = packed
            .par_iter()
            .map(|t| Aabb::of_triangle(&triangle_vertices(t)))
            .collect();
        let mesh_bounds = bounds.iter().fold(Aabb::EMPTY, |a, &b| a.union(b));
        let grid = Grid::build(bounds, Some(&|i| triangle_vertices(&packed[i])), density);
        if with_uvs {
            let uvs = per_triangle(source, &order, |t| t.uvs);
            self.triangle_uvs
                .par_extend(uvs.map(|[uv0, uv1, uv2]| PackedTriangleUv { uv0, uv1, uv2 }));
        }
        self.push_normals(source, &order, first);
        let item_offset = self.cell_items.len() as u32;
        let first_cell = self.cell_start.len() as u32;
        // Cell c's items are cell_start[c]..cell_start[c + 1]: keep one entry per cell
        // plus the end, each moved behind the earlier meshes' items.
        self.cell_start
            .extend(grid.cell_start.iter().map(|&s| s + item_offset));
        self.cell_items.extend_from_slice(&grid.cell_items);
        self.meshes.push(PackedMesh {
            grid_min: grid.min,
            first_cell,
            grid_max: grid.max,
            first_triangle: first as u32,
            grid_cell_size: grid.cell_size,
            num_triangles: order.len() as u32,
            grid_dims: grid.dims,
            _pad0: 0,
        });
        let s = &mut self.stats;
        s.items += grid.stats.items;
        s.cells += grid.stats.cells;
        s.empty_cells += grid.stats.empty_cells;
        s.references += grid.stats.references;
        s.max_items_in_cell = s.max_items_in_cell.max(grid.stats.max_items_in_cell);
        s.build_time += grid.stats.build_time;
        s.memory_bytes += grid.stats.memory_bytes;
        mesh_bounds
    }

    /// The corner normals of the triangles `order` of `source`, packed from `first` on:
    /// only once some mesh has normals (the earlier triangles then get zeros, flat), since
    /// a scene without them drops the array.
    fn push_normals(&mut self, source: &MeshSource, order: &[u32], first: usize) {
        let has_normals = match source {
            MeshSource::Stored(mesh) => mesh.has_normals(),
            MeshSource::Loose(_) => false,
        };
        if has_normals {
            self.triangle_normals
                .resize(first, PackedTriangleNormals::zeroed());
            let normals = per_triangle(source, order, |t| t.normals);
            self.triangle_normals
                .par_extend(normals.map(|[n0, n1, n2]| PackedTriangleNormals { n0, n1, n2 }));
            self.smooth |= self.triangle_normals[first..]
                .iter()
                .any(|n| n.n0 != [0.0; 3]);
        } else if !self.triangle_normals.is_empty() {
            self.triangle_normals
                .resize(first + order.len(), PackedTriangleNormals::zeroed());
        }
    }

    /// Moves the meshes' cells behind a scene grid of `scene_cells` entries of
    /// `cell_start` (cells + 1) and `scene_items` entries of `cell_items`.
    pub fn append_cells(&mut self, scene_cells: usize, scene_items: usize) {
        for mesh in &mut self.meshes {
            mesh.first_cell += scene_cells as u32;
        }
        for s in &mut self.cell_start {
            *s += scene_items as u32;
        }
    }
}
