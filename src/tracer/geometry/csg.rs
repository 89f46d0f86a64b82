//! CSG by interval lists (Roth 1982), without recursion and in fixed memory.
//!
//! A CSG object is one grid item (`KIND_CSG`) whose `params` name a post-order program in
//! `PackedScene::csg_program`: a leaf entry pushes the inside intervals of the ray through
//! one primitive instance (its own transform: t is the world t); an operation pops the
//! top two lists, a below b, and pushes their union, intersection or difference a − b.
//! The one list left is where the ray is inside the object; its first end in (0, t_max) is
//! the hit (from inside the object, that is the exit).
//!
//! Lists are sorted interval ends, alternately entering and leaving, each end with the
//! tag of the leaf it lies on (its instance index) and [`CSG_FLIP`] when that surface is
//! seen from the leaf's inside (a subtracted operand: its normal is negated at the hit).
//! All lists share one array of [`CSG_EVENT_CAPACITY`] ends, stacked in evaluation order;
//! an operation builds its result after the top list and moves it down. Flattening
//! rejects any object whose worst case exceeds the capacity (`flatten::csg_worst_case`
//! simulates exactly this order), so nothing is ever truncated.
//!
//! Combining is a merge of the two sorted lists that tracks "inside a" and "inside b" and
//! emits an end wherever the operation's result changes. Ends of a and b closer than
//! [`CSG_COINCIDENT_RELATIVE`] of the magnitude of the coordinates involved are one
//! place: both flip at once. So a − b with coplanar caps (the rounding of two transforms
//! puts the two caps a few ulps apart, in either order) leaves no zero-width sliver of a's
//! cap, which would show as speckles inside the hole; touching operands of a union leave
//! no internal face.
//!
//! The twin is `src/tracer/geometry/csg.wgsl`, step for step (its lists live in private arrays).

use super::cylinder_cone::{cone_intervals, cylinder_interval};
use super::intersect::{box_interval, sphere_interval, to_object_space};
use super::torus::torus_intervals;
use crate::constants::{
    CSG_COINCIDENT_RELATIVE, CSG_DIFFERENCE, CSG_EVENT_CAPACITY, CSG_FLIP, CSG_INDEX_MASK,
    CSG_INTERSECTION, CSG_LEAF, CSG_LIST_CAPACITY, CSG_OP_SHIFT, CSG_T_LIMIT, KIND_CONE, KIND_CUBE,
    KIND_CYLINDER, KIND_SPHERE, KIND_TORUS, NO_ITEM, T_MISS,
};
use crate::pack::{csg_program_at, load_instance, PackedInstance, PackedScene};
use glam::{Vec3, Vec4};

/// The nearest CSG hit: t (T_MISS on a miss) and the tag of the surface: leaf instance
/// index, with [`CSG_FLIP`] when its normal is to be negated (`NO_ITEM` on a miss).
#[derive(Clone, Copy, Debug, PartialEq)]
// Mirror of src/tracer/geometry/csg.wgsl::CsgHit — change both.
pub struct CsgHit {
    pub t: f32,
    pub part: u32,
}

/// One ray's evaluation state: the interval ends of every live list, stacked. (The GPU's
/// hardware variant keeps the same arrays in a storage slot per ray, `src/gpu/compile/lists.rs`;
/// where they live changes no step.)
#[derive(Clone, Debug)]
// Mirror of the csg_* private variables of src/tracer/geometry/csg.wgsl — change both.
pub struct CsgStack {
    pub t: [f32; CSG_EVENT_CAPACITY as usize],
    pub tag: [u32; CSG_EVENT_CAPACITY as usize],
    pub list_start: [u32; CSG_LIST_CAPACITY as usize],
    pub list_count: [u32; CSG_LIST_CAPACITY as usize],
    /// Live lists.
    pub lists: u32,
}

impl Default for CsgStack {
    fn default() -> Self {
        CsgStack {
            t: [0.0; CSG_EVENT_CAPACITY as usize],
            tag: [0; CSG_EVENT_CAPACITY as usize],
            list_start: [0; CSG_LIST_CAPACITY as usize],
            list_count: [0; CSG_LIST_CAPACITY as usize],
            lists: 0,
        }
    }
}

// The stack's accessors, one a field, each the twin of the WGSL accessor that reads or
// writes the same entry in a private array or in the invocation's list slot
// (src/gpu/compile/lists.rs): the evaluation below goes through them in the WGSL's order.

/// t of interval end k.
// Mirror of src/tracer/geometry/csg.wgsl::csg_t_at — change both.
#[inline(always)]
pub fn csg_t_at(stack: &CsgStack, k: u32) -> f32 {
    stack.t[k as usize]
}

/// Sets t of interval end k.
// Mirror of src/tracer/geometry/csg.wgsl::set_csg_t — change both.
#[inline(always)]
pub fn set_csg_t(stack: &mut CsgStack, k: u32, t: f32) {
    stack.t[k as usize] = t;
}

/// Tag of interval end k.
// Mirror of src/tracer/geometry/csg.wgsl::csg_tag_at — change both.
#[inline(always)]
pub fn csg_tag_at(stack: &CsgStack, k: u32) -> u32 {
    stack.tag[k as usize]
}

/// Sets the tag of interval end k.
// Mirror of src/tracer/geometry/csg.wgsl::set_csg_tag — change both.
#[inline(always)]
pub fn set_csg_tag(stack: &mut CsgStack, k: u32, tag: u32) {
    stack.tag[k as usize] = tag;
}

/// First end of live list l.
// Mirror of src/tracer/geometry/csg.wgsl::csg_start_at — change both.
#[inline(always)]
pub fn csg_start_at(stack: &CsgStack, l: u32) -> u32 {
    stack.list_start[l as usize]
}

/// Sets the first end of live list l.
// Mirror of src/tracer/geometry/csg.wgsl::set_csg_start — change both.
#[inline(always)]
pub fn set_csg_start(stack: &mut CsgStack, l: u32, start: u32) {
    stack.list_start[l as usize] = start;
}

/// Ends of live list l.
// Mirror of src/tracer/geometry/csg.wgsl::csg_count_at — change both.
#[inline(always)]
pub fn csg_count_at(stack: &CsgStack, l: u32) -> u32 {
    stack.list_count[l as usize]
}

/// Sets the ends of live list l.
// Mirror of src/tracer/geometry/csg.wgsl::set_csg_count — change both.
#[inline(always)]
pub fn set_csg_count(stack: &mut CsgStack, l: u32, count: u32) {
    stack.list_count[l as usize] = count;
}

/// The inside intervals of `o + t·d` (world space) through a leaf instance, in world t:
/// [x, y] and [z, w], each empty when its lo > hi, the second after the first.
// Mirror of src/tracer/geometry/csg.wgsl::leaf_intervals — change both.
pub fn leaf_intervals(leaf: &PackedInstance, o: Vec3, d: Vec3) -> Vec4 {
    let (oo, od) = to_object_space(leaf, o, d);
    let empty = Vec4::new(T_MISS, -T_MISS, T_MISS, -T_MISS);
    match leaf.kind {
        KIND_SPHERE => sphere_interval(oo, od).extend(T_MISS).extend(-T_MISS),
        KIND_CUBE => box_interval(oo, od).extend(T_MISS).extend(-T_MISS),
        KIND_CYLINDER => cylinder_interval(oo, od).extend(T_MISS).extend(-T_MISS),
        KIND_CONE => {
            let c = cone_intervals(oo, od, leaf.params[0], leaf.params[1]);
            let mut spans = c.spans;
            // Shift only non-empty spans (an empty one keeps lo > hi).
            if spans.x <= spans.y {
                spans.x += c.t_shift;
                spans.y += c.t_shift;
            }
            if spans.z <= spans.w {
                spans.z += c.t_shift;
                spans.w += c.t_shift;
            }
            spans
        }
        KIND_TORUS => torus_intervals(oo, od, leaf.params[0], leaf.params[1]),
        _ => empty,
    }
}

/// Pushes the list of leaf instance `index` onto `stack`: its non-empty intervals, ends
/// clamped to ±[`CSG_T_LIMIT`] (no NaN: a NaN interval fails lo ≤ hi and is dropped).
// Mirror of src/tracer/geometry/csg.wgsl::csg_push_leaf — change both.
pub fn csg_push_leaf(stack: &mut CsgStack, scene: &PackedScene, index: u32, o: Vec3, d: Vec3) {
    let intervals = leaf_intervals(load_instance(scene, index), o, d);
    let mut start = 0;
    if stack.lists > 0 {
        let top = stack.lists - 1;
        start = csg_start_at(stack, top) + csg_count_at(stack, top);
    }
    let mut count = 0;
    for k in 0..2 {
        let lo = intervals[2 * k];
        let hi = intervals[2 * k + 1];
        if lo <= hi {
            let at = start + count;
            set_csg_t(stack, at, lo.clamp(-CSG_T_LIMIT, CSG_T_LIMIT));
            set_csg_tag(stack, at, index);
            set_csg_t(stack, at + 1, hi.clamp(-CSG_T_LIMIT, CSG_T_LIMIT));
            set_csg_tag(stack, at + 1, index);
            count += 2;
        }
    }
    let top = stack.lists;
    set_csg_start(stack, top, start);
    set_csg_count(stack, top, count);
    stack.lists += 1;
}

/// Whether a point inside a (`in_a`) and/or b (`in_b`) is inside `op`'s result.
// Mirror of src/tracer/geometry/csg.wgsl::csg_inside — change both.
pub fn csg_inside(op: u32, in_a: bool, in_b: bool) -> bool {
    if op == CSG_INTERSECTION {
        in_a && in_b
    } else if op == CSG_DIFFERENCE {
        in_a && !in_b
    } else {
        in_a || in_b
    }
}

/// Replaces the top two lists of `stack` (a below b) by `op`'s result. `magnitude` is the
/// ray origin's largest coordinate: with |t| it bounds the coordinates every end was
/// computed from, so ends of a and b within [`CSG_COINCIDENT_RELATIVE`] of their sum are
/// one place (scale-free: no scene-size epsilon). The place of a step is its nearer end
/// (a's on a tie); a difference flips the tags of b's ends it emits.
// Mirror of src/tracer/geometry/csg.wgsl::csg_combine — change both.
pub fn csg_combine(stack: &mut CsgStack, op: u32, magnitude: f32) {
    let a_list = stack.lists - 2;
    let b_list = stack.lists - 1;
    let a_start = csg_start_at(stack, a_list);
    let a_count = csg_count_at(stack, a_list);
    let b_start = csg_start_at(stack, b_list);
    let b_count = csg_count_at(stack, b_list);
    // The result is built after b, then moved down to where a starts.
    let out = b_start + b_count;
    let b_flip = if op == CSG_DIFFERENCE { CSG_FLIP } else { 0 };
    let (mut ia, mut ib, mut n) = (0, 0, 0);
    let (mut in_a, mut in_b, mut inside) = (false, false, false);
    // Every step takes at least one end.
    for _ in 0..a_count + b_count {
        if ia >= a_count && ib >= b_count {
            break;
        }
        let mut take_a = ia < a_count;
        let mut take_b = ib < b_count;
        let mut ta = T_MISS;
        let mut tb = T_MISS;
        if take_a {
            ta = csg_t_at(stack, a_start + ia);
        }
        if take_b {
            tb = csg_t_at(stack, b_start + ib);
        }
        if take_a && take_b {
            let tolerance = CSG_COINCIDENT_RELATIVE * (magnitude + ta.abs().max(tb.abs()));
            if (ta - tb).abs() > tolerance {
                take_a = ta < tb;
                take_b = !take_a;
            }
        }
        // The place of this step: the nearer end taken, a's on a tie.
        let mut t = ta;
        let mut tag = 0;
        if take_a {
            tag = csg_tag_at(stack, a_start + ia);
            in_a = !in_a;
            ia += 1;
        }
        if take_b {
            if !take_a || tb < ta {
                t = tb;
                tag = csg_tag_at(stack, b_start + ib) ^ b_flip;
            }
            in_b = !in_b;
            ib += 1;
        }
        let now = csg_inside(op, in_a, in_b);
        if now != inside {
            set_csg_t(stack, out + n, t);
            set_csg_tag(stack, out + n, tag);
            n += 1;
            inside = now;
        }
    }
    for k in 0..n {
        set_csg_t(stack, a_start + k, csg_t_at(stack, out + k));
        set_csg_tag(stack, a_start + k, csg_tag_at(stack, out + k));
    }
    set_csg_count(stack, a_list, n);
    stack.lists -= 1;
}

/// Runs the program of CSG instance `inst` for the ray `o + t·d` (world space, the origin
/// near the scene as traversal hands it over): afterwards `stack` holds one list, the
/// object's inside intervals along the whole line.
// Mirror of src/tracer/geometry/csg.wgsl::csg_evaluate — change both.
pub fn csg_evaluate(
    stack: &mut CsgStack,
    scene: &PackedScene,
    inst: &PackedInstance,
    o: Vec3,
    d: Vec3,
) {
    let start = inst.params[0] as u32;
    let len = inst.params[1] as u32;
    let magnitude = o.abs().max_element();
    stack.lists = 0;
    for i in 0..len {
        let entry = csg_program_at(scene, start + i);
        let op = entry >> CSG_OP_SHIFT;
        if op == CSG_LEAF {
            csg_push_leaf(stack, scene, entry & CSG_INDEX_MASK, o, d);
        } else {
            csg_combine(stack, op, magnitude);
        }
    }
}

/// Nearest hit in (0, t_max) of `o + t·d` with CSG instance `inst`: the first end of its
/// inside intervals past the origin (from inside, where the ray leaves).
// Mirror of src/tracer/geometry/csg.wgsl::intersect_csg — change both.
pub fn intersect_csg(
    scene: &PackedScene,
    inst: &PackedInstance,
    o: Vec3,
    d: Vec3,
    t_max: f32,
) -> CsgHit {
    let mut stack = CsgStack::default();
    csg_evaluate(&mut stack, scene, inst, o, d);
    let count = csg_count_at(&stack, 0);
    for k in 0..count {
        let t = csg_t_at(&stack, k);
        if t > 0.0 {
            if t < t_max {
                return CsgHit {
                    t,
                    part: csg_tag_at(&stack, k),
                };
            }
            break;
        }
    }
    CsgHit {
        t: T_MISS,
        part: NO_ITEM,
    }
}
