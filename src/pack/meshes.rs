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
use crate::scene::flatten::{FlatScene, MeshTriangle};
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

/// A mesh's triangles in its space, before packing.
struct MeshSource<'a> {
    triangles: Vec<&'a MeshTriangle>,
}

/// Packs the meshes and mesh instances of `scene` (and its loose triangles) with grids of
/// density `density` (None: brute force, one cell per mesh).
pub fn pack_meshes(scene: &FlatScene, density: Option<f32>) -> Result<PackedMeshes, PackError> {
    let mut sources: Vec<MeshSource> = scene
        .meshes
        .iter()
        .map(|m| MeshSource {
            triangles: m.triangles.iter().collect(),
        })
        .collect();
    // (mesh, object→world, material) of every instance.
    let mut placements: Vec<(usize, DMat4, u32)> = scene
        .mesh_instances
        .iter()
        .map(|i| (i.mesh, i.object_to_world, i.material as u32))
        .collect();
    let loose = loose_meshes(scene);
    for (material, triangles) in &loose {
        sources.push(MeshSource {
            triangles: triangles.iter().collect(),
        });
        placements.push((sources.len() - 1, DMat4::IDENTITY, *material));
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
        mesh_bounds.push(out.push_mesh(source, density));
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

impl PackedMeshes {
    /// Packs one mesh and builds its grid; returns its bounds (empty without triangles).
    fn push_mesh(&mut self, source: &MeshSource, density: Option<f32>) -> Aabb {
        let centroids: Vec<DVec3> = source
            .triangles
            .iter()
            .map(|t| (t.positions[0] + t.positions[1] + t.positions[2]) / 3.0)
            .collect();
        let order: Vec<&MeshTriangle> = super::spatial_order(&centroids)
            .into_iter()
            .map(|i| source.triangles[i])
            .filter(|t| !super::is_degenerate(&t.positions))
            .collect();
        let corners: Vec<[Vec3; 3]> = order
            .par_iter()
            .map(|t| t.positions.map(|p| p.as_vec3()))
            .collect();
        let bounds: Vec<Aabb> = corners.par_iter().map(Aabb::of_triangle).collect();
        let grid = Grid::build(&bounds, Some(&corners), density);
        let first_triangle = self.triangles.len() as u32;
        self.triangles
            .extend(corners.iter().map(|&[p0, p1, p2]| PackedTriangle {
                p0: p0.to_array(),
                p1: p1.to_array(),
                p2: p2.to_array(),
            }));
        self.triangle_uvs
            .extend(order.iter().map(|t| PackedTriangleUv {
                uv0: t.uvs[0],
                uv1: t.uvs[1],
                uv2: t.uvs[2],
            }));
        self.triangle_normals
            .extend(order.iter().map(|t| PackedTriangleNormals {
                n0: t.normals[0],
                n1: t.normals[1],
                n2: t.normals[2],
            }));
        self.smooth |= order.iter().any(|t| t.normals[0] != [0.0; 3]);
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
            first_triangle,
            grid_cell_size: grid.cell_size,
            num_triangles: corners.len() as u32,
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
        bounds.iter().fold(Aabb::EMPTY, |a, &b| a.union(b))
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
