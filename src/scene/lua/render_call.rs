//! `gr.render`: checks its arguments (their kinds first, then their values: the camera,
//! the image's size and the script's bounds on renders and pixels), builds the
//! [`RenderRequest`] and hands it, with the graph built so far, to the caller's callback.

use super::args::{describe, finite, format_number, location, Args};
use super::budget::{charge, grown, memory_left, release};
use super::handles::{LightHandle, NodeHandle};
use super::limits::{ensure_live, reach_limit};
use super::{advice, notes, options, with_state, State};
use crate::scene::flatten::{parallel_or_zero, CAMERA_PARALLEL_SIN2, MAX_PIXELS};
use crate::scene::{Camera, Light, RenderOptions, RenderRequest, SceneGraph};
use glam::DVec3;
use mlua::{Lua, MultiValue, Value};
use std::path::PathBuf;

/// Largest image side accepted (a typo guard, not a hardware limit).
pub const MAX_IMAGE_SIDE: u32 = 1 << 16;

/// Bytes one entry of `gr.render`'s light list takes while the render runs: the list
/// and the copies of it that flattening and packing make.
const LIGHT_BYTES: u64 = 4 * grown(std::mem::size_of::<Light>());

/// The callback `gr.render` invokes with the graph built so far and the request.
pub type OnRender<'a> = dyn FnMut(&SceneGraph, &RenderRequest) -> anyhow::Result<()> + 'a;

/// `{x, y, z}` as a scene writes it.
fn vector(v: DVec3) -> String {
    let [x, y, z] = v.to_array().map(format_number);
    format!("{{{x}, {y}, {z}}}")
}

/// Scenes written for tracers that took a point to look at pass it as `view`: what to
/// pass instead, worked out for this eye.
fn look_at_hint(eye: DVec3, view: DVec3) -> String {
    format!(
        "view is the direction the camera looks in, not a point: for a point to look at, pass \
         point − eye (for the point {} seen from the eye {}: {})",
        vector(view),
        vector(eye),
        vector(view - eye)
    )
}

/// Arguments 5–8 of `gr.render`: eye, view (a non-zero direction), up (not parallel to
/// it) and the vertical field of view.
fn camera(a: &Args) -> mlua::Result<Camera> {
    let eye = a.vec3(5, "eye")?;
    let view = a.vec3(6, "view")?;
    if view == DVec3::ZERO {
        return Err(a.error(format!(
            "argument 6 (view) must be a non-zero direction, got {}; {}",
            vector(view),
            look_at_hint(eye, view)
        )));
    }
    let up = a.vec3(7, "up")?;
    if up == DVec3::ZERO {
        return Err(a.bad(7, "up", "a non-zero direction"));
    }
    if parallel_or_zero(view, up, CAMERA_PARALLEL_SIN2) {
        return Err(a.error(format!(
            "argument 7 (up) must be a non-zero direction not parallel to view, got up = {}, view = {}; {}",
            vector(up),
            vector(view),
            look_at_hint(eye, view)
        )));
    }
    let fov_deg = match finite(a.get(8)) {
        Some(f) if f > 0.0 && f < 180.0 => f,
        _ => return Err(a.bad(8, "fov", "a number of degrees between 0 and 180")),
    };
    advice::check_fov(a, fov_deg);
    Ok(Camera {
        eye,
        view,
        up,
        fov_deg,
    })
}

/// Argument 11 of `gr.render`: a table of render options, or nil. The course's binding
/// ignored whatever followed the lights (thread counts, depths): so does glint, noting it.
fn render_options(a: &Args) -> mlua::Result<RenderOptions> {
    Ok(match a.get(11) {
        Value::Nil | Value::Table(_) => {
            let options = options::parse(a, 11)?;
            notes::check_extra_arguments(a);
            options
        }
        _ => {
            notes::ignored_render_tail(a);
            RenderOptions::default()
        }
    })
}

/// `gr.render(root, file, w, h, eye, view, up, fov, ambient, lights[, options])`.
pub(super) fn render(
    lua: &Lua,
    args: MultiValue,
    on_render: &mut OnRender<'_>,
) -> mlua::Result<()> {
    ensure_live(lua)?;
    let a = Args::new(lua, "gr.render", args);
    if with_state(lua, |s| s.render_error.is_some()) {
        return Err(a.error("an earlier gr.render failed; no more renders"));
    }
    check_render_shape(&a)?;
    let root = a.node(1, "root")?;
    advice::check_root(&a, root);
    let output = output_name(&a)?;
    let width = a.positive_int(3, "width", MAX_IMAGE_SIDE)?;
    let height = a.positive_int(4, "height", MAX_IMAGE_SIDE)?;
    if u64::from(width) * u64::from(height) > MAX_PIXELS {
        return Err(a.bad_in(
            4,
            "height",
            format!("a {width}×{height} image has more than glint's limit of {MAX_PIXELS} pixels"),
        ));
    }
    count_render(&a, u64::from(width) * u64::from(height))?;
    let camera = camera(&a)?;
    let ambient = a.colour(9, "ambient")?;
    let list = a.table(10, "lights", "a table of lights made by gr.light")?;
    let options = render_options(&a)?;
    with_state(lua, notes::flush);
    // The list is counted before it is copied (2²⁶ entries naming one light are 2²⁶
    // copies), and given back after the render.
    let light_bytes = (list.raw_len() as u64).saturating_mul(LIGHT_BYTES);
    charge(&a, light_bytes, "the light list")?;
    let result = render_with_lights(&a, list, output, on_render, |lights| {
        Ok(RenderRequest {
            root,
            output: PathBuf::new(),
            width,
            height,
            camera,
            ambient,
            lights,
            options,
            location: location(lua),
            memory_left: memory_left(lua),
        })
    });
    release(lua, light_bytes);
    result
}

/// `gr.render`'s signature, for messages about its arguments.
pub(super) const RENDER_SIGNATURE: &str =
    "gr.render(root, file, width, height, eye, view, up, fov, ambient, lights[, options])";

/// One positional argument's kind: its name, a test of its value, what it must be.
type ArgumentKind = (&'static str, fn(&Value) -> bool, &'static str);

/// The Lua type each of `gr.render`'s ten positional arguments must have: its name, a
/// test of the value, and what it must be (the words the value checks use).
const RENDER_SHAPE: [ArgumentKind; 10] = [
    (
        "root",
        |v| matches!(v, Value::UserData(u) if u.is::<NodeHandle>()),
        "a node",
    ),
    (
        "file",
        |v| v.is_string(),
        "the image's file name, a string such as 'out.png'",
    ),
    (
        "width",
        |v| v.is_number() || v.is_integer(),
        "a positive integer",
    ),
    (
        "height",
        |v| v.is_number() || v.is_integer(),
        "a positive integer",
    ),
    ("eye", |v| v.is_table(), "a table of 3 numbers {x, y, z}"),
    ("view", |v| v.is_table(), "a table of 3 numbers {x, y, z}"),
    ("up", |v| v.is_table(), "a table of 3 numbers {x, y, z}"),
    (
        "fov",
        |v| v.is_number() || v.is_integer(),
        "a number of degrees between 0 and 180",
    ),
    (
        "ambient",
        |v| v.is_table(),
        "a table of 3 numbers {r, g, b}",
    ),
    (
        "lights",
        |v| v.is_table(),
        "a table of lights made by gr.light",
    ),
];

/// Checks the kinds of `gr.render`'s positional arguments before any value, so that a
/// shifted or missing argument (`gr.render(root, 160, 120, 'a.png', …)`) is named where
/// the shift starts, with the signature, rather than where a value first fails.
fn check_render_shape(a: &Args) -> mlua::Result<()> {
    for (i, (name, fits, what)) in RENDER_SHAPE.iter().enumerate() {
        let n = i + 1;
        if !fits(a.get(n)) {
            let got = describe(a.lua, a.get(n));
            return Err(a.error(format!(
                "argument {n} ({name}) must be {what}, got {got}; the arguments are {RENDER_SIGNATURE}"
            )));
        }
    }
    Ok(())
}

/// Argument 2 of `gr.render`, the output's name: UTF-8 (a name is never mangled into
/// another), without NUL bytes.
fn output_name(a: &Args) -> mlua::Result<PathBuf> {
    Ok(PathBuf::from(a.file_name(2, "file")?))
}

/// Counts one render of `pixels` against the script's bounds (a reached bound is final).
fn count_render(a: &Args, pixels: u64) -> mlua::Result<()> {
    let over = with_state(a.lua, |s| {
        s.renders_requested += 1;
        s.pixels_requested = s.pixels_requested.saturating_add(pixels);
        if s.renders_requested > s.max_renders {
            Some(format!(
                "this is render {} of the script, over the limit of {} renders; --max-renders N raises it",
                s.renders_requested, s.max_renders
            ))
        } else if s.pixels_requested > s.max_render_pixels {
            Some(format!(
                "the script's renders ask for {} pixels in all, over the limit of {}; --max-render-pixels N raises it",
                s.pixels_requested, s.max_render_pixels
            ))
        } else {
            None
        }
    });
    match over {
        Some(message) => Err(reach_limit(a, message)),
        None => Ok(()),
    }
}

/// Reads the light list, builds the request with `request` and renders it.
fn render_with_lights(
    a: &Args,
    list: mlua::Table,
    output: PathBuf,
    on_render: &mut OnRender<'_>,
    request: impl FnOnce(Vec<Light>) -> mlua::Result<RenderRequest>,
) -> mlua::Result<()> {
    let lua = a.lua;
    let mut lights = Vec::with_capacity(list.raw_len());
    for (i, v) in list.sequence_values::<Value>().enumerate() {
        let v = v?;
        let light = match &v {
            Value::UserData(ud) => ud.borrow::<LightHandle>().ok().map(|l| l.0.clone()),
            _ => None,
        };
        lights.push(
            light.ok_or_else(|| a.bad_element(10, "lights", i, "a light made by gr.light", &v))?,
        );
    }
    let request = RenderRequest {
        output,
        ..request(lights)?
    };
    let state = lua
        .app_data_ref::<State>()
        .expect("script state is installed");
    // Renders do not count against the script's time limit.
    state.clock.pause();
    let result = on_render(&state.graph, &request);
    state.clock.resume();
    drop(state);
    match result {
        Ok(()) => {
            with_state(lua, |s| s.report.renders += 1);
            Ok(())
        }
        Err(error) => {
            let message = format!("{}: gr.render: {error:#}", request.location);
            with_state(lua, |s| s.render_error = Some((request.location, error)));
            Err(mlua::Error::RuntimeError(message))
        }
    }
}
