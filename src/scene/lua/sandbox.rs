//! The restricted Lua state scenes run in, and the compatibility globals.
//!
//! A scene is a program downloaded from a course page or a classmate: it gets base,
//! table, string, math, utf8, coroutine and `os.clock/time/date`, nothing that touches
//! files or processes, text chunks only, and instruction and memory limits so that a
//! runaway loop ends with a message instead of a hung terminal (and a wall-clock limit,
//! `watchdog`, for time the hook cannot see). Finalizers (`__gc`) are refused: Lua runs
//! them with hooks off, and at the very end, after the script's state is gone. Removed
//! functions are replaced by stubs that say so, which reads better than "attempt to
//! call a nil value".
//!
//! Compatibility with the pre-2015 scenes: bare `unpack`, `require` of modules beside
//! the scene, and `readobj` as a built-in (their `readobj.lua` helper needed `io`).

use super::args::{location, Args};
use super::watchdog::ScriptClock;
use super::{charge, with_state, ScriptConfig, LOADED_KEY};
use crate::scene::files::{read_regular, MAX_FILE_BYTES};
use crate::scene::obj::PARSE_BYTES_PER_BYTE;
use mlua::chunk::ChunkMode;
use mlua::{HookTriggers, Lua, LuaOptions, MultiValue, StdLib, Table, Value, VmState};
use std::cell::Cell;
use std::rc::Rc;

/// What the hooks report, so the error can be classified after Lua unwinds (and cannot
/// be hidden by a `pcall` in the script).
#[derive(Default)]
pub(super) struct Limits {
    /// The instruction- or time-limit message, once a limit is passed.
    pub exceeded: Rc<Cell<Option<String>>>,
    /// `file:line` where the hook last ran (memory errors carry no position).
    pub last_location: Rc<Cell<Option<String>>>,
}

/// Creates the Lua state with the safe libraries and the limits of `config`; `clock`
/// says when the wall-clock limit has passed.
pub(super) fn new_lua(
    config: &ScriptConfig,
    limits: &Limits,
    clock: ScriptClock,
) -> mlua::Result<Lua> {
    let libs = StdLib::TABLE
        | StdLib::STRING
        | StdLib::MATH
        | StdLib::UTF8
        | StdLib::COROUTINE
        | StdLib::OS;
    let lua = Lua::new_with(libs, LuaOptions::default())?;
    lua.set_memory_limit(config.memory_limit)?;

    // The hook runs every `step` instructions; a step of ~1/1000 of the limit keeps the
    // overshoot small and the hook cost negligible.
    let limit = config.instruction_limit;
    let step = (limit / 1000).clamp(1, 100_000);
    let count = Cell::new(0u64);
    let exceeded = limits.exceeded.clone();
    let last_location = limits.last_location.clone();
    let seconds = config.time_limit.as_secs_f64();
    // A global hook covers coroutines too.
    lua.set_global_hook(
        HookTriggers::new().every_nth_instruction(step as u32),
        move |_lua, debug| {
            count.set(count.get() + step);
            let src = debug.source();
            let name = match src.source.as_deref() {
                Some(s) if s.starts_with('@') => s[1..].to_string(),
                _ => src.short_src.as_deref().unwrap_or("?").to_string(),
            };
            let line = debug
                .current_line()
                .map_or(String::new(), |l| format!(":{l}"));
            let timed_out = clock.expired();
            if count.get() <= limit && !timed_out {
                last_location.set(Some(format!("{name}{line}")));
                return Ok(VmState::Continue);
            }
            let message = if timed_out {
                let m = format!("{name}{line}: script time limit of {seconds} s exceeded (renders not counted); --script-timeout SECONDS raises it");
                clock.note(&m);
                m
            } else {
                format!("{name}{line}: instruction limit of {limit} exceeded — runaway loop?")
            };
            // Keep the first place it was noticed; later hook calls only re-raise.
            let first = exceeded.take().unwrap_or(message);
            exceeded.set(Some(first.clone()));
            Err(mlua::Error::RuntimeError(first))
        },
    )?;
    Ok(lua)
}

/// Installs the stubs, the text-only `load`, `require`, `unpack` and `readobj`.
pub(super) fn install(lua: &Lua) -> mlua::Result<()> {
    let g = lua.globals();

    for name in ["dofile", "loadfile"] {
        g.set(name, stub(lua, name)?)?;
    }
    let os: Table = g.get("os")?;
    for name in [
        "execute",
        "exit",
        "getenv",
        "remove",
        "rename",
        "tmpname",
        "setlocale",
    ] {
        os.set(name, stub(lua, &format!("os.{name}"))?)?;
    }
    // `io`, `debug` and `package.loadlib`: any field is a stub that explains itself.
    g.set("io", stub_table(lua, "io")?)?;
    g.set("debug", stub_table(lua, "debug")?)?;

    // Text chunks only: binary chunks can crash the VM. Keep `load`'s arity exact,
    // since an explicit nil `env` differs from none.
    lua.load(
        r#"
        local raw_load = ...
        load = function(...)
            local chunk, name, _, env = ...
            if select('#', ...) >= 4 then return raw_load(chunk, name, 't', env) end
            return raw_load(chunk, name, 't')
        end
        "#,
    )
    .set_name("=glint")
    .call::<()>(g.get::<Value>("load")?)?;

    // No finalizers: Lua runs `__gc` with hooks off (no limit can stop it) and at the
    // end, when the Lua state closes after the script's state was taken; an error in one
    // is swallowed. Lua marks an object for finalization only when `setmetatable` gives
    // it a metatable that already has a `__gc` field, so checking there is enough
    // (`debug.setmetatable` is not available; userdata metatables are protected).
    lua.load(
        r#"
        local raw_setmetatable, rawget, type, error = ...
        setmetatable = function(t, mt)
            if type(mt) == 'table' and rawget(mt, '__gc') ~= nil then
                error("setmetatable: finalizers (__gc) are not available in glint scenes", 2)
            end
            return raw_setmetatable(t, mt)
        end
        "#,
    )
    .set_name("=glint")
    .call::<()>((
        g.get::<Value>("setmetatable")?,
        g.get::<Value>("rawget")?,
        g.get::<Value>("type")?,
        g.get::<Value>("error")?,
    ))?;

    let loaded = lua.create_table()?;
    lua.set_named_registry_value(LOADED_KEY, &loaded)?;
    let package = lua.create_table()?;
    package.set("loaded", &loaded)?;
    package.set("loadlib", stub(lua, "package.loadlib")?)?;
    g.set("package", package)?;
    g.set("require", lua.create_function(require)?)?;

    // Lua 5.1's global `unpack`, used by the pre-2015 scenes.
    let table_unpack: mlua::Function = g.get::<Table>("table")?.get("unpack")?;
    g.set(
        "unpack",
        lua.create_function(move |lua, args: MultiValue| {
            with_state(lua, |s| s.report.looks_pre2015 = true);
            table_unpack.call::<MultiValue>(args)
        })?,
    )?;

    g.set("readobj", lua.create_function(readobj)?)?;
    Ok(())
}

/// A function that fails with "`name` is not available in glint scenes".
fn stub(lua: &Lua, name: &str) -> mlua::Result<mlua::Function> {
    let name = name.to_string();
    lua.create_function(move |lua, _: MultiValue| -> mlua::Result<()> {
        Err(mlua::Error::RuntimeError(format!(
            "{}: {name} is not available in glint scenes",
            location(lua)
        )))
    })
}

/// A table whose every field is a [`stub`] (reading `io.open` already fails, with the
/// line, so `io.open(...)` and `local f = io.open` both explain themselves).
fn stub_table(lua: &Lua, lib: &str) -> mlua::Result<Table> {
    let t = lua.create_table()?;
    let meta = lua.create_table()?;
    let lib = lib.to_string();
    meta.set(
        "__index",
        lua.create_function(move |lua, (_, key): (Value, Value)| -> mlua::Result<()> {
            let key = match key {
                Value::String(s) => s.to_string_lossy(),
                other => format!("[{}]", other.type_name()),
            };
            Err(mlua::Error::RuntimeError(format!(
                "{}: {lib}.{key} is not available in glint scenes (no file or process access)",
                location(lua)
            )))
        })?,
    )?;
    t.set_metatable(Some(meta))?;
    Ok(t)
}

/// `require(name)`: `readobj` is built in; anything else is `name.lua` (dots as folder
/// separators) beside the scene, run once in the same environment and cached. Called
/// from a prelude (or a module of one), it looks beside the prelude instead, and caches
/// by canonical path (see `preludes`).
fn require(lua: &Lua, args: MultiValue) -> mlua::Result<Value> {
    let a = Args::new(lua, "require", args);
    let name = a.string(1, "module")?;
    let prelude_dir = super::preludes::caller_module_dir(lua);
    if prelude_dir.is_none() {
        with_state(lua, |s| s.report.looks_pre2015 = true);
    }
    if name == "readobj" {
        super::notes::check_extra_arguments(&a);
        return Ok(Value::Boolean(true));
    }
    let loaded: Table = lua.named_registry_value(LOADED_KEY)?;
    if prelude_dir.is_none() {
        let cached: Value = loaded.get(name.as_str())?;
        if !cached.is_nil() {
            return Ok(cached);
        }
    }
    let file = format!("{}.lua", name.replace('.', "/"));
    let found = with_state(lua, |s| match &prelude_dir {
        // A prelude's modules are beside it.
        Some(dir) => {
            let path = dir.join(&file);
            s.read_policy.check(&path, "module").map(|c| (path, c))
        }
        None => s.folders.find(&s.read_policy, &file, "module"),
    });
    // A prelude's modules are cached by canonical path (another folder's module of the
    // same name is another module); the scene's by name, as before.
    let key = match (&prelude_dir, &found) {
        (Some(_), Ok((_, canonical))) => canonical.display().to_string(),
        _ => name.clone(),
    };
    if prelude_dir.is_some() {
        let cached: Value = loaded.get(key.as_str())?;
        if !cached.is_nil() {
            return Ok(cached);
        }
    }
    let source = found
        .and_then(|(path, _)| read_regular(&path, "module", MAX_FILE_BYTES).map(|b| (path, b)));
    let (path, source) = source.map_err(|e| a.error(format!("module '{name}' not found: {e}")))?;
    charge(&a, source.len() as u64, &format!("module '{name}'"))?;
    let chunk = format!("@{}", path.display());
    if let Some(dir) = &prelude_dir {
        super::preludes::adopt_module(lua, &chunk, dir);
    }
    let value: Value = lua
        .load(&source[..])
        .set_name(chunk)
        .set_mode(ChunkMode::Text)
        .call((name.as_str(), path.display().to_string()))?;
    let value = if value.is_nil() {
        Value::Boolean(true)
    } else {
        value
    };
    loaded.set(key.as_str(), &value)?;
    super::notes::check_extra_arguments(&a);
    Ok(value)
}

/// `readobj(path)`: an OBJ file as the `verts, faces` tables of the inline `gr.mesh`
/// form (0-based indices), as the course's old `readobj.lua` returned them.
fn readobj(lua: &Lua, args: MultiValue) -> mlua::Result<(Table, Table)> {
    let a = Args::new(lua, "readobj", args);
    let file = a.string(1, "path")?;
    let found = with_state(lua, |s| {
        s.report.looks_pre2015 = true;
        s.folders.find(&s.read_policy, &file, "mesh file")
    });
    let (path, _) = found.map_err(|e| a.error(e))?;
    super::check_file_cost(&a, &path, PARSE_BYTES_PER_BYTE, "mesh file")?;
    let (verts, faces) = crate::scene::obj::read_obj_raw(&path).map_err(|e| a.error(e))?;
    let vt = lua.create_table_with_capacity(verts.len(), 0)?;
    for v in verts {
        vt.raw_push(lua.create_sequence_from(v)?)?;
    }
    let ft = lua.create_table_with_capacity(faces.len(), 0)?;
    for f in faces {
        ft.raw_push(lua.create_sequence_from(f)?)?;
    }
    super::notes::check_extra_arguments(&a);
    Ok((vt, ft))
}
