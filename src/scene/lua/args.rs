//! Argument checking for the `gr` calls, and the wording of their errors.
//!
//! Every error reads `file:line: function: argument N (name) must be WHAT, got VALUE`, so
//! a student sees where, which call, which argument and what they passed. The location
//! is taken from the nearest Lua frame on the stack, since errors raised by Rust
//! callbacks get no position from Lua itself.

use super::handle_types::{LightHandle, MaterialHandle, NodeHandle, ProceduralHandle};
use super::with_state;
use crate::scene::{short_name, Bounded, MaterialId, NodeId};
use glam::DVec3;
use mlua::{Lua, MultiValue, Table, Value};
use std::cell::Cell;

/// `file:line` of the innermost Lua code running (skipping Rust and C frames, and
/// glint's own Lua wrappers, chunk `=glint`). Code of a prelude (`--prelude`) is skipped
/// too when scene code called it: an error in a call the prelude makes on the scene's
/// behalf names the scene's line (and [`Args::error`] names the prelude's line as well).
pub(crate) fn location(lua: &Lua) -> String {
    let (at, _) = locations(lua);
    at
}

/// The location, and the innermost prelude frame it skipped (if any).
fn locations(lua: &Lua) -> (String, Option<String>) {
    let mut skipped = None;
    for level in 0..64 {
        let frame = lua.inspect_stack(level, |d| {
            let src = d.source();
            let chunk = src.source.as_deref().map(str::to_string);
            let name = match src.source.as_deref() {
                Some("=glint") => None,
                Some(s) if s.starts_with('@') || s.starts_with('=') => Some(s[1..].to_string()),
                _ => Some(src.short_src.as_deref().unwrap_or("?").to_string()),
            };
            (chunk, name, d.current_line())
        });
        match frame {
            None => break,
            // mlua's and glint's own Lua helpers (the `__index` that looks up methods,
            // `methods::INDEX_CHUNK`) are not the scene's code.
            Some((_, Some(name), _))
                if name.starts_with("__mlua") || name.starts_with("__glint") => {}
            Some((chunk, Some(name), Some(line))) => {
                let here = format!("{name}:{line}");
                if is_prelude_chunk(lua, chunk.as_deref()) {
                    skipped.get_or_insert(here);
                    continue;
                }
                return (here, skipped);
            }
            Some(_) => {}
        }
    }
    // Only prelude code on the stack (a prelude's own top level): its line.
    match skipped {
        Some(at) => (at, None),
        None => (String::from("?"), None),
    }
}

/// Whether `chunk` (`@path`) is a prelude or one of its modules.
fn is_prelude_chunk(lua: &Lua, chunk: Option<&str>) -> bool {
    let Some(chunk) = chunk else {
        return false;
    };
    // `try_`: a location asked for while the state is borrowed finds no preludes rather
    // than panicking.
    matches!(
        lua.try_app_data_ref::<super::State>(),
        Ok(Some(s)) if s.module_dirs.contains_key(chunk)
    )
}

/// A Lua-style rendering of a value for "got …" in messages.
pub(crate) fn describe(lua: &Lua, v: &Value) -> String {
    match v {
        Value::Nil => "nil".into(),
        Value::Boolean(b) => b.to_string(),
        Value::Integer(i) => i.to_string(),
        Value::Number(x) => format_number(*x),
        Value::String(s) => {
            // Only the start is copied out of Lua: the string may be hundreds of MiB.
            let s = lossy_prefix(s, 160);
            if s.chars().count() > 40 {
                format!("'{}…'", s.chars().take(40).collect::<String>())
            } else {
                format!("'{s}'")
            }
        }
        Value::Table(t) => match t.raw_len() {
            0 => "a table".into(),
            n => short_numbers(t, n).unwrap_or_else(|| format!("a table of {n} elements")),
        },
        Value::Function(_) => "a function".into(),
        Value::UserData(ud) => {
            if let Ok(n) = ud.borrow::<NodeHandle>() {
                let id = n.0;
                with_state(lua, |s| {
                    format!("node '{}'", short_name(&s.graph.nodes[id].name))
                })
            } else if let Ok(m) = ud.borrow::<MaterialHandle>() {
                let id = m.0;
                with_state(lua, |s| {
                    format!("material '{}'", short_name(&s.graph.materials[id].name))
                })
            } else if ud.is::<LightHandle>() {
                "a light".into()
            } else if let Ok(p) = ud.borrow::<ProceduralHandle>() {
                p.describe()
            } else {
                "a userdata".into()
            }
        }
        other => other.type_name().to_string(),
    }
}

/// A table of at most four numbers and nothing else (a vector, a colour) as Lua writes
/// it: `{0, 0, 0}`, so that an error shows the value that was wrong.
fn short_numbers(t: &Table, n: usize) -> Option<String> {
    if n > 4 || t.pairs::<Value, Value>().count() != n {
        return None;
    }
    let mut parts = Vec::with_capacity(n);
    for i in 1..=n {
        match t.raw_get::<Value>(i).ok()? {
            Value::Integer(x) => parts.push(x.to_string()),
            Value::Number(x) => parts.push(format_number(x)),
            _ => return None,
        }
    }
    Some(format!("{{{}}}", parts.join(", ")))
}

/// Longest string accepted where a short one is meant (file names, axes, operators,
/// orders): longer ones are refused before they are copied out of Lua.
pub const MAX_TEXT_ARG: usize = 4096;

/// At most the first `max` bytes of a Lua string, as text (for messages and keywords).
pub(crate) fn lossy_prefix(s: &mlua::LuaString, max: usize) -> String {
    let bytes = s.as_bytes();
    String::from_utf8_lossy(&bytes[..bytes.len().min(max)]).into_owned()
}

/// Numbers as Lua users write them: `-1`, `0.5`, `nan`, `inf`.
pub(crate) fn format_number(x: f64) -> String {
    if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf" } else { "-inf" }.into()
    } else {
        x.to_string()
    }
}

/// A finite number from a Lua value, or a description of what was wrong.
pub(crate) fn finite(v: &Value) -> Option<f64> {
    match v {
        Value::Integer(i) => Some(*i as f64),
        Value::Number(x) if x.is_finite() => Some(*x),
        _ => None,
    }
}

/// The arguments of one `gr` call, with the call's name for messages. For methods
/// (`node:scale(...)`) the receiver is argument 0 and numbering starts after it, as the
/// user wrote them.
pub(crate) struct Args<'a> {
    pub lua: &'a Lua,
    pub func: String,
    vals: Vec<Value>,
    offset: usize,
    /// The highest argument number the call has looked at (for the notes on arguments
    /// it was passed but does not use, `notes::check_extra_arguments`).
    used: Cell<usize>,
}

impl<'a> Args<'a> {
    pub fn new(lua: &'a Lua, func: &str, args: MultiValue) -> Self {
        Args {
            lua,
            func: func.to_string(),
            vals: args.into_iter().collect(),
            offset: 0,
            used: Cell::new(0),
        }
    }

    pub fn method(lua: &'a Lua, func: &str, args: MultiValue) -> Self {
        Args {
            offset: 1,
            ..Args::new(lua, func, args)
        }
    }

    /// Argument `n` (1-based, as the user counts; 0 is a method's receiver). Looking at
    /// it counts as using it.
    pub fn get(&self, n: usize) -> &Value {
        self.used.set(self.used.get().max(n));
        self.vals.get(n + self.offset - 1).unwrap_or(&Value::Nil)
    }

    /// The highest argument number the call has looked at so far.
    pub fn used(&self) -> usize {
        self.used.get()
    }

    /// The number of arguments passed, trailing nils not counted (the receiver of a
    /// method neither).
    pub fn passed(&self) -> usize {
        let given = &self.vals[self.offset.min(self.vals.len())..];
        given.iter().rposition(|v| !v.is_nil()).map_or(0, |i| i + 1)
    }

    pub fn is_nil(&self, n: usize) -> bool {
        matches!(self.get(n), Value::Nil)
    }

    /// `file:line: func: msg` as a Lua runtime error.
    pub fn error(&self, msg: impl std::fmt::Display) -> mlua::Error {
        let (at, prelude) = locations(self.lua);
        let via = prelude.map_or(String::new(), |p| {
            format!(" (called by the prelude at {p})")
        });
        mlua::Error::RuntimeError(format!("{at}: {}{via}: {msg}", self.func))
    }

    /// `… argument n (name) must be WHAT, got VALUE`; for a method called with `.` whose
    /// argument is missing (the object took its place), how to call it with `:`.
    pub fn bad(&self, n: usize, name: &str, what: &str) -> mlua::Error {
        let got = describe(self.lua, self.get(n));
        let missing = self.offset == 1 && self.get(n).is_nil() && n > self.passed();
        let hint = match missing {
            true => {
                super::dot_call::hint(self.lua, &self.func, &location(self.lua)).unwrap_or_default()
            }
            false => String::new(),
        };
        self.error(format!(
            "argument {n} ({name}) must be {what}, got {got}{hint}"
        ))
    }

    /// `… argument n (name): DETAIL`, for problems inside a table argument.
    pub fn bad_in(&self, n: usize, name: &str, detail: impl std::fmt::Display) -> mlua::Error {
        self.error(format!("argument {n} ({name}): {detail}"))
    }

    /// Element `index` (from 0) of argument `n`'s table is not `what`: the error names the
    /// element as Lua counts (from 1) and what it holds.
    pub fn bad_element(
        &self,
        n: usize,
        name: &str,
        index: usize,
        what: &str,
        got: &Value,
    ) -> mlua::Error {
        let got = describe(self.lua, got);
        self.bad_in(
            n,
            name,
            format!("element {} must be {what}, got {got}", index + 1),
        )
    }

    pub fn string(&self, n: usize, name: &str) -> mlua::Result<String> {
        match self.get(n) {
            Value::String(s) => Ok(s.to_string_lossy()),
            // Lua's own string arguments accept numbers (`gr.node(1)`), so do we.
            Value::Integer(i) => Ok(i.to_string()),
            Value::Number(x) if x.is_finite() => Ok(format_number(*x)),
            _ => Err(self.bad(n, name, "a string")),
        }
    }

    /// A file name argument: a short string ([`Args::text`]) in UTF-8 without NUL bytes
    /// (a name with other bytes would be mangled into another name, and a message
    /// would name neither).
    pub fn file_name(&self, n: usize, name: &str) -> mlua::Result<String> {
        if let Value::String(s) = self.get(n) {
            let bytes = s.as_bytes();
            if bytes.len() <= MAX_TEXT_ARG
                && (std::str::from_utf8(&bytes).is_err() || bytes.contains(&0))
            {
                return Err(self.bad(n, name, "a file name in UTF-8, without NUL bytes"));
            }
        }
        self.text(n, name)
    }

    /// A short string argument (at most [`MAX_TEXT_ARG`] bytes, refused before it is
    /// copied): file names, axes, orders.
    pub fn text(&self, n: usize, name: &str) -> mlua::Result<String> {
        if let Value::String(s) = self.get(n) {
            let len = s.as_bytes().len();
            if len > MAX_TEXT_ARG {
                return Err(self.bad_in(
                    n,
                    name,
                    format!("a string of {len} bytes; at most {MAX_TEXT_ARG} here"),
                ));
            }
        }
        self.string(n, name)
    }

    pub fn number(&self, n: usize, name: &str) -> mlua::Result<f64> {
        finite(self.get(n)).ok_or_else(|| self.bad(n, name, "a finite number"))
    }

    pub fn positive(&self, n: usize, name: &str) -> mlua::Result<f64> {
        match finite(self.get(n)) {
            Some(x) if x > 0.0 => Ok(x),
            _ => Err(self.bad(n, name, "a positive number")),
        }
    }

    pub fn non_negative(&self, n: usize, name: &str) -> mlua::Result<f64> {
        match finite(self.get(n)) {
            Some(x) if x >= 0.0 => Ok(x),
            _ => Err(self.bad(n, name, "a non-negative number")),
        }
    }

    /// A positive integer that fits `max` (image sizes).
    pub fn positive_int(&self, n: usize, name: &str, max: u32) -> mlua::Result<u32> {
        match int_value(self.get(n)) {
            Some(i) if i >= 1 && i <= max as i64 => Ok(i as u32),
            _ => Err(self.bad(n, name, &format!("a positive integer (at most {max})"))),
        }
    }

    /// An integer in the range of a typed option (`Bounded<MIN, MAX>`, e.g.
    /// `ShadowSamples`), or an error naming that range.
    pub fn bounded<const MIN: u32, const MAX: u32>(
        &self,
        n: usize,
        name: &str,
    ) -> mlua::Result<Bounded<MIN, MAX>> {
        int_value(self.get(n))
            .and_then(Bounded::new)
            .ok_or_else(|| self.bad(n, name, &Bounded::<MIN, MAX>::expected()))
    }

    pub fn table(&self, n: usize, name: &str, what: &str) -> mlua::Result<Table> {
        match self.get(n) {
            Value::Table(t) => Ok(t.clone()),
            _ => Err(self.bad(n, name, what)),
        }
    }

    /// `{x, y, z}`: a table whose first three elements are finite numbers.
    pub fn vec3(&self, n: usize, name: &str) -> mlua::Result<DVec3> {
        let t = self.table(n, name, "a table of 3 numbers {x, y, z}")?;
        self.vec3_from(&t, n, name).map(DVec3::from_array)
    }

    /// `{r, g, b}` as a colour.
    pub fn colour(&self, n: usize, name: &str) -> mlua::Result<[f32; 3]> {
        let t = self.table(n, name, "a table of 3 numbers {r, g, b}")?;
        let [r, g, b] = self.vec3_from(&t, n, name)?;
        Ok([r as f32, g as f32, b as f32])
    }

    /// Reads elements 1..=3 of `t` (argument `n`) as finite numbers.
    pub fn vec3_from(&self, t: &Table, n: usize, name: &str) -> mlua::Result<[f64; 3]> {
        let mut out = [0.0; 3];
        for (i, slot) in out.iter_mut().enumerate() {
            let v: Value = t.raw_get(i + 1)?;
            *slot =
                finite(&v).ok_or_else(|| self.bad_element(n, name, i, "a finite number", &v))?;
        }
        Ok(out)
    }

    /// A colour given as one table, three numbers, or (when `grey_ok`) one grey number,
    /// starting at argument `n`.
    pub fn colour_args(&self, n: usize, grey_ok: bool) -> mlua::Result<[f32; 3]> {
        match self.get(n) {
            Value::Table(_) => self.colour(n, "colour"),
            v if finite(v).is_some() => {
                let r = self.number(n, "r")? as f32;
                if grey_ok && self.is_nil(n + 1) && self.is_nil(n + 2) {
                    return Ok([r; 3]);
                }
                let g = self.number(n + 1, "g")? as f32;
                let b = self.number(n + 2, "b")? as f32;
                Ok([r, g, b])
            }
            _ => Err(self.bad(
                n,
                "colour",
                if grey_ok {
                    "a grey number, numbers r, g, b or a table {r, g, b}"
                } else {
                    "numbers r, g, b or a table {r, g, b}"
                },
            )),
        }
    }

    pub fn node(&self, n: usize, name: &str) -> mlua::Result<NodeId> {
        Ok(self.handle::<NodeHandle>(n, name, "a node")?.0)
    }

    pub fn material(&self, n: usize, name: &str) -> mlua::Result<MaterialId> {
        Ok(self
            .handle::<MaterialHandle>(n, name, "a material made by gr.material")?
            .0)
    }

    /// Argument `n`, a handle of type `T`; else an error saying it must be `what`.
    fn handle<T: 'static + Copy>(&self, n: usize, name: &str, what: &str) -> mlua::Result<T> {
        match self.get(n) {
            Value::UserData(ud) => match ud.borrow::<T>() {
                Ok(h) => Ok(*h),
                Err(_) => Err(self.bad(n, name, what)),
            },
            _ => Err(self.bad(n, name, what)),
        }
    }

    /// The receiver of a method call; a clear error if it was called with `.`.
    pub fn receiver<T: 'static + Copy>(&self, kind: &str) -> mlua::Result<T> {
        if let Value::UserData(ud) = self.get(0) {
            if let Ok(h) = ud.borrow::<T>() {
                return Ok(*h);
            }
        }
        Err(self.error(format!(
            "must be called on a {kind} with ':' (x:{}(...)), got {} as the receiver{}",
            self.func.rsplit(':').next().unwrap_or(""),
            describe(self.lua, self.get(0)),
            super::dot_call::hint(self.lua, &self.func, &location(self.lua)).unwrap_or_default()
        )))
    }

    /// The receiver value itself, to return it so that method calls chain.
    pub fn receiver_value(&self) -> Value {
        self.get(0).clone()
    }
}

/// An integer from an integer or integral float value.
pub(crate) fn int_value(v: &Value) -> Option<i64> {
    match v {
        Value::Integer(i) => Some(*i),
        Value::Number(x) if x.is_finite() && x.fract() == 0.0 && x.abs() < 9.0e15 => {
            Some(*x as i64)
        }
        _ => None,
    }
}
