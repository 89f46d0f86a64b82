//! What sizes the wavefront kernels' queues and their indirect arguments
//! ([`WavefrontShape`]): the vec4s a sample's queues take and where in `work_args` each
//! generation's and each glass round's arguments lie. Chains and trees alike.

use crate::constants::MAX_SHADOW_CROSSINGS;
use crate::tracer::wavefront::queues::counters::{counter_words, leg_args, tree_generation_args};
use crate::tracer::wavefront::queues::layout::{paths_per_sample, vec4s_per_sample, Form};
use crate::tracer::wavefront::queues::{COUNTERS, REGIONS};

/// What sizes the wavefront kernels' queues and dispatches: the scene's light points (a
/// vertex's light slots: `tracer::wavefront::batch::light_points`), the generations a path may
/// have (max_depth + 1 with mirrors or glass, else 1), the AA mode's strata, and whether
/// paths branch (a tree: scenes with refraction).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WavefrontShape {
    pub light_points: u32,
    pub generations: u32,
    /// Uniform AA's n: a chunk's samples are n² strata a pixel, averaged by the resolve
    /// pass. None: AA none, a pixel's centre, stored by the gather pass.
    pub uniform: Option<u32>,
    pub tree: bool,
    /// Dispatches of a chain's shadow pass a generation: 1, or with CSG (at most one
    /// invocation per list slot, one request each) the light points, each a slice of at
    /// most a request per sample (`src/tracer/wavefront/wavefront_shadow.wgsl::wavefront_shadow`). A tree's: 1.
    pub shadow_slices: u32,
}

/// Glass shadow rounds a tree's generation runs (`src/tracer/wavefront/wavefront_tree.wgsl`): a leg
/// crosses at most MAX_SHADOW_CROSSINGS surfaces and is blocked at the next.
pub const SHADOW_ROUNDS: u32 = MAX_SHADOW_CROSSINGS + 1;

impl WavefrontShape {
    /// Samples a pixel: n² under uniform AA, else 1.
    pub fn samples_per_pixel(self) -> u64 {
        self.uniform.map_or(1, |n| (n * n) as u64)
    }

    /// The queues' layout: a tree's with refraction, else a chain's.
    fn form(self) -> Form {
        if self.tree {
            Form::Tree
        } else {
            Form::Chain
        }
    }

    /// vec4 entries of the queues a sample of a chunk takes (the regions of
    /// `tracer::wavefront::queues::REGIONS`, laid out by `queues::layout`): its record, two
    /// path queues, a hit, a vertex, its light slots and shadow requests (L each) per path a
    /// generation may hold, and a tree's vertex tree, camera vertex and glass shadow legs.
    pub fn vec4s_per_sample(self) -> u64 {
        vec4s_per_sample(REGIONS, self.form(), self.light_points)
    }

    /// Tracing invocations (list slots) a wavefront dispatch may have per sample of the
    /// chunk: a tree's generation holds up to TREE_PATHS_PER_SAMPLE paths a sample.
    pub fn slots_per_sample(self) -> u64 {
        paths_per_sample(self.form())
    }

    /// Byte offset in work_args of the indirect arguments of generation g's passes over
    /// paths (g ≥ 1; written by generation g − 1's args kernel).
    pub(super) fn paths_args(self, g: u32) -> u64 {
        if self.tree {
            return 4 * tree_generation_args(g - 1) as u64;
        }
        4 * self.generation_words() * (g as u64 - 1)
    }

    /// Byte offset of slice `slice` of generation g's shadow pass's arguments.
    pub(super) fn shadow_args(self, g: u32, slice: u32) -> u64 {
        4 * (3 + 3 * slice as u64) + self.paths_args(g + 1)
    }

    /// Words of work_args a generation: the next generation's passes' 3, then 3 a
    /// shadow slice.
    fn generation_words(self) -> u64 {
        3 + 3 * self.shadow_slices as u64
    }

    /// Byte offset of a tree's round r's leg arguments (the same words every generation).
    pub(super) fn round_args(r: u32) -> u64 {
        4 * leg_args(r) as u64
    }

    /// 24-byte levels of work_args (and 4-byte counters of work_counts) the kernels use:
    /// a generation's 6 words (after a tree's round arguments); at least the counters
    /// (`tracer::wavefront::queues::COUNTERS`: 5 for chains; a tree's 11, also three leg
    /// counters, two vertex bases and the light points).
    pub fn work_levels(self) -> u64 {
        let counters = counter_words(COUNTERS, self.form()) as u64;
        if self.tree {
            (tree_generation_args(self.generations) as u64 / 6).max(counters)
        } else {
            (self.generation_words() * self.generations as u64)
                .div_ceil(6)
                .max(counters)
        }
    }
}
