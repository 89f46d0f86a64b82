//! The tree form's plan (scenes with refraction): every generation's glass rounds and
//! the fold.

use super::*;

/// A tree's bands (scenes with refraction): their queues fit one binding, every
/// closest or shade invocation of a generation (up to TREE_PATHS_PER_SAMPLE a sample)
/// has a list slot, and each band runs the camera pass, then per generation closest,
/// shade, args, shadow, SHADOW_ROUNDS rounds of leg closest and crossing with the leg
/// args between them, gather — then the fold; every indirect offset inside the
/// work-args buffer, rounds at the same offsets every generation, the generations'
/// after them.
#[test]
fn tree_bands_run_every_generation_every_round_and_the_fold() {
    let shape = wavefront_shape(17, 9, None, true);
    assert_eq!(
        shape.vec4s_per_sample(),
        3 + (14 + 10 * 17) * TREE_PATHS_PER_SAMPLE as u64 + 2 * TREE_VERTICES_PER_SAMPLE as u64
    );
    let bounds = wavefront_bounds(shape, 16 << 20, SLOT_WORDS);
    // 1920 samples of 13.5 KiB are more than one 16 MiB binding: rows in pieces.
    for (w, h) in [(256, 256), (1920, 1080), (37, 5)] {
        let plan = FramePlan::new(&globals(w, h, 0), bounds);
        assert_eq!(plan.mode, Mode::Wavefront(shape));
        assert_eq!(plan.mode.entries(), &Entry::WAVEFRONT_TREE[..10]);
        assert_eq!(plan.chunks.len() > h as usize, w == 1920, "{w}×{h}");
        assert_covers(&plan, w, h);
        assert!(plan.samples_len * 16 <= bounds.max_binding, "{w}×{h}");
        assert!(plan.lists_len * 4 <= bounds.max_binding.min(LIST_BUDGET_BYTES));
        assert!(plan.work_levels >= 11, "the eleven counters");
        for (k, c) in plan.chunks.iter().enumerate() {
            assert!(shape.vec4s_per_sample() * c.block_pixels() <= plan.samples_len);
            let paths = TREE_PATHS_PER_SAMPLE as u64 * c.block_pixels();
            assert!(
                paths * SLOT_WORDS as u64 <= plan.lists_len,
                "{w}×{h}: slots"
            );
            let d = plan.dispatches(k, 2, bounds);
            let per_generation = TREE_GENERATION_DISPATCHES;
            assert_eq!(d.len(), 2 + per_generation * shape.generations as usize);
            assert!(d[0].clears_work && d[0].entry == 0);
            let fold = d.last().unwrap();
            assert_eq!((fold.entry, fold.workgroups), (9, d[0].workgroups));
            for (g, pass) in d[1..d.len() - 1].chunks(per_generation).enumerate() {
                let g = g as u32;
                let entries: Vec<usize> = pass.iter().map(|d| d.entry).collect();
                let mut expected = vec![1, 2, 3, 4];
                for r in 0..SHADOW_ROUNDS {
                    expected.extend([5, 6]);
                    if r + 1 < SHADOW_ROUNDS {
                        expected.push(7);
                    }
                }
                expected.push(8);
                assert_eq!(entries, expected);
                let rounds = &pass[4..pass.len() - 1];
                for (r, round) in rounds.chunks(3).enumerate() {
                    assert!(round.iter().all(|d| d.params.level == r as u32));
                    assert_eq!(round[0].workgroups, Workgroups::Indirect(12 * r as u64));
                    assert_eq!(round[1].workgroups, round[0].workgroups);
                    if round.len() == 3 {
                        assert!(round[2].writes_args);
                    }
                }
                for d in pass[..4].iter().chain(&pass[pass.len() - 1..]) {
                    assert_eq!(d.params.level, g);
                }
                assert!(pass[2].writes_args);
                let expected = match g {
                    0 => d[0].workgroups,
                    _ => Workgroups::Indirect(4 * (30 + 6 * (g as u64 - 1))),
                };
                assert_eq!(pass[0].workgroups, expected);
                assert_eq!(pass[1].workgroups, expected);
                assert_eq!(pass[pass.len() - 1].workgroups, expected);
                assert_eq!(
                    pass[3].workgroups,
                    Workgroups::Indirect(4 * (30 + 6 * g as u64 + 3))
                );
                for at in pass.iter().filter_map(|d| match d.workgroups {
                    Workgroups::Indirect(at) => Some(at),
                    Workgroups::Direct(..) => None,
                }) {
                    assert!(at + 12 <= plan.work_levels * 24, "{at}");
                }
            }
        }
    }
}

/// A tree's bands under uniform n×n AA: each pixel's n² samples take n² times a
/// sample's queues and list slots in the band's binding, the generations and the fold
/// run over every sample, and the resolve pass (the 11th entry) ends the band over
/// its pixels.
#[test]
fn uniform_tree_bands_sample_every_stratum_then_fold_then_resolve() {
    let n = 2;
    let shape = wavefront_shape(3, 9, Some(n), true);
    let bounds = wavefront_bounds(shape, 16 << 20, SLOT_WORDS);
    let mut g = globals(200, 120, AA_UNIFORM);
    g.aa_samples = n;
    let plan = FramePlan::new(&g, bounds);
    assert_eq!(plan.mode, Mode::Wavefront(shape));
    assert_eq!(plan.mode.entries(), &Entry::WAVEFRONT_TREE);
    assert_eq!(plan.mode.entries()[10], Entry::WavefrontResolve);
    assert_covers(&plan, 200, 120);
    assert!(plan.samples_len * 16 <= bounds.max_binding);
    for (k, c) in plan.chunks.iter().enumerate() {
        let samples = c.block_pixels() * (n * n) as u64;
        assert!(shape.vec4s_per_sample() * samples <= plan.samples_len);
        let paths = TREE_PATHS_PER_SAMPLE as u64 * samples;
        assert!(paths * SLOT_WORDS as u64 <= plan.lists_len, "slots");
        let d = plan.dispatches(k, 2, bounds);
        let per_generation = TREE_GENERATION_DISPATCHES;
        assert_eq!(d.len(), 3 + per_generation * shape.generations as usize);
        assert_eq!(d[0].params.items as u64, samples);
        let (fold, resolve) = (d[d.len() - 2], d[d.len() - 1]);
        assert_eq!((fold.entry, fold.workgroups), (9, d[0].workgroups));
        let side = bounds.workgroup_side;
        let square = Workgroups::Direct(c.size[0].div_ceil(side), c.size[1].div_ceil(side));
        assert_eq!((resolve.entry, resolve.workgroups), (10, square));
    }
    // Without its shape (another n) uniform AA keeps its own passes.
    g.aa_samples = 3;
    assert!(matches!(
        FramePlan::new(&g, bounds).mode,
        Mode::Uniform { n: 3 }
    ));
}
