//! The `gr` table: the A4 core calls (the methods of what they return are in `handles`).
//!
//! Every call of the contract is defined; an unknown one is an error that names the
//! nearest calls and the dialect preludes (`unknown`).

use super::args::{int_value, location, Args};
use super::handles::{LightHandle, MaterialHandle, NodeHandle};
use super::{charge, check_file_cost, grown, memory_left, notes, options, with_state, OnRender};
use crate::constants::DEFAULT_SHADOW_SAMPLES;
use crate::scene::flatten::{parallel_or_zero, CAMERA_PARALLEL_SIN2, MAX_PIXELS};
use crate::scene::obj::PARSE_BYTES_PER_BYTE;
use crate::scene::{short_name, ShadowSamples};
use crate::scene::{
    AreaLight, Camera, CsgOp, Light, Material, Mesh, Node, NodeId, NodeKind, Primitive,
    RenderRequest, TransformOrder,
};
use glam::{DMat4, DVec3};
use mlua::{Lua, MultiValue, Value};
use std::path::PathBuf;

/// Largest image side accepted (a typo guard, not a hardware limit).
pub const MAX_IMAGE_SIDE: u32 = 1 << 16;

/// Defines the global `gr` table (all calls but `render`, which `run_scene_source` adds as
/// a scoped function borrowing the caller's callback).
pub(super) fn install(lua: &Lua) -> mlua::Result<()> {
    let gr = lua.create_table()?;
    macro_rules! def {
        ($name:literal, $f:expr) => {
            gr.set(
                $name,
                lua.create_function(|lua, args: MultiValue| {
                    super::ensure_live(lua)?;
                    let a = Args::new(lua, concat!("gr.", $name), args);
                    let out = $f(&a)?;
                    notes::check_extra_arguments(&a);
                    Ok(out)
                })?,
            )?;
        };
    }
    def!("node", |a: &Args| transform_node(a));
    // A4's joints carry angle ranges for the puppet assignment; here they are plain nodes
    // (the ranges are accepted, and mean nothing in a still image).
    def!("joint", |a: &Args| {
        let node = transform_node(a);
        let _ranges = (a.get(2), a.get(3));
        node
    });
    def!("sphere", |a: &Args| primitive(a, Primitive::Sphere));
    def!("cube", |a: &Args| primitive(a, Primitive::Cube));
    def!("cylinder", |a: &Args| primitive(a, Primitive::Cylinder));
    def!("cone", cone);
    def!("nh_sphere", nh_sphere);
    def!("nh_box", nh_box);
    def!("torus", torus);
    def!("mesh", mesh);
    def!("csg", csg);
    def!("material", material);
    def!("light", light);
    def!("area_light", area_light);
    def!("transform_order", transform_order);
    def!("ignore_extra_arguments", notes::ignore_extra_arguments);
    super::unknown::install_gr_guard(lua, &gr)?;
    lua.globals().set("gr", gr)
}

/// Bytes a node holds in Rust besides its name: its slot in the node vector and in the
/// parents' vector, with their growth, and the allocator's block for its parent list.
const NODE_BYTES: u64 =
    grown(std::mem::size_of::<Node>()) + grown(std::mem::size_of::<Vec<NodeId>>()) + 64;

/// Bytes a material holds besides its name.
const MATERIAL_BYTES: u64 = grown(std::mem::size_of::<Material>());

/// Bytes one entry of `gr.render`'s light list takes while the render runs: the list
/// and the copies of it that flattening and packing make.
const LIGHT_BYTES: u64 = 4 * grown(std::mem::size_of::<Light>());

/// Argument 1, a node's name, with the node it names counted against the memory budget
/// before the name is copied out of Lua.
fn node_name(a: &Args) -> mlua::Result<String> {
    let len = match a.get(1) {
        Value::String(s) => s.as_bytes().len(),
        _ => 32,
    };
    charge(a, NODE_BYTES + len as u64, "the node and its name")?;
    a.string(1, "name")
}

/// Adds a node (counted by [`node_name`]).
fn new_node(a: &Args, name: String, kind: NodeKind) -> mlua::Result<NodeHandle> {
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

fn geometry(primitive: Primitive, placement: DMat4) -> NodeKind {
    NodeKind::Geometry {
        primitive,
        placement,
    }
}

fn transform_node(a: &Args) -> mlua::Result<NodeHandle> {
    let name = node_name(a)?;
    new_node(a, name, NodeKind::Transform)
}

fn primitive(a: &Args, p: Primitive) -> mlua::Result<NodeHandle> {
    let name = node_name(a)?;
    new_node(a, name, geometry(p, DMat4::IDENTITY))
}

/// `gr.cone(name, zmin, zmax)`: the solid cone x² + y² ≤ z² between z = zmin and z = zmax.
/// The bounds must stay distinct (and finite) in f32, which the tracers use.
fn cone(a: &Args) -> mlua::Result<NodeHandle> {
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

fn nh_sphere(a: &Args) -> mlua::Result<NodeHandle> {
    let name = node_name(a)?;
    let centre = a.vec3(2, "centre")?;
    let radius = a.positive(3, "radius")?;
    let placement = DMat4::from_translation(centre) * DMat4::from_scale(DVec3::splat(radius));
    new_node(a, name, geometry(Primitive::Sphere, placement))
}

fn nh_box(a: &Args) -> mlua::Result<NodeHandle> {
    let name = node_name(a)?;
    let corner = a.vec3(2, "corner")?;
    let size = a.positive(3, "size")?;
    let placement = DMat4::from_translation(corner) * DMat4::from_scale(DVec3::splat(size));
    new_node(a, name, geometry(Primitive::Cube, placement))
}

/// `gr.torus(name, rin, rout)`: both radii finite and positive. `rout > rin` is allowed
/// and gives a self-intersecting "spindle" torus (an apple with a lemon inside, both
/// sheets drawn; `rout == rin` is the horn torus).
fn torus(a: &Args) -> mlua::Result<NodeHandle> {
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
fn csg(a: &Args) -> mlua::Result<NodeHandle> {
    let name = node_name(a)?;
    let op = match a.get(2) {
        Value::String(s) => match super::args::lossy_prefix(s, 8)
            .to_ascii_lowercase()
            .as_str()
        {
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

/// `gr.mesh(name, 'file.obj')` or `gr.mesh(name, verts, faces[, uvs[, normals]])`.
fn mesh(a: &Args) -> mlua::Result<NodeHandle> {
    let name = node_name(a)?;
    let id = match a.get(2) {
        Value::String(_) => {
            let file = a.file_name(2, "file")?;
            let found = with_state(a.lua, |s| {
                s.folders.find(&s.read_policy, &file, "mesh file")
            });
            let (path, canonical) = found.map_err(|e| a.error(e))?;
            match with_state(a.lua, |s| s.mesh_cache.get(&canonical).copied()) {
                Some(id) => id,
                None => {
                    check_file_cost(a, &path, PARSE_BYTES_PER_BYTE, "mesh file")?;
                    let mesh = crate::scene::obj::load_obj(&path, &name).map_err(|e| a.error(e))?;
                    charge(a, mesh_bytes(&mesh), &format!("mesh file '{file}'"))?;
                    with_state(a.lua, |s| {
                        s.graph.meshes.push(mesh);
                        let id = s.graph.meshes.len() - 1;
                        s.mesh_cache.insert(canonical, id);
                        id
                    })
                }
            }
        }
        Value::Table(_) => {
            // Counted (by inline_mesh) before its vectors are built.
            let mesh = inline_mesh(a, &name)?;
            // A prelude's quads are no sign of a pre-2015 scene.
            if super::preludes::caller_module_dir(a.lua).is_none() {
                inline_mesh_evidence(a);
            }
            with_state(a.lua, |s| {
                s.graph.meshes.push(mesh);
                s.graph.meshes.len() - 1
            })
        }
        _ => {
            return Err(a.bad(
                2,
                "vertices",
                "an OBJ file name or a table of vertices {{x,y,z}, …}",
            ))
        }
    };
    new_node(a, name, geometry(Primitive::Mesh(id), DMat4::IDENTITY))
}

/// An inline mesh of the scene's code: built by the scene itself, weak evidence of the
/// pre-2015 course; by a module it `require`s, strong (see `era`).
fn inline_mesh_evidence(a: &Args) {
    let at = location(a.lua);
    let in_scene = with_state(a.lua, |s| {
        at.strip_prefix(s.scene_chunk.as_str())
            .is_some_and(|rest| rest.starts_with(':'))
    });
    if in_scene {
        super::era::inline_mesh(a.lua, at);
    } else {
        super::era::strong(
            a.lua,
            "an inline mesh built by a required module (meshes shipped as Lua modules)",
        );
    }
}

/// Bytes a mesh holds in the scene graph.
fn mesh_bytes(mesh: &Mesh) -> u64 {
    let vertex = std::mem::size_of::<DVec3>()
        + if mesh.uvs.is_some() { 8 } else { 0 }
        + if mesh.normals.is_some() {
            std::mem::size_of::<DVec3>()
        } else {
            0
        };
    (mesh.positions.len() * vertex + mesh.triangles.len() * 12 + mesh.name.len()) as u64
}

/// The inline form: 0-based indices, polygons of 3+ corners fan-triangulated.
fn inline_mesh(a: &Args, name: &str) -> mlua::Result<Mesh> {
    let verts = a.table(2, "vertices", "a table of vertices {{x,y,z}, …}")?;
    let faces = a.table(3, "faces", "a table of faces {{i,j,k,…}, …}")?;
    let triangle_count = inline_triangle_count(&faces)?;
    let vertex_count = verts.raw_len() as u64;
    // Each vertex's position, and its {u, v} and normal when given (arguments 4 and 5).
    let vertex_bytes = std::mem::size_of::<DVec3>() as u64
        + if a.is_nil(4) { 0 } else { 8 }
        + if a.is_nil(5) {
            0
        } else {
            std::mem::size_of::<DVec3>() as u64
        };
    let bytes = vertex_count
        .saturating_mul(vertex_bytes)
        .saturating_add(triangle_count.saturating_mul(12))
        .saturating_add(name.len() as u64);
    charge(a, bytes, "the inline mesh")?;
    let positions = inline_positions(a, &verts, vertex_count as usize)?;
    let n = positions.len();
    let mut triangles = Vec::with_capacity(triangle_count as usize);
    for (f, face) in faces.sequence_values::<Value>().enumerate() {
        let face = face?;
        let Value::Table(t) = &face else {
            return Err(a.bad_in(
                3,
                "faces",
                format!(
                    "element {} must be a table of vertex indices, got {}",
                    f + 1,
                    super::args::describe(a.lua, &face)
                ),
            ));
        };
        let mut ids = Vec::new();
        for (c, idx) in t.sequence_values::<Value>().enumerate() {
            let idx = idx?;
            let i = int_value(&idx).ok_or_else(|| {
                a.bad_in(
                    3,
                    "faces",
                    format!(
                        "face {}, corner {}: index must be an integer, got {}",
                        f + 1,
                        c + 1,
                        super::args::describe(a.lua, &idx)
                    ),
                )
            })?;
            if i < 0 || i as usize >= n {
                return Err(a.bad_in(
                    3,
                    "faces",
                    format!(
                        "face {}, corner {}: index {i} out of range (indices are 0-based; {n} vertices)",
                        f + 1,
                        c + 1
                    ),
                ));
            }
            ids.push(i as u32);
        }
        if ids.len() < 3 {
            return Err(a.bad_in(
                3,
                "faces",
                format!(
                    "face {} has {} corners; a face needs at least 3",
                    f + 1,
                    ids.len()
                ),
            ));
        }
        for k in 1..ids.len() - 1 {
            triangles.push([ids[0], ids[k], ids[k + 1]]);
        }
    }
    let uvs = inline_uvs(a, n)?;
    let normals = inline_normals(a, n)?;
    Ok(Mesh {
        name: name.to_string(),
        positions,
        triangles,
        uvs,
        normals,
    })
}

/// Argument 2 of the inline form: `count` vertices `{x, y, z}`.
fn inline_positions(a: &Args, verts: &mlua::Table, count: usize) -> mlua::Result<Vec<DVec3>> {
    let mut positions = Vec::with_capacity(count);
    for (i, v) in verts.sequence_values::<Value>().enumerate() {
        let v = v?;
        let Value::Table(t) = &v else {
            return Err(a.bad_in(
                2,
                "vertices",
                format!(
                    "element {} must be a table of 3 numbers {{x, y, z}}, got {}",
                    i + 1,
                    super::args::describe(a.lua, &v)
                ),
            ));
        };
        let p = a.vec3_from(t, 2, "vertices").map_err(|_| {
            a.bad_in(
                2,
                "vertices",
                format!("element {} must hold 3 finite numbers {{x, y, z}}", i + 1),
            )
        })?;
        positions.push(DVec3::from_array(p));
    }
    Ok(positions)
}

/// Argument 5 of the inline form: one non-zero normal `{x, y, z}` per vertex (`n` of
/// them), normalised, if given (smooth shading; `uvs` may be nil before it).
fn inline_normals(a: &Args, n: usize) -> mlua::Result<Option<Vec<DVec3>>> {
    if a.is_nil(5) {
        return Ok(None);
    }
    let t = a.table(5, "normals", "a table of normals {x, y, z}, one per vertex")?;
    let mut normals = Vec::with_capacity(n);
    for (i, v) in t.sequence_values::<Value>().enumerate() {
        let v = v?;
        let bad = |what: String| a.bad_in(5, "normals", format!("element {} {what}", i + 1));
        let Some(p) = (match &v {
            Value::Table(t) => a.vec3_from(t, 5, "normals").ok(),
            _ => None,
        }) else {
            return Err(bad(format!(
                "must be a normal of 3 finite numbers {{x, y, z}}, got {}",
                super::args::describe(a.lua, &v)
            )));
        };
        let unit = crate::scene::obj::unit_or_zero(DVec3::from_array(p));
        if unit == DVec3::ZERO {
            return Err(bad(format!(
                "is {{{}, {}, {}}}, which has no direction: a normal must be non-zero",
                p[0], p[1], p[2]
            )));
        }
        normals.push(unit);
    }
    if normals.len() != n {
        return Err(a.bad_in(
            5,
            "normals",
            format!("has {} normals but there are {n} vertices", normals.len()),
        ));
    }
    Ok(Some(normals))
}

/// Triangles the fan triangulation of `faces` makes at most (from the tables' lengths,
/// before anything is built: a face of 786 432 corners listed 2 048 times is 1.6 × 10⁹
/// triangles from 16 MiB of Lua).
fn inline_triangle_count(faces: &mlua::Table) -> mlua::Result<u64> {
    let mut total = 0u64;
    for face in faces.sequence_values::<Value>() {
        if let Value::Table(t) = face? {
            total = total.saturating_add((t.raw_len() as u64).saturating_sub(2));
        }
    }
    Ok(total)
}

/// Argument 4 of the inline form: one `{u, v}` per vertex (`n` of them), if given.
fn inline_uvs(a: &Args, n: usize) -> mlua::Result<Option<Vec<[f32; 2]>>> {
    if a.is_nil(4) {
        Ok(None)
    } else {
        let t = a.table(4, "uvs", "a table of {u, v} pairs, one per vertex")?;
        let mut uvs = Vec::with_capacity(n);
        for (i, uv) in t.sequence_values::<Value>().enumerate() {
            let uv = uv?;
            let pair = match &uv {
                Value::Table(p) => {
                    let u = p.raw_get::<Value>(1)?;
                    let v = p.raw_get::<Value>(2)?;
                    super::args::finite(&u).zip(super::args::finite(&v))
                }
                _ => None,
            };
            let (u, v) = pair.ok_or_else(|| {
                a.bad_in(
                    4,
                    "uvs",
                    format!(
                        "element {} must be a pair of numbers {{u, v}}, got {}",
                        i + 1,
                        super::args::describe(a.lua, &uv)
                    ),
                )
            })?;
            uvs.push([u as f32, v as f32]);
        }
        if uvs.len() != n {
            return Err(a.bad_in(
                4,
                "uvs",
                format!("has {} pairs but there are {n} vertices", uvs.len()),
            ));
        }
        Ok(Some(uvs))
    }
}

/// `gr.material(kd, ks, shininess)` or `gr.material(name)`.
fn material(a: &Args) -> mlua::Result<MaterialHandle> {
    // The name's length is known before it is copied out of Lua.
    let name_len = match a.get(1) {
        Value::String(s) => s.as_bytes().len(),
        _ => 64,
    };
    charge(a, MATERIAL_BYTES + name_len as u64, "the material")?;
    let m = match a.get(1) {
        Value::String(_) => Material {
            name: a.string(1, "name")?,
            ..Material::default()
        },
        _ => Material {
            name: format!("material at {}", location(a.lua)),
            kd: a.colour(1, "kd")?,
            ks: a.colour(2, "ks")?,
            shininess: a.non_negative(3, "shininess")? as f32,
            ..Material::default()
        },
    };
    Ok(with_state(a.lua, |s| {
        s.graph.materials.push(m);
        MaterialHandle(s.graph.materials.len() - 1)
    }))
}

fn light(a: &Args) -> mlua::Result<LightHandle> {
    let position = a.vec3(1, "position")?;
    let colour = a.colour(2, "colour")?;
    let falloff = falloff(a, 3)?;
    Ok(LightHandle(Light {
        position,
        colour,
        falloff,
        area: None,
    }))
}

/// Argument `n` of a light: `{c0, c1, c2}`, non-negative and not all zero.
fn falloff(a: &Args, n: usize) -> mlua::Result<[f32; 3]> {
    let t = a.table(n, "falloff", "a table of 3 numbers {c0, c1, c2}")?;
    let c = a.vec3_from(&t, n, "falloff")?;
    if c.iter().any(|&x| x < 0.0) || c.iter().all(|&x| x == 0.0) {
        return Err(a.bad_in(
            n,
            "falloff",
            format!(
                "coefficients {{c0, c1, c2}} must be non-negative and not all zero, got {{{}, {}, {}}}",
                c[0], c[1], c[2]
            ),
        ));
    }
    Ok(c.map(|x| x as f32))
}

/// `gr.area_light(centre, u, v, colour, {c0, c1, c2}[, n])`: the parallelogram centred at
/// `centre` with edges `u`, `v`; n×n shadow samples (default 4).
fn area_light(a: &Args) -> mlua::Result<LightHandle> {
    let centre = a.vec3(1, "centre")?;
    let u = a.vec3(2, "u")?;
    let v = a.vec3(3, "v")?;
    // Parallel (or zero) edges span no area (compared scale-free, so huge or tiny
    // edges neither overflow nor underflow the test).
    if parallel_or_zero(u, v, 1e-24) {
        return Err(a.bad_in(
            3,
            "v",
            format!(
                "edges u and v must not be parallel or zero, got u = {{{}, {}, {}}}, v = {{{}, {}, {}}}",
                u.x, u.y, u.z, v.x, v.y, v.z
            ),
        ));
    }
    let colour = a.colour(4, "colour")?;
    let falloff = falloff(a, 5)?;
    let samples = if a.is_nil(6) {
        ShadowSamples::constant(DEFAULT_SHADOW_SAMPLES)
    } else {
        a.bounded(6, "n")?
    };
    Ok(LightHandle(Light {
        position: centre,
        colour,
        falloff,
        area: Some(AreaLight { u, v, samples }),
    }))
}

fn transform_order(a: &Args) -> mlua::Result<()> {
    let s = a.text(1, "order")?;
    let order = match s.to_ascii_lowercase().as_str() {
        "pre" => TransformOrder::Pre,
        "post" => TransformOrder::Post,
        _ => return Err(a.bad(1, "order", "'pre' or 'post'")),
    };
    with_state(a.lua, |s| {
        s.report.order_set_by_script = true;
        if !s.order_fixed {
            s.order = order;
        }
    });
    Ok(())
}

/// `{x, y, z}` as a scene writes it.
fn vector(v: DVec3) -> String {
    let [x, y, z] = v.to_array().map(super::args::format_number);
    format!("{{{x}, {y}, {z}}}")
}

/// Scenes written for tracers that took a point to look at pass it as `view`: what to
/// pass instead, worked out for this eye.
fn look_at_hint(eye: DVec3, view: DVec3) -> String {
    format!(
        "view is the direction the camera looks in, not a point: for a point to look at, pass \
         point − eye (for the point {} seen from the eye {}: {})",
        vector(view),
        vector(eye),
        vector(view - eye)
    )
}

/// Arguments 5–8 of `gr.render`: eye, view (a non-zero direction), up (not parallel to
/// it) and the vertical field of view.
fn camera(a: &Args) -> mlua::Result<Camera> {
    let eye = a.vec3(5, "eye")?;
    let view = a.vec3(6, "view")?;
    if view == DVec3::ZERO {
        return Err(a.error(format!(
            "argument 6 (view) must be a non-zero direction, got {}; {}",
            vector(view),
            look_at_hint(eye, view)
        )));
    }
    let up = a.vec3(7, "up")?;
    if up == DVec3::ZERO {
        return Err(a.bad(7, "up", "a non-zero direction"));
    }
    if parallel_or_zero(view, up, CAMERA_PARALLEL_SIN2) {
        return Err(a.error(format!(
            "argument 7 (up) must be a non-zero direction not parallel to view, got up = {}, view = {}; {}",
            vector(up),
            vector(view),
            look_at_hint(eye, view)
        )));
    }
    let fov_deg = match super::args::finite(a.get(8)) {
        Some(f) if f > 0.0 && f < 180.0 => f,
        _ => return Err(a.bad(8, "fov", "a number of degrees between 0 and 180")),
    };
    super::advice::check_fov(a, fov_deg);
    Ok(Camera {
        eye,
        view,
        up,
        fov_deg,
    })
}

/// Argument 11 of `gr.render`: a table of render options, or nil. The course's binding
/// ignored whatever followed the lights (thread counts, depths): so does glint, noting it.
fn render_options(a: &Args) -> mlua::Result<crate::scene::RenderOptions> {
    Ok(match a.get(11) {
        Value::Nil | Value::Table(_) => {
            let options = options::parse(a, 11)?;
            notes::check_extra_arguments(a);
            options
        }
        _ => {
            notes::ignored_render_tail(a);
            crate::scene::RenderOptions::default()
        }
    })
}

/// `gr.render(root, file, w, h, eye, view, up, fov, ambient, lights[, options])`.
pub(super) fn render(
    lua: &Lua,
    args: MultiValue,
    on_render: &mut OnRender<'_>,
) -> mlua::Result<()> {
    super::ensure_live(lua)?;
    let a = Args::new(lua, "gr.render", args);
    if with_state(lua, |s| s.render_error.is_some()) {
        return Err(a.error("an earlier gr.render failed; no more renders"));
    }
    check_render_shape(&a)?;
    let root = a.node(1, "root")?;
    super::advice::check_root(&a, root);
    let output = output_name(&a)?;
    let width = a.positive_int(3, "width", MAX_IMAGE_SIDE)?;
    let height = a.positive_int(4, "height", MAX_IMAGE_SIDE)?;
    if u64::from(width) * u64::from(height) > MAX_PIXELS {
        return Err(a.bad_in(
            4,
            "height",
            format!("a {width}×{height} image has more than glint's limit of {MAX_PIXELS} pixels"),
        ));
    }
    count_render(&a, u64::from(width) * u64::from(height))?;
    let camera = camera(&a)?;
    let ambient = a.colour(9, "ambient")?;
    let list = a.table(10, "lights", "a table of lights made by gr.light")?;
    let options = render_options(&a)?;
    with_state(lua, notes::flush);
    // The list is counted before it is copied (2²⁶ entries naming one light are 2²⁶
    // copies), and given back after the render.
    let light_bytes = (list.raw_len() as u64).saturating_mul(LIGHT_BYTES);
    charge(&a, light_bytes, "the light list")?;
    let result = render_with_lights(&a, list, output, on_render, |lights| {
        Ok(RenderRequest {
            root,
            output: PathBuf::new(),
            width,
            height,
            camera,
            ambient,
            lights,
            options,
            location: location(lua),
            memory_left: memory_left(lua),
        })
    });
    super::release(lua, light_bytes);
    result
}

/// `gr.render`'s signature, for messages about its arguments.
pub(super) const RENDER_SIGNATURE: &str =
    "gr.render(root, file, width, height, eye, view, up, fov, ambient, lights[, options])";

/// One positional argument's kind: its name, a test of its value, what it must be.
type ArgumentKind = (&'static str, fn(&Value) -> bool, &'static str);

/// The Lua type each of `gr.render`'s ten positional arguments must have: its name, a
/// test of the value, and what it must be (the words the value checks use).
const RENDER_SHAPE: [ArgumentKind; 10] = [
    (
        "root",
        |v| matches!(v, Value::UserData(u) if u.is::<NodeHandle>()),
        "a node",
    ),
    (
        "file",
        |v| v.is_string(),
        "the image's file name, a string such as 'out.png'",
    ),
    (
        "width",
        |v| v.is_number() || v.is_integer(),
        "a positive integer",
    ),
    (
        "height",
        |v| v.is_number() || v.is_integer(),
        "a positive integer",
    ),
    ("eye", |v| v.is_table(), "a table of 3 numbers {x, y, z}"),
    ("view", |v| v.is_table(), "a table of 3 numbers {x, y, z}"),
    ("up", |v| v.is_table(), "a table of 3 numbers {x, y, z}"),
    (
        "fov",
        |v| v.is_number() || v.is_integer(),
        "a number of degrees between 0 and 180",
    ),
    (
        "ambient",
        |v| v.is_table(),
        "a table of 3 numbers {r, g, b}",
    ),
    (
        "lights",
        |v| v.is_table(),
        "a table of lights made by gr.light",
    ),
];

/// Checks the kinds of `gr.render`'s positional arguments before any value, so that a
/// shifted or missing argument (`gr.render(root, 160, 120, 'a.png', …)`) is named where
/// the shift starts, with the signature, rather than where a value first fails.
fn check_render_shape(a: &Args) -> mlua::Result<()> {
    for (i, (name, fits, what)) in RENDER_SHAPE.iter().enumerate() {
        let n = i + 1;
        if !fits(a.get(n)) {
            let got = super::args::describe(a.lua, a.get(n));
            return Err(a.error(format!(
                "argument {n} ({name}) must be {what}, got {got}; the arguments are {RENDER_SIGNATURE}"
            )));
        }
    }
    Ok(())
}

/// Argument 2 of `gr.render`, the output's name: UTF-8 (a name is never mangled into
/// another), without NUL bytes.
fn output_name(a: &Args) -> mlua::Result<PathBuf> {
    Ok(PathBuf::from(a.file_name(2, "file")?))
}

/// Counts one render of `pixels` against the script's bounds (a reached bound is final).
fn count_render(a: &Args, pixels: u64) -> mlua::Result<()> {
    let over = with_state(a.lua, |s| {
        s.renders_requested += 1;
        s.pixels_requested = s.pixels_requested.saturating_add(pixels);
        if s.renders_requested > s.max_renders {
            Some(format!(
                "this is render {} of the script, over the limit of {} renders; --max-renders N raises it",
                s.renders_requested, s.max_renders
            ))
        } else if s.pixels_requested > s.max_render_pixels {
            Some(format!(
                "the script's renders ask for {} pixels in all, over the limit of {}; --max-render-pixels N raises it",
                s.pixels_requested, s.max_render_pixels
            ))
        } else {
            None
        }
    });
    match over {
        Some(message) => Err(super::reach_limit(a, message)),
        None => Ok(()),
    }
}

/// Reads the light list, builds the request with `request` and renders it.
fn render_with_lights(
    a: &Args,
    list: mlua::Table,
    output: PathBuf,
    on_render: &mut OnRender<'_>,
    request: impl FnOnce(Vec<Light>) -> mlua::Result<RenderRequest>,
) -> mlua::Result<()> {
    let lua = a.lua;
    let mut lights = Vec::with_capacity(list.raw_len());
    for (i, v) in list.sequence_values::<Value>().enumerate() {
        let v = v?;
        let light = match &v {
            Value::UserData(ud) => ud.borrow::<LightHandle>().ok().map(|l| l.0.clone()),
            _ => None,
        };
        lights.push(light.ok_or_else(|| {
            a.bad_in(
                10,
                "lights",
                format!(
                    "element {} must be a light made by gr.light, got {}",
                    i + 1,
                    super::args::describe(lua, &v)
                ),
            )
        })?);
    }
    let request = RenderRequest {
        output,
        ..request(lights)?
    };
    let state = lua
        .app_data_ref::<super::State>()
        .expect("script state is installed");
    // Renders do not count against the script's time limit.
    state.clock.pause();
    let result = on_render(&state.graph, &request);
    state.clock.resume();
    drop(state);
    match result {
        Ok(()) => {
            with_state(lua, |s| s.report.renders += 1);
            Ok(())
        }
        Err(error) => {
            let message = format!("{}: gr.render: {error:#}", request.location);
            with_state(lua, |s| s.render_error = Some((request.location, error)));
            Err(mlua::Error::RuntimeError(message))
        }
    }
}
