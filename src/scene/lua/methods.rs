//! The method tables of nodes and materials, and the calls that extend them:
//! `gr.extend_node(name, fn)` and `gr.extend_material(name, fn)`.
//!
//! A node's or material's methods live in a plain Lua table per kind, kept in the
//! registry: the built-ins of `handles` first, then whatever the script adds or
//! replaces. The handles' `__index` is a small Lua function over that table; a name it
//! lacks reaches Rust for the error naming the receiver and the methods there are. This
//! is the lever a dialect prelude (`--prelude`) pulls to give handles the methods another
//! CS488 tracer had (`m:set_texture(file)`, `m:set_bumpmap(file)`), written in Lua the
//! user can read. An
//! extension is an ordinary Lua function of the sandbox: it runs under the script's
//! limits and can do no more than the script could by calling the built-ins itself.

use super::args::{describe, Args};
use super::unknown::unknown_method;
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

    fn index_key(self) -> &'static str {
        match self {
            Kind::Node => "glint.methods.node.index",
            Kind::Material => "glint.methods.material.index",
        }
    }

    fn noun(self) -> &'static str {
        match self {
            Kind::Node => "node",
            Kind::Material => "material",
        }
    }
}

/// Fills the method tables with the built-ins (`handles`' node and material methods),
/// makes each kind's `__index`, and defines `gr.extend_node` and `gr.extend_material`
/// (the `gr` table must exist).
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
        // A Lua function, so a method call costs a table lookup as mlua's own dispatch
        // does; only a miss reaches Rust, to name the receiver and the methods there are.
        let miss = lua.create_function(
            move |lua, (this, key): (mlua::AnyUserData, Value)| -> mlua::Result<()> {
                Err(missing(lua, kind, &this, &key))
            },
        )?;
        let index: mlua::Function = lua
            .load(
                "local methods, miss = ...\n\
                 return function(self, key)\n\
                   local f = methods[key]\n\
                   if f ~= nil then return f end\n\
                   return miss(self, key)\n\
                 end",
            )
            .set_name(INDEX_CHUNK)
            .call((&table, miss))?;
        lua.set_named_registry_value(kind.registry_key(), &table)?;
        lua.set_named_registry_value(kind.index_key(), index)?;
        let call = format!("gr.extend_{}", kind.noun());
        gr.raw_set(
            format!("extend_{}", kind.noun()),
            lua.create_function(move |lua, args: MultiValue| {
                extend(&Args::new(lua, &call, args), kind)
            })?,
        )?;
    }
    Ok(())
}

/// The chunk name of the `__index` functions, which `args::location` skips (they are not
/// the scene's code).
pub(crate) const INDEX_CHUNK: &str = "=__glint_method_index";

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

/// The `__index` of the handles of `kind` (made by [`install`]).
pub(super) fn index(lua: &Lua, kind: Kind) -> mlua::Result<mlua::Function> {
    lua.named_registry_value(kind.index_key())
}

/// The error for a method `key` that `this` (a handle of `kind`) lacks, naming it as the
/// scene language does and the methods there are (extensions included).
fn missing(lua: &Lua, kind: Kind, this: &mlua::AnyUserData, key: &Value) -> mlua::Error {
    let names = match lua.named_registry_value::<Table>(kind.registry_key()) {
        Ok(table) => {
            let mut names: Vec<String> = table
                .pairs::<String, Value>()
                .filter_map(|p| p.ok().map(|(k, _)| k))
                .collect();
            names.sort();
            names
        }
        Err(e) => return e,
    };
    let receiver = describe(lua, &Value::UserData(this.clone()));
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    unknown_method(lua, &receiver, key, &names)
}
