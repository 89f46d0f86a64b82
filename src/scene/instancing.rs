//! Meshes stored once: after flattening, each graph mesh that some path reaches becomes
//! one [`SceneMesh`]. A mesh with several instances keeps its object-space vertices and
//! its instances their transforms (a two-level structure, as a TLAS over BLASes); a mesh
//! with one instance is baked into world space under an identity transform, so the
//! common single-use mesh is traced in world coordinates exactly as before instancing
//! (no ray transform, no extra rounding). Vertex normals go along (through the inverse
//! transpose), unless the render option `shading` is `'flat'`.

use super::flat::{FlatScene, SceneMesh};
use super::{SceneGraph, Shading};
use glam::{DMat3, DMat4};
use std::sync::Arc;

/// Replaces the graph mesh ids of `scene.mesh_instances` by indices into the meshes it
/// stores in `scene.meshes` (in order of first use).
pub fn store_meshes(graph: &SceneGraph, scene: &mut FlatScene) {
    let mut uses = vec![0usize; graph.meshes.len()];
    for instance in &scene.mesh_instances {
        uses[instance.mesh] += 1;
    }
    let mut stored: Vec<Option<usize>> = vec![None; graph.meshes.len()];
    for instance in &mut scene.mesh_instances {
        let mesh = &graph.meshes[instance.mesh];
        let single = uses[instance.mesh] == 1;
        let to_stored = if single {
            instance.object_to_world
        } else {
            DMat4::IDENTITY
        };
        let index = match stored[instance.mesh] {
            Some(index) => index,
            None => {
                let normal_matrix = (scene.options.shading == Shading::Smooth
                    && mesh.normals.is_some())
                .then(|| stored_normal_matrix(&to_stored));
                scene
                    .meshes
                    .push(SceneMesh::new(Arc::clone(mesh), to_stored, normal_matrix));
                let index = scene.meshes.len() - 1;
                stored[instance.mesh] = Some(index);
                index
            }
        };
        instance.mesh = index;
        if single {
            instance.object_to_world = DMat4::IDENTITY;
        }
    }
}

/// The map of a mesh's vertex normals to the stored space (`to_stored` maps the mesh's
/// space to it): the inverse transpose of its linear part, divided by that matrix's largest
/// entry, the normals not renormalised one by one (zero stays zero), so that a baked mesh's
/// normals interpolate exactly as an instanced mesh's, whose object-space normals the
/// tracer interpolates before mapping them (under a non-uniform scale, renormalising each
/// would move the blend). [`SceneMesh::triangle`] applies it and drops a triangle's
/// normals when a corner has none.
fn stored_normal_matrix(to_stored: &DMat4) -> DMat3 {
    let normal_matrix = DMat3::from_mat4(*to_stored).inverse().transpose();
    let largest = normal_matrix
        .abs()
        .to_cols_array()
        .into_iter()
        .fold(0.0, f64::max);
    normal_matrix * (1.0 / largest)
}
