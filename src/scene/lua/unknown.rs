//! Calls the scene language does not have, answered with what to do instead: an unknown
//! `gr.X` names the nearest of glint's calls; one that other students' tracers added
//! (`gr.plane`, `gr.arealight`, …) also the one that does the same and the dialect
//! preludes; a method a node, material or light does not have names the type as the
//! scene language calls it (never a Rust type) and its methods.

use super::args::{describe, location};
use mlua::{Lua, Table, Value};

/// Where a scene written for another CS488 tracer finds its calls.
pub(crate) const DIALECT_HINT: &str = "a scene written for another CS488 tracer can map \
    its calls onto glint's with a dialect prelude (glint render SCENE --prelude FILE; \
    see scenes/dialects/)";

/// glint's way of doing what calls of other CS488 tracers did, by their names.
const FOREIGN_CALLS: &[(&[&str], &str)] = &[
    (
        &["plane", "nh_plane", "nh_sheet", "nh_rect", "rect", "quad", "disc", "disk", "sheet"],
        "a flat piece is a gr.mesh of one quad, gr.mesh(name, {{x,y,z}, …}, {{0, 1, 2, 3}}), or a thin gr.cube",
    ),
    (
        &["arealight", "area", "sphericallight", "disc_light", "disk_light", "rect_light"],
        "gr.area_light(centre, u, v, colour, falloff[, n]) is a parallelogram light",
    ),
    (
        &["mirror_material", "clear_material", "transparent_material", "glass_material", "glass", "mirror"],
        "make a gr.material and call m:set_reflection(r) (a mirror) or m:set_refraction(ior) (glass)",
    ),
    (
        &["image_material", "texture", "texture_material", "textured_material"],
        "make a gr.material and call m:set_diffuse('image.png')",
    ),
    (
        &["union", "difference", "intersection", "intersect", "subtract"],
        "gr.csg(name, 'u', a, b) (union), 'd' (a minus b), 'i' (intersection)",
    ),
    (
        &["nh_cylinder", "nh_cone", "nh_torus"],
        "place gr.cylinder, gr.cone or gr.torus with node:scale and node:translate",
    ),
    (&["box", "nh_cube"], "gr.cube(name) or gr.nh_box(name, corner, size)"),
];

/// Methods other CS488 tracers' handles had (the dialect preludes map the first ones):
/// only these get [`DIALECT_HINT`], not a typo of one of glint's methods.
const FOREIGN_METHODS: &[&str] = &[
    "set_texture",
    "set_bumpmap",
    "set_bump_map",
    "set_normal_map",
    "set_transparency",
    "set_transmission",
    "set_ior",
    "set_index",
    "set_reflectivity",
    "set_reflective",
    "set_refractive",
    "set_mirror",
    "set_glossiness",
    "set_position",
    "set_colour",
    "set_color",
    "set_falloff",
];

/// `; DIALECT_HINT` when `name` is a method other tracers' handles had, else nothing.
fn foreign_method_hint(name: &str) -> String {
    if FOREIGN_METHODS.contains(&name.to_ascii_lowercase().as_str()) {
        format!("; {DIALECT_HINT}")
    } else {
        String::new()
    }
}

/// Makes indexing `gr` with a name it does not hold an error that says so (instead of
/// nil, which Lua reports as `attempt to call a nil value (field 'plane')`). A script
/// that wants to test for a call uses `rawget(gr, 'name')`.
pub(super) fn install_gr_guard(lua: &Lua, gr: &Table) -> mlua::Result<()> {
    let meta = lua.create_table()?;
    meta.set(
        "__index",
        lua.create_function(|lua, (gr, key): (Table, Value)| -> mlua::Result<Value> {
            Err(unknown_gr_call(lua, &gr, &key))
        })?,
    )?;
    gr.set_metatable(Some(meta))?;
    Ok(())
}

/// The error for `gr.<key>`, which `gr` does not hold.
fn unknown_gr_call(lua: &Lua, gr: &Table, key: &Value) -> mlua::Error {
    let name = match key {
        Value::String(s) => s.to_string_lossy(),
        other => describe(lua, other),
    };
    let names: Vec<String> = gr
        .pairs::<String, Value>()
        .filter_map(Result::ok)
        .map(|(k, _)| k)
        .collect();
    let nearest: Vec<String> = nearest(&name, &names)
        .into_iter()
        .map(|n| format!("gr.{n}"))
        .collect();
    let mut message = format!(
        "{}: `gr.{name}` is not part of glint's scene language (nearest: {})",
        location(lua),
        nearest.join(", ")
    );
    let lower = name.to_ascii_lowercase();
    // Names other tracers use get glint's way and the dialect preludes; a typo of one of
    // glint's own calls gets the nearest names alone.
    if let Some((_, instead)) = FOREIGN_CALLS
        .iter()
        .find(|(names, _)| names.contains(&lower.as_str()))
    {
        message += &format!("; {instead}; {DIALECT_HINT}");
    }
    mlua::Error::RuntimeError(message)
}

/// The error for `receiver:<key>(…)` on a value of scene-language type `kind` (`node
/// 'root'`, `material 'glass'`, `a light`) whose methods are `methods`.
pub(crate) fn unknown_method(lua: &Lua, kind: &str, key: &Value, methods: &[&str]) -> mlua::Error {
    let name = match key {
        Value::String(s) => s.to_string_lossy(),
        other => describe(lua, other),
    };
    let at = location(lua);
    let dialect = foreign_method_hint(&name);
    if methods.is_empty() {
        return mlua::Error::RuntimeError(format!(
            "{at}: {kind} has no methods (`{name}` was asked for): a light is made whole by \
             gr.light(position, colour, falloff) or gr.area_light(centre, u, v, colour, \
             falloff[, n]) and goes in gr.render's list of lights{dialect}"
        ));
    }
    let names: Vec<String> = methods.iter().map(|m| m.to_string()).collect();
    mlua::Error::RuntimeError(format!(
        "{at}: {kind} has no method `{name}` (its methods: {}; nearest: {}){dialect}",
        methods.join(", "),
        nearest(&name, &names).join(", ")
    ))
}

/// Up to three of `names` nearest to `name` (edit distance, ignoring case; ties by name).
fn nearest(name: &str, names: &[String]) -> Vec<String> {
    let lower = name.to_ascii_lowercase();
    let mut scored: Vec<(usize, &String)> = names
        .iter()
        .map(|n| (edit_distance(&lower, &n.to_ascii_lowercase()), n))
        .collect();
    scored.sort();
    scored.into_iter().take(3).map(|(_, n)| n.clone()).collect()
}

/// Levenshtein distance between `a` and `b`, by characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let substitute = diagonal + usize::from(ca != cb);
            diagonal = row[j + 1];
            row[j + 1] = substitute.min(row[j] + 1).min(row[j + 1] + 1);
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_names_by_edit_distance() {
        assert_eq!(edit_distance("plane", "plane"), 0);
        assert_eq!(edit_distance("nh_box", "nh_bx"), 1);
        assert_eq!(edit_distance("", "abc"), 3);
        let names: Vec<String> = ["sphere", "cube", "cone", "mesh", "light"]
            .map(String::from)
            .to_vec();
        assert_eq!(nearest("Spheres", &names)[0], "sphere");
        assert_eq!(nearest("lights", &names)[0], "light");
    }
}
