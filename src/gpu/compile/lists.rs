//! Per-ray lists in a storage buffer (`LISTS_IN_STORAGE`, the hardware kernel variant):
//! the pending rays of the dielectric ray stack (`src/tracer/path/trace.wgsl`) and the CSG
//! interval lists (`src/tracer/geometry/csg.wgsl`), which as private arrays are larger than the
//! 256 bytes a GPU compiler keeps in registers and so go to scratch memory (RADV for
//! NAVI21: glass.lua's kernel 60 KiB of scratch a wave, scrabble.lua's 143 KiB; issue 38).
//!
//! Each tracing invocation of a dispatch owns one **slot**; word `k` of slot `s` is at
//! `k · slots + s` of the `ray_lists` binding (`src/gpu/compile/lists.wgsl::lane_word`), so that
//! the lanes of a wave reading the same word of their lists read neighbouring words. The
//! binding holds exactly `slots · lane words` words, which is how the kernel learns
//! `slots` (`arrayLength`). A slot's words are written before they are read by the
//! invocation that owns it, within one dispatch: nothing is carried between invocations
//! or dispatches. The layout of a lane's words:
//!
//! - with `REFRACTION`: `RAY_STACK_SIZE` stack entries of [`STACK_ENTRY_WORDS`] each
//!   (ray origin and direction, weight, depth, cone, medium stack), from word 0;
//! - with `CSG`: the interval ends' `t` (f32 bits) and tags, `CSG_EVENT_CAPACITY` each,
//!   then the lists' starts and counts, `CSG_LIST_CAPACITY` each, from word
//!   [`LaneLists::csg_at`].
//!
//! The CPU tracer keeps these lists in arrays of its own (`src/tracer/path/trace.rs`,
//! `src/tracer/geometry/csg.rs::CsgStack`): where they live changes no step and no value.

use crate::constants::{CSG_EVENT_CAPACITY, CSG_LIST_CAPACITY, MEDIUM_STACK_SIZE, RAY_STACK_SIZE};
use crate::gpu::compile::kernel::KernelConfig;
use crate::pack::SceneFeatures;

/// Words of one pending ray: origin 3, direction 3, weight 3, depth 1, cone 2, medium
/// stack (indices and count) `MEDIUM_STACK_SIZE` + 1.
pub const STACK_ENTRY_WORDS: u32 = 12 + MEDIUM_STACK_SIZE + 1;

/// Words of one ray's CSG evaluation state: the ends' t and tags, the lists' starts and
/// counts.
pub const CSG_STATE_WORDS: u32 = 2 * CSG_EVENT_CAPACITY + 2 * CSG_LIST_CAPACITY;

/// Most bytes of per-ray lists a frame keeps: enough slots for the invocations a GPU runs
/// at once (a NAVI21 holds 80 CUs × 2 SIMDs × 16 waves × 32 lanes = 81 920 in flight,
/// and scrabble.lua's 2.2 KiB a slot gives 121 000 slots here), less where the adapter's
/// storage binding is smaller. Chunks are planned so that no tracing dispatch has more
/// invocations than slots (`plan.rs`).
pub const LIST_BUDGET_BYTES: u64 = 256 << 20;

/// Where a lane's lists lie among its words, for one scene's features and kernel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LaneLists {
    /// Words of the pending rays (0: not in storage).
    pub ray_stack: u32,
    /// Words of the CSG state (0: not in storage).
    pub csg: u32,
}

impl LaneLists {
    /// The lists `kernel` keeps in storage for a scene with `features`: none unless
    /// `kernel.lists_in_storage`; the ray stack with refraction (without it the stack
    /// holds one entry, which fits registers), the CSG state with CSG.
    pub fn of(features: SceneFeatures, kernel: KernelConfig) -> LaneLists {
        if !kernel.lists_in_storage {
            return LaneLists {
                ray_stack: 0,
                csg: 0,
            };
        }
        let has = |f| features.contains(f);
        LaneLists {
            ray_stack: if has(SceneFeatures::REFRACTION) {
                RAY_STACK_SIZE * STACK_ENTRY_WORDS
            } else {
                0
            },
            csg: if has(SceneFeatures::CSG) {
                CSG_STATE_WORDS
            } else {
                0
            },
        }
    }

    /// Words of one lane.
    pub fn words(&self) -> u32 {
        self.ray_stack + self.csg
    }

    /// Bytes of one lane.
    pub fn bytes(&self) -> u64 {
        4 * self.words() as u64
    }

    /// First word of the CSG state.
    pub fn csg_at(&self) -> u32 {
        self.ray_stack
    }

    /// The WGSL constants of the layout (`LANE_LIST_WORDS`, `STACK_ENTRY_WORDS`, and
    /// where the CSG state's t, tags, list starts and list counts begin), emitted after
    /// the constants prelude.
    pub fn wgsl_prelude(&self) -> String {
        let t = self.csg_at();
        let tags = t + CSG_EVENT_CAPACITY;
        let starts = tags + CSG_EVENT_CAPACITY;
        let counts = starts + CSG_LIST_CAPACITY;
        let constants = [
            ("LANE_LIST_WORDS", self.words().max(1)),
            ("STACK_ENTRY_WORDS", STACK_ENTRY_WORDS),
            ("CSG_STATE_AT", t),
            ("CSG_TAGS_AT", tags),
            ("CSG_STARTS_AT", starts),
            ("CSG_COUNTS_AT", counts),
        ];
        constants
            .iter()
            .map(|(name, value)| format!("const {name}: u32 = {value}u;\n"))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn with(features: &[SceneFeatures], storage: bool) -> LaneLists {
        let mut set = SceneFeatures::empty();
        for f in features {
            set.insert(*f);
        }
        let kernel = KernelConfig {
            lists_in_storage: storage,
            ..KernelConfig::default()
        };
        LaneLists::of(set, kernel)
    }

    #[test]
    fn only_the_lists_a_scene_uses_and_only_in_storage_kernels() {
        use SceneFeatures as F;
        assert_eq!(with(&[F::REFRACTION, F::CSG], false).words(), 0);
        assert_eq!(with(&[F::REFLECTION, F::SPHERE], true).words(), 0);
        let glass = with(&[F::REFRACTION], true);
        assert_eq!((glass.ray_stack, glass.csg), (16 * 17, 0));
        let both = with(&[F::REFRACTION, F::CSG], true);
        assert_eq!(both.csg_at(), 16 * 17);
        assert_eq!(both.words(), 16 * 17 + 2 * 128 + 2 * 17);
        assert_eq!(with(&[F::CSG], true).csg_at(), 0);
    }
}
