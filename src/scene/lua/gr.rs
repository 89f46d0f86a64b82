//! The `gr` table: installs the A4 core calls, and defines those that make materials and
//! lights and set the transform order. The calls that make nodes are in `nodes` and
//! `meshes`, `gr.render` in `render_call`, the methods of what they return in `handles`.
//!
//! Every call of the contract is defined; an unknown one is an error that names the
//! nearest calls and the dialect preludes (`unknown`).

use super::args::{location, Args};
use super::budget::{charge, grown};
use super::handles::{LightHandle, MaterialHandle};
use super::limits::ensure_live;
use super::meshes::mesh;
use super::nodes::{cone, csg, nh_box, nh_sphere, primitive, torus, transform_node};
use super::{notes, unknown, with_state};
use crate::constants::DEFAULT_SHADOW_SAMPLES;
use crate::scene::flatten::parallel_or_zero;
use crate::scene::ShadowSamples;
use crate::scene::{AreaLight, Light, Material, Primitive, TransformOrder};
use mlua::{Lua, MultiValue, Value};

/// Defines the global `gr` table (all calls but `render`, which `run_scene_source` adds as
/// a scoped function borrowing the caller's callback).
pub(super) fn install(lua: &Lua) -> mlua::Result<()> {
    let gr = lua.create_table()?;
    macro_rules! def {
        ($name:literal, $f:expr) => {
            gr.set(
                $name,
                lua.create_function(|lua, args: MultiValue| {
                    ensure_live(lua)?;
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
    def!("checker", super::procedural::checker);
    def!("noise", super::procedural::noise);
    def!("marble", super::procedural::marble);
    def!("wood", super::procedural::wood);
    def!("light", light);
    def!("area_light", area_light);
    def!("transform_order", transform_order);
    def!("ignore_extra_arguments", notes::ignore_extra_arguments);
    unknown::install_gr_guard(lua, &gr)?;
    lua.globals().set("gr", gr)
}

/// Bytes a material holds besides its name.
const MATERIAL_BYTES: u64 = grown(std::mem::size_of::<Material>());

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
