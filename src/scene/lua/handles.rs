//! The userdata the `gr` calls return, and their methods: `node:add_child`,
//! `set_material`, `scale`, `translate`, `rotate`; `material:set_diffuse`, `set_specular`,
//! `set_shininess`, `set_reflection`, `set_refraction`, `copy` (texture forms and
//! `set_bump` in `maps`). The methods are plain functions kept in a table per kind that
//! the script may extend (`methods`); the userdata's `__index` looks them up there.
//!
//! Userdata carry only an index into the [`SceneGraph`](crate::scene::SceneGraph) arenas
//! (or a small value for lights), so a node can be added under several parents and a
//! material changed after it was set. Methods return their receiver so calls chain.

use super::args::Args;
use super::era::TransformKind;
pub(crate) use super::handle_types::{LightHandle, MaterialHandle, NodeHandle};
use super::methods::Method;
use super::unknown::unknown_method;
use super::with_state;
use crate::scene::{short_name, Material, NodeId, NodeKind};
use glam::{DMat4, DVec3};
use mlua::{Lua, MetaMethod, MultiValue, UserData, UserDataFields, UserDataMethods, Value};

/// `UserData` for a handle into one of the graph's arenas (`$arena`: `nodes`,
/// `materials`): its methods are looked up in a table the script may extend
/// (`gr.extend_node`, `gr.extend_material`: `$kind`), and it prints as `$word 'name'`.
macro_rules! arena_handle_userdata {
    ($handle:ty, $kind:expr, $word:literal, $arena:ident) => {
        impl UserData for $handle {
            fn add_fields<F: UserDataFields<Self>>(fields: &mut F) {
                fields.add_meta_field_with(MetaMethod::Index, |lua| {
                    super::methods::index(lua, $kind)
                });
            }

            fn add_methods<M: UserDataMethods<Self>>(methods: &mut M) {
                methods.add_meta_function(MetaMethod::ToString, |lua, this: mlua::AnyUserData| {
                    let id = this.borrow::<$handle>()?.0;
                    Ok(with_state(lua, |s| {
                        let name = short_name(&s.graph.$arena[id].name);
                        format!(concat!($word, " '{}'"), name)
                    }))
                });
            }
        }
    };
}

arena_handle_userdata!(NodeHandle, super::methods::Kind::Node, "node", nodes);
arena_handle_userdata!(
    MaterialHandle,
    super::methods::Kind::Material,
    "material",
    materials
);

/// What every built-in method does around its body: stops a script past its limits,
/// reads the arguments as `func` (`node:scale`), runs `body` (which checks the
/// receiver), notes arguments it left unused and returns the receiver, so calls chain.
fn builtin_method(
    lua: &Lua,
    func: &str,
    args: MultiValue,
    body: impl FnOnce(&Args) -> mlua::Result<()>,
) -> mlua::Result<Value> {
    super::limits::ensure_live(lua)?;
    let a = Args::method(lua, func, args);
    body(&a)?;
    super::notes::check_extra_arguments(&a);
    Ok(a.receiver_value())
}

/// A built-in method as its table entry `(name, Method)`: `$kind:$name` run through
/// [`builtin_method`], `$body` given the Lua state and the arguments.
macro_rules! builtin {
    ($kind:literal, $name:literal, |$lua:ident, $a:ident| $body:block) => {
        (
            $name,
            (|$lua: &Lua, args: MultiValue| {
                builtin_method($lua, concat!($kind, ":", $name), args, |$a| $body)
            }) as Method,
        )
    };
}

/// The built-in node methods.
pub(super) fn node_methods() -> Vec<(&'static str, Method)> {
    macro_rules! method {
        ($name:literal, $f:expr) => {
            builtin!("node", $name, |_lua, a| {
                a.receiver::<NodeHandle>("node")?;
                $f(a)
            })
        };
    }
    vec![
        method!("add_child", add_child),
        method!("set_material", set_material),
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
            compose(
                a,
                DMat4::from_scale(DVec3::from_array(f)),
                TransformKind::RotateOrScale,
            )
        }),
        method!("translate", |a: &Args| {
            let t = DVec3::new(a.number(1, "x")?, a.number(2, "y")?, a.number(3, "z")?);
            compose(a, DMat4::from_translation(t), TransformKind::Translate)
        }),
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
            super::advice::check_rotate_angle(a, deg);
            compose(a, op, TransformKind::RotateOrScale)
        }),
        method!("set_placement", set_placement),
    ]
}

/// `node:set_placement(origin, x_axis, y_axis, z_axis)`: where a geometry node's
/// primitive lies in its node's frame: the object-space point (x, y, z) goes to
/// origin + x·x_axis + y·y_axis + z·z_axis, before the node's own transforms (as
/// `gr.nh_sphere`'s centre and radius do). Independent of the transform order, so a
/// dialect can stand glint's z-axis cylinder on y whichever order the scene uses. The
/// axes must span space (a flat or mirroring frame is refused: it would flatten the solid
/// or turn it inside out).
fn set_placement(a: &Args) -> mlua::Result<()> {
    let id = a.receiver::<NodeHandle>("node")?.0;
    let origin = a.vec3(1, "origin")?;
    let x = a.vec3(2, "x_axis")?;
    let y = a.vec3(3, "y_axis")?;
    let z = a.vec3(4, "z_axis")?;
    let frame = DMat4::from_cols(
        x.extend(0.0),
        y.extend(0.0),
        z.extend(0.0),
        origin.extend(1.0),
    );
    // Scale-free: the determinant against the product of the axes' lengths.
    let det = x.dot(y.cross(z));
    let size = x.length() * y.length() * z.length();
    // (NaN axes fail the comparison too.)
    let spans_space = det.is_finite() && det > 1e-12 * size;
    if !spans_space {
        return Err(a.bad_in(
            4,
            "z_axis",
            format!(
                "the axes must span space in a right-handed frame (x_axis · (y_axis × z_axis) > 0), got x_axis = {{{}, {}, {}}}, y_axis = {{{}, {}, {}}}, z_axis = {{{}, {}, {}}}",
                x.x, x.y, x.z, y.x, y.y, y.z, z.x, z.y, z.z
            ),
        ));
    }
    let refused = with_state(a.lua, |s| {
        let node = &mut s.graph.nodes[id];
        match &mut node.kind {
            NodeKind::Geometry { placement, .. } => {
                *placement = frame;
                None
            }
            _ => Some(node.name.clone()),
        }
    });
    match refused {
        None => Ok(()),
        Some(name) => Err(a.error(format!(
            "node '{name}' is not a geometry node; a placement places a primitive or mesh (transform it with scale, rotate and translate)"
        ))),
    }
}

/// Applies `op` (a transform of `kind`) to the receiver's matrix in the current
/// transform order.
fn compose(a: &Args, op: DMat4, kind: TransformKind) -> mlua::Result<()> {
    let id = a.receiver::<NodeHandle>("node")?.0;
    super::era::transform(a.lua, id, kind);
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
const LINK_BYTES: u64 = super::budget::grown(2 * std::mem::size_of::<NodeId>());

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
        Ok(()) => super::budget::charge(a, LINK_BYTES, "the child link")?,
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

/// The built-in material methods.
pub(super) fn material_methods() -> Vec<(&'static str, Method)> {
    macro_rules! method {
        ($name:literal, $f:expr) => {
            builtin!("material", $name, |lua, a| {
                let id = a.receiver::<MaterialHandle>("material")?.0;
                let edit = $f(a)?;
                with_state(lua, |s| edit(&mut s.graph.materials[id]));
                Ok(())
            })
        };
    }
    vec![
        method!("set_diffuse", super::maps::set_diffuse),
        method!("set_specular", super::maps::set_specular),
        method!("set_bump", super::maps::set_bump),
        method!("set_reflection", |a: &Args| {
            a.colour_args(1, true)
                .map(|c| move |m: &mut Material| m.reflection = c)
        }),
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
        }),
        method!("set_shininess", |a: &Args| {
            a.non_negative(1, "shininess")
                .map(|p| move |m: &mut Material| m.shininess = p as f32)
        }),
        ("copy", copy_material as Method),
    ]
}

/// `material:copy()`: a new material with every property of the receiver (colours,
/// textures, bump map, reflection, refraction), so that one node's variant of a shared
/// material (a dialect's per-node texture) leaves the others alone.
fn copy_material(lua: &Lua, args: MultiValue) -> mlua::Result<Value> {
    super::limits::ensure_live(lua)?;
    let a = Args::method(lua, "material:copy", args);
    let id = a.receiver::<MaterialHandle>("material")?.0;
    let at = super::args::location(lua);
    let copy = with_state(lua, |s| {
        let mut m = s.graph.materials[id].clone();
        m.name = format!("copy of {} at {at}", m.name);
        s.graph.materials.push(m);
        MaterialHandle(s.graph.materials.len() - 1)
    });
    lua.create_userdata(copy).map(Value::UserData)
}

impl UserData for LightHandle {
    fn add_methods<M: UserDataMethods<Self>>(methods: &mut M) {
        methods.add_meta_method(MetaMethod::ToString, |_, this, ()| {
            Ok(format!(
                "light at ({}, {}, {})",
                this.0.position.x, this.0.position.y, this.0.position.z
            ))
        });
        // Without it Lua would report `attempt to index a LightHandle value`.
        methods.add_meta_function(
            MetaMethod::Index,
            |lua, (_this, key): (mlua::AnyUserData, mlua::Value)| -> mlua::Result<()> {
                Err(unknown_method(lua, "a light", &key, &[]))
            },
        );
    }
}
