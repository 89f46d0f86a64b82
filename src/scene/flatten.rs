//! SceneGraph → world-space [`FlatScene`]: walks the DAG from the render root, composing
//! f64 matrices, so instancing (a node under several parents) yields one object per path.
//! Analytic primitives keep their object-to-world transform; each path to a mesh node
//! becomes a [`MeshInstance`], and [`super::instancing`] stores each mesh once (in its
//! own space when several instances share it, baked into world space when one uses it).
//! A CSG node becomes one [`CsgObject`]: its tree as a post-order program whose leaves are
//! primitive objects with their own object-to-world transforms and materials.

use super::cost::{scene_cost, MAX_PATHS, PIXEL_BYTES, TEXEL_BYTES};
pub use super::flat::{
    csg_worst_case, CsgObject, CsgStep, FlatScene, FlattenError, MeshInstance, MeshTriangle,
    Object, ObjectKind, SceneMesh, Triangle, MAX_NODE_DEPTH, MAX_PIXELS,
};
use super::{Camera, Material, MaterialId, NodeId, NodeKind, Primitive, RenderRequest, SceneGraph};
use crate::constants::{CSG_EVENT_CAPACITY, CSG_LIST_CAPACITY, CSG_MAX_DEPTH};
use glam::{DMat3, DMat4, DVec3};

/// Flattens the graph below `request.root` into world space.
pub fn flatten(graph: &SceneGraph, request: &RenderRequest) -> Result<FlatScene, FlattenError> {
    check_camera(&request.camera)?;
    check_cost(graph, request)?;
    let mut materials = graph.materials.clone();
    let default_material = materials.len();
    materials.push(Material::default());
    let mut scene = FlatScene {
        objects: Vec::new(),
        csg: Vec::new(),
        triangles: Vec::new(),
        meshes: Vec::new(),
        mesh_instances: Vec::new(),
        materials,
        textures: graph.textures.clone(),
        lights: request.lights.clone(),
        // Directions scaled to unit max-norm, so that normalising them downstream cannot
        // overflow (a 1e200 view) or underflow (1e-200).
        camera: Camera {
            view: unit_max_norm(request.camera.view),
            up: unit_max_norm(request.camera.up),
            ..request.camera.clone()
        },
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
    super::instancing::store_meshes(graph, &mut scene);
    Ok(scene)
}

fn visit(
    graph: &SceneGraph,
    id: NodeId,
    parent_to_world: DMat4,
    default_material: MaterialId,
    path: &mut Vec<NodeId>,
    scene: &mut FlatScene,
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
        let path = path
            .iter()
            .map(|&n| super::short_name(&graph.nodes[n].name));
        return Err(FlattenError::TooDeep {
            path: path.collect::<Vec<_>>().join("/"),
        });
    }
    let node_to_world = parent_to_world * node.matrix;
    match &node.kind {
        NodeKind::Geometry {
            primitive,
            placement,
        } => {
            let object_to_world = node_to_world * *placement;
            check_transform(&object_to_world, &path_name)?;
            let material = node.material.unwrap_or(default_material);
            match primitive {
                // The graph's mesh id for now; `store_meshes` renumbers.
                Primitive::Mesh(mesh_id) => scene.mesh_instances.push(MeshInstance {
                    name: path_name(),
                    mesh: *mesh_id,
                    object_to_world,
                    material,
                }),
                analytic => scene.objects.push(Object {
                    name: path_name(),
                    kind: object_kind(analytic).expect("analytic primitive"),
                    object_to_world,
                    material,
                }),
            }
        }
        NodeKind::Csg { .. } => {
            let name = path_name();
            let mut program = Vec::new();
            csg_program(
                graph,
                id,
                node_to_world,
                default_material,
                (&name, &name),
                1,
                &mut program,
            )?;
            let (events, lists) = csg_worst_case(&program);
            if lists > CSG_LIST_CAPACITY {
                // Unreachable within the depth limit; kept so the bound is checked here.
                return Err(FlattenError::CsgTooDeep {
                    at: name.clone(),
                    path: name,
                });
            }
            if events > CSG_EVENT_CAPACITY {
                return Err(FlattenError::CsgTooManyIntervals { path: name, events });
            }
            scene.csg.push(CsgObject {
                name,
                program,
                material: node.material.unwrap_or(default_material),
            });
        }
        NodeKind::Transform => {}
    }
    for &child in &node.children {
        visit(graph, child, node_to_world, default_material, path, scene)?;
    }
    path.pop();
    Ok(())
}

/// The object kind of an analytic primitive (None for meshes).
fn object_kind(primitive: &Primitive) -> Option<ObjectKind> {
    Some(match *primitive {
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
        Primitive::Mesh(_) => return None,
    })
}

/// Appends the post-order program of CSG node `id` (placed in the world by `to_world`,
/// `depth` levels deep) to `out`: operand a, operand b, the operation. An operand's
/// material defaults to the nearest enclosing CSG node's, then to `default_material`.
/// `paths` are the CSG object's and this node's names.
fn csg_program(
    graph: &SceneGraph,
    id: NodeId,
    to_world: DMat4,
    default_material: MaterialId,
    paths: (&str, &str),
    depth: u32,
    out: &mut Vec<CsgStep>,
) -> Result<(), FlattenError> {
    let (top, path) = paths;
    let node = &graph.nodes[id];
    let NodeKind::Csg { op, a, b } = node.kind else {
        unreachable!("csg_program is called on CSG nodes")
    };
    if depth > CSG_MAX_DEPTH {
        return Err(FlattenError::CsgTooDeep {
            path: top.into(),
            at: path.into(),
        });
    }
    let default_material = node.material.unwrap_or(default_material);
    for operand in [a, b] {
        let child = &graph.nodes[operand];
        let child_path = format!("{path}/{}", child.name);
        if !child.children.is_empty() {
            return Err(FlattenError::CsgOperandHasChildren {
                path: path.into(),
                operand: child.name.clone(),
            });
        }
        let child_to_world = to_world * child.matrix;
        match &child.kind {
            NodeKind::Csg { .. } => csg_program(
                graph,
                operand,
                child_to_world,
                default_material,
                (top, &child_path),
                depth + 1,
                out,
            )?,
            NodeKind::Geometry {
                primitive,
                placement,
            } => {
                let bad = |what| FlattenError::CsgBadOperand {
                    path: path.into(),
                    operand: child.name.clone(),
                    what,
                };
                let kind = object_kind(primitive).ok_or_else(|| bad("mesh"))?;
                let object_to_world = child_to_world * *placement;
                check_transform(&object_to_world, &|| child_path.clone())?;
                out.push(CsgStep::Leaf(Object {
                    name: child_path.clone(),
                    kind,
                    object_to_world,
                    material: child.material.unwrap_or(default_material),
                }));
            }
            NodeKind::Transform => {
                return Err(FlattenError::CsgBadOperand {
                    path: path.into(),
                    operand: child.name.clone(),
                    what: "transform node",
                })
            }
        }
    }
    out.push(CsgStep::Op(op));
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

/// Counts what the render will make (see [`scene_cost`]) and refuses it before anything
/// is built when it has too many paths or pixels, or would not fit the memory budget.
fn check_cost(graph: &SceneGraph, request: &RenderRequest) -> Result<(), FlattenError> {
    let pixels = u64::from(request.width) * u64::from(request.height);
    if pixels > MAX_PIXELS {
        return Err(FlattenError::TooManyPixels {
            width: request.width,
            height: request.height,
            pixels,
            limit: MAX_PIXELS,
        });
    }
    let cost = scene_cost(graph, request.root)?;
    if cost.paths > MAX_PATHS {
        return Err(FlattenError::TooManyPaths {
            paths: cost.paths,
            limit: MAX_PATHS,
        });
    }
    let texels: u64 = graph
        .textures
        .iter()
        .map(|t| u64::from(t.width) * u64::from(t.height))
        .sum();
    let needed = cost
        .bytes()
        .saturating_add(pixels * PIXEL_BYTES)
        .saturating_add(texels * TEXEL_BYTES);
    if needed > request.memory_left {
        return Err(FlattenError::OverBudget {
            needed_mib: needed.div_ceil(1 << 20),
            left_mib: request.memory_left >> 20,
            objects: cost.objects,
            triangles: cost.triangles,
            pixels,
        });
    }
    Ok(())
}

/// `v` scaled so that its largest component is ±1 (zero stays zero): directions can be
/// compared without their squared lengths overflowing (1e200) or underflowing (1e-200).
pub fn unit_max_norm(v: DVec3) -> DVec3 {
    let m = v.abs().max_element();
    if m > 0.0 && m.is_finite() {
        v / m
    } else {
        v
    }
}

/// sin² of the smallest angle accepted between the camera's `view` and `up`.
pub const CAMERA_PARALLEL_SIN2: f64 = 1e-20;

/// Whether directions `a` and `b` (finite) are zero or parallel: sin² of their angle at
/// most `sin2`. Scale-free: neither huge nor tiny vectors overflow or underflow it.
pub fn parallel_or_zero(a: DVec3, b: DVec3, sin2: f64) -> bool {
    let (a, b) = (unit_max_norm(a), unit_max_norm(b));
    a.cross(b).length_squared() <= sin2 * a.length_squared() * b.length_squared()
}

fn check_camera(camera: &Camera) -> Result<(), FlattenError> {
    let view = camera.view;
    if view == DVec3::ZERO || !view.is_finite() {
        return Err(FlattenError::Camera(format!(
            "view direction {view} must be a non-zero vector"
        )));
    }
    if !camera.up.is_finite() || parallel_or_zero(view, camera.up, CAMERA_PARALLEL_SIN2) {
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
