//! `gr.mesh`: a mesh node from an OBJ file (loaded once per file) or from tables of
//! vertices and faces written in the script (the inline form, with optional UVs and
//! normals), counted against the memory budget before its vectors are built.

use super::args::{describe, finite, int_value, location, Args};
use super::budget::{charge, check_file_cost};
use super::handles::NodeHandle;
use super::nodes::{geometry, new_node, node_name};
use super::{era, preludes, with_state};
use crate::scene::obj::PARSE_BYTES_PER_BYTE;
use crate::scene::{Mesh, Primitive};
use glam::{DMat4, DVec3};
use mlua::Value;

/// `gr.mesh(name, 'file.obj')` or `gr.mesh(name, verts, faces[, uvs[, normals]])`.
pub(super) fn mesh(a: &Args) -> mlua::Result<NodeHandle> {
    let name = node_name(a)?;
    let id = match a.get(2) {
        Value::String(_) => {
            let file = a.file_name(2, "file")?;
            let found = with_state(a.lua, |s| {
                s.folders.find(&s.read_policy, &file, "mesh file")
            });
            let opened = found.map_err(|e| a.error(e))?;
            let key = opened.id;
            match with_state(a.lua, |s| s.mesh_cache.get(&key).copied()) {
                Some(id) => id,
                None => {
                    check_file_cost(a, &opened, PARSE_BYTES_PER_BYTE, "mesh file")?;
                    let mesh = crate::scene::obj::load_opened_obj(opened, &name)
                        .map_err(|e| a.error(e))?;
                    charge(a, mesh_bytes(&mesh), &format!("mesh file '{file}'"))?;
                    with_state(a.lua, |s| {
                        s.graph.meshes.push(std::sync::Arc::new(mesh));
                        let id = s.graph.meshes.len() - 1;
                        s.mesh_cache.insert(key, id);
                        id
                    })
                }
            }
        }
        Value::Table(_) => {
            // Counted (by inline_mesh) before its vectors are built.
            let mesh = inline_mesh(a, &name)?;
            // A prelude's quads are no sign of a pre-2015 scene.
            if preludes::caller_module_dir(a.lua).is_none() {
                inline_mesh_evidence(a);
            }
            with_state(a.lua, |s| {
                s.graph.meshes.push(std::sync::Arc::new(mesh));
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
        era::inline_mesh(a.lua, at);
    } else {
        era::strong(
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
            return Err(a.bad_element(3, "faces", f, "a table of vertex indices", &face));
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
                        describe(a.lua, &idx)
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
            return Err(a.bad_element(2, "vertices", i, "a table of 3 numbers {x, y, z}", &v));
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
            return Err(a.bad_element(
                5,
                "normals",
                i,
                "a normal of 3 finite numbers {x, y, z}",
                &v,
            ));
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
                    finite(&u).zip(finite(&v))
                }
                _ => None,
            };
            let (u, v) =
                pair.ok_or_else(|| a.bad_element(4, "uvs", i, "a pair of numbers {u, v}", &uv))?;
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
