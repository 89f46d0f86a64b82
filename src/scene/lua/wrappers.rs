//! Library functions wrapped so that the limits see what they cost and cannot be hidden.
//!
//! - `pcall`, `xpcall` (and each call of its message handler) and `coroutine.resume`
//!   weigh a few instructions each (an error costs far more than the instruction that
//!   raised it), and a memory error one of them catches is a reached limit: the script
//!   ends even though it was caught.
//! - `table.move`, `table.concat`, `table.sort`, `string.format`, `string.rep`,
//!   `string.reverse`, `string.upper`, `string.lower` and `collectgarbage` loop in C,
//!   where the instruction hook does not run: each call adds its work (elements, bytes,
//!   the heap a collection walks) to the instruction count before it runs. The GC's
//!   tuning calls are no-ops (a pause of 0 makes every allocation collect).
//! - `load` takes text only, and its chunk name is cut to one short line that cannot
//!   pose as a file (Lua shows it as `[string "…"]`), so a 256 MiB name is not copied
//!   into every message and `load(s, '@/etc/passwd')` blames no other file.

use super::args::location;
use super::limits::Limits;
use super::with_state;
use mlua::{Function, Lua, MultiValue, Table, Value};

/// Instructions one protected call (or message-handler call) weighs.
const PROTECTED_CALL_WEIGHT: u64 = 50;
/// Longest chunk name `load` keeps, in bytes.
const MAX_CHUNK_NAME: usize = 48;

/// Installs every wrapper (after the standard libraries, before the script runs).
pub(super) fn install(lua: &Lua) -> mlua::Result<()> {
    install_load(lua)?;
    install_protected_calls(lua)?;
    install_weighted(lua)?;
    install_collectgarbage(lua)
}

fn limits(lua: &Lua) -> Limits {
    with_state(lua, |s| s.limits.clone())
}

/// Adds `weight` instructions, failing at the caller's line past the limit.
pub(super) fn tick(lua: &Lua, weight: u64) -> mlua::Result<()> {
    limits(lua).tick(weight, || location(lua))
}

fn install_load(lua: &Lua) -> mlua::Result<()> {
    let g = lua.globals();
    let raw: Function = g.get("load")?;
    // Text chunks only: binary chunks can crash the VM. `load`'s arity is kept exact,
    // since an explicit nil `env` differs from none.
    let load = lua.create_function(move |lua, args: MultiValue| {
        let mut args: Vec<Value> = args.into_iter().collect();
        args.resize(args.len().max(3), Value::Nil);
        let given = match (&args[1], &args[0]) {
            (Value::String(s), _) | (Value::Nil, Value::String(s)) => Some(s.as_bytes().to_vec()),
            (Value::Nil, _) => Some(b"=(load)".to_vec()),
            _ => None,
        };
        if let Some(given) = given {
            args[1] = Value::String(lua.create_string(short_chunk_name(&given))?);
        }
        args[2] = Value::String(lua.create_string("t")?);
        raw.call::<MultiValue>(MultiValue::from_iter(args))
            .map_err(|e| relocate(lua, "load", e))
    })?;
    g.set("load", load)
}

/// The first line of `given`, at most [`MAX_CHUNK_NAME`] bytes, without the leading `@`
/// or `=` that would make Lua print it as a file name.
pub(super) fn short_chunk_name(given: &[u8]) -> String {
    let line = given
        .split(|&b| b == b'\n' || b == b'\r')
        .next()
        .unwrap_or(b"");
    let start = line
        .iter()
        .position(|&b| b != b'@' && b != b'=')
        .unwrap_or(line.len());
    let line = &line[start..line.len().min(start + MAX_CHUNK_NAME * 4)];
    let text = String::from_utf8_lossy(line);
    let mut end = text.len().min(MAX_CHUNK_NAME);
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    let cut = if end < text.len() { "…" } else { "" };
    format!("{}{cut}", &text[..end])
}

fn install_protected_calls(lua: &Lua) -> mlua::Result<()> {
    let g = lua.globals();
    let weigh = lua.create_function(|lua, ()| tick(lua, PROTECTED_CALL_WEIGHT))?;
    let checked = lua.create_function(|lua, results: MultiValue| {
        let mut values = results.iter();
        if let (Some(Value::Boolean(false)), Some(error)) = (values.next(), values.next()) {
            if is_memory_error(error) {
                return Err(memory_limit_reached(lua));
            }
        }
        Ok(results)
    })?;
    let coroutine: Table = g.get("coroutine")?;
    lua.load(
        r#"
        local pcall, xpcall, resume, coroutine, weigh, checked, type = ...
        _G.pcall = function(...)
            weigh()
            return checked(pcall(...))
        end
        _G.xpcall = function(f, handler, ...)
            weigh()
            local h = handler
            if type(handler) == 'function' then
                h = function(...) weigh() return handler(...) end
            end
            return checked(xpcall(f, h, ...))
        end
        coroutine.resume = function(...)
            weigh()
            return checked(resume(...))
        end
        "#,
    )
    .set_name("=glint")
    .call::<()>((
        g.get::<Value>("pcall")?,
        g.get::<Value>("xpcall")?,
        coroutine.get::<Value>("resume")?,
        coroutine,
        weigh,
        checked,
        g.get::<Value>("type")?,
    ))
}

/// Whether a caught error is Lua's (or mlua's) memory error.
fn is_memory_error(error: &Value) -> bool {
    match error {
        Value::String(s) => s.as_bytes().as_ref() == b"not enough memory",
        Value::Error(e) => is_memory(e),
        _ => false,
    }
}

fn is_memory(e: &mlua::Error) -> bool {
    match e {
        mlua::Error::MemoryError(_) => true,
        mlua::Error::CallbackError { cause, .. } | mlua::Error::WithContext { cause, .. } => {
            is_memory(cause)
        }
        _ => false,
    }
}

/// The memory limit reached at the caller's line (a caught memory error).
pub(super) fn memory_limit_reached(lua: &Lua) -> mlua::Error {
    let mib = with_state(lua, |s| s.memory_limit) >> 20;
    super::limits::end_thread(lua);
    limits(lua).reach(format!(
        "{}: the script went over the memory limit of {mib} MiB; --memory-limit MIB raises it",
        location(lua)
    ))
}

/// The weight of a library call from its arguments.
type Weigh = fn(&Lua, &MultiValue) -> u64;

fn install_weighted(lua: &Lua) -> mlua::Result<()> {
    let g = lua.globals();
    let string: Table = g.get("string")?;
    let table: Table = g.get("table")?;
    let wrapped: [(&Table, &str, Weigh); 8] = [
        (&table, "move", |_, a| 2 * span(int_at(a, 1), int_at(a, 2))),
        (&table, "concat", |_, a| {
            let last = int_at(a, 3).or_else(|| table_len(a));
            span(int_at(a, 2).or(Some(1)), last)
        }),
        (&table, "sort", |_, a| {
            let n = table_len(a).unwrap_or(0).max(0) as u64;
            n * (64 - n.leading_zeros() as u64) / 4
        }),
        (&string, "format", |_, a| {
            a.iter()
                .map(|v| match v {
                    Value::String(s) => s.as_bytes().len() as u64,
                    _ => 8,
                })
                .sum::<u64>()
        }),
        (&string, "rep", |_, a| {
            let n = int_at(a, 1).unwrap_or(0).max(0) as u64;
            n.saturating_mul(len_of(a, 0) + len_of(a, 2) + 1) / 64
        }),
        (&string, "reverse", |_, a| len_of(a, 0) / 64),
        (&string, "upper", |_, a| len_of(a, 0) / 64),
        (&string, "lower", |_, a| len_of(a, 0) / 64),
    ];
    for (lib, name, weigh) in wrapped {
        let raw: Function = lib.get(name)?;
        let label = name.to_string();
        lib.set(
            name,
            lua.create_function(move |lua, args: MultiValue| {
                tick(lua, weigh(lua, &args))?;
                raw.call::<MultiValue>(args)
                    .map_err(|e| relocate(lua, &label, e))
            })?,
        )?;
    }
    Ok(())
}

/// An error of a wrapped library function, as Lua would have worded it at the caller's
/// line (called from Rust, it lost both the line and its own name).
fn relocate(lua: &Lua, name: &str, e: mlua::Error) -> mlua::Error {
    match e {
        mlua::Error::RuntimeError(m) => mlua::Error::RuntimeError(format!(
            "{}: {}",
            location(lua),
            m.replace("to '?'", &format!("to '{name}'"))
        )),
        mlua::Error::MemoryError(_) => memory_limit_reached(lua),
        other => other,
    }
}

/// Elements from `first` to `last` (0 when either is missing or the range is empty).
fn span(first: Option<i64>, last: Option<i64>) -> u64 {
    match (first, last) {
        (Some(f), Some(l)) if l >= f => (l as i128 - f as i128 + 1).min(u64::MAX as i128) as u64,
        _ => 0,
    }
}

fn int_at(a: &MultiValue, i: usize) -> Option<i64> {
    a.get(i).and_then(super::args::int_value)
}

fn len_of(a: &MultiValue, i: usize) -> u64 {
    match a.get(i) {
        Some(Value::String(s)) => s.as_bytes().len() as u64,
        _ => 0,
    }
}

fn table_len(a: &MultiValue) -> Option<i64> {
    match a.front() {
        Some(Value::Table(t)) => Some(t.raw_len() as i64),
        _ => None,
    }
}

/// `collectgarbage`: a collection or step weighs the heap it walks (16 bytes per
/// instruction); the tuning calls change nothing.
fn install_collectgarbage(lua: &Lua) -> mlua::Result<()> {
    let g = lua.globals();
    let raw: Function = g.get("collectgarbage")?;
    g.set(
        "collectgarbage",
        lua.create_function(move |lua, args: MultiValue| {
            let option = match args.front() {
                Some(Value::String(s)) => s.to_string_lossy(),
                _ => "collect".to_string(),
            };
            match option.as_str() {
                "collect" | "step" => tick(lua, lua.used_memory() as u64 / 16)?,
                "incremental" | "generational" => {
                    return Ok(MultiValue::from_iter([Value::String(
                        lua.create_string("incremental")?,
                    )]))
                }
                "setpause" | "setstepmul" => return Ok(MultiValue::from_iter([Value::Integer(0)])),
                _ => {}
            }
            raw.call::<MultiValue>(args)
                .map_err(|e| relocate(lua, "collectgarbage", e))
        })?,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunk_names_are_short_and_never_files() {
        assert_eq!(short_chunk_name(b"@/etc/passwd"), "/etc/passwd");
        assert_eq!(short_chunk_name(b"=@=x\nsecond"), "x");
        let long = short_chunk_name(&vec![b'n'; 1 << 20]);
        assert!(long.len() <= MAX_CHUNK_NAME + 3, "{long}");
        assert_eq!(
            short_chunk_name("é".repeat(40).as_bytes()).chars().count(),
            25
        );
    }
}
