//! Adaptive AA's plan through the wavefront kernels: the lattice and the queues in
//! one binding, every lattice pass through the generations (a chain's or a tree's).

use super::*;

/// Adaptive AA through the wavefront kernels: square tiles cover the frame once, and
/// each tile's lattice and queues fit one binding, the queues after the lattice at a
/// 256-byte offset; each lattice pass (corners, then one a level) runs its camera
/// pass (bound from the queues), closest, shade, args, shadow and gather per
/// generation (bound from the queues and from the wavefront's counters and
/// arguments, which lie after adaptive AA's levels' and inside the buffers) and its
/// store pass (bound whole); every tracing invocation has a list slot.
#[test]
fn adaptive_wavefront_tiles_hold_lattice_and_queues_and_run_every_lattice_pass() {
    let shape = wavefront_shape(17, 3, None, false);
    let bounds = wavefront_bounds(shape, 16 << 20, SLOT_WORDS);
    let generations = shape.generations as usize;
    for depth in [1, 2, 3] {
        for (w, h) in [(256, 256), (1920, 1080), (37, 5)] {
            let g = PackedGlobals {
                aa_depth: depth,
                ..globals(w, h, AA_ADAPTIVE)
            };
            let plan = FramePlan::new(&g, bounds);
            assert_eq!(plan.mode, Mode::AdaptiveWavefront { depth, shape });
            assert_covers(&plan, w, h);
            assert!(plan.samples_len * 16 <= bounds.max_binding, "{w}×{h}");
            assert!(4 * depth as u64 <= WAVEFRONT_WORK_BYTES);
            let entries = plan.mode.entries();
            let entry = |d: &Dispatch| entries[d.entry];
            for (k, c) in plan.chunks.iter().enumerate() {
                let lattice = (c.side as u64 * (1 << depth) + 1).pow(2);
                let queues = BindingOffsets {
                    samples: lattice_queue_bytes(c.side, depth),
                    work: 0,
                };
                assert_eq!(queues.samples % 256, 0);
                assert!(queues.samples >= 16 * lattice);
                let d = plan.dispatches(k, 2, bounds);
                assert!(d[0].clears_work);
                assert_eq!(entry(&d[0]), Entry::WavefrontLatticeCamera);
                let n = d[0].params.items as u64;
                assert!(queues.samples / 16 + n * shape.vec4s_per_sample() <= plan.samples_len);
                assert!(n * SLOT_WORDS as u64 <= plan.lists_len);
                let cameras: Vec<usize> = (0..d.len())
                    .filter(|&i| entry(&d[i]) == Entry::WavefrontLatticeCamera)
                    .collect();
                assert_eq!(cameras.len(), 1 + depth as usize);
                for (pass, &at) in cameras.iter().enumerate() {
                    let run = &d[at..at + 2 + 5 * generations];
                    let (camera, store) = (run[0], run[run.len() - 1]);
                    assert_eq!(camera.params.level, pass as u32);
                    assert_eq!(camera.offsets, queues);
                    assert_eq!(entry(&store), Entry::WavefrontLatticeStore);
                    assert_eq!(store.params.level, pass as u32);
                    assert_eq!(store.offsets, BindingOffsets::default());
                    assert_eq!(store.workgroups, camera.workgroups);
                    for (g, gen) in run[1..run.len() - 1].chunks(5).enumerate() {
                        let names: Vec<Entry> = gen.iter().map(entry).collect();
                        assert_eq!(names, Entry::WAVEFRONT[1..6]);
                        assert!(gen[2].writes_args);
                        for p in gen {
                            assert_eq!(p.params.level, g as u32);
                            assert_eq!(p.params.items as u64, n);
                            assert_eq!(p.offsets.samples, queues.samples);
                            assert_eq!(p.offsets.work, WAVEFRONT_WORK_BYTES);
                            if let Workgroups::Indirect(at) = p.workgroups {
                                let ours = at >= WAVEFRONT_WORK_BYTES;
                                assert!(ours || g == 0, "{at}");
                                assert!(at + 12 <= plan.work_levels * 24, "{at}");
                            }
                        }
                        if g == 0 {
                            assert_eq!(gen[0].workgroups, camera.workgroups);
                        }
                    }
                }
                // Adaptive AA's own arguments lie before the wavefront's.
                for p in &d {
                    let adaptive = matches!(entry(p), Entry::AdaptiveDecide)
                        || p.offsets.samples == queues.samples && p.offsets.work == 0;
                    if let (true, Workgroups::Indirect(at)) = (adaptive, p.workgroups) {
                        assert!(at + 12 <= WAVEFRONT_WORK_BYTES, "{at}");
                    }
                }
                assert_eq!(entry(&d[d.len() - 1]), Entry::AdaptiveIntegrate);
            }
        }
    }
}

/// Adaptive AA's tiles in a scene with refraction: the lattice and the busiest lattice
/// pass's tree queues fit one binding, each of its paths (TREE_PATHS_PER_SAMPLE a
/// sample) has a list slot, and each lattice pass runs the lattice camera pass, a
/// tree's generations with their rounds at the wavefront's binding offsets (their
/// indirect arguments after adaptive AA's), the fold over the camera pass's
/// invocations, then the store.
#[test]
fn adaptive_tree_tiles_run_the_trees_passes_and_fold_every_lattice_pass() {
    let shape = wavefront_shape(5, 4, None, true);
    let bounds = wavefront_bounds(shape, 64 << 20, SLOT_WORDS);
    let per_generation = TREE_GENERATION_DISPATCHES;
    for depth in [1, 2] {
        let g = PackedGlobals {
            aa_depth: depth,
            ..globals(300, 200, AA_ADAPTIVE)
        };
        let plan = FramePlan::new(&g, bounds);
        assert_eq!(plan.mode, Mode::AdaptiveWavefront { depth, shape });
        assert_covers(&plan, 300, 200);
        assert!(plan.samples_len * 16 <= bounds.max_binding);
        let entries = plan.mode.entries();
        assert_eq!(entries, &Entry::ADAPTIVE_WAVEFRONT_TREE);
        let entry = |d: &Dispatch| entries[d.entry];
        for (k, c) in plan.chunks.iter().enumerate() {
            let queues = lattice_queue_bytes(c.side, depth);
            let d = plan.dispatches(k, 2, bounds);
            let n = d[0].params.items as u64;
            assert!(queues / 16 + n * shape.vec4s_per_sample() <= plan.samples_len);
            let paths = n * TREE_PATHS_PER_SAMPLE as u64;
            assert!(paths * SLOT_WORDS as u64 <= plan.lists_len, "slots");
            let cameras: Vec<usize> = (0..d.len())
                .filter(|&i| entry(&d[i]) == Entry::WavefrontLatticeCamera)
                .collect();
            assert_eq!(cameras.len(), 1 + depth as usize);
            for (pass, &at) in cameras.iter().enumerate() {
                let run = &d[at..at + 3 + per_generation * shape.generations as usize];
                let (camera, fold, store) = (run[0], run[run.len() - 2], run[run.len() - 1]);
                assert_eq!(camera.params.level, pass as u32);
                assert_eq!(camera.offsets.samples, queues);
                assert_eq!(entry(&fold), Entry::WavefrontFold);
                assert_eq!(fold.workgroups, camera.workgroups);
                assert_eq!(entry(&store), Entry::WavefrontLatticeStore);
                assert_eq!(store.workgroups, camera.workgroups);
                assert_eq!(store.offsets, BindingOffsets::default());
                for p in &run[1..run.len() - 1] {
                    assert!(entries[p.entry].is_wavefront(), "{p:?}");
                    assert_eq!(p.params.items as u64, n);
                    assert_eq!(p.offsets.samples, queues);
                    assert_eq!(p.offsets.work, WAVEFRONT_WORK_BYTES);
                    match p.workgroups {
                        Workgroups::Indirect(at) if p.workgroups != camera.workgroups => {
                            assert!(at >= WAVEFRONT_WORK_BYTES, "{at}");
                            assert!(at + 12 <= plan.work_levels * 24, "{at}");
                        }
                        _ => {}
                    }
                }
                let gens = &run[1..run.len() - 2];
                for gen in gens.chunks(per_generation) {
                    let names: Vec<Entry> = gen.iter().map(entry).collect();
                    assert_eq!(names[..4], Entry::WAVEFRONT_TREE[1..5]);
                    assert_eq!(names[per_generation - 1], Entry::WavefrontGather);
                }
            }
            assert_eq!(entry(&d[d.len() - 1]), Entry::AdaptiveIntegrate);
        }
    }
}
