//! The restricted Lua state scenes run in, and the compatibility globals (the limits'
//! record is `limits`).
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
use super::budget::{charge, check_file_cost, lua_share};
use super::config::ScriptConfig;
use super::limits::{
    end_thread, ensure_live, instruction_message, Limits, FREE_SCRIPT_TIME, NANOS_PER_INSTRUCTION,
};
use super::source::{source_text, SOURCE_BYTES_PER_BYTE};
use super::watchdog::ScriptClock;
use super::{with_state, LOADED_KEY};
use crate::scene::files::MAX_FILE_BYTES;
use crate::scene::obj::PARSE_BYTES_PER_BYTE;
use mlua::chunk::ChunkMode;
use mlua::{HookTriggers, Lua, LuaOptions, MultiValue, StdLib, Table, Value, VmState};

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
    lua.set_memory_limit(lua_share(config.memory_limit as u64) as usize)?;

    // The hook runs every `step` instructions; a step of ~1/1000 of the limit keeps the
    // overshoot small and the hook cost negligible.
    let limit = config.instruction_limit;
    let step = (limit / 1000).clamp(1, 100_000);
    let limits = limits.clone();
    let seconds = config.time_limit.as_secs_f64();
    // A global hook covers coroutines too.
    lua.set_global_hook(
        HookTriggers::new().every_nth_instruction(step as u32),
        move |lua, _debug| {
            let by_time = clock.used().saturating_sub(FREE_SCRIPT_TIME).as_nanos()
                / NANOS_PER_INSTRUCTION;
            let by_time = u64::try_from(by_time).unwrap_or(u64::MAX);
            let count = limits.count.get().saturating_add(step).max(by_time);
            limits.count.set(count);
            let timed_out = clock.expired();
            let reached = limits.reached();
            if count <= limit && !timed_out && reached.is_none() {
                // Cheap on most steps: the place is only needed for a memory error.
                limits.last_location.set(Some(location(lua)));
                return Ok(VmState::Continue);
            }
            let at = location(lua);
            let message = match reached {
                Some(m) => m,
                None if timed_out => {
                    let m = format!("{at}: script time limit of {seconds} s exceeded (renders not counted); --script-timeout SECONDS raises it");
                    clock.note(&m);
                    m
                }
                None => instruction_message(&at, limit),
            };
            end_thread(lua);
            Err(limits.reach(message))
        },
    )?;
    Ok(lua)
}

/// Installs the stubs, `require`, `unpack` and `readobj`.
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

    // `load` (text only, short chunk names) is installed by `wrappers`.

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
            ensure_live(lua)?;
            if super::preludes::caller_module_dir(lua).is_none() {
                super::era::strong(lua, "bare unpack (Lua 5.1)");
            }
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
                Value::String(s) => super::args::lossy_prefix(&s, 64),
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
/// by the file's identity (see `preludes`).
fn require(lua: &Lua, args: MultiValue) -> mlua::Result<Value> {
    ensure_live(lua)?;
    let a = Args::new(lua, "require", args);
    let name = a.file_name(1, "module")?;
    let prelude_dir = super::preludes::caller_module_dir(lua);
    if name == "readobj" {
        if prelude_dir.is_none() {
            super::era::strong(lua, "require('readobj'), the old course's mesh reader,");
        }
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
        // A prelude's modules are beside it: its folder is readable to it even where
        // the scene may not read it (a prelude in the home folder).
        Some(dir) => s
            .read_policy
            .with_root(dir)
            .open(&dir.join(&file), "module"),
        None => s.folders.find(&s.read_policy, &file, "module"),
    });
    // A prelude's modules are cached by identity (another folder's module of the
    // same name is another module); the scene's by name, as before.
    let key = match (&prelude_dir, &found) {
        (Some(_), Ok(opened)) => opened.id.key(),
        _ => name.clone(),
    };
    if prelude_dir.is_some() {
        let cached: Value = loaded.get(key.as_str())?;
        if !cached.is_nil() {
            return Ok(cached);
        }
    }
    let opened = found.map_err(|e| a.error(format!("module '{name}' not found: {e}")))?;
    let path = opened.path.clone();
    // Counted before it is read: the text, Lua's copy while parsing, the chunk.
    check_file_cost(&a, &opened, SOURCE_BYTES_PER_BYTE, "module")?;
    let bytes = opened
        .read("module", MAX_FILE_BYTES)
        .map_err(|e| a.error(format!("module '{name}' not found: {e}")))?;
    charge(&a, bytes.len() as u64, &format!("module '{name}'"))?;
    let text = String::from_utf8_lossy(&bytes);
    let shown = crate::display_path::shown(&path);
    let source = source_text(&shown, &text).map_err(|e| a.error(e))?;
    let chunk = format!("@{shown}");
    if let Some(dir) = &prelude_dir {
        super::preludes::adopt_module(lua, &chunk, dir);
    }
    // Nesting past Lua's parser is said at the module's own file and line.
    let left = super::budget::memory_left(lua) as usize;
    let value: Value = lua
        .load(source)
        .set_name(chunk)
        .set_mode(ChunkMode::Text)
        .into_function()
        .map_err(|e| super::deep_nesting::locate(e, source.as_bytes(), &shown, left))?
        .call((name.as_str(), path.to_string_lossy().into_owned()))?;
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
    ensure_live(lua)?;
    let a = Args::new(lua, "readobj", args);
    let file = a.file_name(1, "path")?;
    if super::preludes::caller_module_dir(lua).is_none() {
        super::era::strong(lua, "readobj, the old course's mesh reader,");
    }
    let found = with_state(lua, |s| s.folders.find(&s.read_policy, &file, "mesh file"));
    let opened = found.map_err(|e| a.error(e))?;
    check_file_cost(&a, &opened, PARSE_BYTES_PER_BYTE, "mesh file")?;
    let (verts, faces) = crate::scene::obj::read_obj_raw(opened).map_err(|e| a.error(e))?;
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
