//! The flattened, world-space scene ([`FlatScene`]) that `flatten` produces and packing
//! reads: objects, CSG programs, meshes and their instances, the limits that bound them,
//! and the errors flattening reports. Plain data, so `flatten`, `cost` and `instancing`
//! all depend on it and it on none of them.

use super::{Camera, CsgOp, Light, Material, MaterialId, Mesh, RenderOptions};
use crate::constants::{CSG_EVENT_CAPACITY, CSG_MAX_DEPTH};
use glam::{DMat3, DMat4, DVec3};
use std::sync::Arc;

/// Deepest node nesting accepted; deeper means a cycle (a node added under itself).
pub const MAX_NODE_DEPTH: usize = 256;

/// Most pixels one image may have (a typo guard that also bounds the film's memory).
pub const MAX_PIXELS: u64 = 1 << 27;

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

/// One step of a CSG object's post-order program: push a leaf's inside intervals, or
/// combine the top two lists (a below b) by an operation.
#[derive(Clone, Debug)]
pub enum CsgStep {
    /// An analytic primitive with its own object-to-world transform (the CSG node's
    /// placement composed with the operand's) and its resolved material.
    Leaf(Object),
    Op(CsgOp),
}

/// A CSG node in world space: one solid, one grid item.
#[derive(Clone, Debug)]
pub struct CsgObject {
    pub name: String,
    /// Post-order: leaves push, operations pop two and push one; one list remains.
    pub program: Vec<CsgStep>,
    /// The CSG node's material (or the default): the default of its operands.
    pub material: MaterialId,
}

impl ObjectKind {
    /// Most inside intervals a line can have through this primitive: one for the convex
    /// solids, two for a double cone (both nappes) and a torus (four crossings).
    pub fn max_intervals(self) -> u32 {
        match self {
            ObjectKind::Sphere | ObjectKind::Cube | ObjectKind::Cylinder => 1,
            ObjectKind::Cone { zmin, zmax } => {
                if zmin < 0.0 && zmax > 0.0 {
                    2
                } else {
                    1
                }
            }
            ObjectKind::Torus { .. } => 2,
        }
    }
}

/// The worst case of evaluating `program` (see `tracer::geometry::csg`): the most interval ends held
/// at once (every live list plus the one being built, each at its most) and the most
/// live lists. Both tracers evaluate in exactly this order, so these bound their use.
pub fn csg_worst_case(program: &[CsgStep]) -> (u32, u32) {
    let mut lists: Vec<u32> = Vec::new();
    let (mut peak_events, mut peak_lists) = (0, 0);
    for step in program {
        let used: u32 = lists.iter().sum();
        match step {
            CsgStep::Leaf(o) => {
                let events = 2 * o.kind.max_intervals();
                peak_events = peak_events.max(used + events);
                lists.push(events);
            }
            CsgStep::Op(_) => {
                // Every result boundary is one of the operands' (union, intersection and
                // difference alike): at most |a| + |b| ends, built after both.
                let b = lists.pop().unwrap_or(0);
                let a = lists.pop().unwrap_or(0);
                peak_events = peak_events.max(used + a + b);
                lists.push(a + b);
            }
        }
        peak_lists = peak_lists.max(lists.len() as u32);
    }
    (peak_events, peak_lists)
}

/// One world-space triangle with its own material: loose triangles that tests and
/// benchmarks build directly (packing gathers them into one world-space mesh per
/// material); scripts' meshes arrive as [`SceneMesh`]es instead.
#[derive(Clone, Debug)]
pub struct Triangle {
    pub positions: [DVec3; 3],
    pub material: MaterialId,
    /// The corners' UVs: the mesh's own, else the planar projection of `scene::uv`.
    pub uvs: [[f32; 2]; 3],
}

/// A triangle of a [`SceneMesh`], in the mesh's space (its instances give the material).
#[derive(Clone, Debug)]
pub struct MeshTriangle {
    pub positions: [DVec3; 3],
    /// The corners' UVs: the mesh's own, else the planar projection of `scene::uv`.
    pub uvs: [[f32; 2]; 3],
    /// The corners' normals in the mesh's space, for smooth shading (see
    /// `scene::instancing::stored_normals`); all zero when the triangle is flat (its mesh
    /// has no normals, or a corner lacks one).
    pub normals: [[f32; 3]; 3],
}

/// A mesh as the tracers store it: once, however many instances use it. A view of the
/// graph's mesh (shared, not copied: a big mesh is held once through flattening and
/// packing) through the map from its space to the stored space; its triangles are made
/// one at a time ([`SceneMesh::triangle`]) as packing reads them.
#[derive(Clone, Debug)]
pub struct SceneMesh {
    pub name: String,
    source: Arc<Mesh>,
    to_stored: DMat4,
    /// The normals' map (`scene::instancing::stored_normal_matrix`); None without normals
    /// or under flat shading.
    normal_matrix: Option<DMat3>,
}

impl SceneMesh {
    /// `source` seen through `to_stored`, its normals through `normal_matrix`.
    pub fn new(source: Arc<Mesh>, to_stored: DMat4, normal_matrix: Option<DMat3>) -> SceneMesh {
        SceneMesh {
            name: source.name.clone(),
            source,
            to_stored,
            normal_matrix,
        }
    }

    /// How many triangles it has.
    pub fn len(&self) -> usize {
        self.source.triangles.len()
    }

    /// Whether its triangles carry the mesh's normals (smooth shading).
    pub fn has_normals(&self) -> bool {
        self.normal_matrix.is_some()
    }

    /// Whether it has no triangle.
    pub fn is_empty(&self) -> bool {
        self.source.triangles.is_empty()
    }

    /// Triangle `i`'s corners in the stored space (as [`SceneMesh::triangle`] gives them).
    pub fn positions(&self, i: usize) -> [DVec3; 3] {
        let mesh = &*self.source;
        mesh.triangles[i].map(|v| self.to_stored.transform_point3(mesh.positions[v as usize]))
    }

    /// Triangle `i` in the stored space: its corners mapped one by one as the mesh's
    /// vertices would be (the same f64 operations, so the same values however often a
    /// vertex is shared), the mesh's UVs or the planar projection of its object-space
    /// corners, and its normals when every corner has one.
    pub fn triangle(&self, i: usize) -> MeshTriangle {
        let mesh = &*self.source;
        let t = mesh.triangles[i];
        let object = t.map(|v| mesh.positions[v as usize]);
        MeshTriangle {
            positions: self.positions(i),
            uvs: match &mesh.uvs {
                Some(uvs) => t.map(|v| uvs[v as usize]),
                None => super::uv::planar_uvs(object),
            },
            normals: match (&mesh.normals, self.normal_matrix) {
                (Some(normals), Some(m)) => {
                    let corners = t.map(|v| m * normals[v as usize]);
                    if corners.contains(&DVec3::ZERO) {
                        [[0.0; 3]; 3]
                    } else {
                        corners.map(|n| n.as_vec3().to_array())
                    }
                }
                _ => [[0.0; 3]; 3],
            },
        }
    }

    /// Its triangles in order ([`SceneMesh::triangle`]).
    pub fn triangles(&self) -> impl ExactSizeIterator<Item = MeshTriangle> + '_ {
        (0..self.len()).map(|i| self.triangle(i))
    }
}

/// One placement of a [`SceneMesh`] (index `mesh` in `FlatScene::meshes`).
#[derive(Clone, Debug)]
pub struct MeshInstance {
    pub name: String,
    pub mesh: usize,
    pub object_to_world: DMat4,
    pub material: MaterialId,
}

/// The flattened scene of one `gr.render` call.
#[derive(Clone, Debug)]
pub struct FlatScene {
    pub objects: Vec<Object>,
    /// CSG objects (grid items after `objects`).
    pub csg: Vec<CsgObject>,
    /// Loose world-space triangles (see [`Triangle`]); empty for scripts.
    pub triangles: Vec<Triangle>,
    /// Meshes, each stored once (see `scene::instancing`).
    pub meshes: Vec<SceneMesh>,
    /// Mesh instances (grid items after the CSG objects).
    pub mesh_instances: Vec<MeshInstance>,
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
    #[error(
        "CSG node '{path}' nests CSG operations deeper than {CSG_MAX_DEPTH} levels (at '{at}')"
    )]
    CsgTooDeep { path: String, at: String },
    #[error("CSG node '{path}': operand '{operand}' has children; an operand is only its own solid (add the CSG node, not its operands, under other nodes)")]
    CsgOperandHasChildren { path: String, operand: String },
    #[error("CSG node '{path}': operand '{operand}' must be a primitive or CSG node (sphere, cube, nh_sphere, nh_box, cylinder, cone, torus or csg), not a {what}")]
    CsgBadOperand {
        path: String,
        operand: String,
        what: &'static str,
    },
    #[error("the scene graph below the render root has {paths} paths (node visits) to flatten, over glint's limit of {limit}: instances nest too many times")]
    TooManyPaths { paths: u64, limit: u64 },
    #[error("the image is {width}×{height} = {pixels} pixels, over glint's limit of {limit} pixels (gr.render's size, or --width/--height)")]
    TooManyPixels {
        width: u32,
        height: u32,
        pixels: u64,
        limit: u64,
    },
    #[error("the scene would take about {needed_mib} MiB to build and render ({objects} objects, {triangles} triangles, {pixels} pixels), over the {left_mib} MiB left of the memory limit (--memory-limit MIB)")]
    OverBudget {
        needed_mib: u64,
        left_mib: u64,
        objects: u64,
        triangles: u64,
        pixels: u64,
    },
    #[error("CSG node '{path}' may hold up to {events} interval ends per ray, above glint's fixed capacity of {CSG_EVENT_CAPACITY} (about {} primitives, fewer with tori and double cones): split it into several CSG objects", CSG_EVENT_CAPACITY / 4)]
    CsgTooManyIntervals { path: String, events: u32 },
}
