//! Meshes stored once: after flattening, each graph mesh that some path reaches becomes
//! one [`SceneMesh`]. A mesh with several instances keeps its object-space vertices and
//! its instances their transforms (a two-level structure, as a TLAS over BLASes); a mesh
//! with one instance is baked into world space under an identity transform, so the
//! common single-use mesh is traced in world coordinates exactly as before instancing
//! (no ray transform, no extra rounding). Vertex normals go along (through the inverse
//! transpose), unless the render option `shading` is `'flat'`.

use super::flat::{FlatScene, MeshTriangle, SceneMesh};
use super::{SceneGraph, Shading};
use glam::{DMat3, DMat4, DVec3};

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
                let positions: Vec<_> = mesh
                    .positions
                    .iter()
                    .map(|&p| to_stored.transform_point3(p))
                    .collect();
                let normals = if scene.options.shading == Shading::Smooth {
                    stored_normals(mesh, &to_stored)
                } else {
                    Vec::new()
                };
                let triangles = mesh
                    .triangles
                    .iter()
                    .map(|t| MeshTriangle {
                        positions: t.map(|i| positions[i as usize]),
                        uvs: match &mesh.uvs {
                            Some(uvs) => t.map(|i| uvs[i as usize]),
                            None => super::uv::planar_uvs(t.map(|i| mesh.positions[i as usize])),
                        },
                        normals: triangle_normals(&normals, t),
                    })
                    .collect();
                scene.meshes.push(SceneMesh {
                    name: mesh.name.clone(),
                    triangles,
                });
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

/// The mesh's vertex normals in the stored space (`to_stored` maps the mesh's space to
/// it): through the inverse transpose of its linear part, divided by that matrix's largest
/// entry but not renormalised one by one (zero stays zero), so that a baked mesh's normals
/// interpolate exactly as an instanced mesh's, whose object-space normals the tracer
/// interpolates before mapping them (under a non-uniform scale, renormalising each would
/// move the blend); empty without normals.
fn stored_normals(mesh: &super::Mesh, to_stored: &DMat4) -> Vec<DVec3> {
    let Some(normals) = &mesh.normals else {
        return Vec::new();
    };
    let normal_matrix = DMat3::from_mat4(*to_stored).inverse().transpose();
    let largest = normal_matrix
        .abs()
        .to_cols_array()
        .into_iter()
        .fold(0.0, f64::max);
    let normal_matrix = normal_matrix * (1.0 / largest);
    normals.iter().map(|&n| normal_matrix * n).collect()
}

/// The corner normals of triangle `t` (vertex indices) for packing, as f32: all zero,
/// which marks a flat triangle, unless every corner has one.
fn triangle_normals(normals: &[DVec3], t: &[u32; 3]) -> [[f32; 3]; 3] {
    if normals.is_empty() {
        return [[0.0; 3]; 3];
    }
    let corners = t.map(|i| normals[i as usize]);
    if corners.contains(&DVec3::ZERO) {
        return [[0.0; 3]; 3];
    }
    corners.map(|n| n.as_vec3().to_array())
}
