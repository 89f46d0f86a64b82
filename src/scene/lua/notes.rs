//! Notes on stderr about what a scene passed that glint does not use: arguments beyond
//! those a call reads (`gr.material(kd, ks, p, reflect, ior)`, the course's lenient
//! forms), and a non-table after `gr.render`'s lights. One note per call site
//! (`file:line` and call), however often the line runs; `--ignore-extra-arguments` or
//! `gr.ignore_extra_arguments()` in the scene silences them.
//!
//! Notes are held until the next `gr.render` or the end of the script, so that the
//! scene's own `gr.ignore_extra_arguments()` silences notes of calls before it too.
//!
//! Advice ([`advise`]: a likely mistake the scene makes without an error, such as a field
//! of view in radians) goes the same way, one per call site, but is never silenced: it
//! is about the image, not about arguments another tracer used.

use super::args::{describe, finite, location, Args};
use super::with_state;
use std::collections::HashSet;

/// The notes of one script run.
#[derive(Debug, Default)]
pub(crate) struct Notes {
    /// (`file:line`, call) of the call sites already noted.
    seen: HashSet<(String, String)>,
    /// Notes not yet printed.
    pending: Vec<String>,
    /// Advice not yet printed ([`advise`]).
    pending_advice: Vec<String>,
    /// `--ignore-extra-arguments` or `gr.ignore_extra_arguments()`.
    silenced: bool,
}

impl Notes {
    /// No notes yet; `silenced` by the command line's `--ignore-extra-arguments`.
    pub fn new(silenced: bool) -> Notes {
        Notes {
            silenced,
            ..Notes::default()
        }
    }
}

/// Queues `message` (already prefixed with `file:line: call:`) for the call site `at`,
/// unless that site has a note already.
pub(crate) fn note(a: &Args, at: String, message: String) {
    with_state(a.lua, |s| {
        if s.notes.seen.insert((at, a.func.clone())) {
            s.notes.pending.push(message);
        }
    });
}

/// Queues advice `message` (already prefixed with `file:line: call:`) for the call site
/// `at` under `topic` (one piece of advice per site and topic); never silenced.
pub(crate) fn advise(lua: &mlua::Lua, at: String, topic: &str, message: String) {
    with_state(lua, |s| {
        if s.notes.seen.insert((at, topic.to_string())) {
            s.notes.pending_advice.push(message);
        }
    });
}

/// Prints the pending advice, then the pending notes unless silenced (`glint: note: …`),
/// and records them in the script's report.
pub(crate) fn flush(s: &mut super::State) {
    for message in std::mem::take(&mut s.notes.pending_advice) {
        eprintln!(
            "glint: note: {}",
            crate::display_path::for_terminal(&message)
        );
        s.report.advice.push(message);
    }
    let pending = std::mem::take(&mut s.notes.pending);
    if s.notes.silenced {
        return;
    }
    for message in pending {
        eprintln!(
            "glint: note: {}",
            crate::display_path::for_terminal(&message)
        );
        s.report.notes.push(message);
    }
}

/// After a call that succeeded: a note when it was passed more arguments than it read
/// (trailing nils do not count), saying how many it uses and what to call instead.
pub(crate) fn check_extra_arguments(a: &Args) {
    let (used, passed) = (a.used(), a.passed());
    if passed <= used {
        return;
    }
    let at = location(a.lua);
    let plural = |n: usize| if n == 1 { "" } else { "s" };
    let ignored: Vec<String> = (used + 1..=passed)
        .map(|n| describe(a.lua, a.get(n)))
        .collect();
    let mut message = format!(
        "{at}: {}: uses {used} argument{} but was passed {passed}; glint ignores {} ({})",
        a.func,
        plural(used),
        if passed - used == 1 {
            "the last"
        } else {
            "the rest"
        },
        ignored.join(", ")
    );
    if let Some(hint) = instead(a) {
        message += "; ";
        message += &hint;
    }
    note(a, at, message);
}

/// What to call instead of passing extra arguments to `a`'s call, where glint has it.
fn instead(a: &Args) -> Option<String> {
    let hint = match a.func.as_str() {
        "gr.material" => {
            "for a mirror use m:set_reflection(r), for glass m:set_refraction(ior) (see \
             docs/scene-language.md)"
                .to_string()
        }
        "material:set_refraction" => {
            let (first, second) = (finite(a.get(1)), finite(a.get(2)));
            match (first, second) {
                (Some(x), Some(ior)) if x <= 1.0 && ior > 1.0 => format!(
                    "it took {x} as the index of refraction: if {x} is a transparency and {ior} \
                     the index, write m:set_refraction({ior}) (glass transmits by its Fresnel \
                     term, no transparency needed)"
                ),
                _ => "m:set_refraction(ior) takes the index of refraction alone".to_string(),
            }
        }
        "material:set_reflection" => {
            "m:set_reflection takes one colour (a grey number, r, g, b or {r, g, b}); \
             for glass use m:set_refraction(ior)"
                .to_string()
        }
        "gr.light" => {
            "for an area light use gr.area_light(centre, u, v, colour, falloff[, n])".to_string()
        }
        "gr.sphere" => {
            "for a sphere with a centre and radius use gr.nh_sphere(name, {x, y, z}, r)".to_string()
        }
        "gr.cube" => {
            "for a box with a corner and size use gr.nh_box(name, {x, y, z}, size)".to_string()
        }
        "gr.cylinder" | "gr.cone" | "gr.torus" => {
            "size and place it with node:scale and node:translate".to_string()
        }
        "gr.render" => "argument 11, if any, is a table of render options".to_string(),
        _ => return None,
    };
    Some(hint)
}

/// `gr.render`'s argument 11 when it is neither nil nor a table (a thread count, a depth,
/// `false`): ignored with everything after it, and noted.
pub(crate) fn ignored_render_tail(a: &Args) {
    let at = location(a.lua);
    let got: Vec<String> = (11..=a.passed().max(11))
        .map(|n| describe(a.lua, a.get(n)))
        .collect();
    let message = format!(
        "{at}: gr.render: ignores argument 11 and after ({}): argument 11, if any, is a \
         table of render options (docs/scene-language.md)",
        got.join(", ")
    );
    note(a, at, message);
}

/// `gr.ignore_extra_arguments()`: silences the notes of the whole script.
pub(crate) fn ignore_extra_arguments(a: &Args) -> mlua::Result<()> {
    with_state(a.lua, |s| s.notes.silenced = true);
    Ok(())
}
