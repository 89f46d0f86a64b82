//! The limits' shared record ([`Limits`]): once the instruction, time, memory or render
//! limit is reached, every Lua instruction and every `gr` call fails, so that no `pcall`
//! in the script can carry on past it.

use super::args::Args;
use super::with_state;
use mlua::Lua;
use std::cell::Cell;
use std::rc::Rc;

/// What the hooks report, so the error can be classified after Lua unwinds (and cannot
/// be hidden by a `pcall` in the script). Cheap to clone: the State holds a copy.
#[derive(Clone, Default)]
pub(crate) struct Limits {
    /// The instruction-, time-, memory- or render-limit message, once a limit is
    /// reached: from then on every `gr` call and every Lua instruction fails.
    pub exceeded: Rc<Cell<Option<String>>>,
    /// `file:line` where the hook last ran (memory errors carry no position).
    pub last_location: Rc<Cell<Option<String>>>,
    /// Instructions counted so far (the hook's steps, the weights of costly library
    /// calls, and at least one per [`NANOS_PER_INSTRUCTION`] of script time).
    pub count: Rc<Cell<u64>>,
    /// The instruction limit.
    pub instruction_limit: u64,
}

impl Limits {
    /// The message of the limit reached, if one was.
    pub fn reached(&self) -> Option<String> {
        let m = self.exceeded.take();
        self.exceeded.set(m.clone());
        m
    }

    /// Records that a limit was reached (the first message is kept) and returns the
    /// error to raise: the kept message.
    pub fn reach(&self, message: String) -> mlua::Error {
        let first = self.exceeded.take().unwrap_or(message);
        self.exceeded.set(Some(first.clone()));
        mlua::Error::RuntimeError(first)
    }

    /// Adds `weight` instructions for work done outside the VM (a library call that
    /// loops in C); past the limit, the limit is reached at `at`.
    pub fn tick(&self, weight: u64, at: impl FnOnce() -> String) -> mlua::Result<()> {
        if let Some(m) = self.reached() {
            return Err(mlua::Error::RuntimeError(m));
        }
        let count = self.count.get().saturating_add(weight);
        self.count.set(count);
        if count > self.instruction_limit {
            return Err(self.reach(instruction_message(&at(), self.instruction_limit)));
        }
        Ok(())
    }
}

/// Script time that counts as at least one instruction, beyond the first
/// [`FREE_SCRIPT_TIME`]: steps of the hook that took longer (time spent in C library
/// calls the hook cannot see) count as their time's worth, so that no script runs for
/// long on the instruction limit's allowance (200 million instructions: at most 11 s of
/// script time).
pub(super) const NANOS_PER_INSTRUCTION: u128 = 50;

/// Script time that is not turned into instructions (setting up, small scripts on a
/// busy machine).
pub(super) const FREE_SCRIPT_TIME: std::time::Duration = std::time::Duration::from_secs(1);

pub(super) fn instruction_message(at: &str, limit: u64) -> String {
    format!("{at}: instruction limit of {limit} exceeded — runaway loop?")
}

/// The hook installed once a limit is reached: every instruction fails, so that no
/// `pcall`, `xpcall` handler or coroutine can carry on (the first instruction outside
/// a protected call ends the script). It raises a fixed message; the limit's own
/// message is in [`Limits::exceeded`].
unsafe extern "C-unwind" fn final_hook(
    state: *mut mlua::ffi::lua_State,
    _: *mut mlua::ffi::lua_Debug,
) {
    // SAFETY: called by Lua on a running state; lua_error does not return (it unwinds
    // to the innermost protected call) and no Rust value with a destructor is live.
    unsafe {
        mlua::ffi::lua_pushstring(
            state,
            c"glint: a limit was reached; the script ends".as_ptr(),
        );
        mlua::ffi::lua_error(state);
    }
}

/// Makes every instruction of the running Lua thread fail ([`final_hook`]).
pub(super) fn end_thread(lua: &Lua) {
    let thread = lua.current_thread();
    // SAFETY: the running thread's state, valid while `thread` lives; lua_sethook may be
    // called from inside a hook.
    unsafe {
        mlua::ffi::lua_sethook(
            thread.state(),
            Some(final_hook),
            mlua::ffi::LUA_MASKCOUNT,
            1,
        );
    }
}

/// A limit reached at the call `a` (memory, renders): final, as the hook's limits are.
pub(crate) fn reach_limit(a: &Args, message: String) -> mlua::Error {
    let message = match a.error(message) {
        mlua::Error::RuntimeError(m) => m,
        other => other.to_string(),
    };
    end_thread(a.lua);
    with_state(a.lua, |s| s.limits.clone()).reach(message)
}

/// Fails once a limit has been reached: every `gr` call checks it first.
pub(crate) fn ensure_live(lua: &Lua) -> mlua::Result<()> {
    match with_state(lua, |s| s.limits.reached()) {
        Some(message) => Err(mlua::Error::RuntimeError(message)),
        None => Ok(()),
    }
}
