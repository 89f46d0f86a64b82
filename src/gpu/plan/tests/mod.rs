//! The frame plan's tests, a file a form: here what every form shares (chunks cover
//! the frame once, scratch and list slots fit, linear dispatches stay in bounds) and the
//! helpers the forms' tests use.

mod adaptive;
mod chain;
mod tree;
mod view;

pub(super) use super::adaptive::{lattice_queue_bytes, WAVEFRONT_WORK_BYTES};
pub(super) use super::chunking::{bands, lattice_side};
pub(super) use super::shape::SHADOW_ROUNDS;
pub(super) use super::view::view_wavefront_dispatches;
pub(super) use super::*;
pub(super) use crate::constants::{
    AA_ADAPTIVE, AA_UNIFORM, TREE_PATHS_PER_SAMPLE, TREE_VERTICES_PER_SAMPLE,
};
pub(super) use crate::gpu::compile::lists::LIST_BUDGET_BYTES;

pub(super) fn globals(w: u32, h: u32, aa_mode: u32) -> PackedGlobals {
    PackedGlobals {
        width: w,
        height: h,
        aa_mode,
        aa_samples: 4,
        aa_depth: 3,
        ..bytemuck::Zeroable::zeroed()
    }
}

pub(super) const LAVAPIPE: AdapterBounds = AdapterBounds {
    max_binding: 128 << 20,
    max_workgroups: 65_535,
    workgroup_side: 8,
    lane_list_words: 0,
    wavefront: None,
};

/// Words of a tracing invocation's list slot where a test keeps the lists in storage
/// (scrabble's 562).
pub(super) const SLOT_WORDS: u32 = 562;

/// Dispatches of a tree's generation: closest, shade, args and shadow, SHADOW_ROUNDS
/// rounds of leg closest and crossing with the leg args between them, then gather.
pub(super) const TREE_GENERATION_DISPATCHES: usize =
    5 + 2 * SHADOW_ROUNDS as usize + SHADOW_ROUNDS as usize - 1;

/// A wavefront shape with one shadow slice (no CSG): `light_points` a vertex,
/// `generations` a path, uniform AA's n (None: AA none), a tree or a chain.
pub(super) fn wavefront_shape(
    light_points: u32,
    generations: u32,
    uniform: Option<u32>,
    tree: bool,
) -> WavefrontShape {
    WavefrontShape {
        light_points,
        generations,
        uniform,
        tree,
        shadow_slices: 1,
    }
}

/// Lavapipe's bounds with the wavefront kernels of `shape`, bindings of `max_binding`
/// bytes and list slots of `words` words.
pub(super) fn wavefront_bounds(
    shape: WavefrontShape,
    max_binding: u64,
    words: u32,
) -> AdapterBounds {
    AdapterBounds {
        wavefront: Some(shape),
        max_binding,
        lane_list_words: words,
        ..LAVAPIPE
    }
}

/// Every pixel in exactly one chunk, every chunk in exactly one part.
pub(super) fn assert_covers(plan: &FramePlan, w: u32, h: u32) {
    let mut seen = vec![0u8; (w * h) as usize];
    for c in &plan.chunks {
        assert!(c.size[0] <= c.side, "{c:?}");
        for y in c.origin[1]..c.origin[1] + c.size[1] {
            for x in c.origin[0]..c.origin[0] + c.size[0] {
                seen[(y * w + x) as usize] += 1;
            }
        }
    }
    assert!(seen.iter().all(|&s| s == 1), "{w}×{h} {:?}", plan.mode);
    let covered: Vec<usize> = plan.parts.iter().flat_map(|r| r.clone()).collect();
    assert_eq!(covered, (0..plan.chunks.len()).collect::<Vec<_>>());
}

/// The five counters (three path counters, two shadow counters) fit `work_counts`.
pub(super) fn plan_counters_fit(shape: WavefrontShape) -> bool {
    let bounds = AdapterBounds {
        wavefront: Some(WavefrontShape {
            generations: 1,
            ..shape
        }),
        ..LAVAPIPE
    };
    FramePlan::new(&globals(8, 8, 0), bounds).work_levels >= 5
}

#[test]
fn chunks_cover_the_frame_once_in_a_fixed_number_of_parts() {
    for mode in [0, AA_UNIFORM, AA_ADAPTIVE] {
        let mut part_counts = Vec::new();
        for (w, h) in [(256, 256), (2048, 2048), (1920, 1080), (37, 5), (3000, 7)] {
            let plan = FramePlan::new(&globals(w, h, mode), LAVAPIPE);
            assert_covers(&plan, w, h);
            if w >= 256 && h >= 256 {
                part_counts.push(plan.parts.len());
            }
        }
        assert!(
            part_counts.iter().all(|&p| p == GPU_FRAME_PARTS as usize),
            "{part_counts:?}"
        );
    }
}

#[test]
fn scratch_fits_one_binding() {
    for mode in [AA_UNIFORM, AA_ADAPTIVE] {
        let plan = FramePlan::new(&globals(2048, 2048, mode), LAVAPIPE);
        assert!(
            plan.samples_len * 16 <= LAVAPIPE.max_binding,
            "{:?}",
            plan.mode
        );
        for c in &plan.chunks {
            assert!(c.block_pixels() * 16 <= LAVAPIPE.max_binding);
        }
    }
    assert_eq!(lattice_side(128 << 20), 2048);
}

/// With per-ray lists in storage (scrabble's 562 words a slot), every tracing
/// invocation of every dispatch has a slot of its own (main: a chunk pixel; uniform
/// AA: a sample; adaptive AA: a corner-pass point or AA_SPLIT_POINTS per square of a
/// level), and the slots fit one binding; without lists the plan is as before.
#[test]
fn every_tracing_invocation_has_a_list_slot() {
    let words = SLOT_WORDS as u64;
    let bounds = AdapterBounds {
        lane_list_words: words as u32,
        ..LAVAPIPE
    };
    for mode in [0, AA_UNIFORM, AA_ADAPTIVE] {
        for (w, h) in [(512, 512), (2048, 2048), (37, 5)] {
            let g = globals(w, h, mode);
            let plan = FramePlan::new(&g, bounds);
            assert_covers(&plan, w, h);
            assert!(
                plan.lists_len * 4 <= LAVAPIPE.max_binding,
                "{:?}",
                plan.mode
            );
            let slots = plan.lists_len / words;
            for (k, c) in plan.chunks.iter().enumerate() {
                for d in plan.dispatches(k, 2, bounds) {
                    let traced = match (plan.mode, plan.mode.entries()[d.entry]) {
                        (_, Entry::Render) => c.block_pixels(),
                        (_, Entry::UniformSamples | Entry::AdaptiveCorners) => {
                            d.params.items as u64
                        }
                        (_, Entry::AdaptiveMidpoints) => {
                            8 * (c.side as u64 * (1 << d.params.level)).pow(2)
                        }
                        _ => 0,
                    };
                    assert!(
                        traced <= slots,
                        "{w}×{h} {:?} {d:?}: {traced} > {slots}",
                        plan.mode
                    );
                }
            }
            let unbounded = FramePlan::new(&g, LAVAPIPE);
            assert_eq!(unbounded.lists_len, 0);
            assert!(unbounded.chunks.len() <= plan.chunks.len());
        }
    }
}

#[test]
fn linear_dispatches_stay_within_the_dimension_limit() {
    assert_eq!(linear_workgroups(64 * 10, 64, 65_535), (10, 1));
    assert_eq!(linear_workgroups(64 * 10, 16, 65_535), (40, 1));
    for lanes in [1, 16, 64] {
        let (x, y) = linear_workgroups(5 * 1024 * 1024, lanes, 65_535);
        assert!(x <= 65_535 && x as u64 * y as u64 * lanes as u64 >= 5 * 1024 * 1024);
    }
}
