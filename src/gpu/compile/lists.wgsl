// lists.wgsl — the per-ray lists that do not fit registers (the dielectric ray stack of
// trace.wgsl, the CSG interval lists of csg.wgsl), in the hardware kernel variant
// (LISTS_IN_STORAGE) kept in one storage buffer instead of private arrays, which a GPU
// compiler puts in scratch memory. Each tracing invocation owns one slot; word k of slot
// s is at k · slots + s, so that the lanes of a wave reading the same word of their lists
// read neighbouring words. The layout of a slot's LANE_LIST_WORDS words is
// src/gpu/compile/lists.rs's (the host plans as many slots as a dispatch has tracing
// invocations); the CPU keeps the same lists in arrays of its own.

// #if LISTS_IN_STORAGE
@group(0) @binding(25) var<storage, read_write> ray_lists: array<u32>;
// #if REFRACTION|CSG
// This invocation's slot, and the binding's slots (it holds LANE_LIST_WORDS a slot).
var<private> lane_slot: u32;
var<private> lane_slots: u32;
// #endif
// #endif

// Claims slot `slot` for the lists of the ray this invocation traces (each tracing entry
// point calls it with an index no other invocation of its dispatch has).
fn begin_lane(slot: u32) {
// #if LISTS_IN_STORAGE
// #if REFRACTION|CSG
    lane_slot = slot;
    lane_slots = arrayLength(&ray_lists) / LANE_LIST_WORDS;
// #endif
// #endif
}

// #if LISTS_IN_STORAGE
// #if REFRACTION|CSG
// Index in ray_lists of word k of this invocation's slot.
fn lane_word(k: u32) -> u32 {
    return k * lane_slots + lane_slot;
}

fn lane_f32(k: u32) -> f32 {
    return bitcast<f32>(ray_lists[lane_word(k)]);
}

fn set_lane_f32(k: u32, value: f32) {
    ray_lists[lane_word(k)] = bitcast<u32>(value);
}

fn lane_vec3(k: u32) -> vec3<f32> {
    return vec3<f32>(lane_f32(k), lane_f32(k + 1u), lane_f32(k + 2u));
}

fn set_lane_vec3(k: u32, value: vec3<f32>) {
    set_lane_f32(k, value.x);
    set_lane_f32(k + 1u, value.y);
    set_lane_f32(k + 2u, value.z);
}
// #endif
// #endif
