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
use crate::scene::{short_name, Light, Material, NodeId, NodeKind};
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
                    super::ensure_live(lua)?;
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
            let axis = a.text(1, "axis")?;
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
                format!("node '{}'", short_name(&s.graph.nodes[id].name))
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

/// Most nodes the cycle checks of one script may visit in all (about a second): each
/// check costs about the smaller of the child's subtree and the parent's ancestors, so
/// only graphs that add large subtrees under nodes with many ancestors, over and over,
/// reach it.
pub const MAX_CYCLE_CHECK_VISITS: u64 = 1 << 26;

/// Bytes one `add_child` link holds: the child in the parent's list and the parent in
/// the child's, with vector growth.
const LINK_BYTES: u64 = super::grown(2 * std::mem::size_of::<NodeId>());

fn add_child(a: &Args) -> mlua::Result<()> {
    let parent = a.receiver::<NodeHandle>("node")?.0;
    let child = a.node(1, "child")?;
    let check = with_state(a.lua, |s| {
        let budget = MAX_CYCLE_CHECK_VISITS.saturating_sub(s.cycle_check_visits);
        let (cycle, visits) = makes_cycle(s, parent, child, budget);
        s.cycle_check_visits += visits;
        let names = || {
            (
                short_name(&s.graph.nodes[child].name).into_owned(),
                short_name(&s.graph.nodes[parent].name).into_owned(),
            )
        };
        match cycle {
            Some(true) => Err(Some(names())),
            Some(false) => Ok(()),
            None => Err(None),
        }
    });
    match check {
        Ok(()) => super::charge(a, LINK_BYTES, "the child link")?,
        Err(Some((c, p))) => {
            return Err(a.bad_in(
                1,
                "child",
                format!("adding node '{c}' under node '{p}' would make a cycle"),
            ))
        }
        Err(None) => {
            return Err(a.error(format!(
                "the cycle checks of this script's add_child calls have visited more than {MAX_CYCLE_CHECK_VISITS} nodes; build the graph bottom-up (add children to nodes that have no parent yet)"
            )))
        }
    }
    with_state(a.lua, |s| {
        s.graph.nodes[parent].children.push(child);
        s.add_parent(child, parent);
    });
    Ok(())
}

/// Whether adding `child` under `parent` would make a cycle (None: the search passed
/// `budget` visits), and the visits it took. A cycle needs a path from `child` down to
/// `parent`: searched downwards from `child` and upwards from `parent` in turns, so the
/// answer costs about twice the smaller of the two (a parent nobody holds yet, or a
/// child that holds nothing, answers at once).
fn makes_cycle(
    s: &mut super::State,
    parent: NodeId,
    child: NodeId,
    budget: u64,
) -> (Option<bool>, u64) {
    if child == parent {
        return (Some(true), 0);
    }
    let n = s.graph.nodes.len();
    s.parents.resize(n, Vec::new());
    let search = &mut s.cycle_search;
    search.start(n);
    let nodes = &s.graph.nodes;
    let parents = &s.parents;
    // The i-th node below / above `node` (children, then a CSG node's operands).
    let below = |node: NodeId, i: usize| {
        let children = &nodes[node].children;
        match (children.get(i), &nodes[node].kind) {
            (Some(&c), _) => Some(c),
            (None, NodeKind::Csg { a, b, .. }) => [*a, *b].get(i - children.len()).copied(),
            (None, _) => None,
        }
    };
    let above = |node: NodeId, i: usize| parents[node].get(i).copied();
    // Depth-first, one edge per step (a node with 10⁵ children costs one step, not 10⁵).
    let mut down: Vec<(NodeId, usize)> = vec![(child, 0)];
    let mut up: Vec<(NodeId, usize)> = vec![(parent, 0)];
    search.visit(child, 0);
    search.visit(parent, 1);
    let mut visits = 0;
    loop {
        for (which, stack, target) in [(0, &mut down, parent), (1, &mut up, child)] {
            let Some(top) = stack.last_mut() else {
                // One search is exhausted without meeting its target: no cycle.
                return (Some(false), visits);
            };
            let (node, i) = *top;
            top.1 += 1;
            let next = if which == 0 {
                below(node, i)
            } else {
                above(node, i)
            };
            match next {
                None => {
                    stack.pop();
                }
                Some(m) if m == target => return (Some(true), visits),
                Some(m) => {
                    if search.visit(m, which) {
                        stack.push((m, 0));
                    }
                }
            }
            visits += 1;
        }
        if visits > budget {
            return (None, visits);
        }
    }
}

/// Visited marks for the two searches of [`makes_cycle`], reset in O(1) per check by
/// a new epoch instead of clearing.
#[derive(Default)]
pub(crate) struct CycleSearch {
    epoch: u32,
    marks: [Vec<u32>; 2],
}

impl CycleSearch {
    fn start(&mut self, nodes: usize) {
        for m in &mut self.marks {
            m.resize(nodes, 0);
        }
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 {
            for m in &mut self.marks {
                m.fill(0);
            }
            self.epoch = 1;
        }
    }

    /// Marks `node` in search `which`; false when it was already marked.
    fn visit(&mut self, node: NodeId, which: usize) -> bool {
        let mark = &mut self.marks[which][node];
        if *mark == self.epoch {
            return false;
        }
        *mark = self.epoch;
        true
    }
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
            NodeKind::Transform => Some(short_name(&node.name).into_owned()),
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
                    super::ensure_live(lua)?;
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
                format!("material '{}'", short_name(&s.graph.materials[id].name))
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
