// csg.wgsl — CSG by interval lists, without recursion and in fixed memory: a CSG item's
// post-order program (csg_program) pushes each leaf's inside intervals and combines the
// top two lists by union, intersection or difference; the first end of the last list in
// (0, t_max) is the hit. The method, the tags (leaf index | CSG_FLIP) and the coincidence
// tolerance are described in src/tracer/geometry/csg.rs, which this file follows step for step. The
// lists live in private arrays of CSG_EVENT_CAPACITY ends; flattening rejects any object
// whose worst case needs more, so nothing is truncated. Every loop is bounded.

// (A CSG scene always has some primitive kind among its leaves; the feature sets of the
// validation tests need not.)
// #if CSG
// #if SPHERE|CUBE|CYLINDER|CONE|TORUS
// The nearest CSG hit: t (T_MISS on a miss) and the surface's tag (NO_ITEM on a miss).
// Mirror of src/tracer/geometry/csg.rs::CsgHit — change both.
struct CsgHit {
    t: f32,
    part: u32,
}

// One ray's evaluation state, per invocation: in the hardware variant
// (LISTS_IN_STORAGE) the ends and lists are in this invocation's slot of ray_lists
// (lists.wgsl: t from word CSG_STATE_AT, tags from CSG_TAGS_AT, list starts from
// CSG_STARTS_AT, list counts from CSG_COUNTS_AT), since as
// private arrays (1.2 KiB) they would be scratch memory; the accessors below read and
// write either place.
// Mirror of src/tracer/geometry/csg.rs::CsgStack — change both.
// #if !LISTS_IN_STORAGE
var<private> csg_t: array<f32, CSG_EVENT_CAPACITY>;
var<private> csg_tag: array<u32, CSG_EVENT_CAPACITY>;
var<private> csg_list_start: array<u32, CSG_LIST_CAPACITY>;
var<private> csg_list_count: array<u32, CSG_LIST_CAPACITY>;
// #endif
var<private> csg_lists: u32;

// t of interval end k.
// Mirror of src/tracer/geometry/csg.rs::csg_t_at — change both.
fn csg_t_at(k: u32) -> f32 {
// #if LISTS_IN_STORAGE
    return lane_f32(CSG_STATE_AT + k);
// #else
    return csg_t[k];
// #endif
}

// Sets t of interval end k.
// Mirror of src/tracer/geometry/csg.rs::set_csg_t — change both.
fn set_csg_t(k: u32, t: f32) {
// #if LISTS_IN_STORAGE
    set_lane_f32(CSG_STATE_AT + k, t);
// #else
    csg_t[k] = t;
// #endif
}

// Tag of interval end k.
// Mirror of src/tracer/geometry/csg.rs::csg_tag_at — change both.
fn csg_tag_at(k: u32) -> u32 {
// #if LISTS_IN_STORAGE
    return ray_lists[lane_word(CSG_TAGS_AT + k)];
// #else
    return csg_tag[k];
// #endif
}

// Sets the tag of interval end k.
// Mirror of src/tracer/geometry/csg.rs::set_csg_tag — change both.
fn set_csg_tag(k: u32, tag: u32) {
// #if LISTS_IN_STORAGE
    ray_lists[lane_word(CSG_TAGS_AT + k)] = tag;
// #else
    csg_tag[k] = tag;
// #endif
}

// First end of live list l.
// Mirror of src/tracer/geometry/csg.rs::csg_start_at — change both.
fn csg_start_at(l: u32) -> u32 {
// #if LISTS_IN_STORAGE
    return ray_lists[lane_word(CSG_STARTS_AT + l)];
// #else
    return csg_list_start[l];
// #endif
}

// Sets the first end of live list l.
// Mirror of src/tracer/geometry/csg.rs::set_csg_start — change both.
fn set_csg_start(l: u32, start: u32) {
// #if LISTS_IN_STORAGE
    ray_lists[lane_word(CSG_STARTS_AT + l)] = start;
// #else
    csg_list_start[l] = start;
// #endif
}

// Ends of live list l.
// Mirror of src/tracer/geometry/csg.rs::csg_count_at — change both.
fn csg_count_at(l: u32) -> u32 {
// #if LISTS_IN_STORAGE
    return ray_lists[lane_word(CSG_COUNTS_AT + l)];
// #else
    return csg_list_count[l];
// #endif
}

// Sets the ends of live list l.
// Mirror of src/tracer/geometry/csg.rs::set_csg_count — change both.
fn set_csg_count(l: u32, count: u32) {
// #if LISTS_IN_STORAGE
    ray_lists[lane_word(CSG_COUNTS_AT + l)] = count;
// #else
    csg_list_count[l] = count;
// #endif
}

// The inside intervals of o + t·d (world space) through a leaf instance, in world t:
// [x, y] and [z, w], each empty when its lo > hi, the second after the first.
// Mirror of src/tracer/geometry/csg.rs::leaf_intervals — change both.
fn leaf_intervals(leaf: PackedInstance, o: vec3<f32>, d: vec3<f32>) -> vec4<f32> {
    let local = to_object_space(leaf, o, d);
    let oo = local.origin;
    let od = local.dir;
    let empty = vec4<f32>(T_MISS, -T_MISS, T_MISS, -T_MISS);
// #if SPHERE
    if leaf.kind == KIND_SPHERE {
        return vec4<f32>(sphere_interval(oo, od), T_MISS, -T_MISS);
    }
// #endif
// #if CUBE
    if leaf.kind == KIND_CUBE {
        return vec4<f32>(box_interval(oo, od), T_MISS, -T_MISS);
    }
// #endif
// #if CYLINDER
    if leaf.kind == KIND_CYLINDER {
        return vec4<f32>(cylinder_interval(oo, od), T_MISS, -T_MISS);
    }
// #endif
// #if CONE
    if leaf.kind == KIND_CONE {
        let c = cone_intervals(oo, od, leaf.params.x, leaf.params.y);
        var spans = c.spans;
        // Shift only non-empty spans (an empty one keeps lo > hi).
        if spans.x <= spans.y {
            spans.x += c.t_shift;
            spans.y += c.t_shift;
        }
        if spans.z <= spans.w {
            spans.z += c.t_shift;
            spans.w += c.t_shift;
        }
        return spans;
    }
// #endif
// #if TORUS
    if leaf.kind == KIND_TORUS {
        return torus_intervals(oo, od, leaf.params.x, leaf.params.y);
    }
// #endif
    return empty;
}

// Pushes the list of leaf instance index: its non-empty intervals, ends clamped to
// ±CSG_T_LIMIT (a NaN interval fails lo ≤ hi and is dropped).
// Mirror of src/tracer/geometry/csg.rs::csg_push_leaf — change both.
fn csg_push_leaf(index: u32, o: vec3<f32>, d: vec3<f32>) {
    let intervals = leaf_intervals(load_instance(index), o, d);
    var start = 0u;
    if csg_lists > 0u {
        let top = csg_lists - 1u;
        start = csg_start_at(top) + csg_count_at(top);
    }
    var count = 0u;
    for (var k = 0u; k < 2u; k++) {
        let lo = intervals[2u * k];
        let hi = intervals[2u * k + 1u];
        if lo <= hi {
            let at = start + count;
            set_csg_t(at, clamp(lo, -CSG_T_LIMIT, CSG_T_LIMIT));
            set_csg_tag(at, index);
            set_csg_t(at + 1u, clamp(hi, -CSG_T_LIMIT, CSG_T_LIMIT));
            set_csg_tag(at + 1u, index);
            count += 2u;
        }
    }
    set_csg_start(csg_lists, start);
    set_csg_count(csg_lists, count);
    csg_lists += 1u;
}

// Whether a point inside a (in_a) and/or b (in_b) is inside op's result.
// Mirror of src/tracer/geometry/csg.rs::csg_inside — change both.
fn csg_inside(op: u32, in_a: bool, in_b: bool) -> bool {
    if op == CSG_INTERSECTION {
        return in_a && in_b;
    } else if op == CSG_DIFFERENCE {
        return in_a && !in_b;
    }
    return in_a || in_b;
}

// Replaces the top two lists (a below b) by op's result; ends of a and b within
// CSG_COINCIDENT_RELATIVE of (magnitude + |t|) are one place. The place of a step is its
// nearer end (a's on a tie); a difference flips the tags of b's ends it emits.
// Mirror of src/tracer/geometry/csg.rs::csg_combine — change both.
fn csg_combine(op: u32, magnitude: f32) {
    let a_list = csg_lists - 2u;
    let b_list = csg_lists - 1u;
    let a_start = csg_start_at(a_list);
    let a_count = csg_count_at(a_list);
    let b_start = csg_start_at(b_list);
    let b_count = csg_count_at(b_list);
    // The result is built after b, then moved down to where a starts.
    let out = b_start + b_count;
    var b_flip = 0u;
    if op == CSG_DIFFERENCE {
        b_flip = CSG_FLIP;
    }
    var ia = 0u;
    var ib = 0u;
    var n = 0u;
    var in_a = false;
    var in_b = false;
    var inside = false;
    // Every step takes at least one end.
    for (var step = 0u; step < a_count + b_count; step++) {
        if ia >= a_count && ib >= b_count {
            break;
        }
        var take_a = ia < a_count;
        var take_b = ib < b_count;
        var ta = T_MISS;
        var tb = T_MISS;
        if take_a {
            ta = csg_t_at(a_start + ia);
        }
        if take_b {
            tb = csg_t_at(b_start + ib);
        }
        if take_a && take_b {
            let tolerance = CSG_COINCIDENT_RELATIVE * (magnitude + max(abs(ta), abs(tb)));
            if abs(ta - tb) > tolerance {
                take_a = ta < tb;
                take_b = !take_a;
            }
        }
        // The place of this step: the nearer end taken, a's on a tie.
        var t = ta;
        var tag = 0u;
        if take_a {
            tag = csg_tag_at(a_start + ia);
            in_a = !in_a;
            ia += 1u;
        }
        if take_b {
            if !take_a || tb < ta {
                t = tb;
                tag = csg_tag_at(b_start + ib) ^ b_flip;
            }
            in_b = !in_b;
            ib += 1u;
        }
        let now = csg_inside(op, in_a, in_b);
        if now != inside {
            set_csg_t(out + n, t);
            set_csg_tag(out + n, tag);
            n += 1u;
            inside = now;
        }
    }
    for (var k = 0u; k < n; k++) {
        set_csg_t(a_start + k, csg_t_at(out + k));
        set_csg_tag(a_start + k, csg_tag_at(out + k));
    }
    set_csg_count(a_list, n);
    csg_lists -= 1u;
}

// Runs the program of CSG instance inst for the ray o + t·d (world space): afterwards one
// list remains, the object's inside intervals along the whole line.
// Mirror of src/tracer/geometry/csg.rs::csg_evaluate — change both.
fn csg_evaluate(inst: PackedInstance, o: vec3<f32>, d: vec3<f32>) {
    let start = u32(inst.params.x);
    let len = u32(inst.params.y);
    let magnitude = max_element(abs(o));
    csg_lists = 0u;
    for (var i = 0u; i < len; i++) {
        let entry = csg_program_at(start + i);
        let op = entry >> CSG_OP_SHIFT;
        if op == CSG_LEAF {
            csg_push_leaf(entry & CSG_INDEX_MASK, o, d);
        } else {
            csg_combine(op, magnitude);
        }
    }
}

// Nearest hit in (0, t_max) of o + t·d with CSG instance inst: the first end of its inside
// intervals past the origin (from inside, where the ray leaves).
// Mirror of src/tracer/geometry/csg.rs::intersect_csg — change both.
fn intersect_csg(inst: PackedInstance, o: vec3<f32>, d: vec3<f32>, t_max: f32) -> CsgHit {
    csg_evaluate(inst, o, d);
    let count = csg_count_at(0u);
    for (var k = 0u; k < count; k++) {
        let t = csg_t_at(k);
        if t > 0.0 {
            if t < t_max {
                return CsgHit(t, csg_tag_at(k));
            }
            break;
        }
    }
    return CsgHit(T_MISS, NO_ITEM);
}
// #endif
// #endif
