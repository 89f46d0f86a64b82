//! The userdata the `gr` calls return, and their methods: `node:add_child`,
//! `set_material`, `scale`, `translate`, `rotate`; `material:set_diffuse`, `set_specular`,
//! `set_shininess`, `set_reflection`, `set_refraction` (texture forms and `set_bump` in
//! `maps`).
//!
//! Userdata carry only an index into the [`SceneGraph`](crate::scene::SceneGraph) arenas
//! (or a small value for lights), so a node can be added under several parents and a
//! material changed after it was set. Methods return their receiver so calls chain.

use super::args::Args;
use super::with_state;
use crate::scene::{Light, Material, Node, NodeId, NodeKind};
use glam::{DMat4, DVec3};
use mlua::{MetaMethod, MultiValue, UserData, UserDataMethods};

/// A node made by `gr.node`, `gr.sphere`, … (index into `SceneGraph::nodes`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct NodeHandle(pub NodeId);

/// A material made by `gr.material` (index into `SceneGraph::materials`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct MaterialHandle(pub usize);

/// A light made by `gr.light`; lights live in `gr.render`'s list, not in the graph.
#[derive(Clone, Debug)]
pub(crate) struct LightHandle(pub Light);

impl UserData for NodeHandle {
    fn add_methods<M: UserDataMethods<Self>>(methods: &mut M) {
        macro_rules! method {
            ($name:literal, $f:expr) => {
                methods.add_function($name, |lua, args: MultiValue| {
                    let a = Args::method(lua, concat!("node:", $name), args);
                    a.receiver::<NodeHandle>("node")?;
                    $f(&a)?;
                    Ok(a.receiver_value())
                });
            };
        }
        method!("add_child", add_child);
        method!("set_material", set_material);
        method!("scale", |a: &Args| {
            let v = [(1, "x"), (2, "y"), (3, "z")].map(|(n, name)| (n, name, a.number(n, name)));
            let mut f = [0.0; 3];
            for (k, (n, name, x)) in v.into_iter().enumerate() {
                let x = x?;
                if x == 0.0 {
                    return Err(a.bad(
                        n,
                        name,
                        "a non-zero scale factor (a zero factor makes the transform singular)",
                    ));
                }
                f[k] = x;
            }
            compose(a, DMat4::from_scale(DVec3::from_array(f)))
        });
        method!("translate", |a: &Args| {
            let t = DVec3::new(a.number(1, "x")?, a.number(2, "y")?, a.number(3, "z")?);
            compose(a, DMat4::from_translation(t))
        });
        method!("rotate", |a: &Args| {
            let axis = a.string(1, "axis")?;
            let deg = a.number(2, "angle")?;
            let r = deg.to_radians();
            let op = match axis.to_ascii_lowercase().as_str() {
                "x" => DMat4::from_rotation_x(r),
                "y" => DMat4::from_rotation_y(r),
                "z" => DMat4::from_rotation_z(r),
                _ => return Err(a.bad(1, "axis", "'x', 'y' or 'z' (any case)")),
            };
            compose(a, op)
        });
        methods.add_meta_function(MetaMethod::ToString, |lua, this: mlua::AnyUserData| {
            let id = this.borrow::<NodeHandle>()?.0;
            Ok(with_state(lua, |s| {
                format!("node '{}'", s.graph.nodes[id].name)
            }))
        });
    }
}

/// Applies `op` to the receiver's matrix in the current transform order.
fn compose(a: &Args, op: DMat4) -> mlua::Result<()> {
    let id = a.receiver::<NodeHandle>("node")?.0;
    with_state(a.lua, |s| {
        let node = &mut s.graph.nodes[id];
        node.matrix = s.order.apply(node.matrix, op);
    });
    Ok(())
}

fn add_child(a: &Args) -> mlua::Result<()> {
    let parent = a.receiver::<NodeHandle>("node")?.0;
    let child = a.node(1, "child")?;
    let cycle = with_state(a.lua, |s| {
        reaches(&s.graph.nodes, child, parent).then(|| {
            (
                s.graph.nodes[child].name.clone(),
                s.graph.nodes[parent].name.clone(),
            )
        })
    });
    if let Some((c, p)) = cycle {
        return Err(a.bad_in(
            1,
            "child",
            format!("adding node '{c}' under node '{p}' would make a cycle"),
        ));
    }
    with_state(a.lua, |s| s.graph.nodes[parent].children.push(child));
    Ok(())
}

/// Whether `to` is `from` or one of its descendants (children, or a CSG node's operands).
fn reaches(nodes: &[Node], from: NodeId, to: NodeId) -> bool {
    let mut stack = vec![from];
    let mut seen = vec![false; nodes.len()];
    while let Some(n) = stack.pop() {
        if n == to {
            return true;
        }
        if !std::mem::replace(&mut seen[n], true) {
            stack.extend(&nodes[n].children);
            if let NodeKind::Csg { a, b, .. } = nodes[n].kind {
                stack.extend([a, b]);
            }
        }
    }
    false
}

fn set_material(a: &Args) -> mlua::Result<()> {
    let id = a.receiver::<NodeHandle>("node")?.0;
    let m = a.material(1, "material")?;
    let err = with_state(a.lua, |s| {
        let node = &mut s.graph.nodes[id];
        match node.kind {
            // On a CSG node: the default of its operands that have none.
            NodeKind::Geometry { .. } | NodeKind::Csg { .. } => {
                node.material = Some(m);
                None
            }
            NodeKind::Transform => Some(node.name.clone()),
        }
    });
    match err {
        None => Ok(()),
        Some(name) => Err(a.error(format!(
            "node '{name}' is a transform node; materials go on geometry nodes (gr.sphere, gr.cube, gr.mesh, …) and CSG nodes"
        ))),
    }
}

impl UserData for MaterialHandle {
    fn add_methods<M: UserDataMethods<Self>>(methods: &mut M) {
        macro_rules! method {
            ($name:literal, $f:expr) => {
                methods.add_function($name, |lua, args: MultiValue| {
                    let a = Args::method(lua, concat!("material:", $name), args);
                    let id = a.receiver::<MaterialHandle>("material")?.0;
                    let edit = $f(&a)?;
                    with_state(lua, |s| edit(&mut s.graph.materials[id]));
                    Ok(a.receiver_value())
                });
            };
        }
        method!("set_diffuse", super::maps::set_diffuse);
        method!("set_specular", super::maps::set_specular);
        method!("set_bump", super::maps::set_bump);
        method!("set_reflection", |a: &Args| {
            a.colour_args(1, true)
                .map(|c| move |m: &mut Material| m.reflection = c)
        });
        method!("set_refraction", |a: &Args| {
            a.positive(1, "ior").and_then(|ior| {
                let ior = ior as f32;
                if ior.is_finite() && ior > 0.0 {
                    Ok(move |m: &mut Material| m.ior = Some(ior))
                } else {
                    // Positive in f64 but 0 or ∞ in f32 (1e-50, 1e50).
                    Err(a.bad(1, "ior", "a positive number within f32 range"))
                }
            })
        });
        method!("set_shininess", |a: &Args| {
            a.non_negative(1, "shininess")
                .map(|p| move |m: &mut Material| m.shininess = p as f32)
        });
        methods.add_meta_function(MetaMethod::ToString, |lua, this: mlua::AnyUserData| {
            let id = this.borrow::<MaterialHandle>()?.0;
            Ok(with_state(lua, |s| {
                format!("material '{}'", s.graph.materials[id].name)
            }))
        });
    }
}

impl UserData for LightHandle {
    fn add_methods<M: UserDataMethods<Self>>(methods: &mut M) {
        methods.add_meta_method(MetaMethod::ToString, |_, this, ()| {
            Ok(format!(
                "light at ({}, {}, {})",
                this.0.position.x, this.0.position.y, this.0.position.z
            ))
        });
    }
}
