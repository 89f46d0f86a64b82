//! SceneGraph → world-space [`Scene`]: walks the DAG from the render root, composing
//! f64 matrices, so instancing (a node under several parents) yields one object per path.
//! Analytic primitives keep their object-to-world transform; mesh triangles are baked to
//! world space (shared edges stay bit-identical, which keeps the triangle test watertight).

use super::{
    Camera, Light, Material, MaterialId, NodeId, NodeKind, Primitive, RenderOptions, RenderRequest,
    SceneGraph,
};
use glam::{DMat3, DMat4, DVec3};

/// Deepest node nesting accepted; deeper means a cycle (a node added under itself).
pub const MAX_NODE_DEPTH: usize = 256;

/// An analytic primitive kind (meshes become triangles).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ObjectKind {
    Sphere,
    Cube,
    Cylinder,
    Cone {
        zmin: f32,
        zmax: f32,
    },
    /// Torus in the XY plane around z (`rin` to the middle of the tube, `rout` its radius).
    Torus {
        rin: f32,
        rout: f32,
    },
}

/// One analytic primitive instance in world space.
#[derive(Clone, Debug)]
pub struct Object {
    pub name: String,
    pub kind: ObjectKind,
    pub object_to_world: DMat4,
    pub material: MaterialId,
}

/// One world-space triangle.
#[derive(Clone, Debug)]
pub struct Triangle {
    pub positions: [DVec3; 3],
    pub material: MaterialId,
    /// The corners' UVs: the mesh's own, else the planar projection of `scene::uv`.
    pub uvs: [[f32; 2]; 3],
}

/// The flattened scene of one `gr.render` call.
#[derive(Clone, Debug)]
pub struct Scene {
    pub objects: Vec<Object>,
    pub triangles: Vec<Triangle>,
    /// All materials of the graph, plus the default one at index `default_material`.
    pub materials: Vec<Material>,
    /// The graph's textures (materials index them).
    pub textures: Vec<std::sync::Arc<super::Texture>>,
    pub lights: Vec<Light>,
    pub camera: Camera,
    pub ambient: [f32; 3],
    pub width: u32,
    pub height: u32,
    pub options: RenderOptions,
}

#[derive(Debug, thiserror::Error, PartialEq)]
pub enum FlattenError {
    #[error("node '{path}' has a singular transform (determinant {det:e}): it flattens its geometry to nothing")]
    SingularTransform { path: String, det: f64 },
    #[error("node '{path}' has a non-finite transform (NaN or infinity)")]
    NonFiniteTransform { path: String },
    #[error(
        "node '{path}' is nested deeper than {MAX_NODE_DEPTH} levels: is it added under itself?"
    )]
    TooDeep { path: String },
    #[error("camera: {0}")]
    Camera(String),
}

/// Flattens the graph below `request.root` into world space.
pub fn flatten(graph: &SceneGraph, request: &RenderRequest) -> Result<Scene, FlattenError> {
    check_camera(&request.camera)?;
    let mut materials = graph.materials.clone();
    let default_material = materials.len();
    materials.push(Material::default());
    let mut scene = Scene {
        objects: Vec::new(),
        triangles: Vec::new(),
        materials,
        textures: graph.textures.clone(),
        lights: request.lights.clone(),
        camera: request.camera.clone(),
        ambient: request.ambient,
        width: request.width,
        height: request.height,
        options: request.options.clone(),
    };
    let mut path = Vec::new();
    visit(
        graph,
        request.root,
        DMat4::IDENTITY,
        default_material,
        &mut path,
        &mut scene,
    )?;
    Ok(scene)
}

fn visit(
    graph: &SceneGraph,
    id: NodeId,
    parent_to_world: DMat4,
    default_material: MaterialId,
    path: &mut Vec<NodeId>,
    scene: &mut Scene,
) -> Result<(), FlattenError> {
    let node = &graph.nodes[id];
    path.push(id);
    let path_name = || {
        path.iter()
            .map(|&n| graph.nodes[n].name.as_str())
            .collect::<Vec<_>>()
            .join("/")
    };
    if path.len() > MAX_NODE_DEPTH {
        return Err(FlattenError::TooDeep { path: path_name() });
    }
    let node_to_world = parent_to_world * node.matrix;
    if let NodeKind::Geometry {
        primitive,
        placement,
    } = &node.kind
    {
        let object_to_world = node_to_world * *placement;
        check_transform(&object_to_world, &path_name)?;
        let material = node.material.unwrap_or(default_material);
        match primitive {
            Primitive::Sphere
            | Primitive::Cube
            | Primitive::Cylinder
            | Primitive::Cone { .. }
            | Primitive::Torus { .. } => scene.objects.push(Object {
                name: path_name(),
                kind: match *primitive {
                    Primitive::Sphere => ObjectKind::Sphere,
                    Primitive::Cube => ObjectKind::Cube,
                    Primitive::Cylinder => ObjectKind::Cylinder,
                    Primitive::Cone { zmin, zmax } => ObjectKind::Cone {
                        zmin: zmin as f32,
                        zmax: zmax as f32,
                    },
                    Primitive::Torus { rin, rout } => ObjectKind::Torus {
                        rin: rin as f32,
                        rout: rout as f32,
                    },
                    Primitive::Mesh(_) => unreachable!(),
                },
                object_to_world,
                material,
            }),
            Primitive::Mesh(mesh_id) => {
                let mesh = &graph.meshes[*mesh_id];
                let world: Vec<DVec3> = mesh
                    .positions
                    .iter()
                    .map(|&p| object_to_world.transform_point3(p))
                    .collect();
                scene
                    .triangles
                    .extend(mesh.triangles.iter().map(|t| Triangle {
                        positions: t.map(|i| world[i as usize]),
                        material,
                        uvs: match &mesh.uvs {
                            Some(uvs) => t.map(|i| uvs[i as usize]),
                            None => super::uv::planar_uvs(t.map(|i| mesh.positions[i as usize])),
                        },
                    }));
            }
        }
    }
    for &child in &node.children {
        visit(graph, child, node_to_world, default_material, path, scene)?;
    }
    path.pop();
    Ok(())
}

/// A transform must be finite and invertible: a zero scale would make a primitive
/// (and its inverse transform, which the tracers need) meaningless.
fn check_transform(m: &DMat4, path_name: &dyn Fn() -> String) -> Result<(), FlattenError> {
    if !m.to_cols_array().iter().all(|v| v.is_finite()) {
        return Err(FlattenError::NonFiniteTransform { path: path_name() });
    }
    let linear = DMat3::from_mat4(*m);
    let det = linear.determinant();
    // Compare with the product of the column lengths, so the test is scale-free: a
    // uniform scale by 1e-6 is fine, a matrix whose columns are (nearly) dependent is not.
    let norms = linear.x_axis.length() * linear.y_axis.length() * linear.z_axis.length();
    if norms == 0.0 || (det / norms).abs() < 1e-12 {
        return Err(FlattenError::SingularTransform {
            path: path_name(),
            det,
        });
    }
    Ok(())
}

fn check_camera(camera: &Camera) -> Result<(), FlattenError> {
    let view = camera.view;
    if view.length_squared() == 0.0 || !view.is_finite() {
        return Err(FlattenError::Camera(format!(
            "view direction {view} must be a non-zero vector"
        )));
    }
    if view.cross(camera.up).length_squared()
        <= 1e-20 * view.length_squared() * camera.up.length_squared()
        || !camera.up.is_finite()
    {
        return Err(FlattenError::Camera(format!(
            "up vector {} must be non-zero and not parallel to view {view}",
            camera.up
        )));
    }
    if !camera.eye.is_finite() {
        return Err(FlattenError::Camera("eye position must be finite".into()));
    }
    Ok(())
}
