//! A tree's generations (the wavefront form in scenes with refraction, where a
//! dielectric's hit spawns two paths): per generation the chain's passes with the glass
//! shadow rounds between its shadow pass and its gather, then the fold of the vertex
//! tree into the samples.

use super::shape::{WavefrontShape, SHADOW_ROUNDS};
use super::{Dispatch, Generations, Workgroups};

/// A tree's generations after its camera pass: per generation g closest, shade, args, the
/// shadow pass (each request's first leg), then SHADOW_ROUNDS rounds of leg closest and
/// crossing (level: the round) with the leg args between rounds, and gather; after the
/// last generation the fold over the camera pass's samples (entries `closest` …
/// `closest` + 8 of the mode's list: `Entry::WAVEFRONT_TREE`'s after its camera pass).
/// Generation 0's passes over paths run over the samples as the camera pass, later ones'
/// and every shadow pass and round as the args kernels wrote them.
pub(super) fn tree_generations(shape: WavefrontShape, generations: Generations) -> Vec<Dispatch> {
    let mut out = Vec::new();
    let pass = |entry: usize, level: u32, workgroups: Workgroups| {
        generations.pass(entry, level, workgroups)
    };
    let writes_args = |d: Dispatch| Dispatch {
        writes_args: true,
        ..d
    };
    let one = Workgroups::Direct(1, 1);
    for g in 0..shape.generations {
        let paths = generations.paths(shape, g);
        out.push(pass(0, g, paths));
        out.push(pass(1, g, paths));
        out.push(writes_args(pass(2, g, one)));
        out.push(pass(3, g, generations.args(shape.shadow_args(g, 0))));
        for r in 0..SHADOW_ROUNDS {
            let legs = generations.args(WavefrontShape::round_args(r));
            out.push(pass(4, r, legs));
            out.push(pass(5, r, legs));
            if r + 1 < SHADOW_ROUNDS {
                out.push(writes_args(pass(6, r, one)));
            }
        }
        out.push(pass(7, g, paths));
    }
    out.push(pass(8, 0, generations.camera.workgroups));
    out
}
