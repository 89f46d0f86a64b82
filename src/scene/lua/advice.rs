//! Advice on mistakes a scene makes without an error (the image renders, but not as
//! meant): a field of view in radians, a rotation by an angle in radians, a root with
//! nothing under it. Each is one note on stderr naming the call (`notes::advise`).

use super::args::{format_number, location, Args};
use super::notes::advise;
use super::with_state;
use crate::scene::{short_name, NodeId, NodeKind};

/// A vertical field of view below this many degrees is likely radians given for
/// degrees (`math.rad(50)` is 0.87): a telephoto of 5° is rare in a first scene.
pub const SMALL_FOV_DEGREES: f64 = 5.0;

/// How close a `rotate` angle must be to π/4, π/2 or π (or their negatives) to be read as
/// radians given for degrees (`math.pi / 2`, `math.rad(90)`).
pub const RADIAN_ANGLE_TOLERANCE: f64 = 1e-6;

/// `gr.render`'s fov (argument 8), in degrees: advice when it looks like radians.
pub(crate) fn check_fov(a: &Args, fov_deg: f64) {
    if fov_deg >= SMALL_FOV_DEGREES {
        return;
    }
    let at = location(a.lua);
    let message = format!(
        "{at}: gr.render: argument 8 (fov) is {} degrees, a very narrow view: fov is the vertical field of view in degrees, not radians (for 50°, write 50, not math.rad(50) = {})",
        format_number(fov_deg),
        format_number(50f64.to_radians())
    );
    advise(a.lua, at, "fov", message);
}

/// `node:rotate`'s angle, in degrees: advice when it is π/4, π/2 or π, which are
/// radians given for degrees.
pub(crate) fn check_rotate_angle(a: &Args, degrees: f64) {
    let radians = [
        (std::f64::consts::FRAC_PI_4, "π/4", 45),
        (std::f64::consts::FRAC_PI_2, "π/2", 90),
        (std::f64::consts::PI, "π", 180),
    ];
    let Some((_, name, meant)) = radians
        .iter()
        .find(|(r, _, _)| (degrees.abs() - r).abs() <= RADIAN_ANGLE_TOLERANCE)
    else {
        return;
    };
    let sign = if degrees < 0.0 { "-" } else { "" };
    let at = location(a.lua);
    let message = format!(
        "{at}: node:rotate: argument 2 (angle) is {} degrees, which is {sign}{name} in radians: rotate takes degrees (for a quarter turn write 90, not math.pi / 2; {sign}{meant} here?)",
        format_number(degrees)
    );
    advise(a.lua, at, "rotate", message);
}

/// `gr.render`'s root (argument 1): advice when nothing under it is geometry, so the
/// image is the background alone (a forgotten `root:add_child`).
pub(crate) fn check_root(a: &Args, root: NodeId) {
    let empty = with_state(a.lua, |s| {
        let nodes = &s.graph.nodes;
        let mut stack = vec![root];
        let mut seen = vec![false; nodes.len()];
        while let Some(id) = stack.pop() {
            if std::mem::replace(&mut seen[id], true) {
                continue;
            }
            if !matches!(nodes[id].kind, NodeKind::Transform) {
                return None;
            }
            stack.extend(&nodes[id].children);
        }
        Some(short_name(&nodes[root].name).into_owned())
    });
    let Some(name) = empty else { return };
    let at = location(a.lua);
    let message = format!(
        "{at}: gr.render: argument 1 (root) has nothing under it: node '{name}' holds no primitive or mesh, so the image is the background alone (add them with {name}:add_child(node))"
    );
    advise(a.lua, at, "root", message);
}
