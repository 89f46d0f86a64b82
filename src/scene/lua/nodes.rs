//! The `gr` calls that make nodes: transform nodes (`gr.node`, `gr.joint`), the
//! primitives and CSG nodes, each counted against the memory budget before it is made.
//! `gr.mesh` (in `meshes`) makes its node here too.

use super::args::{lossy_prefix, Args};
use super::budget::{charge, grown};
use super::handles::NodeHandle;
use super::with_state;
use crate::scene::short_name;
use crate::scene::{CsgOp, Node, NodeId, NodeKind, Primitive};
use glam::{DMat4, DVec3};
use mlua::Value;

/// Bytes a node holds in Rust besides its name: its slot in the node vector and in the
/// parents' vector, with their growth, and the allocator's block for its parent list.
const NODE_BYTES: u64 =
    grown(std::mem::size_of::<Node>()) + grown(std::mem::size_of::<Vec<NodeId>>()) + 64;

/// Argument 1, a node's name, with the node it names counted against the memory budget
/// before the name is copied out of Lua.
pub(super) fn node_name(a: &Args) -> mlua::Result<String> {
    let len = match a.get(1) {
        Value::String(s) => s.as_bytes().len(),
        _ => 32,
    };
    charge(a, NODE_BYTES + len as u64, "the node and its name")?;
    a.string(1, "name")
}

/// Adds a node (counted by [`node_name`]).
pub(super) fn new_node(a: &Args, name: String, kind: NodeKind) -> mlua::Result<NodeHandle> {
    Ok(with_state(a.lua, |s| {
        s.graph.nodes.push(Node {
            name,
            kind,
            matrix: DMat4::IDENTITY,
            children: Vec::new(),
            material: None,
        });
        NodeHandle(s.graph.nodes.len() - 1)
    }))
}

pub(super) fn geometry(primitive: Primitive, placement: DMat4) -> NodeKind {
    NodeKind::Geometry {
        primitive,
        placement,
    }
}

pub(super) fn transform_node(a: &Args) -> mlua::Result<NodeHandle> {
    let name = node_name(a)?;
    new_node(a, name, NodeKind::Transform)
}

pub(super) fn primitive(a: &Args, p: Primitive) -> mlua::Result<NodeHandle> {
    let name = node_name(a)?;
    new_node(a, name, geometry(p, DMat4::IDENTITY))
}

/// `gr.cone(name, zmin, zmax)`: the solid cone x² + y² ≤ z² between z = zmin and z = zmax.
/// The bounds must stay distinct (and finite) in f32, which the tracers use.
pub(super) fn cone(a: &Args) -> mlua::Result<NodeHandle> {
    let name = node_name(a)?;
    let zmin = a.number(2, "zmin")?;
    if !(zmin as f32).is_finite() {
        return Err(a.bad(2, "zmin", "a finite number (within f32 range)"));
    }
    let zmax = a.number(3, "zmax")?;
    if !(zmax as f32).is_finite() {
        return Err(a.bad(3, "zmax", "a finite number (within f32 range)"));
    }
    if (zmin as f32) >= (zmax as f32) {
        return Err(a.bad(3, "zmax", &format!("a number greater than zmin ({zmin})")));
    }
    new_node(
        a,
        name,
        geometry(Primitive::Cone { zmin, zmax }, DMat4::IDENTITY),
    )
}

/// `gr.nh_sphere(name, centre, radius)`: the unit sphere scaled by `radius` and moved to
/// `centre`.
pub(super) fn nh_sphere(a: &Args) -> mlua::Result<NodeHandle> {
    placed_primitive(a, Primitive::Sphere, "centre", "radius")
}

/// `gr.nh_box(name, corner, size)`: the unit cube scaled by `size` and moved to `corner`.
pub(super) fn nh_box(a: &Args) -> mlua::Result<NodeHandle> {
    placed_primitive(a, Primitive::Cube, "corner", "size")
}

/// The non-hierarchical primitives' form: `(name, point, scale)` places the unit
/// primitive, scaled uniformly by the positive `scale` and moved to the `point`; the
/// names are the arguments' names in messages.
fn placed_primitive(
    a: &Args,
    primitive: Primitive,
    point_name: &str,
    scale_name: &str,
) -> mlua::Result<NodeHandle> {
    let name = node_name(a)?;
    let point = a.vec3(2, point_name)?;
    let scale = a.positive(3, scale_name)?;
    let placement = DMat4::from_translation(point) * DMat4::from_scale(DVec3::splat(scale));
    new_node(a, name, geometry(primitive, placement))
}

/// `gr.torus(name, rin, rout)`: both radii finite and positive. `rout > rin` is allowed
/// and gives a self-intersecting "spindle" torus (an apple with a lemon inside, both
/// sheets drawn; `rout == rin` is the horn torus).
pub(super) fn torus(a: &Args) -> mlua::Result<NodeHandle> {
    let name = node_name(a)?;
    let rin = a.positive(2, "rin")?;
    let rout = a.positive(3, "rout")?;
    new_node(
        a,
        name,
        geometry(Primitive::Torus { rin, rout }, DMat4::IDENTITY),
    )
}

/// `gr.csg(name, op, a, b)`: `op` is `'u'` (union), `'i'` (intersection) or `'d'`
/// (difference, a minus b), any case; `a` and `b` are analytic primitive nodes (sphere,
/// cube, nh_sphere, nh_box, cylinder, cone, torus) or CSG nodes. Meshes and transform
/// nodes are refused here, naming the argument: a mesh has no inside the tracers could
/// classify a ray against, and a transform node's children are a group, not one solid
/// (the operand's own transforms place it inside the CSG node).
pub(super) fn csg(a: &Args) -> mlua::Result<NodeHandle> {
    let name = node_name(a)?;
    let op = match a.get(2) {
        Value::String(s) => match lossy_prefix(s, 8).to_ascii_lowercase().as_str() {
            "u" => Some(CsgOp::Union),
            "i" => Some(CsgOp::Intersection),
            "d" => Some(CsgOp::Difference),
            _ => None,
        },
        _ => None,
    }
    .ok_or_else(|| {
        a.bad(
            2,
            "op",
            "'u' (union), 'i' (intersection) or 'd' (difference, a minus b)",
        )
    })?;
    let mut operands = [0; 2];
    for (slot, (n, arg)) in operands.iter_mut().zip([(3, "a"), (4, "b")]) {
        let id = a.node(n, arg)?;
        let refused = with_state(a.lua, |s| {
            let node = &s.graph.nodes[id];
            match node.kind {
                NodeKind::Geometry {
                    primitive: Primitive::Mesh(_),
                    ..
                } => Some(format!(
                    "mesh node '{}' (meshes cannot be CSG operands)",
                    short_name(&node.name)
                )),
                NodeKind::Transform => Some(format!(
                    "transform node '{}' (a transform node is a group, not a solid: use the primitive itself, with its own transforms)",
                    short_name(&node.name)
                )),
                _ => None,
            }
        });
        if let Some(got) = refused {
            return Err(a.error(format!(
                "argument {n} ({arg}) must be a primitive or CSG node (sphere, cube, nh_sphere, nh_box, cylinder, cone, torus or csg), got {got}"
            )));
        }
        *slot = id;
    }
    let [na, nb] = operands;
    let handle = new_node(a, name, NodeKind::Csg { op, a: na, b: nb })?;
    with_state(a.lua, |s| {
        s.add_parent(na, handle.0);
        s.add_parent(nb, handle.0);
    });
    Ok(handle)
}
