//! The method tables of nodes and materials, and the calls that extend them:
//! `gr.extend_node(name, fn)` and `gr.extend_material(name, fn)`.
//!
//! A node's or material's methods live in a plain Lua table per kind, kept in the
//! registry and set as the userdata's `__index` (a table lookup: as fast as mlua's own
//! method dispatch): the built-ins of `handles` first, then whatever the script adds or
//! replaces. A name the table lacks reaches the table's own `__index`, which raises an
//! error naming the methods there are. This is the lever a dialect prelude
//! (`--prelude`) pulls to give handles the methods another CS488 tracer had
//! (`m:set_texture(file)`, `m:set_bumpmap(file)`), written in Lua the user can read. An
//! extension is an ordinary Lua function of the sandbox: it runs under the script's
//! limits and can do no more than the script could by calling the built-ins itself.

use super::args::{location, Args};
use mlua::{Lua, MultiValue, Table, Value};

/// A built-in method: a plain function of the receiver and its arguments, kept in the
/// methods table of its kind.
pub(super) type Method = fn(&Lua, MultiValue) -> mlua::Result<Value>;

/// Which handles a method table serves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    Node,
    Material,
}

impl Kind {
    fn registry_key(self) -> &'static str {
        match self {
            Kind::Node => "glint.methods.node",
            Kind::Material => "glint.methods.material",
        }
    }

    fn noun(self) -> &'static str {
        match self {
            Kind::Node => "node",
            Kind::Material => "material",
        }
    }
}

/// Fills the method tables with the built-ins (`handles`' node and material methods) and
/// defines `gr.extend_node` and `gr.extend_material` (the `gr` table must exist).
pub(super) fn install(
    lua: &Lua,
    node_methods: Vec<(&'static str, Method)>,
    material_methods: Vec<(&'static str, Method)>,
) -> mlua::Result<()> {
    let gr: Table = lua.globals().get("gr")?;
    for (kind, builtins) in [
        (Kind::Node, node_methods),
        (Kind::Material, material_methods),
    ] {
        let table = lua.create_table()?;
        for (name, method) in builtins {
            table.raw_set(name, lua.create_function(method)?)?;
        }
        let on_miss = lua.create_table()?;
        on_miss.raw_set(
            "__index",
            lua.create_function(
                move |lua, (table, key): (Table, Value)| -> mlua::Result<()> {
                    Err(missing(lua, kind, &table, &key))
                },
            )?,
        )?;
        table.set_metatable(Some(on_miss))?;
        lua.set_named_registry_value(kind.registry_key(), table)?;
        let call = format!("gr.extend_{}", kind.noun());
        gr.set(
            format!("extend_{}", kind.noun()),
            lua.create_function(move |lua, args: MultiValue| {
                extend(&Args::new(lua, &call, args), kind)
            })?,
        )?;
    }
    Ok(())
}

/// `gr.extend_KIND(name, fn)`: `fn` becomes method `name` of every handle of the kind,
/// made before or after (`x:name(...)` calls `fn(x, ...)`); a built-in of that name is
/// replaced. Returns the method it replaces (nil if there was none), so an extension can
/// hand on the calls it does not change.
fn extend(a: &Args, kind: Kind) -> mlua::Result<Value> {
    let name = a.string(1, "name")?;
    if name.is_empty() {
        return Err(a.bad(1, "name", "a method name"));
    }
    let Value::Function(f) = a.get(2).clone() else {
        return Err(a.bad(2, "method", "a function (called with the handle first)"));
    };
    let table: Table = a.lua.named_registry_value(kind.registry_key())?;
    let previous: Value = table.raw_get(name.as_str())?;
    table.raw_set(name, f)?;
    Ok(previous)
}

/// The method table of `kind` (the handles' `__index`).
pub(super) fn table(lua: &Lua, kind: Kind) -> mlua::Result<Table> {
    lua.named_registry_value(kind.registry_key())
}

/// The error for a method `key` that handles of `kind` lack, naming the methods there are.
fn missing(lua: &Lua, kind: Kind, table: &Table, key: &Value) -> mlua::Error {
    let mut names: Vec<String> = table
        .pairs::<String, Value>()
        .filter_map(|p| p.ok().map(|(k, _)| k))
        .collect();
    names.sort();
    let key = match key {
        Value::String(s) => format!("'{}'", s.to_string_lossy()),
        other => super::args::describe(lua, other),
    };
    mlua::Error::RuntimeError(format!(
        "{}: a {noun} has no method {key} (a {noun}'s methods: {}; gr.extend_{noun} adds one)",
        location(lua),
        names.join(", "),
        noun = kind.noun(),
    ))
}
