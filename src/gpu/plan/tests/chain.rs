//! The wavefront form's plan (chains): AA none's and uniform AA's bands through the
//! wavefront kernels.

use super::*;

/// AA none through the wavefront kernels: bands cover the frame once, every band's
/// queues fit one binding, and each band runs the camera pass (clearing its counters)
/// then closest, shade, args, shadow and gather per generation — generation 0's over
/// the band's samples, the rest and every shadow pass at the args kernel's offsets,
/// inside the work-args buffer. With CSG the shadow pass is one dispatch per slice,
/// every slice 0 … L − 1 once (a skipped one would leave its requests unlit), each at
/// its own arguments (the args kernel's 3 + 3L words a generation).
#[test]
fn wavefront_bands_fit_their_queues_and_run_every_generation() {
    for shadow_slices in [1, 17] {
        let shape = WavefrontShape {
            light_points: 17,
            generations: 6,
            uniform: None,
            tree: false,
            shadow_slices,
        };
        assert_wavefront_bands(shape);
    }
}

fn assert_wavefront_bands(shape: WavefrontShape) {
    let bounds = AdapterBounds {
        wavefront: Some(shape),
        max_binding: 16 << 20,
        ..LAVAPIPE
    };
    let slices = shape.shadow_slices as usize;
    let words = 4 * (3 + 3 * slices as u64);
    for (w, h) in [(256, 256), (1920, 1080), (37, 5)] {
        let plan = FramePlan::new(&globals(w, h, 0), bounds);
        assert_eq!(plan.mode, Mode::Wavefront(shape));
        assert_covers(&plan, w, h);
        assert!(plan.samples_len * 16 <= bounds.max_binding, "{w}×{h}");
        for (k, c) in plan.chunks.iter().enumerate() {
            assert!(shape.vec4s_per_sample() * c.block_pixels() <= plan.samples_len);
            let d = plan.dispatches(k, 2, bounds);
            assert_eq!(d.len(), 1 + (4 + slices) * shape.generations as usize);
            assert!(d[0].clears_work && d[0].entry == 0);
            for (g, pass) in d[1..].chunks(4 + slices).enumerate() {
                let entries: Vec<usize> = pass.iter().map(|d| d.entry).collect();
                let mut expected_entries = vec![1, 2, 3];
                expected_entries.extend(std::iter::repeat_n(4, slices));
                expected_entries.push(5);
                assert_eq!(entries, expected_entries);
                assert!(pass.iter().all(|d| d.params.level == g as u32));
                assert!(pass[2].writes_args);
                assert_eq!(pass[2].params.slice, shape.shadow_slices);
                let offsets = pass.iter().filter_map(|d| match d.workgroups {
                    Workgroups::Indirect(at) => Some(at),
                    Workgroups::Direct(..) => None,
                });
                for at in offsets {
                    assert!(at + 12 <= plan.work_levels * 24, "{at}");
                }
                let expected = match g {
                    0 => d[0].workgroups,
                    _ => Workgroups::Indirect(words * (g as u64 - 1)),
                };
                assert_eq!(pass[0].workgroups, expected);
                assert_eq!(pass[3 + slices].workgroups, expected);
                let shadows = &pass[3..3 + slices];
                let slice_of: Vec<u32> = shadows.iter().map(|d| d.params.slice).collect();
                assert_eq!(slice_of, (0..slices as u32).collect::<Vec<_>>());
                for (s, shadow) in shadows.iter().enumerate() {
                    let at = words * g as u64 + 12 + 12 * s as u64;
                    assert_eq!(shadow.workgroups, Workgroups::Indirect(at));
                }
            }
        }
        // Uniform AA keeps its own passes.
        let uniform = FramePlan::new(&globals(w, h, AA_UNIFORM), bounds);
        assert!(matches!(uniform.mode, Mode::Uniform { .. }));
    }
    assert!(plan_counters_fit(shape));
}

/// Uniform AA through the wavefront kernels: a band's samples are its pixels × n²
/// (stratum s of pixel p is sample p·n² + s), its queues fit one binding and each of
/// its samples has a list slot; each band runs the camera pass, the generations over
/// its samples, then the resolve pass over its pixels. AA none's shape leaves uniform
/// AA to its own passes, and uniform AA's shape AA none.
#[test]
fn wavefront_uniform_bands_sample_every_stratum_then_resolve() {
    let words = 272u64;
    for n in [1, 2, 3, 4] {
        let shape = wavefront_shape(5, 3, Some(n), false);
        // (A row of 1920 pixels at 4×4 takes 30 720 slots: 32 MiB of lists.)
        let bounds = wavefront_bounds(shape, 64 << 20, words as u32);
        for (w, h) in [(256, 256), (1920, 1080), (37, 5)] {
            let g = PackedGlobals {
                aa_samples: n,
                ..globals(w, h, AA_UNIFORM)
            };
            let plan = FramePlan::new(&g, bounds);
            assert_eq!(plan.mode, Mode::Wavefront(shape));
            assert_eq!(plan.mode.entries(), &Entry::WAVEFRONT);
            assert_covers(&plan, w, h);
            assert!(plan.samples_len * 16 <= bounds.max_binding, "{w}×{h}");
            assert!(plan.lists_len * 4 <= bounds.max_binding, "{w}×{h}");
            let nn = (n * n) as u64;
            for (k, c) in plan.chunks.iter().enumerate() {
                let samples = c.size[0] as u64 * c.size[1] as u64 * nn;
                assert!(shape.vec4s_per_sample() * samples <= plan.samples_len);
                assert!(
                    samples * words <= plan.lists_len,
                    "{w}×{h}: a slot a sample"
                );
                let d = plan.dispatches(k, 2, bounds);
                assert_eq!(d.len(), 2 + 5 * shape.generations as usize);
                assert!(d[..d.len() - 1]
                    .iter()
                    .all(|d| d.params.items as u64 == samples));
                assert_eq!(d[0].workgroups, d[1].workgroups, "camera, generation 0");
                let Workgroups::Direct(x, y) = d[0].workgroups else {
                    panic!("the camera pass is direct")
                };
                assert!(x as u64 * y as u64 * 64 >= samples);
                let resolve = d.last().unwrap();
                assert_eq!(resolve.entry, 6);
                assert_eq!(
                    resolve.workgroups,
                    Workgroups::Direct(c.size[0].div_ceil(8), c.size[1].div_ceil(8))
                );
            }
            let none = FramePlan::new(&globals(w, h, 0), bounds);
            assert!(matches!(none.mode, Mode::None));
            let aa_none = AdapterBounds {
                wavefront: Some(WavefrontShape {
                    uniform: None,
                    ..shape
                }),
                ..bounds
            };
            let uniform = FramePlan::new(&g, aa_none);
            assert!(matches!(uniform.mode, Mode::Uniform { .. }));
            assert_eq!(
                FramePlan::new(&globals(w, h, 0), aa_none).mode.entries(),
                &Entry::WAVEFRONT[..6]
            );
        }
    }
}
