//! What a traversal returns (the nearest hit), what it may count (`--stats`), and the
//! direct-mapped slots both levels' mailboxes remember tested items in.

use crate::constants::{NO_ITEM, T_MISS};

/// The nearest hit: distance, item (a scene grid item: an instance), for triangles the
/// barycentric weights of p1 and p2, and `part`: for a mesh instance the triangle hit
/// (its index in `PackedScene::triangles`), for a CSG item the surface hit (leaf instance
/// index, with `CSG_FLIP` when its normal is negated); `NO_ITEM` otherwise.
// Mirror of src/tracer/traversal/hit.wgsl::Hit — change both.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f32,
    pub item: u32,
    pub b1: f32,
    pub b2: f32,
    pub part: u32,
}

/// No hit: t = `T_MISS`, no item, no part.
// Mirror of src/tracer/traversal/hit.wgsl::hit_miss — change both.
pub const fn hit_miss() -> Hit {
    Hit {
        t: T_MISS,
        item: NO_ITEM,
        b1: 0.0,
        b2: 0.0,
        part: NO_ITEM,
    }
}

impl Hit {
    // Mirror of src/tracer/traversal/hit.wgsl::is_hit — change both.
    pub fn is_hit(&self) -> bool {
        self.item != NO_ITEM
    }
}

/// Traversal counters (CPU only, for `--stats`); the no-op impl costs nothing.
pub trait TraversalCounters {
    fn traversal_started(&mut self) {}
    /// A cell of either level of grid.
    fn cell_visited(&mut self) {}
    /// A primitive (analytic, CSG or triangle) tested.
    fn item_tested(&mut self) {}
    /// An area light reached a shaded point through some of its shadow samples but not
    /// all (a penumbra): adaptive AA splits the squares around such a sample
    /// (`tracer::sampling::pixel_sample::hinted_sample`).
    fn partial_light(&mut self) {}
    /// The item the camera ray of a sample hit first (`NO_ITEM`: none): adaptive AA splits
    /// squares whose samples hit different items (`tracer::sampling::pixel_sample::hinted_sample`).
    fn camera_hit(&mut self, _item: u32) {}
    /// The camera ray's first hit showed texture detail at the pixel's scale
    /// (`texture::texture_detail` over AA_TEXTURE_DETAIL_SHARE of `aa_threshold`):
    /// adaptive AA splits around it as around a penumbra.
    fn texture_detail(&mut self) {}
    /// The camera ray's first surface is a mirror (reflective, not a dielectric) and
    /// the ray it reflects hit `item` first (`NO_ITEM`: none): adaptive AA keys the sample
    /// by both items, so edges seen in a mirror split as edges seen directly do.
    fn mirror_hit(&mut self, _item: u32) {}
}

/// Counters that count nothing.
pub struct NoCounters;
impl TraversalCounters for NoCounters {}

/// Counters that count.
#[derive(Clone, Copy, Debug, Default)]
pub struct Counters {
    pub cells_visited: u64,
    pub items_tested: u64,
}
impl TraversalCounters for Counters {
    fn cell_visited(&mut self) {
        self.cells_visited += 1;
    }
    fn item_tested(&mut self) {
        self.items_tested += 1;
    }
}

/// The direct-mapped slots both levels' mailboxes remember tested items in
/// (`traverse::Mailbox`, `traverse_mesh::TriangleMailbox`): N slots (a power of two), a
/// value in slot `value & slot_mask` (`None`: nothing is remembered).
pub struct Slots<const N: usize> {
    slots: [u32; N],
    slot_mask: Option<u32>,
}

impl<const N: usize> Slots<N> {
    /// Every slot empty (`NO_ITEM`).
    pub fn new(slot_mask: Option<u32>) -> Slots<N> {
        Slots {
            slots: [NO_ITEM; N],
            slot_mask,
        }
    }

    /// Whether `value` is in its slot; if not, it is now.
    #[inline(always)]
    pub fn seen(&mut self, value: u32) -> bool {
        if let Some(mask) = self.slot_mask {
            // (The constant mask too, so the index needs no bounds check.)
            let slot = &mut self.slots[(value & mask) as usize & (N - 1)];
            if *slot == value {
                return true;
            }
            *slot = value;
        }
        false
    }
}
