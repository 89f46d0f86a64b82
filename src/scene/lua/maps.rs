//! The calls that take images: the material methods `set_diffuse` and `set_specular` (a
//! colour, a texture file or a procedural texture) and `set_bump('height.png'[,
//! strength])` (or a procedural texture in place of the file), and `gr.render`'s
//! `environment` option (an HDR map). Files are resolved against the scene's directory
//! and decoded in Rust (`scene::texture`, `scene::environment`); each texture file is
//! loaded once per script.

use super::args::Args;
use super::budget::{charge, check_file_cost, memory_left};
use super::handle_types::ProceduralHandle;
use super::limits::reach_limit;
use super::with_state;
use crate::scene::environment::{environment_bytes, load_opened_environment, Environment};
use crate::scene::texture::{load_opened_texture, texture_bytes, OVER_BUDGET};
use crate::scene::{Material, TextureId, TextureRef};
use mlua::Value;
use std::sync::Arc;

/// An edit of the receiver material, applied once the arguments have been checked.
pub(super) type Edit = Box<dyn FnOnce(&mut Material)>;

/// Default `set_bump` strength: the normal tilts by the height's slope per texture unit.
pub const DEFAULT_BUMP_STRENGTH: f64 = 1.0;

/// `m:set_diffuse(r, g, b)` / `m:set_diffuse(grey)` / `m:set_diffuse('img.png')`.
pub(super) fn set_diffuse(a: &Args) -> mlua::Result<Edit> {
    colour_or_map(a, |m| &mut m.kd, |m| &mut m.diffuse_map)
}

/// `m:set_specular(r, g, b)` / `m:set_specular(grey)` / `m:set_specular('img.png')`.
pub(super) fn set_specular(a: &Args) -> mlua::Result<Edit> {
    colour_or_map(a, |m| &mut m.ks, |m| &mut m.specular_map)
}

/// A colour's setter: an image file's name or a procedural texture sets the material's
/// `map` to the texture (the colour stays, unused), a colour (numbers, grey or a table)
/// sets `colour` and clears the map.
fn colour_or_map(
    a: &Args,
    colour: fn(&mut Material) -> &mut [f32; 3],
    map: fn(&mut Material) -> &mut Option<TextureRef>,
) -> mlua::Result<Edit> {
    if let Some(p) = procedural(a, 1) {
        return Ok(Box::new(move |m: &mut Material| *map(m) = Some(p)));
    }
    if let Value::String(_) = a.get(1) {
        let id = texture(a, 1, "file")?;
        return Ok(Box::new(move |m: &mut Material| {
            *map(m) = Some(TextureRef::Image(id))
        }));
    }
    let c = a.colour_args(1, true)?;
    Ok(Box::new(move |m: &mut Material| {
        *colour(m) = c;
        *map(m) = None;
    }))
}

/// Argument `n` as a procedural texture (`gr.checker`, …), if it is one.
fn procedural(a: &Args, n: usize) -> Option<TextureRef> {
    match a.get(n) {
        Value::UserData(ud) => ud
            .borrow::<ProceduralHandle>()
            .ok()
            .map(|p| TextureRef::Procedural(p.0)),
        _ => None,
    }
}

/// `m:set_bump('height.png'[, strength])` or `m:set_bump(gr.noise(…)[, strength])`:
/// strength ≥ 0, default [`DEFAULT_BUMP_STRENGTH`]. A procedural texture's height is its
/// pattern (0 … 1), its slope the pattern's analytic gradient.
pub(super) fn set_bump(a: &Args) -> mlua::Result<Edit> {
    let procedural = procedural(a, 1);
    if procedural.is_none() && !matches!(a.get(1), Value::String(_)) {
        return Err(a.bad(
            1,
            "file",
            "the file name of a height map (PNG or JPEG) or a procedural texture",
        ));
    }
    // Check the strength before reading the file: a cheap error first.
    let strength = if a.is_nil(2) {
        DEFAULT_BUMP_STRENGTH
    } else {
        a.non_negative(2, "strength")?
    };
    let map = match procedural {
        Some(p) => p,
        None => TextureRef::Image(texture(a, 1, "file")?),
    };
    Ok(Box::new(move |m: &mut Material| {
        m.bump_map = Some(map);
        m.bump_strength = strength as f32;
    }))
}

/// Argument `n`, a file name, as a texture of the scene graph (loaded on first use; a
/// file is one texture under any spelling of its path). Its texels are counted against
/// the memory budget from the image's header, before it is decoded.
fn texture(a: &Args, n: usize, name: &str) -> mlua::Result<TextureId> {
    let file = a.file_name(n, name)?;
    let found = with_state(a.lua, |s| s.folders.find(&s.read_policy, &file, "texture"));
    let opened = found.map_err(|e| a.bad_in(n, name, e))?;
    let key = opened.id;
    if let Some(id) = with_state(a.lua, |s| s.texture_cache.get(&key).copied()) {
        return Ok(id);
    }
    // The file is held while it is decoded.
    check_file_cost(a, &opened, 1, "texture")?;
    // The file is held while it is decoded; the decoder counts the rest itself.
    let left = memory_left(a.lua).saturating_sub(opened.len);
    let texture = load_opened_texture(opened, left).map_err(|e| {
        if e.contains(OVER_BUDGET) {
            // The memory budget refused it: a reached limit, final as the others are.
            reach_limit(a, format!("argument {n} ({name}): {e}"))
        } else {
            a.bad_in(n, name, e)
        }
    })?;
    charge(
        a,
        texture_bytes(texture.width, texture.height),
        &format!("texture '{file}'"),
    )?;
    Ok(with_state(a.lua, |s| {
        s.graph.textures.push(Arc::new(texture));
        let id = s.graph.textures.len() - 1;
        s.texture_cache.insert(key, id);
        id
    }))
}

/// The `environment` option of the options table (argument `n`): `v`, a file name, read
/// and decoded as an [`Environment`], its texels charged to the memory budget (counted
/// from the image's header before it is decoded).
pub(super) fn environment(a: &Args, n: usize, v: &Value) -> mlua::Result<Arc<Environment>> {
    let bad = |detail: String| a.bad_in(n, "options", format!("environment: {detail}"));
    let file = match v {
        Value::String(s) if s.as_bytes().len() <= super::args::MAX_TEXT_ARG => s
            .to_str()
            .map(|s| s.to_string())
            .ok()
            .filter(|s| !s.contains('\0')),
        _ => None,
    }
    .ok_or_else(|| {
        bad(format!(
            "must be the file name of an OpenEXR or Radiance HDR image, got {}",
            super::args::describe(a.lua, v)
        ))
    })?;
    let found = with_state(a.lua, |s| {
        s.folders.find(&s.read_policy, &file, "environment")
    });
    let opened = found.map_err(bad)?;
    check_file_cost(a, &opened, 1, "environment")?;
    // The file is held while it is decoded; the decoder counts the rest itself.
    let left = memory_left(a.lua).saturating_sub(opened.len);
    let environment = load_opened_environment(opened, left).map_err(|e| {
        if e.contains(OVER_BUDGET) {
            reach_limit(a, format!("argument {n} (options): environment: {e}"))
        } else {
            bad(e)
        }
    })?;
    charge(
        a,
        environment_bytes(environment.width, environment.height),
        &format!("environment '{file}'"),
    )?;
    Ok(Arc::new(environment))
}
