//! The scene graph built by a script, in rich Rust types (f64 transforms), and the
//! requests that `gr.render` issues. Everything here lives above `pack`: the tracers
//! never see these types, only the packed arrays made from them.

/// At most [`SHORT_NAME_BYTES`] of a node or material name, for messages: a name may
/// be hundreds of MiB (it is counted against the budget), its quotes in errors are not;
/// its control characters escaped ([`crate::display_path::shown_text`]: a name holding a
/// newline or a terminal escape stays on its line and sends the terminal nothing).
pub fn short_name(name: &str) -> std::borrow::Cow<'_, str> {
    let cut = if name.len() <= SHORT_NAME_BYTES {
        name
    } else {
        let mut end = SHORT_NAME_BYTES;
        while !name.is_char_boundary(end) {
            end -= 1;
        }
        &name[..end]
    };
    let ellipsis = if cut.len() < name.len() { "…" } else { "" };
    if ellipsis.is_empty() && !cut.chars().any(char::is_control) {
        return name.into();
    }
    format!("{}{ellipsis}", crate::display_path::shown_text(cut)).into()
}

/// Longest name quoted whole by [`short_name`].
pub const SHORT_NAME_BYTES: usize = 64;

pub mod bounded;
pub mod cost;
pub mod environment;
pub mod files;
pub mod flat;
pub mod flatten;
pub mod instancing;
pub mod lua;
pub mod obj;
mod obj_stream;
pub mod options;
pub mod paths;
pub mod procedural;
pub mod texture;
pub mod uv;

use glam::{DMat4, DVec3};
use std::path::PathBuf;
use std::sync::Arc;

pub use bounded::{AaDepth, AaSamples, Bounded, ShadowSamples, TraceDepth};
pub use options::{
    AaMode, Background, DebugView, GridMode, OptionOverrides, RenderOptions, Shading,
};
pub use procedural::{Procedural, ProceduralKind, TextureRef};
pub use texture::{Texture, TextureId};

/// Index of a node in [`SceneGraph::nodes`].
pub type NodeId = usize;
/// Index of a material in [`SceneGraph::materials`].
pub type MaterialId = usize;
/// Index of a mesh in [`SceneGraph::meshes`].
pub type MeshId = usize;

/// The analytic or tessellated shape a geometry node carries, in its own object space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Primitive {
    /// Unit sphere at the origin.
    Sphere,
    /// Box from (0,0,0) to (1,1,1).
    Cube,
    /// Solid capped cylinder around the z axis: radius 1, z from 0 to 1.
    Cylinder,
    /// Solid capped cone x² + y² = z² between the planes z = zmin and z = zmax
    /// (zmin < zmax); with zmin < 0 < zmax, both nappes (a double cone meeting at the tip).
    Cone { zmin: f64, zmax: f64 },
    /// Torus centred at the origin in the XY plane (axis z): `rin` from the centre to the
    /// middle of the tube, `rout` the radius of the tube.
    Torus { rin: f64, rout: f64 },
    /// Triangle mesh (fan-triangulated polygons).
    Mesh(MeshId),
}

/// A CSG operation (`gr.csg`'s `op`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CsgOp {
    /// `'u'`: in a or in b.
    Union,
    /// `'i'`: in a and in b.
    Intersection,
    /// `'d'`: in a and not in b.
    Difference,
}

/// What a node is: a pure transform, geometry with a fixed placement of its primitive, or
/// a CSG combination of two operand nodes.
#[derive(Clone, Debug)]
pub enum NodeKind {
    Transform,
    Geometry {
        primitive: Primitive,
        /// Placement of the primitive inside the node (`nh_sphere`'s centre and radius,
        /// `nh_box`'s corner and size); identity for the hierarchical primitives. Applied
        /// before the node's own matrix, so `nh_*` nodes stay transformable.
        placement: DMat4,
    },
    /// `gr.csg(name, op, a, b)`: `a` and `b` are analytic primitive or CSG nodes, each
    /// placed by its own matrix inside this node (their children are not part of it).
    Csg {
        op: CsgOp,
        a: NodeId,
        b: NodeId,
    },
}

#[derive(Clone, Debug)]
pub struct Node {
    pub name: String,
    pub kind: NodeKind,
    /// Object-to-parent transform, built up by `scale`/`rotate`/`translate`.
    pub matrix: DMat4,
    pub children: Vec<NodeId>,
    pub material: Option<MaterialId>,
}

/// A4 Phong material plus glint's extensions.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    pub kd: [f32; 3],
    pub ks: [f32; 3],
    pub shininess: f32,
    /// Mirror colour: adds `reflection × colour seen along the reflected ray`.
    pub reflection: [f32; 3],
    /// Dielectric with this index of refraction (`set_refraction`), if any.
    pub ior: Option<f32>,
    /// Texture replacing `kd` (`set_diffuse('img.png')`, `set_diffuse(gr.checker(…))`).
    pub diffuse_map: Option<TextureRef>,
    /// Texture replacing `ks` (`set_specular('img.png')`).
    pub specular_map: Option<TextureRef>,
    /// Height field of the bump map (`set_bump('height.png', strength)`, or a
    /// procedural's pattern).
    pub bump_map: Option<TextureRef>,
    /// Bump strength: the normal tilts by strength × the height's slope per texture unit.
    pub bump_strength: f32,
}

impl Default for Material {
    /// The defaults of `gr.material(name)`: kd 0.5 grey, ks 0, shininess 1, no mirror.
    fn default() -> Self {
        Material {
            name: String::from("default"),
            kd: [0.5; 3],
            ks: [0.0; 3],
            shininess: 1.0,
            reflection: [0.0; 3],
            ior: None,
            diffuse_map: None,
            specular_map: None,
            bump_map: None,
            bump_strength: 0.0,
        }
    }
}

/// A triangle mesh in its own object space. Polygons are already fan-triangulated.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub name: String,
    pub positions: Vec<DVec3>,
    pub triangles: Vec<[u32; 3]>,
    /// Per-vertex UVs (inline `uvs` table or OBJ `vt` resolved per vertex), if given.
    pub uvs: Option<Vec<[f32; 2]>>,
    /// Per-vertex unit normals (inline `normals` table or OBJ `vn` resolved per vertex),
    /// if given; a zero vector marks a vertex without one (its triangles are flat).
    pub normals: Option<Vec<DVec3>>,
}

/// A light in world space: a point light at `position`, or, with `area`, a parallelogram
/// centred there (`colour` is then its total over the area).
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    pub position: DVec3,
    pub colour: [f32; 3],
    /// Attenuation 1/(c0 + c1·d + c2·d²).
    pub falloff: [f32; 3],
    /// `None` for a point light.
    pub area: Option<AreaLight>,
}

/// The shape of an area light (`gr.area_light`): edge vectors `u`, `v` of the
/// parallelogram centred at the light's position, and n of its n×n shadow samples.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AreaLight {
    pub u: DVec3,
    pub v: DVec3,
    pub samples: ShadowSamples,
}

/// Pinhole camera as `gr.render` gives it: `view` is a direction (not normalised), `up`
/// need not be perpendicular to it, `fov_deg` is the vertical field of view.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    pub eye: DVec3,
    pub view: DVec3,
    pub up: DVec3,
    pub fov_deg: f64,
}

/// Order in which `scale`/`rotate`/`translate` compose with a node's matrix.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum TransformOrder {
    /// M = Op·M: calls act on the object in the order written (Fall 2015 and later).
    #[default]
    Pre,
    /// M = M·Op: OpenGL style (A4 scenes up to Summer 2015).
    Post,
}

impl TransformOrder {
    /// Composes `op` into `matrix` in this order.
    pub fn apply(self, matrix: DMat4, op: DMat4) -> DMat4 {
        match self {
            TransformOrder::Pre => op * matrix,
            TransformOrder::Post => matrix * op,
        }
    }
}

/// Everything a script has built so far. Nodes, materials and meshes live in arenas and
/// refer to each other by index, so a node may have several parents (instancing).
#[derive(Clone, Debug, Default)]
pub struct SceneGraph {
    pub nodes: Vec<Node>,
    pub materials: Vec<Material>,
    pub meshes: Vec<Arc<Mesh>>,
    /// Images of texture and bump maps (shared, not copied, by each render's scene).
    pub textures: Vec<Arc<Texture>>,
}

/// One `gr.render` call: what to render, where, and how.
#[derive(Clone, Debug)]
pub struct RenderRequest {
    pub root: NodeId,
    /// Output path as the script gave it (resolved against the current directory).
    pub output: PathBuf,
    pub width: u32,
    pub height: u32,
    pub camera: Camera,
    pub ambient: [f32; 3],
    pub lights: Vec<Light>,
    pub options: RenderOptions,
    /// `file:line` of the `gr.render` call, for messages.
    pub location: String,
    /// Bytes of the script's memory budget left for flattening, packing and rendering
    /// this request (flattening refuses a scene that would need more).
    pub memory_left: u64,
}
